"""Sweeps that survive faults, on real Dask clusters and real processes: `pl.sweep` at the top level of a script
fails at once naming the fix; a worker killed mid-case is restarted and the case run again, bit for bit a single
run; a case that kills its worker every time fails after two retries while the others finish; a lost or silent
scheduler stops the sweep with ConnectionError, and the next call runs only the cases not finished.

The factories are module functions (the workers import this module: pytest puts tests/ on sys.path, which the
workers inherit); they leave marker files so that a case behaves differently on its first attempt."""

from __future__ import annotations

import functools
import json
import os
import signal
import subprocess
import sys
import threading
import time
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay.analysis import sweep as sweeping
from pipelay.scenario import apply_overrides, parse_scenario
from pipelay.sweep import run_case
from test_sweep import SCENARIO

distributed = pytest.importorskip("distributed")

BASE = tomllib.loads(SCENARIO)
OVER = {"pipe.wall_thickness": [0.015, 0.02]}
WAIT = 90.0  # s: the longest any helper thread waits for the sweep to get somewhere


def slow_once(markers: str, slow: float, case: dict[str, Any]) -> dict[str, Any]:
    """The case's scenario; on the first attempt of the case with wall thickness `slow` (m), a run to
    t_end = 1e6 s (killable: it would take minutes), its process id written to ``markers/slow``. Every call's
    process id is appended to ``markers/calls-<thickness>``."""
    data = apply_overrides(BASE, case)
    thickness = case["pipe.wall_thickness"]
    with (Path(markers) / f"calls-{thickness}").open("a") as calls:
        calls.write(f"{os.getpid()}\n")
    marker = Path(markers) / "slow"
    if thickness == slow and not marker.exists():
        marker.write_text(str(os.getpid()))
        data["solver"]["t_end"] = 1e6
    return data


def deadly(markers: str, value: float, case: dict[str, Any]) -> dict[str, Any]:
    """The case's scenario, except that the case with wall thickness `value` (m) kills its own worker (SIGKILL),
    every time, after appending its process id to ``markers/deaths``."""
    if case["pipe.wall_thickness"] == value:
        with (Path(markers) / "deaths").open("a") as deaths:
            deaths.write(f"{os.getpid()}\n")
        os.kill(os.getpid(), signal.SIGKILL)
    return apply_overrides(BASE, case)


def datasets(path: Path) -> dict[str, np.ndarray]:
    """Every variable of a results file, as stored (h5py: faster than `pl.load` for a comparison)."""
    import h5py

    with h5py.File(path, "r") as file:
        return {name: item[()] for name, item in file.items() if isinstance(item, h5py.Dataset)}


def assert_single_run(done: Any, thickness: float, tmp_path: Path) -> None:
    """The case of that wall thickness (m) finished, its file's every variable and its statistics bit for bit
    those of its single run (`run_case`, in this process); no temporary file left in the sweep's folder."""
    case = {"pipe.wall_thickness": thickness}
    here = tmp_path / f"single-{thickness}.nc"
    expected = run_case(parse_scenario(apply_overrides(BASE, case)), here)
    there = done.cases[(thickness,)]
    found, wanted = datasets(there), datasets(here)
    assert sorted(found) == sorted(wanted) and "positions" in found and "eta" in found
    for name, values in wanted.items():
        assert np.array_equal(found[name], values, equal_nan=values.dtype.kind == "f"), name
    assert json.loads(there.with_suffix(".json").read_text())["statistics"] == expected
    assert not list(done.output.rglob("*.part")), "a killed run's temporary file was left"


def in_thread(work: Callable[[], None]) -> tuple[threading.Thread, list[BaseException]]:
    """`work` started in a daemon thread, and the list its exception goes to."""
    errors: list[BaseException] = []

    def guarded() -> None:
        try:
            work()
        except BaseException as error:  # noqa: BLE001 - reported by the test
            errors.append(error)

    thread = threading.Thread(target=guarded, daemon=True)
    thread.start()
    return thread, errors


def wait_for(condition: Callable[[], bool], what: str) -> None:
    """Polls `condition` every 20 ms for at most WAIT seconds."""
    deadline = time.monotonic() + WAIT
    while not condition():
        if time.monotonic() > deadline:
            raise TimeoutError(f"waited {WAIT} s for {what}")
        time.sleep(0.02)


# --- pl.sweep at the top level of a script ---------------------------------------------------------------


def script(tmp_path: Path, name: str, guarded: bool) -> Path:
    """A script that sweeps a case on the sweep's own local cluster and prints how many finished, at its top
    level or under the main guard."""
    (tmp_path / "scenario.toml").write_text(SCENARIO)
    over = {"pipe.wall_thickness": [0.02]}
    call = (
        f"done = pl.sweep({str(tmp_path / 'scenario.toml')!r}, {over!r}, output={str(tmp_path / name)!r}, "
        "workers=1, progress=False)\nprint('finished', len(done.cases))\n"
    )
    body = (
        call
        if not guarded
        else 'if __name__ == "__main__":\n' + "".join(f"    {line}\n" for line in call.splitlines())
    )
    path = tmp_path / f"{name}.py"
    path.write_text(f"import pipelay as pl\n\n{body}")
    return path


def test_a_module_level_sweep_fails_at_once_naming_the_fix(tmp_path: Path) -> None:
    """`pl.sweep` at a script's top level: exit 1 in seconds, before any cluster or folder, the last line of
    stderr saying to put the call under the main guard, in a traceback of a few lines."""
    path = script(tmp_path, "unguarded", guarded=False)
    begun = time.perf_counter()
    done = subprocess.run(
        [sys.executable, str(path)], check=False, capture_output=True, text=True, timeout=120
    )
    elapsed = time.perf_counter() - begun
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 1, done.stderr
    assert 'if __name__ == "__main__":' in lines[-1] and lines[-1].startswith("RuntimeError: pl.sweep")
    assert len(lines) < 15 and done.stderr.count("Traceback") == 1, done.stderr
    assert not (tmp_path / "unguarded").exists()  # nothing ran
    assert elapsed < 20.0  # the imports; no cluster started


def test_under_the_main_guard_the_same_script_runs_every_case(tmp_path: Path) -> None:
    """The same call under ``if __name__ == "__main__":`` (the check has no false alarm): every case runs."""
    path = script(tmp_path, "guarded", guarded=True)
    done = subprocess.run(
        [sys.executable, str(path)], check=False, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["finished", "1"]
    assert len(list((tmp_path / "guarded" / "cases").glob("*.json"))) == 1


def test_a_module_level_sweep_without_its_source_fails_as_clearly(tmp_path: Path) -> None:
    """Run from a .pyc whose source is gone (the script cannot be read before the cluster starts): each worker
    re-running the script stops with the one-line message instead of a traceback, and the sweep raises the
    same message instead of the cluster's "Nanny failed to start" traceback."""
    import py_compile

    source = script(tmp_path, "compiled", guarded=False)
    compiled = Path(py_compile.compile(str(source), cfile=str(tmp_path / "compiled.pyc")))
    source.unlink()
    done = subprocess.run(
        [sys.executable, str(compiled)], check=False, capture_output=True, text=True, timeout=120
    )
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 1, done.stderr
    assert lines[-1].startswith("RuntimeError: pl.sweep") and 'if __name__ == "__main__":' in lines[-1]
    assert lines[-1].endswith("the local cluster did not start: Nanny failed to start.")
    assert lines[0].startswith("pipelay: error: pl.sweep was called from the top level of a script")
    assert len(lines) < 20 and done.stderr.count("Traceback") == 1, done.stderr


# --- workers that die ------------------------------------------------------------------------------------


def test_a_worker_killed_mid_case_is_restarted_and_the_case_run_again(tmp_path: Path) -> None:
    """SIGKILL to the worker process while its case streams its run (the case's temporary file there, its
    record not): its nanny restarts it, the case runs again in another process and the sweep finishes with
    every case, the killed one bit for bit its single run; the killed run's temporary files are removed."""
    markers, out = tmp_path / "markers", tmp_path / "out"
    markers.mkdir()
    cases = out / "cases"
    killed: list[tuple[int, list[str]]] = []

    def kill() -> None:
        wait_for(lambda: (markers / "slow").exists(), "the slow case to start")
        # The run streams to <temporary>.part (pipelay.results.streaming) inside the atomic write's temporary.
        wait_for(lambda: any("0.02" in p.name for p in cases.glob(".*.part.part")), "its run to stream")
        pid = int((markers / "slow").read_text())
        killed.append((pid, sorted(path.name for path in cases.iterdir())))
        os.kill(pid, signal.SIGKILL)

    thread, errors = in_thread(kill)
    factory = functools.partial(slow_once, str(markers), 0.02)
    done = pl.sweep(factory, OVER, output=out, workers=2, progress=False)
    thread.join(timeout=5.0)
    assert not errors, errors
    ((pid, seen),) = killed
    assert not any("0.02-" in name and name.endswith(".json") for name in seen)  # killed mid-case
    calls = (markers / "calls-0.02").read_text().split()
    assert len(calls) == 2 and calls[0] == str(pid) and calls[1] != str(pid)  # run again, elsewhere
    assert done.failures == {} and sorted(done.cases) == [(0.015,), (0.02,)]
    assert_single_run(done, 0.02, tmp_path)


def test_a_case_that_kills_its_worker_every_time_fails_after_two_retries(tmp_path: Path) -> None:
    """The case dies with its worker on each of its 3 attempts (the sweep's cluster allows 2 retries): it is
    a failure naming the deaths, not saved (the next call tries it again), and the other cases finish."""
    markers, out = tmp_path / "markers", tmp_path / "out"
    markers.mkdir()
    factory = functools.partial(deadly, str(markers), 0.02)
    over = {"pipe.wall_thickness": [0.015, 0.02, 0.025]}
    done = pl.sweep(factory, over, output=out, workers=2, progress=False)
    deaths = (markers / "deaths").read_text().split()
    assert len(deaths) == sweeping.ALLOWED_FAILURES + 1 == 3 and len(set(deaths)) == 3
    assert list(done.failures) == [(0.02,)]
    message = done.failures[(0.02,)]
    assert message.startswith("KilledWorker: the worker running this case died 3 times")
    assert "allowed-failures = 2" in message and "next call runs it again" in message
    assert sorted(done.cases) == [(0.015,), (0.025,)]
    assert done.summary["failed"].values.tolist() == [0, 1, 0]
    assert done.summary["error"].values[1] == message
    assert len(list((out / "cases").glob("*.json"))) == 2  # the failure is this call's only


# --- the scheduler lost ----------------------------------------------------------------------------------


def test_a_lost_scheduler_stops_the_sweep_and_a_second_call_runs_only_the_rest(tmp_path: Path) -> None:
    """The test's own cluster closed from another thread while the slow case runs: ConnectionError saying so
    within seconds, the finished case's files and a summary with it kept; the same call on a fresh cluster
    (the sweep's own) leaves that case's files untouched and runs the other, bit for bit its single run."""
    markers, out = tmp_path / "markers", tmp_path / "out"
    markers.mkdir()
    factory = functools.partial(slow_once, str(markers), 0.02)
    closed: list[float] = []
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):

        def close() -> None:
            wait_for(lambda: len(list((out / "cases").glob("*0.015*.json"))) == 1, "the fast case")
            wait_for(lambda: (markers / "slow").exists(), "the slow case to start")
            closed.append(time.monotonic())
            cluster.close()

        thread, errors = in_thread(close)
        with pytest.raises(ConnectionError, match="lost the Dask scheduler at tcp://") as raised:
            pl.sweep(factory, OVER, client=client, output=out, progress=False)
        thread.join(timeout=30.0)
        assert not errors, errors
        assert time.monotonic() - closed[0] < 30.0
    assert "with 1 of the 2 cases to run not finished" in str(raised.value)
    assert "call pl.sweep again" in str(raised.value)
    kept = sorted((out / "cases").glob("*.json")) + sorted((out / "cases").glob("*.nc"))
    assert [path.suffix for path in kept] == [".json", ".nc"] and all("0.015" in p.name for p in kept)
    stamps = {path: path.stat().st_mtime_ns for path in kept}
    import xarray as xr

    with xr.open_dataset(out / "summary.nc", engine="h5netcdf") as summary:
        assert summary.attrs["finished"] == 1
        assert np.isfinite(summary["top_tension_max"].values[0]) and np.isnan(
            summary["top_tension_max"].values[1]
        )
    again = pl.sweep(factory, OVER, output=out, workers=1, progress=False)
    assert {path: path.stat().st_mtime_ns for path in kept} == stamps
    assert len((markers / "calls-0.015").read_text().split()) == 1  # not run again
    assert again.failures == {} and sorted(again.cases) == [(0.015,), (0.02,)]
    assert_single_run(again, 0.02, tmp_path)


def test_a_scheduler_that_stops_answering_is_taken_as_lost(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A scheduler process stopped (SIGSTOP: its connections stay open, it answers nothing) while a case runs:
    ConnectionError once it has not answered for SCHEDULER_TIMEOUT (2 s here), not a hang."""
    monkeypatch.setattr(sweeping, "PROBE_EVERY", 0.5)
    monkeypatch.setattr(sweeping, "SCHEDULER_TIMEOUT", 2.0)
    markers, out, address_file = tmp_path / "markers", tmp_path / "out", tmp_path / "scheduler.json"
    markers.mkdir()
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    scheduler = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
         "--dashboard-address", ":0", "--scheduler-file", str(address_file)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=environment,
    )  # fmt: skip
    worker = None
    try:
        wait_for(address_file.exists, "the scheduler")
        wait_for(lambda: "address" in address_file.read_text(), "the scheduler's address")
        address = json.loads(address_file.read_text())["address"]
        worker = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", address, "--no-nanny", "--nthreads", "1",
             "--no-dashboard"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=environment,
        )  # fmt: skip
        stopped: list[float] = []

        def stop() -> None:
            wait_for(lambda: (markers / "slow").exists(), "the slow case to start")
            stopped.append(time.monotonic())
            os.kill(scheduler.pid, signal.SIGSTOP)

        thread, errors = in_thread(stop)
        factory = functools.partial(slow_once, str(markers), 0.015)
        with pytest.raises(ConnectionError, match="no answer within 2 s"):
            pl.sweep(factory, OVER, client=address, output=out, progress=False)
        waited = time.monotonic() - stopped[0]
        thread.join(timeout=5.0)
        assert not errors, errors
        assert waited < 15.0, waited
    finally:
        for process in (worker, scheduler):
            if process is not None:
                process.kill()
                process.wait(timeout=30.0)


def test_with_no_worker_the_sweep_warns_and_waits_for_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A scheduler that answers but has no worker (an adaptive or batch cluster before its jobs start): the
    sweep warns once it has waited SCHEDULER_TIMEOUT (1 s here), and finishes when a worker comes."""
    monkeypatch.setattr(sweeping, "PROBE_EVERY", 0.2)
    monkeypatch.setattr(sweeping, "SCHEDULER_TIMEOUT", 1.0)
    (tmp_path / "scenario.toml").write_text(SCENARIO)
    with (
        distributed.LocalCluster(
            n_workers=0, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):

        def scale() -> None:
            time.sleep(2.0)
            cluster.scale(1)

        thread, errors = in_thread(scale)
        with pytest.warns(RuntimeWarning, match="has had no worker for 1 s; the sweep waits for one"):
            done = pl.sweep(
                tmp_path / "scenario.toml", {"pipe.wall_thickness": [0.02]}, client=client, output=tmp_path / "out",
                progress=False,
            )  # fmt: skip
        thread.join(timeout=5.0)
        assert not errors, errors
    assert done.failures == {} and list(done.cases) == [(0.02,)]
