"""The figures of a staged lay (a run through ``pl.Stages``): the top tension and the A&R wire's tension over
the stages, and the line's shape at the end of each stage.

Each record of a staged run belongs to the stage whose steps end there (``results.stage``); a stage's span
is ``results.stage_starts[k]`` to ``results.stage_starts[k + 1]`` (s). The wire is told from the pipe by its
segments (`pipelay.analysis.stages.wire_segments`: from the model's cable sections when the model is given,
else the segment a hand-over joined at the top), and the laydown head is the node where the wire meets the
pipe (`pipelay.analysis.stages.head_positions`).

Imports of pipelay: the engine (`pipelay._core`), `pipelay.analysis.stages` and `pipelay.plots.canvas`
(and `pipelay.plots.lay` for the top tension).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure

from pipelay._core import Model, Results
from pipelay.analysis.stages import head_positions, staged, wire_elements
from pipelay.plots.canvas import _figure, _finish, _PathLike
from pipelay.plots.lay import _top_tension_series

__all__ = ["stage_configurations", "stage_tensions"]

_SHADES = ("0.86", "0.95")
"""Face colours of the stages' spans, alternately."""


def _wire_tension(results: Results, model: Model | None = None) -> npt.NDArray[np.float64]:
    """The wire's largest axial force in each record (T,) (N): the largest of `section_forces[:, :, 0]` over
    the wire's elements; NaN in records without wire (before the hand-over).

    Args:
        results: a run.
        model: the model run (its cable sections are the wire); None: the wire as
            `pipelay.analysis.stages.wire_segments` finds it.
    """
    is_wire = wire_elements(results, model)
    forces = np.where(is_wire, results.section_forces[:, :, 0], -np.inf)
    return np.where(is_wire.any(axis=1), forces.max(axis=1), np.nan)


def stage_tensions(results: Results, path: _PathLike | None = None, model: Model | None = None) -> Figure:
    """The top tension and, once a hand-over has joined it, the A&R wire's largest tension against time (kN),
    over the stages of a lay.

    The top tension is the lay summary's, at whatever holds the line (the tensioner, the tower or, after a
    hand-over, the winch). Each stage's span is shaded, alternately darker and lighter, with its name at the
    top; dotted vertical lines mark the boundaries between stages.

    Args:
        results: a run through ``pl.Stages``.
        path: where to save the figure, if anywhere.
        model: the model run (its cable sections are the wire); None: the wire as
            `pipelay.analysis.stages.wire_segments` finds it.

    Returns:
        The figure, one axes: its lines are the top tension (label "top tension"), the wire's largest tension
        (label "A&R wire, largest", only when the run has wire) and the boundaries; its patches the stages'
        spans, in order; its texts the stages' names.

    Raises:
        pipelay.InputError: naming `results`, for a run without stages.
    """
    _, names, starts = staged(results, "stage_tensions")
    time = results.time
    figure, axes = _figure(10.0, 4.8, 1, 1)
    (axis,) = axes
    for k, name in enumerate(names):
        axis.axvspan(starts[k], starts[k + 1], facecolor=_SHADES[k % 2], edgecolor="none", zorder=0)
        axis.text(
            0.5 * (starts[k] + starts[k + 1]),
            0.98,
            name,
            transform=axis.get_xaxis_transform(),
            ha="center",
            va="top",
            fontsize=9,
        )
    axis.plot(time, _top_tension_series(results) / 1e3, color="k", linewidth=1.5, label="top tension")
    wire = _wire_tension(results, model)
    if np.isfinite(wire).any():
        axis.plot(time, wire / 1e3, color="tab:red", linestyle="--", label="A&R wire, largest")
    for boundary in starts[1:-1]:
        axis.axvline(boundary, color="0.4", linestyle=":", linewidth=1.0)
    axis.set_xlim(starts[0], starts[-1])
    axis.set_xlabel("time t (s)")
    axis.set_ylabel("tension (kN)")
    axis.set_title("Tension over the stages of the lay")
    axis.legend(fontsize=8, loc="lower right")
    return _finish(figure, axes, path)


def stage_configurations(
    results: Results,
    path: _PathLike | None = None,
    depth: float | None = None,
    model: Model | None = None,
) -> Figure:
    """Side view (x against elevation −z, m) of the line at the end of each stage (its last record), one
    colour per stage: the pipe solid, the A&R wire dashed, the laydown head marked ●.

    Args:
        results: a run through ``pl.Stages``.
        path: where to save the figure, if anywhere.
        depth: water depth (m); when given, the sea surface is drawn at elevation depth. The seabed (z = 0) is
            always drawn.
        model: the model run (its cable sections are the wire); None: the wire as
            `pipelay.analysis.stages.wire_segments` finds it.

    Returns:
        The figure, one axes. Per stage k with records, its lines have gid "pipe:k" (the nodes of the pipe's
        elements, NaN elsewhere, labelled with the stage's name and time), "wire:k" (the wire's nodes, NaN
        elsewhere; only with wire) and "head:k" (the head, only when the line has wire at its top).

    Raises:
        pipelay.InputError: naming `results`, for a run without stages.
    """
    stage, names, _ = staged(results, "stage_configurations")
    time = results.time
    positions = results.positions
    is_wire = wire_elements(results, model)
    present = np.isfinite(results.segment)
    heads = head_positions(results, model)
    figure, axes = _figure(10.0, 5.0, 1, 1)
    (axis,) = axes
    for k, name in enumerate(names):
        records = np.flatnonzero(stage == k)
        if len(records) == 0:
            continue
        r = records[-1]
        color = f"C{k % 10}"
        elements = int(present[r].sum())
        p = positions[r, : elements + 1]
        wire = is_wire[r, :elements]
        on_wire = np.zeros(elements + 1, dtype=bool)
        on_wire[:-1] |= wire
        on_wire[1:] |= wire
        on_pipe = np.zeros(elements + 1, dtype=bool)
        on_pipe[:-1] |= ~wire
        on_pipe[1:] |= ~wire
        x, elevation = p[:, 0], -p[:, 2]
        axis.plot(
            np.where(on_pipe, x, np.nan),
            np.where(on_pipe, elevation, np.nan),
            color=color,
            linewidth=1.5,
            label=f"{name} (t = {time[r]:g} s)",
            gid=f"pipe:{k}",
        )
        if wire.any():
            axis.plot(
                np.where(on_wire, x, np.nan),
                np.where(on_wire, elevation, np.nan),
                color=color,
                linestyle="--",
                linewidth=1.2,
                gid=f"wire:{k}",
            )
        if np.all(np.isfinite(heads[r])):
            axis.plot(
                heads[r, 0],
                -heads[r, 2],
                marker="o",
                markersize=7,
                color=color,
                linestyle="none",
                gid=f"head:{k}",
            )
    axis.axhline(0.0, color="saddlebrown", linewidth=1.5, label="seabed (z = 0)")
    if depth is not None:
        axis.axhline(depth, color="tab:cyan", linewidth=1.5, label=f"sea surface (−z = {depth:g} m)")
    axis.set_xlabel("x (m)")
    axis.set_ylabel("elevation above seabed −z (m)")
    axis.set_title("The line at the end of each stage (dashed: A&R wire, ● laydown head)")
    axis.legend(fontsize=8, loc="best")
    return _finish(figure, axes, path)
