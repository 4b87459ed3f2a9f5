"""The figures of a lay: the touchdown's path and track against the vessel's, the laid pipe's deviation from the
route (`lay_deviation`, `lay_accuracy`), the top tension of several runs, a lay configuration on the stinger and
the lay summary over a run.

Imports of pipelay: the engine (`pipelay._core`), `pipelay.plots.canvas`, `pipelay.analysis.supports`, and the
package (``pl.checks``) when
a lay configuration is drawn.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from textwrap import fill
from typing import Any

import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure

from pipelay._core import Results, Route, State
from pipelay.analysis.supports import support_count
from pipelay.plots.canvas import (
    _LINESTYLES,
    _figure,
    _finish,
    _PathLike,
    _records,
    _RouteLike,
    _style,
    _time_label,
)

__all__ = [
    "lay_accuracy",
    "lay_configuration",
    "lay_deviation",
    "lay_summary",
    "tension_comparison",
    "touchdown_path",
    "touchdown_track",
]


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
    """Top tension (T,) (N): the effective tension the tensioner, the tower or the top support holds, as
    everywhere in pipelay (`pipelay.analysis.extremes.top_tension`: the lay summary's with a vessel, else the
    axial force of the element at end B)."""
    from pipelay.analysis.extremes import top_tension

    return top_tension(results)


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

    The top tension is the lay summary's (at the tensioner or tower) for a run with a vessel, else the axial
    force of the element at end B (`pipelay.analysis.extremes.top_tension`).

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
        check: arguments of ``pl.checks.dnv_st_f101`` and ``pl.checks.propagation_buckling`` (a scenario's
            ``Scenario.checks``; e.g. grade="X65"); the utilisation panel (each check's largest value and
            element in the legend, the basis below) says why it is empty when the check cannot run (a section
            without a wall thickness).

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
    liftoff = summary["liftoff_roller"]  # 0-based; rollers (boxes) are numbered from 1 for people
    count, noun = support_count(state.roller_supports)
    at = f" at {noun} {liftoff + 1} of {count}" if liftoff is not None and rollers is not None else ""
    detail.set_title(f"At the vessel: departure {np.degrees(summary['departure_angle']):.1f}°{at}")
    detail.set_xlabel("x (m)")
    arc = state.reference_arc_length
    middle = 0.5 * (arc[:-1] + arc[1:])
    strain_axis.plot(middle, 100 * state.strain, color="k")
    strain_axis.set_xlabel("arc length from end A (m)")
    strain_axis.set_ylabel("largest strain (%)")
    strain_axis.set_title("Strain (axial + bending at the outer fibre)")
    try:
        utilisation = pl.checks.dnv_st_f101(state, **check)
        propagation = pl.checks.propagation_buckling(state, **check)
    except (pl.InputError, ValueError) as error:
        utilisation_axis.text(0.5, 0.5, f"no DNV check: {error}", ha="center", va="center", wrap=True)
    else:
        for name, values in (
            ("load-controlled", utilisation.load_controlled),
            ("displacement-controlled", utilisation.displacement_controlled),
            ("propagation buckling", propagation.utilisation),
        ):
            worst = int(np.argmax(values))
            utilisation_axis.plot(middle, values, label=f"{name}: {values[worst]:.3f} (element {worst})")
        utilisation_axis.axhline(1.0, color="tab:red", linewidth=0.8)
        utilisation_axis.legend(fontsize=8, loc="best")
        basis = utilisation.basis.removeprefix("DNV-ST-F101, ")
        utilisation_axis.text(
            0.0, -0.28, fill(basis, 90), transform=utilisation_axis.transAxes, fontsize=7, va="top"
        )
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
