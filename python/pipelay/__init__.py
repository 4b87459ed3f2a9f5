"""pipelay: offshore pipelay simulation with a geometrically exact pipe model.

SI units throughout; the inertial frame e has its origin at the pipe's seabed end, e1 along the lay
direction and e3 pointing down (gravity is +g·e3); the sea surface is the plane z = −depth.
Rod end "A" is node 0 (seabed end), "B" is node n (top end).
"""

import sys

from pipelay import checks, lay
from pipelay._core import (
    PID,
    Bathymetry,
    ConvergenceError,
    Current,
    Force,
    InputError,
    JLay,
    Model,
    Raos,
    Results,
    Rod,
    Route,
    Sea,
    Seabed,
    Section,
    Simulation,
    SLay,
    State,
    Stinger,
    TensionControl,
    Touchdown,
    Vessel,
    Waves,
)
from pipelay.lay import find_lay_position
from pipelay.results import load, resume, streaming
from pipelay.sweep import sweep


def _simulation(self: Model, state: State | None = None, dt: float = 0.05) -> Simulation:
    """A time simulation from `state` (default: ``self.static()``) with time step `dt` (s), using the
    energy–momentum conserving integrator; the same as ``Simulation(self, state, dt)``."""
    return Simulation(self, state, dt)


Model.simulation = _simulation  # type: ignore[attr-defined]

# The modules' old import paths, kept for compatibility: each is the module itself under its old name (not a
# copy), so setting an attribute through either name sets it for both. The files at the old paths re-export
# the same names for type checkers and readers; Python takes these instead.
for _old, _module in {"streaming": streaming}.items():
    sys.modules[f"pipelay.{_old}"] = _module
del _old, _module

__all__ = [
    "PID",
    "Bathymetry",
    "ConvergenceError",
    "Current",
    "Force",
    "InputError",
    "JLay",
    "Model",
    "Raos",
    "Results",
    "Rod",
    "Route",
    "SLay",
    "Sea",
    "Seabed",
    "Section",
    "Simulation",
    "State",
    "Stinger",
    "TensionControl",
    "Touchdown",
    "Vessel",
    "Waves",
    "checks",
    "find_lay_position",
    "lay",
    "load",
    "resume",
    "streaming",
    "sweep",
]
__version__ = "0.1.0"
