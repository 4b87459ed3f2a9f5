"""What each stage of a lay did: the extremes users check per stage (``Results.stage_summary``), and the laydown
head's track.

A run through ``pl.Stages`` marks each record with its stage (``results.stage``: the stage whose steps end
there). The summary takes, per stage, the extremes of the top tension (at the tensioner or the winch), of the
A&R wire's tension, of the pipe's axial force and strain, of the DNV-ST-F101 utilisation (with ``checks``),
of the touchdown's arc length, of the roller loads and the stinger's tip clearance, and the laydown head's position (the node where the
wire meets the pipe) and its height above the seabed.

Units: N, m, s; strains and utilisations are dimensionless.

Imports of pipelay: the engine (`pipelay._core`) and `pipelay.analysis.extremes`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from pipelay._core import InputError, Model, Results
from pipelay.analysis.extremes import top_elements, utilisation

__all__ = ["head_positions", "stage_summary", "staged", "wire_elements", "wire_segments"]

FloatArray = npt.NDArray[np.float64]


def staged(results: Results, caller: str) -> tuple[npt.NDArray[np.int64], list[str], npt.NDArray[np.float64]]:
    """The stage of each record (T,), the stages' names and their starts with the last one's end (s), of a run
    through ``pl.Stages``.

    Raises:
        pipelay.InputError: naming `results` (and `caller`, what needs them), for a run without stages.
    """
    stage, names, starts = results.stage, results.stage_names, results.stage_starts
    if stage is None or names is None or starts is None:
        raise InputError(f"results: results of a run through pl.Stages ({caller}), got a run without stages")
    return np.asarray(stage, dtype=np.int64), list(names), np.asarray(starts, dtype=np.float64)


def wire_segments(results: Results, model: Model | None = None) -> set[int]:
    """The segments of `results` that are cables: those of `model`'s sections that are (the A&R wire among
    them: ``attach_vessel(winch=)`` adds its section); without a model, the segment of the top element at the
    last record if it differs from that at the first (the wire a hand-over joined), else none."""
    if model is not None:
        return {k for k, section in enumerate(model.rod.sections) if section.is_cable}
    segment = results.segment[[0, -1]]
    first, last = segment[[0, 1], top_elements(segment)].astype(int)
    return {int(last)} if last != first else set()


def wire_elements(results: Results, model: Model | None = None) -> npt.NDArray[np.bool_]:
    """Which elements of each record (T, n) are the wire's (see `wire_segments`; False on NaN padding)."""
    segment = results.segment
    return np.isin(segment, list(wire_segments(results, model))) & np.isfinite(segment)


def head_positions(results: Results, model: Model | None = None) -> FloatArray:
    """The laydown head's position in each record (T, 3) (m, in e): the first node of the trailing run of wire
    elements (see `wire_segments`); NaN rows where the line has no wire at its top."""
    is_wire = wire_elements(results, model)
    positions = results.positions
    heads = np.full((len(is_wire), 3), np.nan)
    for k, top in enumerate(top_elements(results.segment)):
        wire = is_wire[k, : top + 1]
        if not wire[top]:
            continue
        run = int(np.argmax(~wire[::-1])) if not wire.all() else top + 1
        node = top + 1 - run
        if node > 0:
            heads[k] = positions[k, node]
    return heads


def stage_summary(
    results: Results,
    model: Model | None = None,
    checks: Mapping[str, Any] | None = None,
) -> Any:
    """Per stage of a staged run, the extremes users check, as a ``pandas.DataFrame`` (one row per stage, in
    order; columns below, NaN where a stage has no such value).

    Columns: ``name``; ``start``, ``end`` (s); ``top_tension_max``, ``top_tension_min`` (N, at the hold:
    tensioner, tower or winch); ``wire_tension_max``, ``wire_tension_min`` (N, over the wire's elements);
    ``pipe_force_min`` (N, the pipe's smallest axial force: negative is compression); ``strain_max`` (the
    largest of the lay summary's overbend and sagbend strains); ``utilisation_max`` (DNV-ST-F101, with
    `checks`); ``touchdown_min``, ``touchdown_max`` (m, touchdown's arc length from end A);
    ``roller_reaction_max`` (N); ``tip_clearance_min`` (m, the least gap between the line and the stinger's
    last roller, ≤ 0 in contact); ``head_x``, ``head_z`` (m, the head at the stage's end); ``head_height_min``
    (m, the head's least height above the plane of end A's seabed, z = 0).

    Args:
        results: a run through ``pl.Stages``.
        model: the model run (its sections tell the wire from the pipe, and its pipe section serves the
            checks); without it the wire is found as ``wire_segments`` says.
        checks: keyword arguments of ``pipelay.checks.dnv_st_f101`` (e.g. ``{"grade": "X65"}``) evaluated at
            every record on the pipe's elements (needs `model`); None: no utilisation column.

    Raises:
        pipelay.InputError: for results of a run without stages, or `checks` without a model.
    """
    import pandas as pd

    stage, names, starts = staged(results, "stage_summary")
    forces = results.section_forces[:, :, 0]
    is_wire = wire_elements(results, model)
    is_pipe = ~is_wire & np.isfinite(results.segment)
    lay = results.lay_summary() or {}
    top = lay.get("top_tension", np.full(len(stage), np.nan))
    strain = np.fmax(lay.get("overbend_strain", np.nan), lay.get("sagbend_strain", np.nan))
    clearance = lay.get("tip_clearance", np.full(len(stage), np.nan))
    touchdown = results.touchdown_arc_length
    rollers = results.roller_reactions
    heads = head_positions(results, model)
    utilisation = _pipe_utilisation(results, model, checks, is_pipe) if checks is not None else None
    rows = []
    for k, name in enumerate(names):
        records = np.flatnonzero(stage == k)
        row: dict[str, Any] = {"name": name, "start": float(starts[k]), "end": float(starts[k + 1])}
        row["top_tension_max"] = _extreme(top[records], np.nanmax)
        row["top_tension_min"] = _extreme(top[records], np.nanmin)
        row["wire_tension_max"] = _extreme(np.where(is_wire, forces, np.nan)[records], np.nanmax)
        row["wire_tension_min"] = _extreme(np.where(is_wire, forces, np.nan)[records], np.nanmin)
        row["pipe_force_min"] = _extreme(np.where(is_pipe, forces, np.nan)[records], np.nanmin)
        row["strain_max"] = _extreme(np.asarray(strain)[records], np.nanmax)
        if utilisation is not None:
            row["utilisation_max"] = _extreme(utilisation[records], np.nanmax)
        row["touchdown_min"] = _extreme(touchdown[records], np.nanmin) if touchdown is not None else np.nan
        row["touchdown_max"] = _extreme(touchdown[records], np.nanmax) if touchdown is not None else np.nan
        row["roller_reaction_max"] = _extreme(rollers[records], np.nanmax) if rollers is not None else np.nan
        row["tip_clearance_min"] = _extreme(np.asarray(clearance)[records], np.nanmin)
        last = records[-1] if len(records) else None
        row["head_x"] = float(heads[last, 0]) if last is not None else np.nan
        row["head_z"] = float(heads[last, 2]) if last is not None else np.nan
        row["head_height_min"] = _extreme(-heads[records, 2], np.nanmin)
        rows.append(row)
    return pd.DataFrame(rows)


def _extreme(values: FloatArray, reduce: Any) -> float:
    """`reduce` (np.nanmax or np.nanmin) of `values`, NaN when there is no finite value."""
    values = np.asarray(values, dtype=np.float64)
    if values.size == 0 or not np.isfinite(values).any():
        return float("nan")
    return float(reduce(values))


def _pipe_utilisation(
    results: Results, model: Model | None, checks: Mapping[str, Any], is_pipe: npt.NDArray[np.bool_]
) -> FloatArray:
    """The DNV-ST-F101 utilisation of the pipe's elements at every record (T, n), NaN on the wire's."""

    if model is None:
        raise InputError("model: the model run, for the checks of stage_summary (its pipe section), got None")
    pipes = [section for section in model.rod.sections if not section.is_cable]
    if not pipes:
        raise InputError("model: a model with a pipe section to check, got one of cables only")
    values = utilisation(results, section=pipes[0], sea=model.sea, checks=checks)
    return np.where(is_pipe, values, np.nan)


def _attach() -> None:
    """Makes `stage_summary` a method of the engine's Results: ``Results.stage_summary``."""

    def results_stage_summary(
        self: Results, model: Model | None = None, checks: Mapping[str, Any] | None = None
    ) -> Any:
        """Per stage, the extremes of tensions, strain, utilisation, touchdown, roller loads and the head's
        position (a pandas.DataFrame): see pipelay.analysis.stages.stage_summary."""
        return stage_summary(self, model, checks)

    Results.stage_summary = results_stage_summary  # type: ignore[attr-defined]


_attach()
