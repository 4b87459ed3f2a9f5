"""Figures of a pipelay run: pipe shapes, vessel motion, top tension, tension and bending along the pipe, the
energy balance, and for a lay with pay-out the touchdown's track, the laid pipe's deviation from the route and
the top tension of several runs, for a staged lay the tensions over the stages and the line at the end of
each, a vessel's DP capability envelope and the fatigue damage along the pipe.

Every function returns a :class:`matplotlib.figure.Figure` drawn on its own Agg canvas (pyplot is not used, so
neither the user's backend nor pyplot's list of open figures is touched) and, when ``path`` is given, also
saves it there (PNG at 120 dpi; another suffix such as ``.pdf`` selects that format).

Frame e has e3 pointing down: elevations are plotted as −z (m above the seabed end, z = 0), and the sea
surface, the plane z = −depth, is at elevation depth.

Usage::

    from pipelay import plots

    plots.shape(results, times=(0.0, 30.0, 200.0), depth=800.0, path="shape.png")
    plots.all_figures(results, "figures", depth=800.0)

The figures come in families, one module each: `pipelay.plots.run` (any run, and `all_figures`),
`pipelay.plots.lay` (a lay), `pipelay.plots.stages` (a staged lay), `pipelay.plots.operability` (a sweep),
`pipelay.plots.capability` (a DP capability analysis), `pipelay.plots.fatigue` (fatigue damage), all drawn on `pipelay.plots.canvas`; this package has
the names of them all, those the module ``pipelay.plots`` had, and those added since.

Imports of pipelay: the engine and these modules (the lay configuration's checks through ``pl.checks``).
"""

from pipelay.plots.canvas import DPI as DPI
from pipelay.plots.capability import capability
from pipelay.plots.fatigue import damage_along
from pipelay.plots.lay import (
    lay_accuracy,
    lay_configuration,
    lay_deviation,
    lay_summary,
    tension_comparison,
    touchdown_path,
    touchdown_track,
)
from pipelay.plots.lay_table import lay_table
from pipelay.plots.operability import operability
from pipelay.plots.run import all_figures, energy, shape, tension_and_bending, top_tension, vessel_motion
from pipelay.plots.stages import stage_configurations, stage_tensions

__all__ = [
    "all_figures",
    "capability",
    "damage_along",
    "energy",
    "lay_accuracy",
    "lay_configuration",
    "lay_deviation",
    "lay_summary",
    "lay_table",
    "operability",
    "shape",
    "stage_configurations",
    "stage_tensions",
    "tension_and_bending",
    "tension_comparison",
    "top_tension",
    "touchdown_path",
    "touchdown_track",
    "vessel_motion",
]
