"""The DP capability plot: the largest wind speed held at each heading, as a polar envelope (`capability`).

The usual DP plot's conventions: the heading the environment comes from, relative to the bow, 0° (head-on)
at the top and increasing clockwise seen from above (90°: from starboard, on the right; 270°: from port);
the wind speed (m/s, 1-hour mean at 10 m) radially.

Imports of pipelay: `pipelay.plots.canvas`. An envelope is anything with the fields of
`pipelay.analysis.Capability` (`Envelope`), so that the analysis, which draws itself here, is not imported.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Protocol

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from pipelay.plots.canvas import DPI, _PathLike

__all__ = ["Envelope", "capability"]


class Envelope(Protocol):
    """What the plot reads of a DP capability envelope (`pipelay.analysis.Capability`)."""

    @property
    def headings(self) -> np.ndarray: ...
    @property
    def wind_speed(self) -> np.ndarray: ...
    @property
    def pipe_load(self) -> np.ndarray: ...
    @property
    def current(self) -> float: ...
    @property
    def max_wind(self) -> float: ...
    @property
    def label(self) -> str: ...
    @property
    def at_limit(self) -> np.ndarray: ...


_STYLES = ("-", "--", "-.", ":")
_SIDES = {0: "\nhead-on", 90: "\nstarboard", 180: "\nastern", 270: "\nport"}
"""Where the environment comes from at the quarter headings, under their degree labels."""


def _closed(headings: np.ndarray, speeds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The envelope's points in heading order (rad in [0, 2π)), closed back to the first when the headings go
    round the circle (the gap across 0 no wider than the widest between them)."""
    angles = np.mod(headings, 2.0 * np.pi)
    order = np.argsort(angles, kind="stable")
    angles, speeds = angles[order], speeds[order]
    if len(angles) >= 3:
        gaps = np.diff(angles)
        wrap = 2.0 * np.pi - (angles[-1] - angles[0])
        if wrap <= 1.01 * float(np.max(gaps)):
            angles = np.append(angles, angles[0] + 2.0 * np.pi)
            speeds = np.append(speeds, speeds[0])
    return angles, speeds


def _load_text(load: np.ndarray) -> str:
    """The pipe load of an envelope, in words (kN, kN·m)."""
    if not np.any(load):
        return "no pipe load"
    return f"pipe load X = {load[0] / 1e3:.0f} kN, Y = {load[1] / 1e3:.0f} kN, N = {load[5] / 1e3:.0f} kN·m"


def capability(
    envelopes: Envelope | Sequence[Envelope] | Mapping[str, Envelope],
    ax: Axes | None = None,
    path: _PathLike | None = None,
    title: str | None = None,
) -> Figure:
    """The DP capability plot of one envelope or several on the same axes.

    Args:
        envelopes: a `pipelay.analysis.Capability` (``dp_capability``'s result), a sequence of them, or a
            mapping of legend labels to them (a sequence is labelled by their pipe loads, or their `label`s
            when those differ).
        ax: polar axes to draw on; None: a new figure (6 × 6.4 inches).
        path: save the figure there (PNG at DPI unless the suffix says otherwise).
        title: the figure's title; None: "DP capability", the label, the current and, for one envelope, its
            pipe load (X, Y in kN and N in kN·m, body frame).

    Headings where the wind is held up to the search's limit (`max_wind`) are marked with open circles: the
    envelope lies beyond them.

    Raises:
        ValueError: `ax` is not polar, or no envelope is given.
    """
    if isinstance(envelopes, Mapping):
        named = dict(envelopes)
    else:
        listed = [envelopes] if not isinstance(envelopes, Sequence) else list(envelopes)
        labels = [e.label for e in listed]
        distinct = len(set(labels)) == len(labels)
        named = {(e.label if distinct else _load_text(e.pipe_load)): e for e in listed}
        if len(named) < len(listed):
            named = {f"{k + 1}: {_load_text(e.pipe_load)}": e for k, e in enumerate(listed)}
    if not named:
        raise ValueError("envelopes: give at least one Capability")
    if ax is None:
        figure = Figure(figsize=(6.0, 6.4), layout="constrained")
        FigureCanvasAgg(figure)
        axis: Axes = figure.add_subplot(projection="polar")
    else:
        if ax.name != "polar":
            raise ValueError(f"ax: must be polar axes (projection='polar'), got {ax.name!r}")
        axis = ax
        figure = ax.get_figure(root=True)  # type: ignore[assignment]
    axis.set_theta_zero_location("N")  # type: ignore[attr-defined]
    axis.set_theta_direction(-1)  # type: ignore[attr-defined]
    top = 0.0
    for k, (name, envelope) in enumerate(named.items()):
        angles, speeds = _closed(np.asarray(envelope.headings), np.asarray(envelope.wind_speed))
        (line,) = axis.plot(angles, speeds, linestyle=_STYLES[k % len(_STYLES)], marker=".", label=name)
        limited = envelope.at_limit
        if np.any(limited):
            axis.plot(
                np.asarray(envelope.headings)[limited],
                np.asarray(envelope.wind_speed)[limited],
                linestyle="none",
                marker="o",
                markerfacecolor="none",
                color=line.get_color(),
            )
        top = max(top, float(np.max(envelope.wind_speed)))
    handles, _ = axis.get_legend_handles_labels()
    limits = {e.max_wind for e in named.values() if np.any(e.at_limit)}
    if limits:
        marker = Line2D([], [], linestyle="none", marker="o", markerfacecolor="none", color="0.3")
        marker.set_label(f"held to {', '.join(f'{v:g}' for v in sorted(limits))} m/s, the search's limit")
        handles.append(marker)
    axis.set_ylim(0.0, max(1.0, 1.05 * top))
    degrees = range(0, 360, 30)
    labels = [f"{d}°" + _SIDES.get(d, "") for d in degrees]
    axis.set_thetagrids(list(degrees), labels=labels)  # type: ignore[attr-defined]
    axis.set_rlabel_position(135.0)  # type: ignore[attr-defined]
    axis.text(  # the radial axis' unit, by its labels
        np.radians(135.0), 1.1 * axis.get_ylim()[1], "wind speed (m/s)", ha="center", va="center", fontsize=9
    )
    axis.grid(alpha=0.4)
    if title is None:
        first = next(iter(named.values()))
        currents = {e.current for e in named.values()}
        current = f"current {first.current:g} m/s" if len(currents) == 1 else "currents differ"
        head = "DP capability" + (f": {first.label}" if len(named) == 1 else "")
        lines = [head, f"environment from (relative to the bow), {current}, Beaufort sea"]
        if len(named) == 1:
            lines.append(_load_text(first.pipe_load) + " (body frame)")
        title = "\n".join(lines)
    axis.set_title(title, fontsize=10)
    if len(named) > 1 or limits:
        axis.legend(
            handles=handles, loc="lower center", bbox_to_anchor=(0.5, -0.2), fontsize=8, frameon=False
        )
    if path is not None:
        figure.savefig(path, dpi=DPI)
    return figure
