"""The scenario a results file was computed from, kept in the file: what a replay or a report rebuilds the model
from (the rollers, the seabed, the waves, the section), with no other file to hand.

``pipelay run`` and every case of a sweep write, as global attributes of their results file:

* ``scenario``: the scenario's TOML data as JSON text (`Scenario.source`);
* ``scenario_origin``: where it came from (the file's path, or a sweep case's description);
* ``scenario_folder``: the absolute folder its relative file paths (RAO and hull tables) are relative to.

`scenario_of_results(path)` reads them back as a `Scenario` (the model built again, nothing solved), or None
for a file without them (written by ``Results.to_netcdf`` or ``Simulation.run(output=...)`` from the API).

Imports of pipelay: `pipelay.scenario.reading`.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pipelay as pl
from pipelay.scenario.reading import Scenario, parse_scenario

__all__ = ["SCENARIO_ATTRIBUTES", "mark_results", "scenario_of_results"]

SCENARIO_ATTRIBUTES = ("scenario", "scenario_origin", "scenario_folder")
"""The global attributes of a results file that hold its scenario."""


def mark_results(path: str | os.PathLike[str], scenario: Scenario) -> None:
    """Adds `scenario`'s attributes (`SCENARIO_ATTRIBUTES`) to the results file at `path` (netCDF-4)."""
    import h5py

    with h5py.File(path, "a", locking=False) as file:
        file.attrs["scenario"] = json.dumps(scenario.source, default=str)
        file.attrs["scenario_origin"] = scenario.origin
        file.attrs["scenario_folder"] = scenario.folder or str(Path.cwd())


def scenario_of_results(path: str | os.PathLike[str]) -> Scenario | None:
    """The scenario the results file at `path` was computed from, or None if the file does not hold one.

    Raises pl.InputError if the file is not readable as netCDF-4 (HDF5), or its scenario no longer builds
    (a table file it names has moved): the message names the file.
    """
    import h5py

    target = Path(path)
    if not target.is_file():
        raise pl.InputError(f"path: no results file at {str(target)!r}")
    try:
        with h5py.File(target, "r", locking=False) as file:
            attributes = {key: file.attrs[key] for key in SCENARIO_ATTRIBUTES if key in file.attrs}
    except (OSError, KeyError) as error:
        raise pl.InputError(f"path: cannot read the attributes of {str(target)!r}: {error}") from None
    if "scenario" not in attributes:
        return None
    text = {
        key: value.decode() if isinstance(value, bytes) else str(value) for key, value in attributes.items()
    }
    try:
        data = json.loads(text["scenario"])
    except json.JSONDecodeError as error:
        raise pl.InputError(
            f"path: the scenario stored in {str(target)!r} is not valid JSON ({error})"
        ) from None
    origin = text.get("scenario_origin", str(target))
    try:
        return parse_scenario(data, origin, text.get("scenario_folder"))
    except pl.InputError as error:
        raise pl.InputError(
            f"path: the scenario stored in {str(target)!r} does not build again: {error}"
        ) from None
