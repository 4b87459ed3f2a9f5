"""The fatigue damage along the line (`damage_along`): the largest Miner's sum around each element's section
against the distance from end A, on a log scale, with the hot spot of the largest marked.

Imports of pipelay: `pipelay.plots.canvas`. A damage is anything with the fields of
`pipelay.analysis.fatigue.Damage` (`DamageAlong`), so that the analysis, which draws itself here, is not
imported.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from pipelay.plots.canvas import DPI, _figure, _PathLike

__all__ = ["DamageAlong", "damage_along"]


class DamageAlong(Protocol):
    """What the plot reads of a damage (`pipelay.analysis.fatigue.Damage`)."""

    @property
    def values(self) -> np.ndarray: ...
    @property
    def arc_length(self) -> np.ndarray: ...
    @property
    def angles(self) -> np.ndarray: ...
    @property
    def duration(self) -> float: ...
    @property
    def method(self) -> str: ...


def damage_along(damage: DamageAlong, ax: Axes | None = None, path: _PathLike | None = None) -> Figure:
    """The largest damage around each element's section against its distance from end A (m), log scale.

    Args:
        damage: a `pipelay.analysis.fatigue.Damage` (or a scatter diagram's ``.damage()``).
        ax: axes to draw on; None: a new figure (8 × 4 inches).
        path: save the figure there (PNG unless the suffix says otherwise).
    """
    if ax is None:
        figure, axes = _figure(8.0, 4.0, 1, 1)
        axis = axes[0]
    else:
        axis = ax
        figure = ax.get_figure(root=True)  # type: ignore[assignment]
    values = np.asarray(damage.values, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        largest = np.max(values, axis=1)
    shown = np.where(largest > 0.0, largest, np.nan)
    axis.semilogy(damage.arc_length, shown, color="C0", label="largest around the section")
    if np.isfinite(shown).any():
        element = int(np.nanargmax(shown))
        point = int(np.nanargmax(values[element]))
        angle = math.degrees(float(damage.angles[point]))
        axis.plot(
            damage.arc_length[element],
            shown[element],
            "o",
            color="C3",
            label=f"max {shown[element]:.3g} at {damage.arc_length[element]:.0f} m, hot spot {angle:.0f}°",
        )
        if shown[element] >= 0.1:
            axis.axhline(1.0, color="0.3", linestyle="--", linewidth=1.0, label="D = 1")
    hours = damage.duration / 3600.0
    axis.set_title(f"Fatigue damage over {hours:g} h ({damage.method.replace('_', ' ')})")
    axis.set_xlabel("distance from end A (m)")
    axis.set_ylabel("Miner's sum D")
    axis.legend(loc="best", fontsize="small")
    axis.grid(alpha=0.3, which="both")  # the canvas's ×10ⁿ tick labels do not apply to a log scale
    if path is not None:
        figure.savefig(path, dpi=DPI)
    return figure
