"""Cycle counting of a stress history and Miner's sum of the damage of the cycles on an S-N curve.

* `rainflow(series)`: the rainflow count of ASTM E1049-85 (2011) §5.4.4, as (range, count) pairs, half
  cycles counted 0.5 (``rainflow.count_cycles`` of the `rainflow` package);
* `cycle_ranges(series)`: the range and count of every extracted cycle as two arrays
  (``rainflow.extract_cycles``), for the damage of many long series;
* `miner(cycles, curve)`: the Palmgren–Miner sum D = Σ n_i / N(Δσ_i).

Reversals first
---------------
Both counts depend only on the series' reversals (its local extremes, with the first and the last point).
The series is reduced to them with numpy before the (pure-Python) counting of the `rainflow` package sees
it, exactly as ``rainflow.reversals`` finds them (repeated consecutive values merged, a reversal where the
slope changes sign): the cycles are the same as the package's on the whole series, and a sampled response of
n samples per period is counted about n/2 times faster. The package counts no cycle in a series of exactly
two points (``rainflow.count_cycles([0, 1])`` is empty, while ``[0, 0.5, 1]`` gives a half cycle of 1); here
any monotonic series gives its half cycle, as ASTM E1049 counts it. A constant series has no cycles.

References
----------
* ASTM E1049-85 (Reapproved 2011), *Standard Practices for Cycle Counting in Fatigue Analysis*, §5.4.4
  rainflow counting, Fig. 6 and Table 4 (the worked example).
* DNV-RP-C203 (2016) §2.2: Miner's sum D = Σ n_i / N_i, with the S-N curve's N_i at the stress range Δσ_i.

Units: stress (range) in MPa where a curve is used; the counts take any unit.

Imports of pipelay: `pipelay.analysis.checks` (its input errors) and `pipelay.analysis.fatigue.curves`.
"""

from __future__ import annotations

import itertools

import numpy as np
import rainflow as _rainflow  # type: ignore[import-untyped]
from numpy.typing import ArrayLike, NDArray

from pipelay.analysis.checks import _Described, _input_error
from pipelay.analysis.fatigue.curves import SNCurve

__all__ = ["cycle_ranges", "miner", "rainflow"]

FloatArray = NDArray[np.float64]


def rainflow(series: ArrayLike) -> list[tuple[float, float]]:
    """Rainflow count of `series` (ASTM E1049-85 §5.4.4): the (range, count) pairs, sorted by range.

    Parameters
    ----------
    series : array-like (T,)
        The history (e.g. a stress in MPa), T ≥ 2 finite real numbers.

    Returns
    -------
    list of (float, float)
        (range, count) for each distinct range, ascending; full cycles count 1, half cycles 0.5
        (``rainflow.count_cycles``). Empty for a constant series.

    Raises
    ------
    pipelay.InputError
        If `series` is not a 1-D series of at least 2 finite real numbers.
    """
    reversals = _reversals(_series("series", series))
    if reversals.size < 2:
        return []
    counted = _rainflow.count_cycles(_for_counting(reversals))
    return [(float(range_), float(count)) for range_, count in counted]


def cycle_ranges(series: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Range and count of every cycle rainflow extracts from `series` (``rainflow.extract_cycles``).

    Unlike `rainflow`, cycles of equal range are not merged: the arrays hold one entry per extracted
    (full or half) cycle, in the order of extraction.

    Parameters
    ----------
    series : array-like (T,)
        The history (e.g. a stress in MPa), T ≥ 2 finite real numbers.

    Returns
    -------
    ranges : ndarray (k,)
        Range of each cycle (unit of the series), ≥ 0.
    counts : ndarray (k,)
        1.0 for a full cycle, 0.5 for a half cycle. Both empty for a constant series.

    Raises
    ------
    pipelay.InputError
        If `series` is not a 1-D series of at least 2 finite real numbers.
    """
    reversals = _reversals(_series("series", series))
    if reversals.size < 2:
        return np.zeros(0), np.zeros(0)
    extracted = _rainflow.extract_cycles(_for_counting(reversals))
    # (range, mean, count, start index, end index) per cycle, flattened without a Python loop of our own.
    table = np.fromiter(itertools.chain.from_iterable(extracted), dtype=np.float64).reshape(-1, 5)
    return np.ascontiguousarray(table[:, 0]), np.ascontiguousarray(table[:, 2])


def miner(cycles: ArrayLike, curve: SNCurve) -> float:
    """Palmgren–Miner damage D = Σ n_i / N(Δσ_i) of counted cycles on an S-N curve.

    Parameters
    ----------
    cycles : sequence of (stress_range, count) pairs, or array (k, 2)
        Stress ranges Δσ_i (MPa) ≥ 0 and their counts n_i ≥ 0 (half cycles 0.5), finite: the output of
        `rainflow`, or ``np.column_stack(cycle_ranges(series))``. May be empty (damage 0).
    curve : SNCurve
        The S-N curve giving N(Δσ).

    Returns
    -------
    float
        Miner's sum D (dimensionless; failure at D = 1 without a design fatigue factor). A range of 0 does
        no damage.

    Raises
    ------
    pipelay.InputError
        If `cycles` is not (k, 2) of finite numbers with ranges and counts ≥ 0, or `curve` is not an SNCurve.
    """
    if not isinstance(curve, SNCurve):
        raise _input_error(
            "curve",
            _Described(f"a {type(curve).__name__}"),
            "an SNCurve (SNCurve.dnv(...), SNCurve.user(...))",
        )
    allowed = "(stress_range MPa, count) pairs, an array (k, 2), finite, ranges and counts >= 0"
    try:
        table = np.asarray(cycles, dtype=np.float64)
    except (TypeError, ValueError):
        raise _input_error(
            "cycles", _Described(f"a {type(cycles).__name__}"), allowed, "is not numeric"
        ) from None
    if table.size == 0:
        return 0.0
    if table.ndim != 2 or table.shape[1] != 2:
        raise _input_error("cycles", _Described(f"an array of shape {table.shape}"), allowed, "is not (k, 2)")
    if not np.all(np.isfinite(table)):
        raise _input_error("cycles", _Described("an array"), allowed, "holds NaN or infinite entries")
    negative = table < 0.0
    if np.any(negative):
        row, column = (int(index) for index in np.argwhere(negative)[0])
        what = "stress range" if column == 0 else "count"
        raise _input_error(
            "cycles",
            _Described(f"pair {row}"),
            allowed,
            f"holds a negative {what} ({float(table[row, column])!r})",
        )
    return float(np.sum(table[:, 1] / curve.cycles(table[:, 0])))


# --- helpers ---------------------------------------------------------------------------------------------


def _series(argument: str, series: ArrayLike) -> FloatArray:
    """`series` as a finite 1-D float array of at least 2 samples, else an input error."""
    return _finite_vector(argument, series, "a 1-D series of at least 2 finite real numbers", minimum=2)


def _finite_vector(argument: str, values: ArrayLike, allowed: str, *, minimum: int = 0) -> FloatArray:
    """`values` as a finite real 1-D float array of at least `minimum` entries, else an input error saying
    what is wrong and `allowed`."""
    if np.iscomplexobj(values):
        raise _input_error(argument, _Described("a complex array"), allowed, "is not real")
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise _input_error(
            argument, _Described(f"a {type(values).__name__}"), allowed, "is not numeric"
        ) from None
    if array.ndim != 1:
        raise _input_error(argument, _Described(f"an array of shape {array.shape}"), allowed, "is not 1-D")
    if array.size < minimum:
        raise _input_error(argument, _Described(f"a series of {array.size} samples"), allowed, "is too short")
    bad = np.count_nonzero(~np.isfinite(array))
    if bad:
        raise _input_error(
            argument,
            _Described(f"an array of {array.size} values"),
            allowed,
            f"has {bad} NaN or infinite ones",
        )
    return array


def _reversals(values: FloatArray) -> FloatArray:
    """The reversals of `values` as ``rainflow.reversals`` finds them: the first and last points and every
    point where the slope changes sign, repeated consecutive values merged. One value for a constant series."""
    distinct = np.empty(values.size, dtype=bool)
    distinct[0] = True
    np.not_equal(values[1:], values[:-1], out=distinct[1:])
    merged = values[distinct]
    if merged.size < 3:
        return merged
    rising = np.diff(merged) > 0.0  # no zero differences after merging
    turns = np.flatnonzero(rising[1:] != rising[:-1]) + 1
    return np.concatenate((merged[:1], merged[turns], merged[-1:]))


def _for_counting(reversals: FloatArray) -> list[float]:
    """The reversals as the list `rainflow` counts, with the last value repeated: the package then counts
    the half cycle of a two-point history (it counts none in a series of two points), and the repeated
    value changes nothing else (the package merges repeated values)."""
    values: list[float] = reversals.tolist()
    values.append(values[-1])
    return values
