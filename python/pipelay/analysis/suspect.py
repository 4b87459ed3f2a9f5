"""Warnings for a solution that solved but whose physics is suspect.

A `PhysicsWarning` (a `UserWarning`) names where and how much:

* the pipe in compression at the hold point (the lay summary's top tension below zero): a pipe cannot be laid
  pushed, and the equilibrium found may be a buckled one; for a section given by its stiffnesses that is
  stiffer in bending than a solid steel bar of its diameter (the paper's EI = 1e11 N·m²), the warning says so;
* a strain beyond the steel's yield strain SMYS/E (of the section's grade, X65 where it has none): the rod is
  linear elastic, so its stresses there are not real (sections without a steel wall are not checked);
* the vessel heeled (roll) or trimmed (pitch) beyond 10°, outside the small-angle hydrostatics of its model;
* the A&R wire's tension at the winch beyond the winch's `tension_limit` (the winch does not render: the run
  goes on at its speed).

`Model.static` checks the state it returns, `Simulation.run` the records of its run.
"""

from __future__ import annotations

import contextlib
import math
import warnings
from collections.abc import Iterator
from typing import Any

import numpy as np

from pipelay.analysis.checks import DEFAULT_GRADE, DEFAULT_YOUNGS_MODULUS, GRADES
from pipelay.analysis.extremes import top_elements

__all__ = [
    "HEEL_LIMIT",
    "PhysicsWarning",
    "suspect_results",
    "suspect_state",
    "suspect_winch",
    "warn",
    "worst_of_each_kind",
]

HEEL_LIMIT = math.radians(10.0)
"""Largest roll or pitch of the vessel (rad) within its model's small-angle hydrostatics."""


class PhysicsWarning(UserWarning):
    """A solution whose physics is suspect: compression at the hold point, strain beyond yield, large heel.

    `kind` is what is suspect ("compression", "strain", "heel", "trim" or "winch") and `size` how much (N of
    compression, strain, rad), so that a caller can keep the worst of each kind."""

    def __init__(self, message: str, kind: str = "", size: float = 0.0) -> None:
        super().__init__(message)
        self.kind = kind
        self.size = size


Suspect = tuple[str, float, str]
"""What is suspect: its kind, its size and the message."""


def _yield_strain(section: Any) -> tuple[float, str] | None:
    """SMYS/E of the section's steel and its grade; None for a section without a steel wall, or whose wall's
    material yields (its stresses beyond yield are computed)."""
    if section.wall_thickness is None:
        return None
    material = getattr(section, "material", None)
    if material is not None and material.kind != "elastic":
        return None
    grade = section.grade or DEFAULT_GRADE
    return GRADES[grade][0] / section.youngs_modulus, grade


def _messages(
    top_tension: np.ndarray | None,
    strain: tuple[float, str] | None,
    eta: np.ndarray | None,
    section: Any,
    time: np.ndarray | None,
) -> list[Suspect]:
    """What is suspect: the top tension (N) and the vessel's pose η over records (first axis; one record for
    a state), and the largest strain with where it is."""

    def when(record: int) -> str:
        return "" if time is None else f" at t = {time[record]:.6g} s"

    messages: list[Suspect] = []
    # Compression beyond the round-off of the axial force (about 1e-13 EA per element).
    if top_tension is not None and np.nanmin(top_tension) < -1e-9 * section.EA:
        record = int(np.nanargmin(top_tension))
        message = (
            f"the pipe is in compression at the hold point{when(record)}: top tension "
            f"{top_tension[record] / 1e3:.4g} kN{_stiffness_note(section)}"
        )
        messages.append(("compression", float(-top_tension[record]), message))
    limit = _yield_strain(section)
    if limit is not None and strain is not None and strain[0] > limit[0]:
        message = (
            f"strain {100 * strain[0]:.3g} % {strain[1]} exceeds the yield strain {100 * limit[0]:.3g} % of "
            f"{limit[1]}: the pipe model is linear elastic, so its stresses beyond yield are not real"
        )
        messages.append(("strain", strain[0], message))
    if eta is not None:
        for index, kind, name in ((3, "heel", "heels (roll)"), (4, "trim", "trims (pitch)")):
            angle = np.abs(eta[:, index])
            record = int(np.nanargmax(angle))
            if angle[record] > HEEL_LIMIT:
                message = (
                    f"the vessel {name} {math.degrees(angle[record]):.1f}°{when(record)}, beyond "
                    f"{math.degrees(HEEL_LIMIT):.0f}° (its hydrostatics are linear in small angles)"
                )
                messages.append((kind, float(angle[record]), message))
    return messages


def _stiffness_note(section: Any) -> str:
    """For a section given by its stiffnesses whose bending stiffness exceeds that of a solid steel bar of its
    outer diameter, E π D⁴/64 (E = 207 GPa): what that does to the line (the paper's EI = 1e11 N·m² is 76 times
    a solid 0.6 m bar's); else nothing."""
    if section.youngs_modulus is not None or not section.outer_diameter > 0.0:
        return ""
    bending = max(section.EI)
    bar = DEFAULT_YOUNGS_MODULUS * math.pi * section.outer_diameter**4 / 64.0
    if bending <= bar:
        return ""
    return (
        f"; its bending stiffness EI = {bending:.3g} N·m² is {bending / bar:.0f} times a solid steel bar's of its "
        f"{section.outer_diameter:g} m diameter ({bar:.3g} N·m²): a line that stiff hangs as a beam and pushes "
        "on the vessel where a pipe would pull"
    )


def _element_strain(state: Any, at: str = "") -> tuple[float, str] | None:
    """The largest |strain| of a state's elements, with the element and its distance from end A (m)."""
    strain = np.abs(np.asarray(state.strain))
    if not strain.size:
        return None
    element = int(np.nanargmax(strain))
    arcs = np.asarray(state.reference_arc_length)
    middle = 0.5 * (arcs[element] + arcs[element + 1])
    return float(strain[element]), f"in element {element} ({middle:.1f} m from end A){at}"


def suspect_state(state: Any) -> list[Suspect]:
    """What is suspect in a `pl.State` (empty if nothing is)."""
    summary = state.lay_summary()
    eta = state.eta
    return _messages(
        None if summary is None else np.array([summary["top_tension"]]),
        _element_strain(state),
        None if eta is None else np.asarray(eta)[np.newaxis],
        state.section,
        None,
    )


def suspect_results(results: Any, final: Any) -> list[Suspect]:
    """What is suspect in the records of a run that ended in the `pl.State` `final` (empty if nothing is). The strain is the larger of the final state's, over every element, and, with a vessel, the
    recorded overbend and sagbend strains: the records' whole strain field is not read (it can be larger than
    the memory)."""
    summary = results.lay_summary()
    time = np.asarray(results.time)
    candidates = [_element_strain(final, f" at t = {final.time:.6g} s")]
    if summary is not None:
        for region in ("overbend", "sagbend"):
            series = np.abs(np.asarray(summary[f"{region}_strain"]))
            if series.size and not np.all(np.isnan(series)):
                record = int(np.nanargmax(series))
                candidates.append((float(series[record]), f"in the {region} at t = {time[record]:.6g} s"))
    strain = max((c for c in candidates if c is not None), default=None, key=lambda c: c[0])
    return _messages(
        None if summary is None else np.asarray(summary["top_tension"]),
        strain,
        None if results.eta is None else np.asarray(results.eta),
        final.section,
        time,
    )


def suspect_winch(results: Any, limit: float | None, wire: int | None) -> list[Suspect]:
    """The A&R wire's tension at the winch beyond its `limit` (N) in the records where the wire (segment `wire`)
    is the line's top: the worst of them (empty if none, or without a limit)."""
    summary = results.lay_summary()
    if limit is None or wire is None or summary is None:
        return []
    segment = np.asarray(results.segment)
    held = segment[np.arange(len(segment)), top_elements(segment)] == wire
    tension = np.where(held, np.asarray(summary["top_tension"]), -np.inf)
    record = int(np.argmax(tension))
    if tension[record] <= limit:
        return []
    time = float(np.asarray(results.time)[record])
    message = (
        f"the A&R wire's tension {tension[record] / 1e3:.1f} kN at t = {time:.6g} s exceeds the winch's "
        f"tension_limit {limit / 1e3:.1f} kN: the winch does not render, the run went on at its speed"
    )
    return [("winch", float(tension[record] - limit), message)]


def warn(suspects: list[Suspect], stacklevel: int = 3) -> None:
    """Each suspect as a `PhysicsWarning`, attributed `stacklevel` frames up (the user's call)."""
    for kind, size, message in suspects:
        warnings.warn(PhysicsWarning(message, kind, size), stacklevel=stacklevel)


@contextlib.contextmanager
def worst_of_each_kind() -> Iterator[dict[str, PhysicsWarning]]:
    """Collects the `PhysicsWarning`s raised inside, keeping the worst of each kind (a long run, streamed in
    segments, raises one per segment), into the dict it yields; other warnings pass on."""
    worst: dict[str, PhysicsWarning] = {}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", PhysicsWarning)
        yield worst
    for warning in caught:
        found = warning.message
        if isinstance(found, PhysicsWarning):
            if found.kind not in worst or found.size > worst[found.kind].size:
                worst[found.kind] = found
        else:
            warnings.warn_explicit(found, warning.category, warning.filename, warning.lineno)
