"""Operability sweeps on a real Dask cluster (pipelay.sweep, `pipelay sweep`, `pipelay plot summary.nc`,
`pipelay schema`): each case's file is a single run's bit for bit and its statistics those of that run; failed
cases are recorded while the others finish; a second call reuses the finished cases; a bad key is rejected
before anything runs."""

from __future__ import annotations

import functools
import json
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
import xarray as xr
from pipelay import cli, plots, statistics
from pipelay.scenario import apply_overrides, parse_scenario
from pipelay.sweep import Sweep, case_statistics, run_case

distributed = pytest.importorskip("distributed")

# A DP vessel holding a 12-element pipe that rests on the seabed, with a current and a sway force from
# t = 2 s: 21 records, a fraction of a second a case.
SCENARIO = """
title = "sweep test: DP vessel, pipe on the seabed"

[pipe]
outer_diameter = 0.6
wall_thickness = 0.015
contents_density = 1025.0
drag = [1.5, 1.5]

[rod]
start = [0.0, 0.0, 0.0]
end = [1200.0, 0.0, 0.0]
elements = 12

[sea]
depth = 800.0

[sea.seabed]
stiffness = 1e5
friction = 0.3

[sea.current]
kind = "linear"
surface_velocity = [0.0, -0.8, 0.0]
start = 2.0

[supports.A]
kind = "pin"

[vessel]
end = "B"
model = "osv"
eta = [730.0, 0.0, -800.0, 0.0, 0.0, 0.0]
angle = [0.0, -1.33, 0.0]

[controller]
kp = [0.5e6, 0.5e6, 0, 0, 0, 0]
kd = [0.4e7, 0.4e7, 0, 0, 0, 0]
reference = [730.0, 0.0, 0.0, 0.0, 0.0, 0.0]

[[environment]]
value = [0.0, 6e5, 0.0, 0.0, 0.0, 0.0]
start = 2.0

[solver]
dt = 0.5
t_end = 10.0
"""
OVER = {
    "sea.current.surface_velocity": [[0.0, -0.4, 0.0], [0.0, -0.8, 0.0]],
    "pipe.wall_thickness": [0.015, 0.02],
}


@pytest.fixture(scope="module")
def client() -> Any:
    """A cluster of two single-threaded worker processes, for the whole module."""
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as connected,
    ):
        yield connected


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("sweep")
    (path / "scenario.toml").write_text(SCENARIO)
    return path


@pytest.fixture(scope="module")
def swept(client: Any, folder: Path) -> Sweep:
    """The sweep of OVER over the scenario file, run once on the cluster."""
    return pl.sweep(folder / "scenario.toml", OVER, client=client, output=folder / "out", progress=False)


def single_run(case: dict[str, Any]) -> tuple[pl.Results, pl.Model]:
    """The case run in this process, in memory, from the scenario with the case's keys set by hand."""
    data = tomllib.loads(SCENARIO)
    data["sea"]["current"]["surface_velocity"] = case["sea.current.surface_velocity"]
    data["pipe"]["wall_thickness"] = case["pipe.wall_thickness"]
    scenario = parse_scenario(data)
    state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    simulation = scenario.model.simulation(state=state, dt=scenario.dt)
    return simulation.run(scenario.t_end, progress=False, record_every=scenario.record_every), scenario.model


def test_each_case_is_a_single_run_bit_for_bit(swept: Sweep, folder: Path) -> None:
    """The cluster's files equal in-process runs exactly; the summary holds those runs' statistics."""
    summary = swept.summary
    assert swept.failures == {}
    assert list(summary.dims) == list(OVER)
    assert summary["pipe.wall_thickness"].values.tolist() == [0.015, 0.02]
    assert summary["pipe.wall_thickness"].attrs["units"] == "m"
    assert summary["sea.current.surface_velocity"].attrs["units"] == "m/s"
    assert summary.attrs["source"] == str(folder / "scenario.toml")
    assert summary["top_tension_max"].attrs["units"] == "N"
    assert len(swept.cases) == 4
    for i, velocity in enumerate(OVER["sea.current.surface_velocity"]):
        for j, thickness in enumerate(OVER["pipe.wall_thickness"]):
            case = {"sea.current.surface_velocity": velocity, "pipe.wall_thickness": thickness}
            path = swept.cases[(tuple(velocity), thickness)]
            assert path.parent == folder / "out" / "cases" and summary["case"].values[i, j] == path.stem
            cluster, (local, model) = pl.load(path), single_run(case)
            for name in ("positions", "rotations", "section_forces", "eta", "tau"):
                assert np.array_equal(getattr(cluster, name), getattr(local, name)), name
            assert np.array_equal(cluster.reaction("B"), local.reaction("B"))
            # The statistics: from the in-process run, by statistics.extremes and by hand.
            found = {
                name: float(summary[name].values[i, j])
                for name in summary.data_vars
                if name not in ("case", "error")
            }
            expected = statistics.extremes(local, model=model, checks={})
            for name in ("top_tension_max", "top_tension_min", "strain_max", "moment_max", "utilisation_max"):
                assert found[name] == expected[name], name
            assert found["offset_max"] == np.max(np.hypot(*(local.eta[:, :2] - local.eta[0, :2]).T))
            assert found["thrust_max"] == np.max(np.hypot(local.tau[:, 0], local.tau[:, 1]))
            touchdown = local.touchdown[:, :2]
            assert found["touchdown_excursion"] == np.max(np.hypot(*(touchdown - touchdown[0]).T))
            # The streamed ledger may differ from the in-memory one in its last bit.
            assert found["passivity_margin_min"] == pytest.approx(-local.passivity_margin(), abs=1e-6)
            assert found["failed"] == 0
    # summary.nc is the summary.
    with xr.open_dataset(folder / "out" / "summary.nc", engine="h5netcdf") as written:
        for name in summary.data_vars:
            assert np.array_equal(written[name].values, summary[name].values), name


def test_run_case_here_equals_the_cluster(swept: Sweep, tmp_path: Path) -> None:
    """`run_case`, the function the workers run, gives the same file and statistics in this process."""
    case = {"sea.current.surface_velocity": [0.0, -0.8, 0.0], "pipe.wall_thickness": 0.02}
    scenario = parse_scenario(apply_overrides(tomllib.loads(SCENARIO), case))
    found = run_case(scenario, tmp_path / "here.nc")
    here, there = pl.load(tmp_path / "here.nc"), pl.load(swept.cases[((0.0, -0.8, 0.0), 0.02)])
    assert np.array_equal(here.positions, there.positions)
    assert np.array_equal(here.reaction("B"), there.reaction("B"))
    assert found == case_statistics(there, scenario.model)
    assert found["top_tension_max"] == float(swept.summary["top_tension_max"].values[1, 1])


def test_failed_cases_are_recorded_and_the_others_finish(client: Any, tmp_path: Path) -> None:
    """A factory's case with a negative wall thickness (InputError, on its worker) and a 100 GN sway force on
    the vessel, whose time steps fail (ConvergenceError), are failures with their messages; the good case
    finishes."""
    factory = functools.partial(apply_overrides, tomllib.loads(SCENARIO))
    held, pushed = (0.0, 6e5, 0.0, 0.0, 0.0, 0.0), (0.0, 1e11, 0.0, 0.0, 0.0, 0.0)
    over = {"pipe.wall_thickness": [0.015, -0.01], "environment[0].value": [list(held), list(pushed)]}
    done = pl.sweep(factory, over, client=client, output=tmp_path / "out", progress=False)
    assert set(done.failures) == {(0.015, pushed), (-0.01, held), (-0.01, pushed)}
    assert done.failures[(-0.01, held)].startswith("InputError: pipe.wall_thickness")
    assert "ConvergenceError" in done.failures[(0.015, pushed)]
    assert list(done.cases) == [(0.015, held)] and done.cases[(0.015, held)].is_file()
    summary = done.summary
    assert summary["failed"].values.tolist() == [[0, 1], [1, 1]]
    assert np.isfinite(summary["top_tension_max"].values[0, 0])
    assert np.isnan(summary["top_tension_max"].values[[0, 1, 1], [1, 0, 1]]).all()
    assert summary["error"].values[1, 0] == done.failures[(-0.01, held)]
    # Failed cases have no results file, only their record.
    assert len(list((tmp_path / "out" / "cases").glob("*.nc"))) == 1
    assert len(list((tmp_path / "out" / "cases").glob("*.json"))) == 4


def test_a_second_call_reuses_the_finished_cases(swept: Sweep, folder: Path, client: Any) -> None:
    """Same folder: nothing runs again (files untouched, fast) and the summary is the same; a case whose files
    are gone is the only one run again."""
    files = sorted((folder / "out" / "cases").iterdir())
    stamps = {path: path.stat().st_mtime_ns for path in files}
    begun = time.perf_counter()
    again = pl.sweep(folder / "scenario.toml", OVER, client=None, output=folder / "out", progress=False)
    assert time.perf_counter() - begun < 2.0  # no cluster started: it would take longer
    assert {path: path.stat().st_mtime_ns for path in files} == stamps
    for name in swept.summary.data_vars:
        assert np.array_equal(again.summary[name].values, swept.summary[name].values), name
    lost = swept.cases[((0.0, -0.4, 0.0), 0.02)]
    lost.unlink()
    lost.with_suffix(".json").unlink()
    third = pl.sweep(folder / "scenario.toml", OVER, client=client, output=folder / "out", progress=False)
    assert lost.is_file()
    assert {path: path.stat().st_mtime_ns for path in files if path.stem != lost.stem} == {
        path: stamp for path, stamp in stamps.items() if path.stem != lost.stem
    }
    assert np.array_equal(third.summary["top_tension_max"].values, swept.summary["top_tension_max"].values)


def test_cli_sweep_on_a_scheduler_then_plot(
    client: Any, folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`pipelay sweep --scheduler ADDRESS` runs on that cluster; `pipelay plot summary.nc` maps a result."""
    out, summary_file = folder / "cli", str(folder / "cli" / "summary.nc")
    gains = "controller.kp=[5e5, 5e5, 0, 0, 0, 0],[1e6, 1e6, 0, 0, 0, 0]"
    status = cli.main(
        ["sweep", str(folder / "scenario.toml"), "--over", gains, "--over", "pipe.wall_thickness=0.015,0.02",
         "-o", str(out), "--scheduler", client.scheduler.address, "--no-progress"]
    )  # fmt: skip
    printed = capsys.readouterr()
    assert status == 0, printed.err
    assert "4 cases, 4 finished, 0 failed" in printed.out
    with xr.open_dataset(summary_file, engine="h5netcdf") as summary:
        assert list(summary.dims) == ["controller.kp", "pipe.wall_thickness"]
        assert summary["controller.kp"].values.tolist() == [
            "[500000.0, 500000.0, 0, 0, 0, 0]",
            "[1000000.0, 1000000.0, 0, 0, 0, 0]",
        ]
        tension = summary["top_tension_max"].values
    assert np.isfinite(tension).all()
    figure = folder / "map.png"
    limit = str(float(np.mean(tension)))
    status = cli.main(
        ["plot", summary_file, "--variable", "top_tension_max", "--limit", limit, "-o", str(figure)]
    )
    assert status == 0
    assert figure.stat().st_size > 10_000
    # One value of the other key selected: a single row, written beside the summary.
    selected = "controller.kp=[1e6, 1e6, 0, 0, 0, 0]"
    status = cli.main(
        ["plot", summary_file, "--variable", "offset_max", "--x", "pipe.wall_thickness", "--select", selected]
    )
    assert status == 0
    assert (out / "offset_max.png").stat().st_size > 10_000
    assert cli.main(["plot", summary_file, "--variable", "no_such_thing"]) == 2
    assert "top_tension_max" in capsys.readouterr().err


def test_ctrl_c_keeps_the_finished_cases(folder: Path, tmp_path: Path) -> None:
    """SIGINT to `pipelay sweep` while a long case runs: exit 130, the short case's files and a summary with
    it (the long one NaN) stay, no temporary file is left; a second call reuses the short case."""
    out = tmp_path / "out"
    command = [sys.executable, "-m", "pipelay", "sweep", str(folder / "scenario.toml"), "--over",
               "solver.t_end=1.0,1e6", "-o", str(out), "--workers", "1", "--no-progress"]  # fmt: skip
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120.0
    while not list((out / "cases").glob("*.json")) and time.monotonic() < deadline:
        time.sleep(0.2)
    time.sleep(1.0)  # the long case is running
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=60.0)
    assert process.returncode == 130, err
    finished = list((out / "cases").glob("*.json"))
    assert len(finished) == 1 and "t_end=1.0" in finished[0].name
    assert len(list((out / "cases").glob("*.nc"))) == 1
    assert not list(out.rglob("*.part"))
    with xr.open_dataset(out / "summary.nc", engine="h5netcdf") as summary:
        tension = summary["top_tension_max"].values
    assert np.isfinite(tension[0]) and np.isnan(tension[1])
    begun = time.perf_counter()
    again = pl.sweep(folder / "scenario.toml", {"solver.t_end": [1.0]}, output=out, progress=False)
    assert time.perf_counter() - begun < 5.0 and not again.failures
    assert float(again.summary["top_tension_max"].values[0]) == tension[0]


def test_the_sweeps_own_workers_keep_glibcs_memory_trimming(monkeypatch: pytest.MonkeyPatch) -> None:
    """Dask starts workers with MALLOC_TRIM_THRESHOLD_=65536, which slows a case's engine by 5 %; the sweep's
    own cluster leaves it out (the other variables Dask sets, such as OMP_NUM_THREADS=1, stay)."""
    import os

    from pipelay.analysis.sweep import _connected

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with _connected(None, 1, 1) as local:
        trim = local.run(os.getenv, "MALLOC_TRIM_THRESHOLD_")
        threads = local.run(os.getenv, "OMP_NUM_THREADS")
    assert list(trim.values()) == [None]
    assert list(threads.values()) == ["1"]


def test_a_bad_key_or_value_is_rejected_before_anything_runs(
    folder: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Exit 2 naming the key, in well under a second: no cluster started, no folder made."""
    begun = time.perf_counter()
    for over, named in (
        ("sea.curent.surface_velocity=[0, -1, 0]", "sea.curent"),
        ("pipe.wall_thickness=0.015,-0.01", "pipe.wall_thickness"),
    ):
        status = cli.main(
            ["sweep", str(folder / "scenario.toml"), "--over", over, "-o", str(tmp_path / "out")]
        )
        error = capsys.readouterr().err
        assert status == 2 and named in error and "Traceback" not in error, error
    assert not (tmp_path / "out").exists()
    with pytest.raises(pl.InputError, match="pipe.wal_thickness"):
        pl.sweep(folder / "scenario.toml", {"pipe.wal_thickness": [0.01]}, output=tmp_path / "out")
    with pytest.raises(pl.InputError, match="distinct"):
        pl.sweep(folder / "scenario.toml", {"pipe.wall_thickness": [0.01, 0.01]}, output=tmp_path / "out")
    assert time.perf_counter() - begun < 2.0
    assert not (tmp_path / "out").exists()


def test_operability_panels_and_failed_cells() -> None:
    """The map of a three-key summary: one panel per value of the third key, failed cells hatched."""
    shape = (3, 2, 2)
    rng = np.random.default_rng(1)
    failed = np.zeros(shape, dtype=np.int8)
    failed[2, 1, 0] = 1
    values = np.where(failed, np.nan, rng.uniform(1.0, 3.0, shape))
    dims = ["a.x", "b.y", "c"]
    summary = xr.Dataset(
        {"top_tension_max": (dims, values, {"units": "N"}), "failed": (dims, failed)},
        coords={"a.x": ("a.x", [1.0, 2.0, 3.0], {"units": "m/s"}), "b.y": [10, 20], "c": ["p", "q"]},
    )
    figure = plots.operability(summary, "top_tension_max", "a.x", "b.y", limit=2.0)
    panels = [axis for axis in figure.axes if axis.get_visible() and axis.get_label() != "<colorbar>"]
    assert len(panels) == 2 and panels[0].get_xlabel() == "a.x (m/s)"
    assert any(patch.get_hatch() == "xx" for axis in panels for patch in axis.patches)
    with pytest.raises(ValueError, match="select"):
        plots.operability(summary, "top_tension_max", "a.x", "b.y", ax=panels[0])
    single = plots.operability(summary.sel({"c": "q", "b.y": 20}), "top_tension_max", "a.x")  # a single row
    assert "c = q" in single.axes[0].get_title()


def test_schema_prints_json(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """`pipelay schema` prints (or writes) pipelay.scenario.json_schema() as JSON, a valid JSON Schema."""
    scenario = pytest.importorskip("pipelay.scenario")
    if not hasattr(scenario, "json_schema"):
        pytest.skip("pipelay.scenario.json_schema is not there yet")
    assert cli.main(["schema"]) == 0
    schema = json.loads(capsys.readouterr().out)
    assert isinstance(schema, dict) and schema
    assert cli.main(["schema", "-o", str(tmp_path / "schema.json")]) == 0
    assert json.loads((tmp_path / "schema.json").read_text()) == schema
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.validators.validator_for(schema).check_schema(schema)
