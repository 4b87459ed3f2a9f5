"""Results as labelled arrays and netCDF files: the file layout (`LAYOUT`, `GROUPS`), xarray datasets
(`to_xarray`), netCDF written atomically (`to_netcdf`) and exact reloading (`load`). Importing it makes the
first two the methods ``Results.to_xarray`` and ``Results.to_netcdf``.

The netCDF layout (`Results.to_xarray`): dimensions ``time``, ``node`` (n + 1), ``element`` (n), ``axis``
(x, y, z of frame e), ``column`` (of a rotation matrix) and ``dof`` (6 components: force/moment or η/ν
entries); every variable carries ``units`` and ``long_name`` attributes. With pay-out the mesh grows during a
run: ``node`` and ``element`` count the most any record had, and the node and element values a record did not
have are NaN (the last valid node of a record is end B). A run streamed to a file
(``Simulation.run(..., output=path)``, pipelay.results.streaming) writes the same layout with ``time``,
``node`` and ``element`` unlimited, holding the variables of the groups it recorded (``GROUPS``) and a global
attribute ``recorded_groups``.

Imports of pipelay: the engine (`pipelay._core`) and `pipelay.results.atomic`.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from datetime import UTC, datetime
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from pipelay._core import InputError, Results
from pipelay.results.atomic import _atomic_write

__all__ = ["GROUPS", "LAYOUT", "LOAD_GROUPS", "load", "to_netcdf", "to_xarray"]

AXES = ["x", "y", "z"]
FORCE_DOFS = ["Fx", "Fy", "Fz", "Mx", "My", "Mz"]

# name: (dimensions, units, description)
LAYOUT: dict[str, tuple[tuple[str, ...], str, str]] = {
    "positions": (("time", "node", "axis"), "m", "node positions in frame e (e3 down)"),
    "rotations": (("time", "node", "axis", "column"), "1", "nodal rotation matrices R_t^e"),
    "velocities": (("time", "node", "axis"), "m s-1", "node velocities"),
    "section_forces": (
        ("time", "element", "dof"),
        "N, N m",
        "material force [N1, N2, N3] (N) and moment [M1, M2, M3] (N m) at element midpoints",
    ),
    "tension": (("time", "element"), "N", "axial force N1 at element midpoints, positive in tension"),
    "segment": (("time", "element"), "1", "the segment of the line each element belongs to, NaN: no element"),
    "reaction_A": (("time", "dof"), "N, N m", "force and moment of the rod on the support at end A, frame e"),
    "reaction_B": (("time", "dof"), "N, N m", "force and moment of the rod on the support at end B, frame e"),
    "pipe_kinetic": (("time",), "J", "pipe kinetic energy"),
    "pipe_strain": (("time",), "J", "pipe strain energy"),
    "pipe_gravity": (("time",), "J", "potential of the pipe's submerged weight"),
    "vessel_kinetic": (("time",), "J", "vessel kinetic energy"),
    "vessel_potential": (("time",), "J", "vessel hydrostatic restoring energy"),
    "seabed_energy": (("time",), "J", "energy stored in the seabed contact (normal and friction springs)"),
    "roller_energy": (("time",), "J", "energy stored in the roller contacts"),
    "total_energy": (("time",), "J", "storage function E = pipe + vessel + seabed + roller energy"),
    "roller_reactions": (("time", "roller"), "N", "normal force of each roller (0: lifted off)"),
    "top_tension": (("time",), "N", "effective tension at the hold point (tensioner or tower)"),
    "departure_angle": (("time",), "rad", "pipe angle below the horizontal where it leaves the equipment"),
    "liftoff_roller": (("time",), "1", "index of the last roller in contact, NaN: none"),
    "liftoff_arc_length": (("time",), "m", "arc length of the lift-off point from end A"),
    "inflection_arc_length": (
        ("time",),
        "m",
        "arc length of the steepest point (overbend/sagbend) from end A",
    ),
    "layback": (("time",), "m", "horizontal distance from the hold point to the touchdown, NaN: none"),
    "overbend_strain": (("time",), "1", "largest strain from the hold point to the inflection point"),
    "sagbend_strain": (("time",), "1", "largest strain from the inflection point to the touchdown"),
    "sagbend_moment": (("time",), "N m", "largest bending moment from the inflection point to the touchdown"),
    "tip_clearance": (
        ("time",),
        "m",
        "gap between the line and the stinger's last roller (<= 0: in contact)",
    ),
    "touchdown": (
        ("time", "axis"),
        "m",
        "touchdown point (last point on the seabed seen from end A), NaN: none",
    ),
    "touchdown_arc_length": (
        ("time",),
        "m",
        "touchdown arc length along the reference from end A, NaN: none",
    ),
    "laid_length": (("time",), "m", "reference length of pipe on the seabed"),
    "length": (("time",), "m", "unstretched pipe length (changes with pay-out)"),
    "pay_out_energy": (
        ("time",),
        "J",
        "energy pay-out brought in since the start of the run (in supplied_work)",
    ),
    "supplied_work": (("time",), "J", "work supplied since the start of the run"),
    "dissipated": (("time",), "J", "energy dissipated since the start of the run"),
    "iterations": (("time",), "1", "Newton iterations of the step leading to the record"),
    "eta": (
        ("time", "dof"),
        "m, rad",
        "vessel pose [x, y, z, phi, theta, psi] in frame e: total motion (low and wave frequency)",
    ),
    "eta_low_frequency": (("time", "dof"), "m, rad", "vessel low-frequency pose, what the DP controls"),
    "eta_wave_frequency": (
        ("time", "dof"),
        "m, rad",
        "vessel wave-frequency motion, eta - eta_low_frequency",
    ),
    "eta_estimate": (("time", "dof"), "m, rad", "the observer's estimate of the low-frequency pose"),
    "tau_commanded": (("time", "dof"), "N, N m", "the controller's command, body frame"),
    "thrust": (("time", "thruster"), "N", "each thruster's delivered thrust"),
    "azimuth": (("time", "thruster"), "rad", "each thruster's azimuth, from the bow toward starboard"),
    "nu": (("time", "dof"), "m s-1, rad s-1", "vessel velocity [u, v, w, p, q, r], body frame"),
    "tau": (("time", "dof"), "N, N m", "thrust applied, body frame"),
    "chi": (("time", "dof"), "N, N m", "force and moment of the pipe on the vessel, body frame"),
}
ENERGY_KEYS = ["pipe_kinetic", "pipe_strain", "pipe_gravity", "vessel_kinetic", "vessel_potential"]


# The groups of variables a streamed run can record (``Simulation.run(..., output=path, record=groups)``);
# ``time`` is always recorded. A group the model lacks (a vessel, a seabed, lay equipment) is simply absent.
GROUPS: dict[str, tuple[str, ...]] = {
    "positions": ("positions",),
    "rotations": ("rotations",),
    "velocities": ("velocities",),
    "section_forces": ("section_forces", "tension", "segment"),
    "reactions": ("reaction_A", "reaction_B"),
    "energy": (
        *ENERGY_KEYS,
        "seabed_energy",
        "roller_energy",
        "total_energy",
        "supplied_work",
        "dissipated",
        "pay_out_energy",
        "length",
        "iterations",
    ),
    "vessel": (
        "eta",
        "nu",
        "tau",
        "chi",
        "eta_low_frequency",
        "eta_wave_frequency",
        "eta_estimate",
        "tau_commanded",
        "thrust",
        "azimuth",
    ),
    "seabed": ("touchdown", "touchdown_arc_length", "laid_length"),
    "lay": (
        "roller_reactions",
        "top_tension",
        "departure_angle",
        "liftoff_roller",
        "liftoff_arc_length",
        "inflection_arc_length",
        "layback",
        "overbend_strain",
        "sagbend_strain",
        "sagbend_moment",
        "tip_clearance",
    ),
}
# The groups ``load`` needs to build a Results (the engine's Results has no missing arrays).
LOAD_GROUPS = ("positions", "rotations", "velocities", "section_forces", "reactions", "energy")
# Variables the engine's Results cannot do without.
_REQUIRED = (
    "positions",
    "rotations",
    "velocities",
    "section_forces",
    "reaction_A",
    "reaction_B",
    *ENERGY_KEYS,
    "supplied_work",
    "dissipated",
    "iterations",
)


def _arrays(results: Results, names: Iterable[str] | None = None) -> dict[str, np.ndarray]:
    """The recorded arrays of `results` by their netCDF name: all of them, or only those in `names` (the others
    are not even fetched from the engine). Series the model does not have (no vessel, say) are left out."""
    cache: dict[str, Any] = {}

    def part(key: str) -> Any:
        if "energy" not in cache:
            cache["energy"] = results.energy
        return cache["energy"][key]

    def summary(key: str) -> Any:
        if "lay" not in cache:
            cache["lay"] = results.lay_summary()
        return None if cache["lay"] is None else cache["lay"][key]

    getters: dict[str, Callable[[], Any]] = {
        "positions": lambda: results.positions,
        "rotations": lambda: results.rotations,
        "velocities": lambda: results.velocities,
        "section_forces": lambda: results.section_forces,
        "tension": lambda: results.tension,
        "segment": lambda: results.segment,
        "reaction_A": lambda: results.reaction("A"),
        "reaction_B": lambda: results.reaction("B"),
        **{key: partial(part, key) for key in ENERGY_KEYS},
        "seabed_energy": lambda: part("seabed"),
        "roller_energy": lambda: part("rollers"),
        "total_energy": lambda: part("total"),
        "length": lambda: results.length,
        "pay_out_energy": lambda: results.pay_out_energy,
        "supplied_work": lambda: results.supplied_work,
        "dissipated": lambda: results.dissipated,
        "iterations": lambda: results.iterations,
        **{key: partial(getattr, results, key) for key in (*GROUPS["seabed"], *GROUPS["vessel"])},
        "roller_reactions": lambda: results.roller_reactions,
        # touchdown_arc_length is recorded with the seabed already.
        **{key: partial(summary, key) for key in GROUPS["lay"][1:]},
    }
    arrays: dict[str, np.ndarray] = {}
    for name in getters if names is None else names:
        value = getters[name]()
        if value is not None:
            arrays[name] = value
    return arrays


def to_xarray(results: Results) -> Any:
    """The results as an ``xarray.Dataset`` (dimensions time, node, element, axis, column, dof; units in the
    variables' attributes)."""
    import xarray as xr

    arrays = _arrays(results)
    nodes = results.positions.shape[1]
    variables = {
        name: xr.Variable(LAYOUT[name][0], value, {"units": LAYOUT[name][1], "long_name": LAYOUT[name][2]})
        for name, value in arrays.items()
    }
    coords = {
        "time": ("time", results.time, {"units": "s", "long_name": "time"}),
        "node": ("node", np.arange(nodes), {"long_name": "node index (0: end A, n: end B)"}),
        "element": ("element", np.arange(nodes - 1), {"long_name": "element index"}),
        "axis": ("axis", AXES),
        "column": ("column", AXES),
        "dof": ("dof", np.arange(6), {"long_name": "component: force/moment or eta/nu entry"}),
    }
    dataset = xr.Dataset(variables, coords=coords, attrs=_file_attributes())
    dataset.attrs.update(stage_attributes(results.stage_names, results.stage_starts))
    if results.stage is not None:
        dataset["stage"] = xr.Variable(("time",), results.stage, {"long_name": "stage index of the record"})
    return dataset


def stage_attributes(names: list[str] | None, starts: Sequence[float] | np.ndarray | None) -> dict[str, Any]:
    """The global attributes that mark a run's stages: ``stage_names`` (one per line) and ``stage_starts`` (s,
    each stage's start and the last one's end); none for a run without stages."""
    if names is None or starts is None:
        return {}
    return {"stage_names": "\n".join(names), "stage_starts": np.asarray(starts, dtype=float)}


def with_stages(results: Results, attributes: Any) -> Results:
    """`results` marked with the stages a file's `attributes` name (as written by ``stage_attributes``)."""
    if "stage_names" not in attributes:
        return results
    names = str(attributes["stage_names"]).split("\n")
    starts = np.atleast_1d(np.asarray(attributes["stage_starts"], dtype=float))
    return results._with_stages(names, starts.tolist())


def _file_attributes() -> dict[str, str]:
    """The global attributes of a results file."""
    return {
        "title": "pipelay simulation results",
        "conventions": "SI units; frame e: origin at the seabed end, e1 lay direction, e3 down",
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "force_dofs": " ".join(FORCE_DOFS),
    }


def to_netcdf(results: Results, path: str | os.PathLike[str]) -> Path:
    """Writes the results to a netCDF-4 file (h5netcdf) atomically: a temporary file, then a rename."""
    dataset = to_xarray(results)
    target = Path(path)
    _atomic_write(target, lambda temporary: dataset.to_netcdf(temporary, engine="h5netcdf"))
    return target


def load(path: str | os.PathLike[str]) -> Results:
    """Reads results written by ``Results.to_netcdf`` or streamed by ``Simulation.run(..., output=path)`` back,
    bit for bit. A streamed file recorded with only some groups (``record=...``) loads if it has the groups a
    Results is made of (``LOAD_GROUPS``: positions, rotations, velocities, section_forces, reactions, energy);
    the optional ones (vessel, seabed, lay) are then None in the Results. A file without one of those groups
    raises InputError naming the missing groups: read it with ``xarray.open_dataset(path)``."""
    import xarray as xr

    target = Path(path)
    if not target.is_file():
        raise InputError(f"path: no results file at {str(target)!r}")
    with xr.open_dataset(target, engine="h5netcdf") as dataset:
        missing = [name for name in _REQUIRED if name not in dataset.data_vars]
        if missing:
            groups = [group for group in GROUPS if any(name in GROUPS[group] for name in missing)]
            raise InputError(
                f"path: a results file with the groups {', '.join(LOAD_GROUPS)} to make a Results (read any "
                f"results file with xarray.open_dataset), got {str(target)!r} without {', '.join(groups)}"
            )
        arrays = {name: dataset[name].values for name in dataset.data_vars if name in LAYOUT}
        arrays["time"] = dataset["time"].values
        nodes = int(dataset.sizes["node"])
        attributes = dict(dataset.attrs)
    return with_stages(Results._from_arrays(nodes, arrays), attributes)


def _attach() -> None:
    """Makes these functions methods of the engine's Results: ``Results.to_xarray``, ``Results.to_netcdf``."""

    def results_to_xarray(self: Results) -> Any:
        """The results as an xarray.Dataset (dimensions time, node, element, axis, column, dof; units)."""
        return to_xarray(self)

    def results_to_netcdf(self: Results, path: str | os.PathLike[str]) -> Path:
        """Write a netCDF-4 file atomically; pl.load reads it back exactly."""
        return to_netcdf(self, path)

    Results.to_xarray = results_to_xarray  # type: ignore[attr-defined]
    Results.to_netcdf = results_to_netcdf  # type: ignore[attr-defined]


_attach()
