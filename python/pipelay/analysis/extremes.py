"""The top tension of a run, its extremes, and the utilisation of every element at every record.

* `top_tension(results)`: the top tension at every record, the one definition every figure, table, summary and
  statistic of pipelay uses;
* `extremes(results, ...)`: the largest and smallest top tension, the largest reaction at end B, the largest
  strain, bending moment and effective axial force and (optionally) the largest DNV-ST-F101 utilisation of a
  run, each with its time (and element);
* `utilisation(results, ...)`: the DNV-ST-F101 (or a user check's) utilisation of every element at every
  record.

The top tension is the effective tension that the tensioner, the J-lay tower, the A&R winch or the support at
the top holds: the effective axial force N1 of the line's top element. With a vessel it is the lay summary's
``top_tension`` (``results.lay_summary()["top_tension"]``, the element at the hold point); without one (a line
hanging from a support or a driven end) the axial force of the element at end B (the last element each record
has, with pay-out). It is not the magnitude |F_B| of the reaction at end B: that also carries the shear force
and, at a stinger, the pull of the line's weight beyond the hold point, and is named "reaction at B |F_B|"
where it is shown.

Units: N, N·m, s; strains and utilisations are dimensionless. `pipelay.analysis.statistics` exposes both with
the statistics of time series (``pl.statistics.extremes``).

Imports of pipelay: `pipelay.analysis.checks`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from types import SimpleNamespace
from typing import Any

import numpy as np
from numpy.typing import NDArray

# One way of wording input errors across the package's Python modules.
from pipelay.analysis.checks import (
    Utilisation,
    _Described,
    _input_error,
    _number,
    _records_utilisation,
    dnv_st_f101,
)

__all__ = ["extremes", "record_state", "top_elements", "top_tension", "utilisation"]

FloatArray = NDArray[np.float64]


def extremes(
    results: Any,
    *,
    section: Any = None,
    sea: Any = None,
    model: Any = None,
    checks: Mapping[str, Any] | Callable[[Any], Any] | None = None,
) -> dict[str, float]:
    """The extremes of a run, each with the time (s) of its record and, for a value along the pipe, the index
    of its element (0 at end A).

    NaN entries (the nodes and elements a record of a pay-out run did not have yet) are skipped: reductions
    are nan-aware.

    Keys (plain floats; ``*_element`` are ints):

    * ``top_tension_max``, ``top_tension_min`` (N): the top tension (`top_tension`: the effective tension at
      the tensioner, tower or top support), with ``*_time``;
    * ``reaction_B_max`` (N): the largest reaction at B |F_B| = |``results.reaction("B")[:, :3]``|, the
      force of the line on what holds end B (the vessel's or the support's load), with ``*_time``;
    * ``tension_max``, ``tension_min`` (N): the effective axial force N1 over all elements (negative:
      compression), with ``*_time`` and ``*_element``;
    * ``moment_max`` (N·m): the bending moment |M| = √(M2² + M3²), with ``*_time`` and ``*_element``;
    * ``strain_max`` (1): the largest longitudinal strain at the outer fibre, ε = N1/EA + (d_o/2)|κ| with
      κ = (M2/EI2, M3/EI3) (as ``State.strain``), with ``*_time`` and ``*_element``; only with a section;
    * ``utilisation_max`` (1), with ``*_time`` and ``*_element``; only with `checks`; with DNV parameters
      also ``load_controlled_max`` and ``displacement_controlled_max``, each with ``*_time``, ``*_element``.

    Parameters
    ----------
    results : pipelay.Results
        The run (``time``, ``reaction``, ``section_forces``, ``positions``, ``lay_summary``).
    section : pipelay.Section or None
        The pipe's section (anything with ``EA`` (N), ``EI`` (N·m², one number or the pair (EI2, EI3)) and
        ``outer_diameter`` (m)); None: ``model.rod.section`` if `model` is given, else no strain.
    sea : pipelay.Sea or None
        The sea (``depth`` (m), ``density`` (kg/m³)) for the hydrostatic pressure of the checks; None:
        ``model.sea`` if `model` is given, else none (no external pressure).
    model : pipelay.Model or None
        The model of the run, a source of `section` and `sea`.
    checks : mapping, callable or None
        None: no utilisation. A mapping: keyword arguments of ``pipelay.checks.dnv_st_f101`` (e.g.
        ``{"grade": "X65", "safety_class": "low"}``, ``{}`` for its defaults; needs a section made by
        ``Section.pipe``), evaluated at every record; the utilisation of an element is the larger of its
        load- and displacement-controlled ones. A callable: ``checks(record)`` for every record, returning a
        ``pipelay.checks.Utilisation`` or the elements' utilisations (n,) (a scalar counts as the record's,
        element −1). A record is state-like: ``time``, ``section_forces`` (n, 6), ``tension`` (n,),
        ``positions`` (n + 1, 3), ``strain`` (n,) (None without a section), ``section``, ``water_depth`` and
        ``water_density`` (None without a sea), with only the nodes and elements the record has.

    Returns
    -------
    dict of str to float

    Raises
    ------
    pipelay.InputError
        If `section` lacks a positive EA, EI or a non-negative outer diameter, `checks` is neither a mapping
        nor a callable or is given as a mapping without a section, or a record has no values at all.
    """
    time = np.asarray(results.time, dtype=np.float64)
    section, sea = _section_and_sea(section, sea, model)
    stiffness = None if section is None else _section_stiffness(section)

    found: dict[str, float] = {}

    top = top_tension(results)
    _put(found, "top_tension_max", top, time, largest=True)
    _put(found, "top_tension_min", top, time, largest=False)
    reaction = np.linalg.norm(np.asarray(results.reaction("B"), dtype=np.float64)[:, :3], axis=1)
    _put(found, "reaction_B_max", reaction, time, largest=True)

    forces = np.asarray(results.section_forces, dtype=np.float64)
    axial = forces[:, :, 0]
    _put(found, "tension_max", axial, time, largest=True)
    _put(found, "tension_min", axial, time, largest=False)
    _put(found, "moment_max", np.hypot(forces[:, :, 4], forces[:, :, 5]), time, largest=True)
    strain = None
    if stiffness is not None:
        strain = _strain(forces, *stiffness)
        _put(found, "strain_max", strain, time, largest=True)

    if checks is not None:
        worst, load, displacement, scalar = _utilisations(results, time, forces, strain, section, sea, checks)
        _put(found, "utilisation_max", worst, time, largest=True)
        if scalar:
            found["utilisation_max_element"] = -1
        if np.isfinite(load).any():
            _put(found, "load_controlled_max", load, time, largest=True)
            _put(found, "displacement_controlled_max", displacement, time, largest=True)
    return found


def top_elements(segment: FloatArray) -> NDArray[np.int64]:
    """The last element each record has (T,), of `segment` (T, n) (the rest is NaN padding of a run with
    pay-out)."""
    finite = np.isfinite(segment)
    return segment.shape[1] - 1 - np.argmax(finite[:, ::-1], axis=1)


def top_tension(results: Any) -> FloatArray:
    """The top tension at every record (T,) (N): the effective tension the tensioner, the tower or the top
    support holds, the effective axial force N1 of the line's top element (see the module's docstring).

    With a vessel, the lay summary's ``top_tension`` (the element at the hold point); without one, the axial
    force of the element at end B, the last element each record has (a run with pay-out pads the rest with
    NaN).

    Parameters
    ----------
    results : pipelay.Results, xarray.Dataset or Results-like
        The run: a ``pipelay.Results`` (or anything with ``lay_summary()`` and ``section_forces`` (T, n, 6)),
        or a results file opened with ``xarray.open_dataset`` (its ``top_tension`` variable, else its
        ``section_forces``; only the axial forces are read).

    Returns
    -------
    ndarray (T,)
        A new array (N): positive in tension.
    """
    if callable(getattr(results, "lay_summary", None)):
        summary = results.lay_summary()
        if summary is not None:
            return np.array(summary["top_tension"], dtype=np.float64)
        axial = np.asarray(results.section_forces, dtype=np.float64)[:, :, 0]
    elif "top_tension" in results:
        return np.array(results["top_tension"].values, dtype=np.float64)
    else:
        axial = np.asarray(results["section_forces"].isel(dof=0).values, dtype=np.float64)
    top = top_elements(axial)
    result: FloatArray = axial[np.arange(len(top)), top]
    return result


def _strain(forces: FloatArray, ea: float, ei2: float, ei3: float, diameter: float) -> FloatArray:
    """ε = N1/EA + (d_o/2)|(M2/EI2, M3/EI3)| for forces (..., 6); NaN stays NaN."""
    result: FloatArray = forces[..., 0] / ea + 0.5 * diameter * np.hypot(
        forces[..., 4] / ei2, forces[..., 5] / ei3
    )
    return result


def utilisation(
    results: Any,
    *,
    section: Any = None,
    sea: Any = None,
    model: Any = None,
    checks: Mapping[str, Any] | Callable[[Any], Any],
) -> FloatArray:
    """The utilisation of every element at every record, (records, elements) (1; NaN where a record of a
    pay-out run had no such element): the larger of the load- and displacement-controlled ones of
    `checks` (see `extremes` for the arguments). A callable returning one number per record puts it in
    element 0.

    Raises
    ------
    pipelay.InputError
        As `extremes`.
    """
    section, sea = _section_and_sea(section, sea, model)
    time = np.asarray(results.time, dtype=np.float64)
    forces = np.asarray(results.section_forces, dtype=np.float64)
    stiffness = None if section is None else _section_stiffness(section)
    strain = None if stiffness is None else _strain(forces, *stiffness)
    return _utilisations(results, time, forces, strain, section, sea, checks)[0]


def record_state(
    results: Any, record: int, *, section: Any = None, sea: Any = None, model: Any = None
) -> SimpleNamespace:
    """Record `record` of a run as the checks (`pl.checks.dnv_st_f101`, `pl.checks.propagation_buckling`) read
    a state: its time, section forces, tension (N), positions (m), strain (from the forces, as `extremes`),
    section and sea (`section` and `sea`, or the model's). The elements and nodes the record has: a pay-out
    run's rows end in NaN.

    Raises
    ------
    pipelay.InputError
        Without a section (or a model), or for a record out of range.
    """
    section, sea = _section_and_sea(section, sea, model)
    if section is None:
        raise _input_error("section", None, "a section or a model", "is missing")
    count = len(results.time)
    if isinstance(record, bool) or not isinstance(record, (int, np.integer)) or not -count <= record < count:
        raise _input_error("record", record, f"an index of the {count} records")
    forces = np.asarray(results.section_forces[record], dtype=np.float64)
    positions = np.asarray(results.positions[record], dtype=np.float64)
    strain = _strain(forces, *_section_stiffness(section))
    return _record(float(results.time[record]), forces, positions, strain, section, sea)


def _record(
    time: float, forces: FloatArray, positions: FloatArray, strain: FloatArray | None, section: Any, sea: Any
) -> SimpleNamespace:
    """A record as a state the checks read, its missing (NaN) elements and nodes left out."""
    valid = np.isfinite(forces).all(axis=1)
    nodes = np.isfinite(positions).all(axis=1)
    return SimpleNamespace(
        time=time,
        section_forces=forces[valid],
        tension=forces[valid][:, 0],
        positions=positions[nodes],
        strain=None if strain is None else strain[valid],
        section=section,
        water_depth=None if sea is None else float(sea.depth),
        water_density=None if sea is None else float(sea.density),
    )


def _section_and_sea(section: Any, sea: Any, model: Any) -> tuple[Any, Any]:
    """`section` and `sea`, or the model's where they are None."""
    if section is None and model is not None:
        section = model.rod.section
    if sea is None and model is not None:
        sea = model.sea
    return section, sea


def _utilisations(
    results: Any,
    time: FloatArray,
    forces: FloatArray,
    strain: FloatArray | None,
    section: Any,
    sea: Any,
    checks: Mapping[str, Any] | Callable[[Any], Any],
) -> tuple[FloatArray, FloatArray, FloatArray, bool]:
    """Evaluates `checks` at every record: the utilisation, its load- and displacement-controlled parts
    (records, elements) and whether the checks gave one number per record."""
    if isinstance(checks, Mapping):
        if section is None:
            raise _input_error(
                "section", None, "a pipe section (Section.pipe) or a model, for the DNV checks", "is missing"
            )
        parameters = dict(checks)
        positions = np.asarray(results.positions, dtype=np.float64)
        if strain is not None and np.isfinite(forces).all() and np.isfinite(positions).all():
            # Every record has every element (no pay-out): all records together, in blocks, the same numbers.
            water = None if sea is None else (float(sea.depth), float(sea.density))
            load, displacement = _records_utilisation(section, forces, strain, positions, water, parameters)
            return np.maximum(load, displacement), load, displacement, False

        def dnv(record: Any) -> Any:
            return dnv_st_f101(record, **parameters)

        evaluate: Callable[[Any], Any] = dnv
    elif callable(checks):
        evaluate = checks
    else:
        raise _input_error(
            "checks",
            _Described(f"an object of type {type(checks).__name__}"),
            "None, a mapping of dnv_st_f101 arguments or a callable",
        )

    positions = np.asarray(results.positions, dtype=np.float64)
    count, elements = forces.shape[:2]
    worst = np.full((count, elements), np.nan)
    load = np.full((count, elements), np.nan)
    displacement = np.full((count, elements), np.nan)
    scalar = False
    for k in range(count):
        valid = np.isfinite(forces[k]).all(axis=1)
        n = int(valid.sum())
        record = _record(
            float(time[k]), forces[k], positions[k], None if strain is None else strain[k], section, sea
        )
        outcome = evaluate(record)
        if isinstance(outcome, Utilisation):
            load[k, valid] = outcome.load_controlled
            displacement[k, valid] = outcome.displacement_controlled
            worst[k, valid] = np.maximum(outcome.load_controlled, outcome.displacement_controlled)
            continue
        values = np.asarray(outcome, dtype=np.float64)
        if values.ndim == 0:
            scalar = True
            worst[k, 0] = values
        elif values.shape == (n,):
            worst[k, valid] = values
        else:
            raise _input_error(
                "checks",
                _Described(f"a callable returning shape {values.shape} at t = {time[k]:g} s"),
                f"a Utilisation, a number or ({n},) values, one per element",
                "is not usable",
            )
    return worst, load, displacement, scalar


def _put(found: dict[str, float], key: str, values: FloatArray, time: FloatArray, *, largest: bool) -> None:
    """found[key] = the nan-aware max (or min) of values (T,) or (T, n), with found[key_time] and, for (T, n),
    found[key_element]."""
    if not np.isfinite(values).any():
        raise _input_error("results", _Described(f"no finite values for {key}"), "records with values", "has")
    flat = values.reshape(values.shape[0], -1)
    missing = np.isnan(flat)
    # Without NaN entries (a run without pay-out) the values themselves: a long run's are hundreds of MB.
    filled = np.where(missing, -np.inf if largest else np.inf, flat) if missing.any() else flat
    index = int(np.argmax(filled) if largest else np.argmin(filled))
    record, element = divmod(index, flat.shape[1])
    found[key] = float(flat[record, element])
    found[f"{key}_time"] = float(time[record])
    if values.ndim == 2:
        found[f"{key}_element"] = element


def _section_stiffness(section: Any) -> tuple[float, float, float, float]:
    """(EA, EI2, EI3, d_o) of a section, validated."""
    for name in ("EA", "EI", "outer_diameter"):
        if not hasattr(section, name):
            raise _input_error(
                f"section.{name}", _Described("(absent)"), f"a {name!r} attribute", "is missing"
            )
    ea = _number("section.EA", section.EA, positive=True)
    raw = section.EI
    if isinstance(raw, (tuple, list, np.ndarray)):
        if len(raw) != 2:
            raise _input_error("section.EI", raw, "a number or a pair (EI2, EI3)", "is not a pair")
        ei2 = _number("section.EI", raw[0], positive=True)
        ei3 = _number("section.EI", raw[1], positive=True)
    else:
        ei2 = ei3 = _number("section.EI", raw, positive=True)
    diameter = _number("section.outer_diameter", section.outer_diameter, minimum=0.0)
    return ea, ei2, ei3, diameter
