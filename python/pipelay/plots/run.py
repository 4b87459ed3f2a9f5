"""The figures of any run: the pipe's shape, the vessel's motion, the top tension, tension and bending along the
pipe, the energy balance; and `all_figures`, which writes every figure that applies to a run.

Imports of pipelay: the engine (`pipelay._core`), `pipelay.analysis.extremes` (`top_tension`),
`pipelay.plots.canvas`, `pipelay.plots.lay` and `pipelay.plots.stages`.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure

from pipelay._core import Results, State
from pipelay.analysis import extremes
from pipelay.plots.canvas import (
    _End,
    _figure,
    _finish,
    _PathLike,
    _records,
    _RouteLike,
    _style,
    _time_label,
)
from pipelay.plots.lay import lay_accuracy, lay_summary, touchdown_path, touchdown_track
from pipelay.plots.stages import stage_configurations, stage_tensions

__all__ = ["all_figures", "energy", "shape", "tension_and_bending", "top_tension", "vessel_motion"]


def _end_force(results: Results, end: _End) -> tuple[npt.NDArray[np.float64], str]:
    """Force (T, 3) (N, in e) of the pipe on what holds `end` (its reaction), and what that is: "vessel" when
    the end node sits at the vessel's origin η[:3], else "support"."""
    if end not in ("A", "B"):
        raise ValueError(f"end must be 'A' (node 0, seabed end) or 'B' (node n, top end), got {end!r}")
    eta = results.eta
    node = results.positions[:, 0] if end == "A" else _last_nodes(results.positions)
    holder = "vessel" if eta is not None and np.allclose(node, eta[:, :3], atol=1e-6) else "support"
    return results.reaction(end)[:, :3], holder


def _last_nodes(positions: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """The position of end B in each record (T, 3): the last node that is not NaN padding (a record of a run
    with pay-out has as many nodes as its mesh had then)."""
    finite = np.all(np.isfinite(positions), axis=2)
    last = positions.shape[1] - 1 - np.argmax(finite[:, ::-1], axis=1)
    return positions[np.arange(len(positions)), last]


def shape(
    results: Results,
    times: Sequence[float] | None = None,
    path: _PathLike | None = None,
    depth: float | None = None,
) -> Figure:
    """Side view (x against elevation −z) and plan view (x against y) of the pipe at chosen times.

    Args:
        results: a run.
        times: times (s); each shows the nearest record, labelled with that record's time. None: the first,
            middle and last records.
        path: where to save the figure, if anywhere.
        depth: water depth (m); when given, the side view shows the sea surface (−z = depth) and the seabed
            (z = 0).

    Returns:
        The figure, two axes: side view, plan view (m).
    """
    figure, axes = _figure(11.0, 4.5, 1, 2)
    side, plan = axes
    time = results.time
    positions = results.positions
    touchdown = results.touchdown
    for j, k in enumerate(_records(time, times)):
        p = positions[k]
        lines = side.plot(p[:, 0], -p[:, 2], label=_time_label(time[k]), **_style(j))
        plan.plot(p[:, 0], p[:, 1], label=_time_label(time[k]), **_style(j))
        if touchdown is not None and np.all(np.isfinite(touchdown[k])):
            td = touchdown[k]
            color = lines[0].get_color()
            side.plot(td[0], -td[2], marker="v", markersize=9, color=color, linestyle="none")
            plan.plot(td[0], td[1], marker="v", markersize=9, color=color, linestyle="none")
    if depth is not None:
        side.axhline(depth, color="tab:cyan", linewidth=1.5, label=f"sea surface (−z = {depth:g} m)")
        side.axhline(0.0, color="saddlebrown", linewidth=1.5, label="seabed (z = 0)")
    side.set_xlabel("x (m)")
    side.set_ylabel("elevation above seabed −z (m)")
    side.set_title("Side view (▼ touchdown)" if touchdown is not None else "Side view")
    plan.set_xlabel("x (m)")
    plan.set_ylabel("y (m)")
    plan.set_title("Plan view (y axis scaled to fit)")
    side.legend(fontsize=8, loc="best")
    plan.legend(fontsize=8, loc="best")
    figure.suptitle("Pipe shape")
    return _finish(figure, axes, path)


def vessel_motion(
    results: Results, reference: npt.ArrayLike | None = None, path: _PathLike | None = None
) -> Figure:
    """The vessel pose η(t) in six panels: x, y, z (m) on the left, φ, θ, ψ (degrees) on the right.

    Args:
        results: a run with a vessel.
        reference: the DP set-point η_ref (6,) or (T, 6) in m and rad, in e as η is, drawn dotted and labelled
            "η_ref (DP set-point)"; NaN entries are not drawn: give NaN for the degrees of freedom the
            controller leaves free (K_p = 0), whose set-point is not a place the vessel is held at.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, six axes, row by row: x, φ; y, θ; z, ψ.

    Raises:
        ValueError: the results have no vessel, or `reference` has the wrong shape.
    """
    eta = results.eta
    if eta is None:
        raise ValueError(
            "vessel_motion needs results of a model with a vessel (Model.attach_vessel); these have none"
        )
    time = results.time
    target = None
    if reference is not None:
        given = np.asarray(reference, dtype=float)
        if given.shape not in ((6,), eta.shape):
            raise ValueError(
                f"reference must be η_ref of shape (6,) or {eta.shape} (m and rad), got shape {given.shape}"
            )
        target = np.broadcast_to(given, eta.shape)
    labels = ("x (m)", "y (m)", "z (m, down positive)", "roll φ (deg)", "pitch θ (deg)", "yaw ψ (deg)")
    figure, axes = _figure(10.0, 8.0, 3, 2, sharex=True)
    for k, axis in enumerate(axes[0::2] + axes[1::2]):  # x, y, z down the left column, φ, θ, ψ the right
        scale = 1.0 if k < 3 else 180.0 / np.pi
        axis.plot(time, scale * eta[:, k], color="k", label="η")
        if target is not None and np.any(np.isfinite(target[:, k])):
            axis.plot(
                time,
                scale * target[:, k],
                color="tab:blue",
                linestyle=":",
                linewidth=2,
                label="η_ref (DP set-point)",
            )
            axis.legend(fontsize=8, loc="best")
        axis.set_ylabel(labels[k])
    for axis in axes[-2:]:
        axis.set_xlabel("time t (s)")
    figure.suptitle("Vessel motion η(t)")
    return _finish(figure, axes, path)


def top_tension(results: Results, end: _End = "B", path: _PathLike | None = None) -> Figure:
    """The top tension and the reaction at an end against time (kN).

    At end B the first curve is the top tension (`pipelay.analysis.statistics.top_tension`): the effective
    tension the tensioner, the tower or the support at the top holds, the axial force of the top element (the
    lay summary's ``top_tension`` with a vessel). Then the reaction at the end, `results.reaction(end)`: the
    force of the pipe on the vessel (at the end attached to one) or on the support, its magnitude |F| and its
    horizontal and vertical components. The reaction also carries the shear force, so |F_B| differs from the
    top tension. At end A only the reaction is drawn.

    Args:
        results: a run.
        end: "A" (node 0, seabed end) or "B" (node n, top end).
        path: where to save the figure, if anywhere.

    Returns:
        The figure, one axes.
    """
    force, holder = _end_force(results, end)
    time = results.time
    figure, axes = _figure(9.0, 4.5, 1, 1)
    (axis,) = axes
    if end == "B":
        axis.plot(
            time, extremes.top_tension(results) / 1e3, color="tab:blue", linewidth=2.5, label="top tension"
        )
    axis.plot(
        time,
        np.linalg.norm(force, axis=1) / 1e3,
        color="k",
        linewidth=1.2,
        label=f"reaction at {end} |F_{end}|",
    )
    axis.plot(time, np.hypot(force[:, 0], force[:, 1]) / 1e3, "--", label="its horizontal part |(F₁, F₂)|")
    axis.plot(time, force[:, 2] / 1e3, "-.", label="its vertical part F₃ (down positive)")
    axis.set_xlabel("time t (s)")
    axis.set_ylabel("force (kN)")
    reaction = f"the pipe's force on the {holder} at end {end}"
    axis.set_title(f"Top tension and reaction ({reaction})" if end == "B" else f"Reaction: {reaction}")
    axis.legend(fontsize=8, loc="best")
    return _finish(figure, axes, path)


def tension_and_bending(
    results_or_state: Results | State, times: Sequence[float] | None = None, path: _PathLike | None = None
) -> Figure:
    """Tension N₁ (kN) and bending moment |(M₂, M₃)| (kN·m) along the pipe, at element midpoints.

    The arc length s of the midpoints (m, from end A) is measured along the pipe's positions at each time.

    Args:
        results_or_state: a State, or a run.
        times: for a run, times (s); each shows the nearest record, labelled with that record's time. None:
            the first, middle and last records. Must be None for a State.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, two axes: tension, bending moment.
    """
    if isinstance(results_or_state, State):
        if times is not None:
            raise ValueError("times selects records of a Results; a State has a single time: give times=None")
        curves = [
            (_time_label(results_or_state.time), results_or_state.positions, results_or_state.section_forces)
        ]
    else:
        time = results_or_state.time
        positions = results_or_state.positions
        forces = results_or_state.section_forces
        curves = [(_time_label(time[k]), positions[k], forces[k]) for k in _records(time, times)]
    figure, axes = _figure(9.0, 7.0, 2, 1, sharex=True)
    tension, bending = axes
    for j, (label, p, f) in enumerate(curves):
        segment = np.linalg.norm(np.diff(p, axis=0), axis=1)
        s = np.cumsum(segment) - 0.5 * segment
        tension.plot(s, f[:, 0] / 1e3, label=label, **_style(j))
        bending.plot(s, np.hypot(f[:, 4], f[:, 5]) / 1e3, label=label, **_style(j))
    tension.axhline(0.0, color="0.5", linewidth=0.8)
    tension.set_ylabel("tension N₁ (kN)")
    tension.set_title("Tension (negative: compression)")
    bending.set_ylabel("bending moment |(M₂, M₃)| (kN·m)")
    bending.set_title("Bending moment")
    bending.set_xlabel("arc length s from end A (m)")
    for axis in (tension, bending):
        axis.legend(fontsize=8, loc="best")
    return _finish(figure, axes, path)


def energy(results: Results, path: _PathLike | None = None) -> Figure:
    """The energy balance against time.

    Top: the changes of the energy parts and of the total since the start, the supplied work W and the
    dissipation D, in kJ, or in MJ when any reaches 1 MJ. Bottom: the balance residual E − E(0) − (W − D) (J),
    round-off for pipelay's energy-consistent integrator.

    Args:
        results: a run; the vessel's parts are shown when it has a vessel.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, two axes: energies, residual.
    """
    time = results.time
    parts = results.energy
    work = results.supplied_work
    dissipated = results.dissipated
    names = {"pipe_kinetic": "pipe kinetic", "pipe_strain": "pipe strain", "pipe_gravity": "pipe gravity"}
    if results.eta is not None:
        names |= {"vessel_kinetic": "vessel kinetic", "vessel_potential": "vessel potential"}
    if results.touchdown is not None:
        names |= {"seabed": "seabed contact"}
    change = parts["total"] - parts["total"][0]
    curves = {f"Δ {label}": parts[key] - parts[key][0] for key, label in names.items()}
    largest = max(np.max(np.abs(c)) for c in (change, work, dissipated, *curves.values()))
    scale, unit = (1e6, "MJ") if largest >= 1e6 else (1e3, "kJ")
    balance = change - (work - dissipated)

    figure, axes = _figure(9.0, 7.0, 2, 1, sharex=True)
    top, bottom = axes
    top.plot(time, change / scale, color="0.6", linewidth=4.0, label="Δ total E − E(0)")
    for label, curve in curves.items():
        top.plot(time, curve / scale, label=label)
    top.plot(time, work / scale, "k--", label="supplied work W")
    top.plot(time, dissipated / scale, "k:", label="dissipated D")
    top.set_ylabel(f"energy ({unit})")
    top.set_title("Energy: changes since the start, supplied work and dissipation")
    top.legend(fontsize=8, loc="best")
    bottom.plot(time, balance, color="tab:red")
    bottom.set_xlabel("time t (s)")
    bottom.set_ylabel("E − E(0) − (W − D) (J)")
    bottom.set_title(f"Balance residual (largest |·| {np.max(np.abs(balance)):.2e} J)")
    return _finish(figure, axes, path)


def _pays_out(results: Results) -> bool:
    """Whether the run paid pipe out or in (its unstretched length changed)."""
    length = getattr(results, "length", None)
    return length is not None and len(length) > 0 and bool(np.ptp(length) > 0.0)


def all_figures(
    results: Results,
    directory: _PathLike,
    reference: npt.ArrayLike | None = None,
    depth: float | None = None,
    route: _RouteLike | None = None,
) -> list[Path]:
    """Write every figure that applies to `results` into `directory` (created if missing).

    Files: shape.png, vessel_motion.png (only with a vessel), touchdown.png (only with a seabed),
    touchdown_track.png and lay_accuracy.png (only with pay-out, a vessel and a seabed), top_tension.png
    (end B), lay_summary.png (only with lay equipment's rollers), tension_bending.png, energy.png, with the
    default times, and stage_tensions.png and stage_configurations.png (only for a run through pl.Stages).

    Args:
        results: a run.
        directory: the output folder.
        reference: η_ref for `vessel_motion` (m, rad; NaN entries not drawn); unused without a vessel.
        depth: water depth (m) for the sea surface and seabed lines of `shape` and `stage_configurations`.
        route: the lay route for the pay-out figures, a pl.Route or ((x, y), heading) (m, rad); None: the line
            through the vessel's first position along its first heading.

    Returns:
        The paths written, in the order above.
    """
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    written = [out / "shape.png"]
    shape(results, path=written[-1], depth=depth)
    if results.eta is not None:
        written.append(out / "vessel_motion.png")
        vessel_motion(results, reference=reference, path=written[-1])
    if results.touchdown is not None:
        written.append(out / "touchdown.png")
        touchdown_path(results, path=written[-1])
        if results.eta is not None and _pays_out(results):
            written.append(out / "touchdown_track.png")
            touchdown_track(results, route=route, path=written[-1])
            written.append(out / "lay_accuracy.png")
            lay_accuracy(results, route=route, path=written[-1])
    written.append(out / "top_tension.png")
    top_tension(results, path=written[-1])
    if results.lay_summary() is not None and results.roller_reactions is not None:
        written.append(out / "lay_summary.png")
        lay_summary(results, path=written[-1])
    written.append(out / "tension_bending.png")
    tension_and_bending(results, path=written[-1])
    written.append(out / "energy.png")
    energy(results, path=written[-1])
    if results.stage is not None:
        written.append(out / "stage_tensions.png")
        stage_tensions(results, path=written[-1])
        written.append(out / "stage_configurations.png")
        stage_configurations(results, path=written[-1], depth=depth)
    return written
