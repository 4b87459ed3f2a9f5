"""The operability map of a sweep: a statistic of its summary over two swept keys (`operability`).

Imports of pipelay: `pipelay.plots.canvas`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from pipelay.plots.canvas import DPI, _figure, _PathLike

__all__ = ["operability"]


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
