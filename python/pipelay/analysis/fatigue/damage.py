"""Fatigue damage of a run: Miner's sum at every hot spot of every element, over a given duration.

``damage(results, curve, scf=1.0, duration=3600.0)`` takes the hot-spot stress histories of the run
(`pipelay.analysis.fatigue.stresses`), counts their cycles (rainflow, ASTM E1049) or takes their response
spectra (Dirlik, narrow band), sums n/N on the S-N curve (DNV-RP-C203, Miner's rule) and scales the sum from
the record's span to `duration`: the record stands for a stationary sea state lasting `duration`. Stress
ranges enter the S-N curve in MPa.

Imports of pipelay: `pipelay.analysis.checks` (input errors) and the fatigue package's own modules.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from pipelay.analysis.checks import _Described, _input_error, _number
from pipelay.analysis.fatigue.counting import cycle_ranges
from pipelay.analysis.fatigue.curves import SNCurve
from pipelay.analysis.fatigue.spectral import series_spectral_damage
from pipelay.analysis.fatigue.stresses import HotSpotStresses, hot_spot_stresses

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["METHODS", "Damage", "damage", "damage_of_stresses"]

FloatArray = NDArray[np.float64]

METHODS = ("rainflow", "dirlik", "narrow_band")
"""How stress cycles are found: rainflow counting of the history (ASTM E1049), or from its response spectrum by
Dirlik's formula or the narrow-band (Rayleigh) one."""

PASCAL_PER_MPA = 1e6


@dataclass(frozen=True, eq=False)
class Damage:
    """Miner's sums of a run, per element and hot spot, over `duration`.

    Attributes
    ----------
    values : ndarray (n, points)
        Damage D = Σ n/N over `duration` at each element and hot spot (1: failure by Miner's rule); NaN for an
        element without a steel wall.
    angles : ndarray (points,)
        The hot spots' angles around the section (rad, from d2 toward d3).
    arc_length : ndarray (n,)
        Each element midpoint's distance along the line from end A (m).
    duration : float
        The duration the damage is for (s).
    record : float
        The span of the records counted (s).
    method : str
        "rainflow", "dirlik" or "narrow_band".
    """

    values: FloatArray
    angles: FloatArray
    arc_length: FloatArray
    duration: float
    record: float
    method: str

    @property
    def per_element(self) -> FloatArray:
        """The largest damage around each element's section (n,) (NaN for an element without a wall)."""
        with np.errstate(invalid="ignore"):
            result: FloatArray = np.max(self.values, axis=1)
        return result

    def max(self) -> float:
        """The largest damage along the line."""
        return float(np.nanmax(self.values))

    def worst(self) -> tuple[int, float]:
        """The element (index from end A) and hot-spot angle (rad) of the largest damage."""
        flat = np.where(np.isnan(self.values), -np.inf, self.values)
        element, point = np.unravel_index(int(np.argmax(flat)), flat.shape)
        return int(element), float(self.angles[point])

    def plot(self, ax: Axes | None = None, path: str | os.PathLike[str] | None = None) -> Figure:
        """The damage along the line (`pipelay.plots.fatigue.damage_along`), on `ax` if given, saved to `path`
        if given."""
        from pipelay.plots.fatigue import damage_along

        return damage_along(self, ax=ax, path=path)


def damage(
    results: Any,
    curve: SNCurve | Sequence[SNCurve],
    *,
    scf: float | Sequence[float] = 1.0,
    duration: float = 3600.0,
    method: str = "rainflow",
    points: int = 8,
    surface: str = "outer",
    internal_pressure: float = 0.0,
    start: float | None = None,
    pipe_walls: Sequence[tuple[float, float] | None] | None = None,
    water: tuple[float, float] | None = None,
) -> Damage:
    """Fatigue damage at `points` hot spots around every element of a run, scaled to `duration`.

    Parameters
    ----------
    results : pipelay.Results
        The run, in memory or loaded from its file (``pl.load``).
    curve : SNCurve or sequence of SNCurve
        The S-N curve of the welds (``SNCurve.dnv("D", environment="seawater_cp")``), or one per segment.
    scf : float or sequence of float
        Stress concentration factor (≥ 1), for the line or per segment.
    duration : float
        The time the run's sea state lasts (s, > 0): the damage of the record is scaled by duration / record.
    method : {"rainflow", "dirlik", "narrow_band"}
        Rainflow counting of each history, or the spectral methods on its Welch spectrum.
    points, surface, internal_pressure, start, pipe_walls, water
        As `hot_spot_stresses`: the hot spots, the records before `start` (s) left out, and the line and sea
        where the results do not record them.

    Returns
    -------
    Damage

    Raises
    ------
    pipelay.InputError
        A bad argument (its name in the message), or results that cannot give stresses (see
        `hot_spot_stresses`).
    """
    stresses = hot_spot_stresses(
        results,
        points=points,
        scf=scf,
        surface=surface,
        internal_pressure=internal_pressure,
        start=start,
        pipe_walls=pipe_walls,
        water=water,
    )
    return damage_of_stresses(stresses, curve, duration=duration, method=method)


def damage_of_stresses(
    stresses: HotSpotStresses,
    curve: SNCurve | Sequence[SNCurve],
    *,
    duration: float = 3600.0,
    method: str = "rainflow",
) -> Damage:
    """The damage of hot-spot stress histories (`hot_spot_stresses`) over `duration` (s); see `damage`."""
    span = _number("duration", duration, positive=True)
    if method not in METHODS:
        raise _input_error("method", method, ", ".join(METHODS))
    time = stresses.time
    record = float(time[-1] - time[0])
    steps = np.diff(time)
    if record <= 0.0 or not np.allclose(steps, steps[0], rtol=1e-6, atol=0.0):
        raise _input_error(
            "results",
            _Described("records at uneven times"),
            "records at a constant interval (record_every constant, a fixed time step)",
        )
    curves = _per_segment_curves(curve, int(stresses.segment_of.max()) + 1)
    elements, points = stresses.stress.shape[1:]
    values = np.full((elements, points), np.nan)
    megapascal = stresses.stress / PASCAL_PER_MPA
    for element in range(elements):
        if np.isnan(megapascal[0, element, 0]):
            continue
        sn = curves[stresses.segment_of[element]]
        for point in range(points):
            series = megapascal[:, element, point]
            if method == "rainflow":
                ranges, counts = cycle_ranges(series)
                values[element, point] = float(np.sum(counts / sn.cycles(ranges))) * span / record
            else:
                values[element, point] = series_spectral_damage(
                    series, float(steps[0]), sn, duration=span, method=method
                )
    return Damage(
        values=values,
        angles=stresses.angles,
        arc_length=stresses.arc_length,
        duration=span,
        record=record,
        method=method,
    )


def _per_segment_curves(curve: SNCurve | Sequence[SNCurve], segments: int) -> list[SNCurve]:
    """The S-N curve of each segment."""
    given = [curve] if isinstance(curve, SNCurve) else list(curve) if isinstance(curve, Sequence) else [curve]
    if len(given) not in (1, segments) or not all(isinstance(c, SNCurve) for c in given):
        raise _input_error(
            "curve",
            _Described(repr(curve)),
            f"an SNCurve (SNCurve.dnv(...), SNCurve.user(...)), or one per segment ({segments})",
        )
    return given * segments if len(given) == 1 else given
