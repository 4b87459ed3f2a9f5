"""The figure of a lay table (`pipelay.analysis.lay_table.lay_table`): each quantity of its rows against the
water depth, in people's units (kN, degrees, percent), as its CSV writes them.

Imports of pipelay: `pipelay.analysis.lay_table` (the table's columns) and `pipelay.plots.canvas`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from pipelay.analysis.lay_table import COLUMNS, utilisation_basis
from pipelay.plots.canvas import _figure, _finish, _PathLike

__all__ = ["lay_table"]

_PANELS: tuple[tuple[str, tuple[str, ...], str], ...] = (
    ("top tension", ("top_tension",), "kN"),
    ("departure angle", ("departure_angle",), "°"),
    ("layback", ("layback",), "m"),
    ("vessel position and pipe length", ("vessel_x", "pipe_length"), "m"),
    ("strain", ("overbend_strain", "sagbend_strain"), "%"),
    ("tip clearance", ("tip_clearance",), "m"),
    ("largest roller load (lift-off roller)", ("roller_reaction_max",), "kN"),
    (
        "DNV-ST-F101 utilisation",
        ("load_controlled_max", "displacement_controlled_max", "propagation_max"),
        "–",
    ),
)
"""The panels: title, the table's variables drawn in it, their unit (the CSV's)."""

_LABELS = {
    "overbend_strain": "overbend",
    "sagbend_strain": "sagbend",
    "load_controlled_max": "load-controlled",
    "displacement_controlled_max": "displacement-controlled",
    "propagation_max": "propagation buckling",
    "vessel_x": "vessel η x",
    "pipe_length": "pipe's length",
}
"""Legend labels of the panels with more than one variable."""


def lay_table(table: Any, path: _PathLike | None = None) -> Figure:
    """The quantities of a lay table against the water depth (m), one panel each: top tension (kN), departure
    angle (°), layback (m), the vessel's η x and the pipe's length (m), overbend and sagbend strain (%), tip
    clearance (m), the largest roller load (kN) with the lift-off roller's number (from 1 at the stinger's
    vessel end) beside each point, and the largest DNV-ST-F101 load- and displacement-controlled utilisations
    with unity dotted and what they assume (the table's ``utilisation_basis``) under the figure. The target
    is dashed in its quantity's panel (whose scale spans at least ±1 % around it), and depths where it is not
    met are dotted red lines across every panel.

    Args:
        table: a lay table (the ``xarray.Dataset`` of `pipelay.analysis.lay_table.lay_table`).
        path: where to save the figure, if anywhere.

    Returns:
        The figure: eight axes, their lines with gid the table's variable names; the suptitle names the
        target.
    """
    target, value = str(table.attrs["target"]), float(table.attrs["target_value"])
    order = np.argsort(table["depth"].values, kind="stable")
    depth = table["depth"].values[order]
    failed = depth[np.array([bool(text) for text in table["failure"].values[order]], dtype=bool)]
    figure, axes = _figure(15.0, 7.0, 2, 4, sharex=True)
    for axis, (title, names, unit) in zip(axes, _PANELS, strict=True):
        for name in names:
            values = table[name].values[order] * COLUMNS[name].scale
            axis.plot(depth, values, marker="o", markersize=4, gid=name, label=_LABELS.get(name))
        if len(names) > 1:
            axis.legend(fontsize=8)
        for where in failed:
            axis.axvline(where, color="tab:red", linestyle=":", linewidth=1.2)
        if target in names:
            aim = value * COLUMNS[target].scale
            axis.axhline(aim, color="0.3", linestyle="--", linewidth=1.0)
            low, high = axis.get_ylim()
            axis.set_ylim(min(low, 0.99 * aim), max(high, 1.01 * aim))
        axis.set_title(title, fontsize=10)
        axis.set_ylabel(unit)
    rollers = axes[6]
    loads = table["roller_reaction_max"].values[order] * COLUMNS["roller_reaction_max"].scale
    for x, load, roller in zip(depth, loads, table["liftoff_roller"].values[order], strict=True):
        if np.isfinite(load) and np.isfinite(roller):
            rollers.annotate(
                f"{roller:.0f}", (x, load), textcoords="offset points", xytext=(0, 5), ha="center", fontsize=8
            )
    axes[7].axhline(1.0, color="0.3", linestyle=":", linewidth=1.0)
    for axis in axes[4:]:
        axis.set_xlabel("water depth (m)")
    basis = utilisation_basis(table)
    failures = (
        f"; dotted red: target not met at {', '.join(f'{d:g}' for d in failed)} m" if len(failed) else ""
    )
    shown = {"N": (1e-3, " kN"), "rad": (180.0 / np.pi, "°"), "m": (1.0, " m")}.get(
        str(table.attrs["target_units"]), (100.0, " %") if target.endswith("strain") else (1.0, "")
    )
    figure.suptitle(f"Lay table: vessel placed for {target} = {value * shown[0]:.6g}{shown[1]}{failures}")
    if basis:
        figure.supxlabel(f"utilisations: {basis}", fontsize=8)
    return _finish(figure, axes, path)
