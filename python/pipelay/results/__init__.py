"""Results as labelled arrays and files: netCDF (written atomically, read back exactly), runs streamed to a
file as they go, and checkpoints that let a long run be resumed exactly.

* `pipelay.results.netcdf`: the file layout (`LAYOUT`, `GROUPS`), `to_xarray`, `to_netcdf` and `load`;
* `pipelay.results.streaming`: ``Simulation.run(t_end, output=path)``, a run streamed to a netCDF file;
* `pipelay.results.checkpoints`: `checkpoint` and `resume`;
* `pipelay.results.atomic`: writing a file whole or not at all.

Importing the package makes them methods of the engine's classes: ``Results.to_xarray``,
``Results.to_netcdf``, ``Simulation.checkpoint``, and ``Simulation.run`` streaming when given an `output`. It
has the names the module ``pipelay.results`` had before it became this package (``pl.load`` and
``pl.resume`` among them; of its private helpers, ``_arrays``).

Imports of pipelay: the engine (`pipelay._core`) and these modules; nothing of `pipelay.scenario` or
`pipelay.analysis`, which build on it.
"""

# The old module's names; those outside __all__ are imported `as` themselves: re-exported, not unused.
from pipelay.results import streaming as streaming
from pipelay.results.checkpoints import checkpoint, resume
from pipelay.results.netcdf import AXES as AXES
from pipelay.results.netcdf import ENERGY_KEYS as ENERGY_KEYS
from pipelay.results.netcdf import FORCE_DOFS as FORCE_DOFS
from pipelay.results.netcdf import GROUPS, LOAD_GROUPS, load, to_netcdf, to_xarray
from pipelay.results.netcdf import LAYOUT as LAYOUT
from pipelay.results.netcdf import _arrays as _arrays

__all__ = ["GROUPS", "LOAD_GROUPS", "checkpoint", "load", "resume", "to_netcdf", "to_xarray"]
