"""Results files and checkpoints: netCDF round trip (exact), labelled dimensions and units, atomic writes, and
a resumed simulation equal to an uninterrupted one."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import jensen2009 as paper

FIELDS = [
    "time",
    "positions",
    "rotations",
    "velocities",
    "section_forces",
    "tension",
    "supplied_work",
    "dissipated",
]


@pytest.fixture(scope="module")
def vessel_run() -> tuple[pl.Model, pl.Simulation, pl.Results]:
    """The paper's PID scenario, 60 s at Δt = 0.25 s."""
    model = paper.scenario(paper.controllers()["PID"])
    simulation = model.simulation(state=model.static(), dt=0.25)
    return model, simulation, simulation.run(60.0, progress=False)


def test_netcdf_round_trip_is_exact(vessel_run, tmp_path: Path) -> None:
    """Every array comes back bit for bit, the vessel's series included."""
    _, _, results = vessel_run
    path = results.to_netcdf(tmp_path / "run.nc")
    back = pl.load(path)
    for name in FIELDS:
        assert np.array_equal(getattr(results, name), getattr(back, name)), name
    for end in ("A", "B"):
        assert np.array_equal(results.reaction(end), back.reaction(end))
    for name in ("eta", "nu", "tau", "chi"):
        assert np.array_equal(getattr(results, name), getattr(back, name)), name
    for key, value in results.energy.items():
        assert np.array_equal(value, back.energy[key]), key
    assert back.passivity_margin() == results.passivity_margin()
    assert [p.name for p in tmp_path.iterdir()] == ["run.nc"]  # no temporary file left


def test_xarray_dataset_has_dimensions_and_units(vessel_run) -> None:
    _, _, results = vessel_run
    dataset = results.to_xarray()
    assert dict(dataset.sizes) == {"time": 241, "node": 11, "element": 10, "axis": 3, "column": 3, "dof": 6}
    assert dataset["positions"].dims == ("time", "node", "axis")
    assert dataset["positions"].attrs["units"] == "m"
    assert dataset["tension"].attrs["units"] == "N"
    assert dataset["eta"].attrs["units"] == "m, rad"
    assert dataset["time"].attrs["units"] == "s"
    np.testing.assert_array_equal(dataset["tension"].values, results.tension)


def test_a_failed_write_leaves_no_file(vessel_run, tmp_path: Path) -> None:
    """Writing into a path whose directory cannot be created fails without leaving anything behind."""
    _, _, results = vessel_run
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    with pytest.raises(OSError):
        results.to_netcdf(blocker / "run.nc")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_resumed_simulation_equals_the_uninterrupted_one(vessel_run, tmp_path: Path) -> None:
    """Checkpoint at 60 s, continue to 100 s in a fresh simulation: identical to continuing directly."""
    model, simulation, _ = vessel_run
    path = simulation.checkpoint(tmp_path / "state.npz")
    straight_on = simulation.run(100.0, progress=False)
    resumed = pl.resume(model, path).run(100.0, progress=False)
    for name in FIELDS:
        assert np.array_equal(getattr(straight_on, name), getattr(resumed, name)), name
    assert np.array_equal(straight_on.eta, resumed.eta) and np.array_equal(straight_on.tau, resumed.tau)


def test_missing_files_raise_input_errors(tmp_path: Path) -> None:
    with pytest.raises(pl.InputError, match="path"):
        pl.load(tmp_path / "none.nc")
    model = paper.scenario(paper.controllers()["PD"])
    with pytest.raises(pl.InputError, match="path"):
        pl.resume(model, tmp_path / "none.npz")
