"""pipelay: offshore pipelay simulation with a geometrically exact pipe model.

SI units throughout; the inertial frame e has its origin at the pipe's seabed end, e1 along the lay
direction and e3 pointing down (gravity is +g·e3); the sea surface is the plane z = −depth.
Rod end "A" is node 0 (seabed end), "B" is node n (top end).

The package's parts, each building only on those named before it: the engine `pipelay._core` (`Model`,
`Rod`, `Section`, ..., re-exported here); `pipelay.results`, results as files: netCDF, streamed runs,
checkpoints (`load`, `resume`, `streaming`); `pipelay.scenario`, scenario files; `pipelay.analysis`, what a
state or a run means: `checks`, `statistics`, `lay` (`find_lay_position`) and `sweep`; `pipelay.plots`, the
figures; and `pipelay.cli`, the ``pipelay`` command.
"""

import functools
import sys
from collections.abc import Callable
from importlib import metadata
from typing import Any

from pipelay._core import (
    PID,
    Allocation,
    Bathymetry,
    Clump,
    Coating,
    ConvergenceError,
    Current,
    DriftCoefficients,
    Force,
    HullCoefficients,
    InputError,
    JLay,
    Material,
    Model,
    Observer,
    Raos,
    ReelLay,
    Results,
    Rod,
    RollerBox,
    Route,
    Sea,
    Seabed,
    Section,
    Segment,
    Simulation,
    SLay,
    Stage,
    Stages,
    State,
    Stinger,
    StingerSection,
    Straightener,
    TensionControl,
    Thruster,
    Touchdown,
    Vessel,
    Waves,
    Winch,
    Wind,
    design_straightener,
)
from pipelay.analysis import checks, curve_lay, fatigue, lay, statistics, suspect
from pipelay.analysis import stages as _stages  # noqa: F401 (attaches Results.stage_summary)
from pipelay.analysis.capability import Capability, dp_capability
from pipelay.analysis.lay import find_lay_position
from pipelay.analysis.lay_table import lay_table
from pipelay.analysis.stinger_design import StingerDesign, design_stinger
from pipelay.analysis.supports import SupportLoads, support_loads
from pipelay.analysis.suspect import PhysicsWarning
from pipelay.analysis.sweep import sweep
from pipelay.cosimulation import Controller
from pipelay.results import load, resume, streaming


def _simulation(
    self: Model,
    state: State | None = None,
    dt: float = 0.05,
    stages: Stages | None = None,
    high_frequency_damping: float = 0.0,
) -> Simulation:
    """A time simulation from `state` (default: ``self.static()``) with time step `dt` (s), using the
    energy–momentum conserving integrator, through `stages` (a `pl.Stages`) if given, with the
    `high_frequency_damping` ξ ≥ 0 of the line's strains (0: energy conserving); the same as
    ``Simulation(self, state, dt, stages, high_frequency_damping)``."""
    return Simulation(self, state, dt, stages, high_frequency_damping)


Model.simulation = _simulation  # type: ignore[attr-defined]


def _checking_static(static: Callable[..., State]) -> Callable[..., State]:
    """`Model.static`, warning (`PhysicsWarning`) of what is suspect in the state it returns."""

    @functools.wraps(static)
    def checked(self: Model, *args: Any, **kwargs: Any) -> State:
        state = static(self, *args, **kwargs)
        suspect.warn(suspect.suspect_state(state))
        return state

    return checked


def _checking_run(run: Callable[..., Results]) -> Callable[..., Results]:
    """`Simulation.run`, warning (`PhysicsWarning`) of what is suspect in the run's records."""

    @functools.wraps(run)
    def checked(self: Simulation, *args: Any, **kwargs: Any) -> Results:
        results = run(self, *args, **kwargs)
        if len(results):
            winch = suspect.suspect_winch(results, self.winch_tension_limit, self.winch_wire_segment)
            suspect.warn(suspect.suspect_results(results, self.state) + winch)
        return results

    return checked


def _view(self: Results, model: Model | None = None, **options: Any) -> Any:
    """The 3-D replay of the run: a plotly Figure (shown in Jupyter; ``.write_html(path)``), the pipe coloured
    by ``colour`` ("tension", "moment", "strain", "utilisation"); `model` adds the rollers or tower, the seabed
    and the waves. The options are those of `pipelay.plots.replay.replay`."""
    from pipelay.plots.replay import replay

    return replay(self, model, **options)


Results.view = _view  # type: ignore[attr-defined]
Model.static = _checking_static(Model.static)  # type: ignore[method-assign]
Simulation.run = _checking_run(Simulation.run)  # type: ignore[method-assign]

# The modules' old import paths, kept for compatibility, and `pipelay.fatigue`, the short path of
# `pipelay.analysis.fatigue`: each is registered as the module itself (not a copy), so an attribute set through
# either name is set for both, and a later `import pipelay.sweep` finds the module registered instead of
# binding it over `pl.sweep`, the function. The files at the old paths re-export the same names for type
# checkers and readers.
for _old, _new in {
    "checks": "analysis.checks",
    "fatigue": "analysis.fatigue",
    "lay": "analysis.lay",
    "statistics": "analysis.statistics",
    "streaming": "results.streaming",
    "sweep": "analysis.sweep",
}.items():
    sys.modules[f"pipelay.{_old}"] = sys.modules[f"pipelay.{_new}"]
del _old, _new

__all__ = [
    "PID",
    "Allocation",
    "Bathymetry",
    "Capability",
    "Clump",
    "Coating",
    "Controller",
    "ConvergenceError",
    "Current",
    "DriftCoefficients",
    "Force",
    "HullCoefficients",
    "InputError",
    "JLay",
    "Material",
    "Model",
    "Observer",
    "PhysicsWarning",
    "Raos",
    "ReelLay",
    "Results",
    "Rod",
    "RollerBox",
    "Route",
    "SLay",
    "Sea",
    "Seabed",
    "Section",
    "Segment",
    "Simulation",
    "Stage",
    "Stages",
    "State",
    "Stinger",
    "StingerDesign",
    "StingerSection",
    "Straightener",
    "SupportLoads",
    "TensionControl",
    "Thruster",
    "Touchdown",
    "Vessel",
    "Waves",
    "Winch",
    "Wind",
    "checks",
    "curve_lay",
    "design_stinger",
    "design_straightener",
    "dp_capability",
    "fatigue",
    "find_lay_position",
    "lay",
    "lay_table",
    "load",
    "resume",
    "statistics",
    "streaming",
    "support_loads",
    "sweep",
]
__version__: str = metadata.version("pipelay")
"""The installed package's version, from its metadata (pyproject.toml's `version`)."""
