"""Figures of a pipelay run: pipe shapes, vessel motion, top tension, tension and bending along the pipe, the
energy balance, and for a lay with pay-out the touchdown's track, the laid pipe's deviation from the route and
the top tension of several runs.

Every function returns a :class:`matplotlib.figure.Figure` drawn on its own Agg canvas (pyplot is not used, so
neither the user's backend nor pyplot's list of open figures is touched) and, when ``path`` is given, also
saves it there (PNG at 120 dpi; another suffix such as ``.pdf`` selects that format).

Frame e has e3 pointing down: elevations are plotted as −z (m above the seabed end, z = 0), and the sea
surface, the plane z = −depth, is at elevation depth.

Usage::

    from pipelay import plots

    plots.shape(results, times=(0.0, 30.0, 200.0), depth=800.0, path="shape.png")
    plots.all_figures(results, "figures", depth=800.0)
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Literal

import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from pipelay._core import Results, Route, State

__all__ = [
    "all_figures",
    "energy",
    "lay_accuracy",
    "lay_configuration",
    "lay_deviation",
    "lay_summary",
    "operability",
    "shape",
    "tension_and_bending",
    "tension_comparison",
    "top_tension",
    "touchdown_path",
    "touchdown_track",
    "vessel_motion",
]

DPI = 120
"""Resolution of saved figures (dots per inch)."""

_LINESTYLES = ("-", "--", "-.", ":")
_PathLike = str | os.PathLike[str]
_End = Literal["A", "B"]
_RouteLike = Route | tuple[Sequence[float], float]
"""A lay route: a pl.Route, or its line as ((x, y), heading) (m, rad)."""


def _figure(
    width: float, height: float, rows: int, columns: int, sharex: bool = False
) -> tuple[Figure, list[Axes]]:
    """A figure of width × height (inches) on an Agg canvas with a rows × columns grid of axes, listed row
    by row."""
    figure = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(figure)
    axes: list[Axes] = figure.subplots(rows, columns, sharex=sharex, squeeze=False).ravel().tolist()
    return figure, axes


def _finish(figure: Figure, axes: list[Axes], path: _PathLike | None) -> Figure:
    """Grid and ×10ⁿ tick labels for large or small values on every axes; save to `path` (PNG at DPI unless
    its suffix says otherwise) when given."""
    for axis in axes:
        axis.grid(alpha=0.3)
        axis.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4), useMathText=True)
    if path is not None:
        figure.savefig(path, dpi=DPI)
    return figure


def _records(time: npt.NDArray[np.float64], times: Sequence[float] | None) -> list[int]:
    """Indices of the records nearest to `times` (s), in order and without repeats.

    None selects the first, middle and last records."""
    if times is None:
        wanted = [0, (len(time) - 1) // 2, len(time) - 1]
    elif len(times) == 0:
        raise ValueError("times is empty: give at least one time (s), or None for the first, middle and last")
    else:
        wanted = [int(np.argmin(np.abs(time - t))) for t in times]
    return list(dict.fromkeys(wanted))


def _time_label(t: float) -> str:
    """Legend text of a record's time t (s)."""
    return f"t = {t:g} s"


def _style(j: int) -> dict[str, Any]:
    """Line style of the j-th curve of a set of times: a line style cycle, with dots at the data points."""
    return {"linestyle": _LINESTYLES[j % len(_LINESTYLES)], "marker": ".", "markersize": 4.0}


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


def _pays_out(results: Results) -> bool:
    """Whether the run paid pipe out or in (its unstretched length changed)."""
    length = getattr(results, "length", None)
    return length is not None and len(length) > 0 and bool(np.ptp(length) > 0.0)


def _route_line(
    results: Results, route: _RouteLike | None
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], str]:
    """The route's start (2,), its unit direction (2,) and a legend label. None: the vessel's first position
    and heading."""
    if isinstance(route, Route):
        pose, _ = route.at(-1e30)  # before its start time a route waits at its start
        origin, heading, label = np.asarray(pose[:2], dtype=float), float(pose[5]), "route"
    elif route is not None:
        start, heading = route
        origin, heading, label = np.asarray(start, dtype=float), float(heading), "route"
        if origin.shape != (2,) or not np.all(np.isfinite(origin)) or not np.isfinite(heading):
            raise ValueError(f"route must be a pl.Route or ((x, y), heading) in m and rad, got {route!r}")
    else:
        eta = results.eta
        if eta is None:
            raise ValueError("without a vessel the route must be given: a pl.Route or ((x, y), heading)")
        origin, heading, label = eta[0, :2].copy(), float(eta[0, 5]), "route (the vessel's starting heading)"
    return origin, np.array([np.cos(heading), np.sin(heading)]), label


def _along_across(
    points: npt.NDArray[np.float64], origin: npt.NDArray[np.float64], direction: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Distance along the route's line from `origin` and signed lateral offset of points (..., ≥ 2) (m), positive
    to starboard: along b2 = (−sin ψ, cos ψ) of a vessel on the route's heading ψ (e3 points down)."""
    offset = points[..., :2] - origin
    return offset @ direction, offset @ np.array([-direction[1], direction[0]])


def lay_deviation(
    results: Results, route: _RouteLike | None = None, record: int = -1
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Where the laid pipe lies relative to the route: the distance along the route from its start (m) and the
    lateral deviation from it (m, positive to starboard, the right of the route's heading) of each node on the
    seabed, from end A to the touchdown, in one record.

    A node is laid when its arc length from end A (measured along the record's positions) is at most the
    touchdown's arc length from A.

    Args:
        results: a run of a model with a seabed.
        route: the lay route, a pl.Route or ((x, y), heading) (m, rad); None: the line through the vessel's
            first position along its first heading.
        record: which record (an index into results.time; −1: the last).

    Returns:
        Two arrays (k,), empty when the pipe does not touch the seabed in that record.

    Raises:
        ValueError: the results have no seabed, or no vessel and no route is given.
    """
    arc = results.touchdown_arc_length
    if arc is None:
        raise ValueError("lay_deviation needs results of a model with a seabed (pl.Sea(seabed=...))")
    origin, direction, _ = _route_line(results, route)
    p = results.positions[record]
    p = p[np.all(np.isfinite(p), axis=1)]
    reached = arc[record]
    if not np.isfinite(reached):
        return np.empty(0), np.empty(0)
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))))
    return _along_across(p[s <= reached + 1e-9], origin, direction)


def _top_tension_series(results: Results) -> npt.NDArray[np.float64]:
    """Top tension (T,) (N): the lay summary's with lay equipment or a vessel, else |force| at end B."""
    summary = results.lay_summary()
    if summary is not None:
        return np.asarray(summary["top_tension"], dtype=float)
    return np.linalg.norm(results.reaction("B")[:, :3], axis=1)


def _moving_average(
    time: npt.NDArray[np.float64], values: npt.NDArray[np.float64], window: float
) -> npt.NDArray[np.float64]:
    """The mean of `values` over the trailing `window` seconds at each time (NaN values left out)."""
    finite = np.isfinite(values)
    total = np.concatenate(([0.0], np.cumsum(np.where(finite, values, 0.0))))
    count = np.concatenate(([0], np.cumsum(finite)))
    first = np.searchsorted(time, time - window, side="left")
    last = np.arange(1, len(time) + 1)
    n = count[last] - count[first]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, (total[last] - total[first]) / np.maximum(n, 1), np.nan)


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
        reference: η_ref (6,) or (T, 6) in m and rad, drawn dotted; NaN entries are not drawn (give NaN for
            the degrees of freedom the controller leaves free).
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
            axis.plot(time, scale * target[:, k], color="tab:blue", linestyle=":", linewidth=2, label="η_ref")
            axis.legend(fontsize=8, loc="best")
        axis.set_ylabel(labels[k])
    for axis in axes[-2:]:
        axis.set_xlabel("time t (s)")
    figure.suptitle("Vessel motion η(t)")
    return _finish(figure, axes, path)


def top_tension(results: Results, end: _End = "B", path: _PathLike | None = None) -> Figure:
    """The force of the pipe at an end against time (kN): magnitude, horizontal and vertical components.

    At the end attached to a vessel this is the pipe's force on the vessel, elsewhere the reaction on the
    support (both `results.reaction(end)`).

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
    axis.plot(time, np.linalg.norm(force, axis=1) / 1e3, color="k", linewidth=2, label="magnitude |F|")
    axis.plot(time, np.hypot(force[:, 0], force[:, 1]) / 1e3, "--", label="horizontal |(F₁, F₂)|")
    axis.plot(time, force[:, 2] / 1e3, "-.", label="vertical F₃ (down positive)")
    axis.set_xlabel("time t (s)")
    axis.set_ylabel("force F (kN)")
    axis.set_title(f"Force of the pipe on the {holder} at end {end}")
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


def touchdown_path(results: Results, path: _PathLike | None = None) -> Figure:
    """The touchdown point over time: its arc length from end A (m) and its path in plan (x, y).

    Args:
        results: a run of a model with a seabed.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, two axes: arc length against time, plan view of the path.

    Raises:
        ValueError: the results have no seabed.
    """
    touchdown = results.touchdown
    arc = results.touchdown_arc_length
    if touchdown is None or arc is None:
        raise ValueError("touchdown_path needs results of a model with a seabed (pl.Sea(seabed=...))")
    figure, axes = _figure(11.0, 4.5, 1, 2)
    history, plan = axes
    history.plot(results.time, arc, color="k")
    history.set_xlabel("time t (s)")
    history.set_ylabel("touchdown arc length from A (m)")
    history.set_title("Touchdown along the pipe")
    plan.plot(touchdown[:, 0], touchdown[:, 1], color="k", marker=".", markersize=3)
    finite = np.isfinite(touchdown[:, 0])
    if np.any(finite):
        first, last = np.flatnonzero(finite)[[0, -1]]
        plan.plot(
            *touchdown[first, :2], marker="o", color="tab:green", label=_time_label(results.time[first])
        )
        plan.plot(*touchdown[last, :2], marker="s", color="tab:red", label=_time_label(results.time[last]))
        plan.legend(fontsize=8, loc="best")
    plan.set_xlabel("x (m)")
    plan.set_ylabel("y (m)")
    plan.set_title("Touchdown path (plan)")
    figure.suptitle("Touchdown point")
    return _finish(figure, axes, path)


def touchdown_track(
    results: Results, route: _RouteLike | None = None, path: _PathLike | None = None
) -> Figure:
    """The touchdown's track against the vessel's during a lay: plan view of both with the route, and how far
    each has advanced along the route over time (parallel lines in a steady lay, layback apart).

    Args:
        results: a run of a model with a vessel and a seabed.
        route: the lay route, a pl.Route or ((x, y), heading) (m, rad); None: the line through the vessel's
            first position along its first heading.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, two axes: plan view (x, y), advance along the route against time (m).

    Raises:
        ValueError: the results have no vessel or no seabed.
    """
    touchdown, eta = results.touchdown, results.eta
    if touchdown is None or eta is None:
        raise ValueError("touchdown_track needs results of a model with a vessel and a seabed")
    origin, direction, label = _route_line(results, route)
    time = results.time
    figure, axes = _figure(12.0, 4.8, 1, 2)
    plan, advance = axes
    ends = np.array([0.0, 1.0])
    reach = _along_across(
        np.vstack([eta[:, :2], touchdown[np.isfinite(touchdown[:, 0]), :2]]), origin, direction
    )
    span = np.array([reach[0].min(), reach[0].max()])
    line = origin + np.outer(span[0] + ends * (span[1] - span[0]), direction)
    plan.plot(line[:, 0], line[:, 1], color="0.5", linestyle=":", linewidth=2, label=label)
    plan.plot(eta[:, 0], eta[:, 1], color="tab:blue", label="vessel (CO)")
    plan.plot(touchdown[:, 0], touchdown[:, 1], color="k", label="touchdown")
    finite = np.flatnonzero(np.isfinite(touchdown[:, 0]))
    for k, marker, color in ((0, "o", "tab:green"), (-1, "s", "tab:red")):
        plan.plot(*eta[k, :2], marker=marker, color=color, linestyle="none")
        if len(finite):
            plan.plot(*touchdown[finite[k], :2], marker=marker, color=color, linestyle="none")
    plan.plot([], [], "o", color="tab:green", label=_time_label(time[0]))
    plan.plot([], [], "s", color="tab:red", label=_time_label(time[-1]))
    plan.set_xlabel("x (m)")
    plan.set_ylabel("y (m)")
    plan.set_title("Plan view (y axis scaled to fit)")
    plan.legend(fontsize=8, loc="best")
    vessel_along, _ = _along_across(eta[:, :2], origin, direction)
    touchdown_along, _ = _along_across(touchdown[:, :2], origin, direction)
    advance.plot(time, vessel_along - vessel_along[0], color="tab:blue", label="vessel")
    if len(finite):
        advance.plot(
            time, touchdown_along - touchdown_along[finite[0]], color="k", linestyle="--", label="touchdown"
        )
    advance.set_xlabel("time t (s)")
    advance.set_ylabel("advance along the route (m)")
    advance.set_title("Advance since the start")
    advance.legend(fontsize=8, loc="best")
    figure.suptitle("Touchdown and vessel tracks")
    return _finish(figure, axes, path)


def lay_accuracy(
    results: Results,
    route: _RouteLike | None = None,
    times: Sequence[float] | None = None,
    path: _PathLike | None = None,
) -> Figure:
    """Lay accuracy: the lateral deviation of the laid pipe's nodes from the route against the distance along
    it (see `lay_deviation`), with the stretch laid during the run marked.

    Args:
        results: a run of a model with a seabed (and a vessel, unless `route` is given).
        route: the lay route, a pl.Route or ((x, y), heading) (m, rad); None: the line through the vessel's
            first position along its first heading.
        times: times (s); each shows the nearest record. None: the last record.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, one axes (m).

    Raises:
        ValueError: the results have no seabed, or no vessel and no route is given.
    """
    if results.touchdown is None:
        raise ValueError("lay_accuracy needs results of a model with a seabed (pl.Sea(seabed=...))")
    time = results.time
    records = [len(time) - 1] if times is None else _records(time, times)
    origin, direction, label = _route_line(results, route)
    touchdown_along, touchdown_across = _along_across(results.touchdown, origin, direction)
    figure, axes = _figure(10.0, 4.5, 1, 1)
    (axis,) = axes
    axis.axhline(0.0, color="0.5", linestyle=":", linewidth=2, label=label)
    worst = 0.0
    for j, k in enumerate(records):
        along, across = lay_deviation(results, route, k)
        if len(across):
            worst = max(worst, float(np.max(np.abs(across))))
        lines = axis.plot(along, across, label=f"laid pipe, {_time_label(time[k])}", **_style(j))
        if np.isfinite(touchdown_along[k]):
            axis.plot(
                touchdown_along[k],
                touchdown_across[k],
                marker="v",
                markersize=9,
                color=lines[0].get_color(),
                linestyle="none",
            )
    finite = np.flatnonzero(np.isfinite(touchdown_along))
    if len(finite) and finite[-1] > finite[0]:
        first, last = touchdown_along[finite[0]], touchdown_along[finite[-1]]
        axis.axvspan(
            min(first, last), max(first, last), color="tab:orange", alpha=0.12, label="laid during the run"
        )
    axis.set_xlabel("distance along the route from its start (m)")
    axis.set_ylabel("lateral deviation from the route (m, + to starboard)")
    axis.set_title(f"Lay accuracy: largest deviation {worst:.2f} m (▼ touchdown)")
    axis.legend(fontsize=8, loc="best")
    return _finish(figure, axes, path)


def tension_comparison(
    runs: Mapping[str, Results],
    target: float | None = None,
    window: float = 20.0,
    path: _PathLike | None = None,
) -> Figure:
    """Top tension against time for several runs (e.g. with and without the lay-tension loop): each run's
    series thin and its trailing mean over `window` seconds thick.

    The top tension is the lay summary's (at the tensioner or tower) for a run with a vessel, else the force at
    end B.

    Args:
        runs: label → run, in legend order.
        target: a tension to mark (N), e.g. the loop's target.
        window: length of the trailing mean (s), > 0.
        path: where to save the figure, if anywhere.

    Returns:
        The figure, one axes (kN).
    """
    if not runs:
        raise ValueError("runs is empty: give at least one labelled run")
    if not window > 0.0:
        raise ValueError(f"window must be a length of time > 0 (s), got {window!r}")
    figure, axes = _figure(10.0, 4.8, 1, 1)
    (axis,) = axes
    for j, (name, results) in enumerate(runs.items()):
        tension = _top_tension_series(results) / 1e3
        color = f"C{j}"
        axis.plot(results.time, tension, color=color, linewidth=0.5, alpha=0.45)
        mean = _moving_average(results.time, tension, window)
        axis.plot(
            results.time,
            mean,
            color=color,
            linewidth=2.0,
            linestyle=_LINESTYLES[j % 4],
            label=f"{name} ({window:g} s mean)",
        )
    if target is not None:
        axis.axhline(
            target / 1e3, color="k", linestyle=":", linewidth=1.2, label=f"target {target / 1e3:g} kN"
        )
    axis.set_xlabel("time t (s)")
    axis.set_ylabel("top tension (kN)")
    axis.set_title("Top tension")
    axis.legend(fontsize=8, loc="best")
    return _finish(figure, axes, path)


def lay_configuration(state: State, path: _PathLike | None = None, **check: Any) -> Figure:
    """A lay configuration: the pipe on the stinger's rollers and down to the seabed (side view, whole and near
    the vessel), and the strain and DNV-ST-F101 utilisations along the pipe.

    Args:
        state: a static or simulated state of a model held by a vessel.
        path: where to save the figure, if anywhere.
        check: arguments of ``pl.checks.dnv_st_f101`` (e.g. grade="X65"); the utilisation panel is left out
            when the check cannot run (a section without a wall thickness).

    Returns:
        The figure: side view, detail at the vessel, strain, utilisation.
    """
    import pipelay as pl

    summary = state.lay_summary()
    if summary is None:
        raise ValueError("lay_configuration needs a state of a model held by a vessel")
    x, elevation = state.positions[:, 0], -state.positions[:, 2]
    rollers = state.roller_positions
    figure, axes = _figure(11.0, 8.0, 2, 2)
    whole, detail, strain_axis, utilisation_axis = axes
    for axis in (whole, detail):
        axis.plot(x, elevation, color="k", linewidth=1.2, label="pipe")
        axis.plot(x[-1], elevation[-1], marker="s", color="tab:blue", label="hold point")
        if rollers is not None:
            loaded = state.roller_reactions > 0
            axis.plot(
                *rollers[~loaded][:, [0, 2]].T * [[1], [-1]], "o", mfc="none", color="0.4", label="roller"
            )
            axis.plot(
                *rollers[loaded][:, [0, 2]].T * [[1], [-1]], "o", color="tab:red", label="roller in contact"
            )
        if state.touchdown is not None:
            axis.plot(
                *state.touchdown.position[[0, 2]] * [1, -1], marker="v", color="tab:green", label="touchdown"
            )
        if state.water_depth is not None:
            axis.axhline(state.water_depth, color="tab:blue", linewidth=0.8, linestyle="--")
    whole.axhline(0.0, color="0.3", linewidth=0.8)
    whole.set_title("Lay configuration (side view)")
    whole.set_xlabel("x (m)")
    whole.set_ylabel("elevation −z (m)")
    whole.legend(fontsize=8, loc="best")
    near = np.linalg.norm(state.positions - state.positions[-1], axis=1) < max(
        60.0, 1.3 * (np.ptp(rollers[:, 0]) if rollers is not None else 0.0) + 40.0
    )
    detail.set_xlim(x[near].min() - 5.0, x[near].max() + 5.0)
    detail.set_ylim(elevation[near].min() - 5.0, elevation[near].max() + 5.0)
    detail.set_title(f"At the vessel: departure {np.degrees(summary['departure_angle']):.1f}°")
    detail.set_xlabel("x (m)")
    arc = state.reference_arc_length
    middle = 0.5 * (arc[:-1] + arc[1:])
    strain_axis.plot(middle, 100 * state.strain, color="k")
    strain_axis.set_xlabel("arc length from end A (m)")
    strain_axis.set_ylabel("largest strain (%)")
    strain_axis.set_title("Strain (axial + bending at the outer fibre)")
    try:
        utilisation = pl.checks.dnv_st_f101(state, **check)
    except (pl.InputError, ValueError) as error:
        utilisation_axis.text(0.5, 0.5, f"no DNV check: {error}", ha="center", va="center", wrap=True)
    else:
        utilisation_axis.plot(middle, utilisation.load_controlled, label="load-controlled")
        utilisation_axis.plot(middle, utilisation.displacement_controlled, label="displacement-controlled")
        utilisation_axis.axhline(1.0, color="tab:red", linewidth=0.8)
        utilisation_axis.legend(fontsize=8, loc="best")
    utilisation_axis.set_xlabel("arc length from end A (m)")
    utilisation_axis.set_ylabel("utilisation (1 = limit)")
    utilisation_axis.set_title("DNV-ST-F101 utilisation")
    return _finish(figure, axes, path)


def lay_summary(results: Results, path: _PathLike | None = None) -> Figure:
    """The lay summary over a run: top tension, departure angle, overbend and sagbend strain, layback.

    Raises:
        ValueError: the results have no vessel.
    """
    summary = results.lay_summary()
    if summary is None:
        raise ValueError("lay_summary needs results of a model held by a vessel")
    t = results.time
    figure, axes = _figure(11.0, 7.0, 2, 2, sharex=True)
    tension, angle, strain, layback = axes
    tension.plot(t, summary["top_tension"] / 1e3, color="k")
    tension.set_ylabel("top tension (kN)")
    angle.plot(t, np.degrees(summary["departure_angle"]), color="k")
    angle.set_ylabel("departure angle (°)")
    strain.plot(t, 100 * summary["overbend_strain"], label="overbend")
    strain.plot(t, 100 * summary["sagbend_strain"], label="sagbend")
    strain.set_ylabel("largest strain (%)")
    strain.legend(fontsize=8, loc="best")
    layback.plot(t, summary["layback"], color="k")
    layback.set_ylabel("layback (m)")
    for axis in (strain, layback):
        axis.set_xlabel("time t (s)")
    figure.suptitle("Lay summary")
    return _finish(figure, axes, path)


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
    default times.

    Args:
        results: a run.
        directory: the output folder.
        reference: η_ref for `vessel_motion` (m, rad; NaN entries not drawn); unused without a vessel.
        depth: water depth (m) for `shape`'s sea surface and seabed lines.
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
    return written


def operability(
    summary: Any,
    variable: str,
    x: str,
    y: str | None = None,
    limit: float | None = None,
    ax: Axes | None = None,
    path: _PathLike | None = None,
    cmap: str = "viridis",
) -> Figure:
    """Operability map of a sweep: `variable` of its summary over the swept keys `x` and `y` as a heat map
    (one cell per case), the failed cases hatched, and the contour where the variable equals `limit`.

    Args:
        summary: the xarray.Dataset of ``pipelay.sweep`` (``Sweep.summary``, or ``summary.nc`` opened): one
            dimension per swept key, its statistics with ``units`` and ``long_name``, and ``failed``.
        variable: the statistic to map, e.g. "top_tension_max".
        x: the swept key along the horizontal axis.
        y: the swept key along the vertical axis; None: a single row (a sweep over one key).
        limit: the value (in the variable's units) whose contour to draw in red, e.g. an allowable tension;
            drawn where the map crosses it (at least 2 × 2 cases).
        ax: axes to draw on (then every other swept key must have been selected, ``summary.sel(key=value)``);
            None: a new figure with one panel per combination of the other keys' values.
        path: save the figure there (PNG at DPI unless the suffix says otherwise).
        cmap: matplotlib colour map.

    Numeric keys are placed by value (cells centred on the swept values); other values (vectors, words) are
    evenly spaced, labelled by their text. Axes are labelled with the keys and their units.

    Raises:
        ValueError: `variable` is not in the summary, `x` or `y` not one of its dimensions, or other
            dimensions are left with `ax` given.
    """
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.patches import Patch, Rectangle

    if variable not in summary:
        raise ValueError(
            f"variable: {variable!r} is not in the summary; one of {', '.join(summary.data_vars)}"
        )
    data = summary[variable]
    for key in (x, y):
        if key is not None and key not in data.dims:
            raise ValueError(
                f"{key!r} is not a swept key of {variable}; one of {', '.join(map(str, data.dims))}"
            )
    others = [str(dim) for dim in data.dims if dim not in (x, y)]
    if ax is not None and others:
        raise ValueError(
            f"with ax given, select one value of {', '.join(others)} first: summary.sel(key=value)"
        )
    panels = [dict(zip(others, index, strict=True)) for index in np.ndindex(*(data.sizes[d] for d in others))]
    if ax is None:
        columns = min(len(panels), 3)
        rows = -(-len(panels) // columns)
        figure, axes = _figure(5.0 * columns + 1.0, 4.0 * rows, rows, columns)
        for spare in axes[len(panels) :]:
            spare.set_visible(False)
    else:
        figure, axes = ax.get_figure(root=True), [ax]  # type: ignore[assignment]
    values = np.asarray(data.values, dtype=np.float64)
    finite = values[np.isfinite(values)]
    norm = Normalize(*(finite.min(), finite.max()) if finite.size else (0.0, 1.0))
    units = data.attrs.get("units", "")
    for axis, selection in zip(axes, panels, strict=False):
        panel = summary.isel(selection)
        grid = []  # (centres, edges, labels or None) along x, then y
        for key in (x, y):
            if key is None:
                grid.append((np.zeros(1), np.array([-0.5, 0.5]), None))
                continue
            coordinate = panel[key].values
            if coordinate.dtype.kind in "iuf":
                panel = panel.sortby(key)
                centres = panel[key].values.astype(np.float64)
                middle = 0.5 * (centres[1:] + centres[:-1])
                first = centres[0] - (middle[0] - centres[0] if len(centres) > 1 else 0.5)
                last = centres[-1] + (centres[-1] - middle[-1] if len(centres) > 1 else 0.5)
                grid.append((centres, np.concatenate([[first], middle, [last]]), None))
            else:
                count = len(coordinate)
                grid.append((np.arange(count, dtype=np.float64), np.arange(count + 1) - 0.5, coordinate))
        order = [y, x] if y is not None else [x]
        field = np.asarray(panel[variable].transpose(*order).values, dtype=np.float64).reshape(
            len(grid[1][0]), len(grid[0][0])
        )
        axis.pcolormesh(grid[0][1], grid[1][1], np.ma.masked_invalid(field), cmap=cmap, norm=norm)
        if "failed" in panel:
            failed = np.asarray(panel["failed"].transpose(*order).values).reshape(field.shape)
            for j, i in zip(*np.nonzero(failed), strict=True):
                (xe, ye) = grid[0][1], grid[1][1]
                axis.add_patch(
                    Rectangle(
                        (xe[i], ye[j]),
                        xe[i + 1] - xe[i],
                        ye[j + 1] - ye[j],
                        fill=False,
                        hatch="xx",
                        edgecolor="0.35",
                        linewidth=0.0,
                    )
                )
            if failed.any():
                axis.legend(
                    handles=[Patch(fill=False, hatch="xx", edgecolor="0.35", label="failed")], fontsize=8
                )
        inside = field[np.isfinite(field)]
        if limit is not None and min(field.shape) > 1 and inside.size and inside.min() < limit < inside.max():
            lines = axis.contour(
                grid[0][0],
                grid[1][0],
                np.ma.masked_invalid(field),
                levels=[limit],
                colors="tab:red",
                linewidths=1.5,
            )
            axis.clabel(lines, fmt=f"limit {limit:g} {units}".strip(), fontsize=8)
        for (centres, _, labels), key, set_label, set_ticks in (
            (grid[0], x, axis.set_xlabel, axis.set_xticks),
            (grid[1], y, axis.set_ylabel, axis.set_yticks),
        ):
            if key is None:
                set_ticks([])
                continue
            unit = summary[key].attrs.get("units", "")
            set_label(f"{key} ({unit})" if unit else key)
            if labels is not None:
                set_ticks(centres, [str(label) for label in labels], fontsize=8)
        if selection:
            axis.set_title(", ".join(f"{key} = {panel[key].item()}" for key in others), fontsize=9)
    title = variable
    # The keys selected beforehand (summary.sel) are scalar coordinates.
    fixed = [f"{key} = {summary[key].item()}" for key in summary.coords if summary[key].ndim == 0]
    title = "\n".join([title, ", ".join(fixed)]) if fixed else title
    (figure.suptitle if len(panels) > 1 else axes[0].set_title)(title, fontsize=10)
    scale = ScalarMappable(norm=norm, cmap=cmap)
    figure.colorbar(scale, ax=axes[: len(panels)], label=f"{variable} ({units})" if units else variable)
    if path is not None:
        figure.savefig(path, dpi=DPI)
    return figure
