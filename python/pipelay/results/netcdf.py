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

Both writers mark the file with the global attributes ``pipelay_format`` (the layout's version, an integer:
`FORMAT`) and ``pipelay_version`` (the pipelay that wrote it). `load` reads any format up to its own (files
without the attribute, from before it, too) and refuses a newer one, and a file that is not a pipelay results
file, an empty, truncated or damaged one, with an InputError naming the file and what is wrong with it.

Imports of pipelay: the engine (`pipelay._core`) and `pipelay.results.atomic`.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable, Sequence
from datetime import UTC, datetime
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from pipelay._core import InputError, Results
from pipelay.results.atomic import _atomic_write

__all__ = ["FORMAT", "GROUPS", "LAYOUT", "LOAD_GROUPS", "load", "to_netcdf", "to_xarray"]

# The version of the file layout both writers write (global attribute ``pipelay_format``) and the newest
# `load` reads. Raise it when a change would make an older pipelay misread a new file (a variable's meaning, units or
# dimensions changed); adding a variable older readers ignore does not need it.
FORMAT = 1

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
    "stinger_energy": (
        ("time",),
        "J",
        "an articulated stinger's sections: kinetic, weight less buoyancy's potential and the hinges' springs",
    ),
    "total_energy": (("time",), "J", "storage function E = pipe + vessel + seabed + roller + stinger energy"),
    "hinge_angles": (
        ("time", "hinge"),
        "rad",
        "each articulated stinger section's hinge angle, positive with its aft end turned down",
    ),
    "roller_reactions": (("time", "roller"), "N", "normal force of each roller (0: lifted off)"),
    "roller_reaction_vectors": (
        ("time", "roller", "axis"),
        "N",
        "each roller's force on the pipe in the vessel's body frame (forward, starboard, down)",
    ),
    "top_tension": (("time",), "N", "effective tension at the hold point (tensioner or tower)"),
    "departure_angle": (("time",), "rad", "pipe angle below the horizontal where it leaves the equipment"),
    "liftoff_roller": (
        ("time",),
        "1",
        "0-based index of the last support (lone roller or roller box) in contact, NaN: none",
    ),
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
        "gap between the line and the stinger's last support (<= 0: in contact)",
    ),
    "tip_offset": (
        ("time",),
        "m",
        "lateral offset (to starboard) of the line from the last support's station, NaN: none",
    ),
    "residual_curvature": (
        ("time",),
        "1/m",
        "the laid pipe's largest residual curvature from its history through the lay, NaN: no wall yields",
    ),
    "boxes_left": (
        ("time",),
        "1",
        "number of roller boxes with the pipe at a roller's end (0: in its boxes)",
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
    "pay_out_speed": (
        ("time",),
        "m/s",
        "pay-out speed of the last step: the tensioner's, or the winch's once it holds",
    ),
    "pay_out_energy": (
        ("time",),
        "J",
        "energy pay-out brought in since the start of the run (in supplied_work)",
    ),
    "supplied_work": (("time",), "J", "work supplied since the start of the run"),
    "dissipated": (("time",), "J", "energy dissipated since the start of the run"),
    "plastic_dissipation": (
        ("time",),
        "J",
        "energy the yielding walls dissipated since the start of the run (part of dissipated)",
    ),
    "iterations": (("time",), "1", "Newton iterations of the step leading to the record"),
    "substeps": (
        ("time",),
        "1",
        "the most substeps any step since the record before was taken in (1: none split)",
    ),
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
    "passivity_reserve": (
        ("time",),
        "J",
        "the energy a certifying controller may still give the vessel: its storage at the start less its work",
    ),
    "passivity_withheld": (
        ("time",),
        "J",
        "the controller's work the passivity controller withheld since the simulation started",
    ),
    "passivity_steps": (
        ("time",),
        "1",
        "the steps the passivity controller acted in since the simulation started",
    ),
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
        "stinger_energy",
        "total_energy",
        "supplied_work",
        "dissipated",
        "plastic_dissipation",
        "pay_out_energy",
        "length",
        "pay_out_speed",
        "iterations",
        "substeps",
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
        "passivity_reserve",
        "passivity_withheld",
        "passivity_steps",
    ),
    "seabed": ("touchdown", "touchdown_arc_length", "laid_length"),
    "lay": (
        "roller_reactions",
        "roller_reaction_vectors",
        "hinge_angles",
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
        "tip_offset",
        "boxes_left",
        "residual_curvature",
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
        "plastic_dissipation": lambda: part("plastic_dissipation"),
        "stinger_energy": lambda: part("stinger"),
        "total_energy": lambda: part("total"),
        "length": lambda: results.length,
        "pay_out_speed": lambda: results.pay_out_speed,
        "pay_out_energy": lambda: results.pay_out_energy,
        "supplied_work": lambda: results.supplied_work,
        "dissipated": lambda: results.dissipated,
        "iterations": lambda: results.iterations,
        "substeps": lambda: results.substeps,
        **{key: partial(getattr, results, key) for key in (*GROUPS["seabed"], *GROUPS["vessel"])},
        "roller_reactions": lambda: results.roller_reactions,
        "roller_reaction_vectors": lambda: results.roller_reaction_vectors,
        "hinge_angles": lambda: results.hinge_angles,
        # touchdown_arc_length is recorded with the seabed already.
        **{key: partial(summary, key) for key in GROUPS["lay"][3:]},
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
    dataset.attrs.update(line_attributes(results.pipe_walls, results.water))
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


def line_attributes(
    walls: Sequence[tuple[float, float] | None], water: tuple[float, float] | None
) -> dict[str, Any]:
    """The global attributes that describe a run's line and sea, as its stresses need them (fatigue):
    ``pipe_wall_outer_diameter`` and ``pipe_wall_thickness`` (m, one per segment from end A; NaN for a segment
    without a steel wall), ``water_depth`` (m) and ``water_density`` (kg/m³) (none without a sea)."""
    attributes: dict[str, Any] = {}
    if walls:
        attributes["pipe_wall_outer_diameter"] = np.array([np.nan if w is None else w[0] for w in walls])
        attributes["pipe_wall_thickness"] = np.array([np.nan if w is None else w[1] for w in walls])
    if water is not None:
        attributes["water_depth"], attributes["water_density"] = float(water[0]), float(water[1])
    return attributes


def with_line(results: Results, attributes: Any) -> Results:
    """`results` marked with the line and sea a file's `attributes` describe (as written by
    ``line_attributes``); files written before these attributes existed leave `results` as they are."""
    walls: list[tuple[float, float] | None] = []
    if "pipe_wall_outer_diameter" in attributes:
        diameters = np.atleast_1d(np.asarray(attributes["pipe_wall_outer_diameter"], dtype=float))
        thicknesses = np.atleast_1d(np.asarray(attributes["pipe_wall_thickness"], dtype=float))
        walls = [
            None if np.isnan(d) else (float(d), float(t)) for d, t in zip(diameters, thicknesses, strict=True)
        ]
    water = None
    if "water_depth" in attributes:
        water = (float(attributes["water_depth"]), float(attributes["water_density"]))
    if not walls and water is None:
        return results
    return results._with_line(walls, water)


def _file_attributes() -> dict[str, Any]:
    """The global attributes of a results file: its title, conventions, creation time, the order of a force's
    components, and the layout's version (``pipelay_format``, an integer) with the pipelay that wrote it."""
    return {
        "title": TITLE,
        "pipelay_format": FORMAT,
        "pipelay_version": _version(),
        "conventions": "SI units; frame e: origin at the seabed end, e1 lay direction, e3 down",
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "force_dofs": " ".join(FORCE_DOFS),
    }


TITLE = "pipelay simulation results"


def _version() -> str:
    """The installed pipelay's version ("unknown" when run from a source tree it was not installed from)."""
    from importlib import metadata

    try:
        return metadata.version("pipelay")
    except metadata.PackageNotFoundError:
        return "unknown"


def to_netcdf(results: Results, path: str | os.PathLike[str]) -> Path:
    """Writes the results to a netCDF-4 file (h5netcdf) atomically: a temporary file, then a rename."""
    dataset = to_xarray(results)
    target = Path(path)
    _atomic_write(target, lambda temporary: dataset.to_netcdf(temporary, engine="h5netcdf"))
    return target


def load(path: str | os.PathLike[str]) -> Results:
    """Reads results written by ``Results.to_netcdf`` or streamed by ``Simulation.run(..., output=path)`` back,
    bit for bit (the ``.part`` file of a run still going or killed, too: it holds the records written so far).
    A streamed file recorded with only some groups (``record=...``) loads if it has the groups a Results is
    made of (``LOAD_GROUPS``: positions, rotations, velocities, section_forces, reactions, energy); the optional
    ones (vessel, seabed, lay) are then None in the Results. A file without one of those groups raises
    InputError naming the missing groups: read it with ``xarray.open_dataset(path)``.

    Raises InputError naming the file and the problem for a path that is no file, an empty file, one that is
    not netCDF-4 (HDF5; a text file, a netCDF-3 file), a netCDF file that is not a pipelay results file, a
    truncated or damaged file, and a file of a newer format (``pipelay_format`` above `FORMAT`: upgrade
    pipelay)."""
    import h5py
    import xarray as xr

    target = Path(path)
    if not target.is_file():
        raise InputError(f"path: no results file at {str(target)!r}")
    _check_signature(target)
    try:
        # h5py first: a file it cannot open or whose attributes it cannot read fails here, not half-way into
        # h5netcdf's File (which then complains on stderr as it is collected); the format is checked before
        # anything else is read.
        with h5py.File(target, "r", locking=False) as file:
            _check_format(target, {key: file.attrs[key] for key in file.attrs})
        # phony_dims: an HDF5 file that is not netCDF opens too, and is refused below for its variables.
        dataset = xr.open_dataset(target, engine="h5netcdf", phony_dims="sort")
    except InputError:
        raise
    except Exception as error:  # noqa: BLE001 - h5py and h5netcdf raise OSError, ValueError, KeyError ...
        raise _unreadable(target, error) from None
    with dataset:
        attributes = dict(dataset.attrs)
        missing = [name for name in _REQUIRED if name not in dataset.data_vars]
        if missing:
            if len(missing) == len(_REQUIRED) and not _is_ours(dataset, attributes):
                others = ", ".join(sorted(map(str, dataset.data_vars))[:8]) or "none"
                raise InputError(
                    f"path: {str(target)!r} is a netCDF-4 (HDF5) file but not a pipelay results file: it has "
                    f"none of the variables {', '.join(_REQUIRED[:6])}, … and no pipelay_format attribute "
                    f"(its variables: {others})"
                )
            groups = [group for group in GROUPS if any(name in GROUPS[group] for name in missing)]
            raise InputError(
                f"path: a results file with the groups {', '.join(LOAD_GROUPS)} to make a Results (read any "
                f"results file with xarray.open_dataset), got {str(target)!r} without {', '.join(groups)}"
            )
        try:
            arrays = {name: dataset[name].values for name in dataset.data_vars if name in LAYOUT}
            arrays["time"] = dataset["time"].values
            nodes = int(dataset.sizes["node"])
        except Exception as error:  # noqa: BLE001 - a chunk cut off or damaged: OSError, RuntimeError ...
            raise _unreadable(target, error) from None
    try:
        results = Results._from_arrays(nodes, arrays)
    except (InputError, ValueError, TypeError) as error:
        raise InputError(
            f"path: {str(target)!r} is not a valid pipelay results file: its arrays do not make a Results "
            f"({error})"
        ) from None
    return with_line(with_stages(results, attributes), attributes)


# HDF5's signature, at byte 0 or, after a user block, at 512, 1024, 2048, ... (the HDF5 file format).
_HDF5 = b"\x89HDF\r\n\x1a\n"


def _check_signature(target: Path) -> None:
    """Raises InputError if `target` is empty or not an HDF5 file (a netCDF-4 file is one)."""
    size = target.stat().st_size
    if size == 0:
        raise InputError(f"path: {str(target)!r} is empty (0 bytes), not a pipelay results file")
    with open(target, "rb") as file:
        head = file.read(8)
        offset = 512
        while offset + 8 <= size:
            if head == _HDF5:
                return
            file.seek(offset)
            head, offset = file.read(8), 2 * offset
        if head == _HDF5:
            return
        file.seek(0)
        start = file.read(16)
    if size < len(_HDF5) and _HDF5.startswith(start):
        raise InputError(f"path: {str(target)!r} is truncated: {size} bytes, the start of an HDF5 signature")
    if start[:3] == b"CDF":
        raise InputError(
            f"path: {str(target)!r} is a netCDF-3 (classic) file, not a pipelay results file: those are "
            "netCDF-4 (HDF5), written by Results.to_netcdf or a streamed run"
        )
    raise InputError(
        f"path: {str(target)!r} is not a pipelay results file: not a netCDF-4 (HDF5) file (it starts with "
        f"{start!r})"
    )


def _unreadable(target: Path, error: BaseException) -> InputError:
    """The InputError for an HDF5 file h5py or h5netcdf could not read: truncated, damaged, or not netCDF."""
    reason = str(error) or type(error).__name__
    cut = re.search(r"eof = (\d+).*stored_eof = (\d+)", reason)
    if cut:
        return InputError(
            f"path: {str(target)!r} is truncated: it has {int(cut.group(1))} of the {int(cut.group(2))} "
            "bytes its header announces (a copy cut short, a full disk?)"
        )
    return InputError(
        f"path: {str(target)!r} is an HDF5 file that cannot be read as a pipelay results file (truncated or "
        f"damaged, or not netCDF-4): {type(error).__name__}: {reason}"
    )


def _check_format(target: Path, attributes: dict[str, Any]) -> None:
    """Raises InputError if the file's ``pipelay_format`` is not a format number or is newer than `FORMAT`
    (a file without it, from before the attribute, is format 1)."""
    if "pipelay_format" not in attributes:
        return
    value = attributes["pipelay_format"]
    number = np.asarray(value)  # netCDF attributes are arrays: one number for this one
    if number.size == 1:
        number = number.reshape(())
    if number.shape != () or number.dtype.kind not in "iu" or int(number) < 1:
        raise InputError(
            f"path: {str(target)!r} has a pipelay_format attribute that is not a format number (an integer "
            f">= 1), got {number.tolist()!r}"
        )
    if int(number) > FORMAT:
        writer = attributes.get("pipelay_version")
        written = f", written by pipelay {writer}" if isinstance(writer, str) else ""
        raise InputError(
            f"path: the file's format {int(number)} is newer than this pipelay reads ({FORMAT}); upgrade "
            f"pipelay to read {str(target)!r}{written}"
        )


def _is_ours(dataset: Any, attributes: dict[str, Any]) -> bool:
    """Whether a netCDF file is a pipelay results file (then one missing groups, not someone else's file)."""
    return (
        "pipelay_format" in attributes
        or attributes.get("title") == TITLE
        or any(name in LAYOUT for name in dataset.data_vars)
    )


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
