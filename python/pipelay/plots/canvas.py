"""The canvas every figure of `pipelay.plots` is drawn on: a figure on its own Agg canvas (pyplot is not used),
its finish (grids, ×10ⁿ tick labels, saved at `DPI`), and what the figure families share: the records nearest
to chosen times, their legend labels and line styles.

Imports of pipelay: the engine (`pipelay._core`, for the type of a route).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any, Literal

import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from pipelay._core import Route

__all__ = ["DPI"]

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
