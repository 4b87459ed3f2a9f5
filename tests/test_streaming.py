"""Runs streamed to a netCDF file (``Simulation.run(..., output=path, record=groups)``): the file equals the
in-memory run across segments (the energy ledger carried over), a chosen subset of groups, a failed or interrupted
run keeps its file, pay-out grows the node dimension, the ``.part`` file is readable while the run goes and after
the process is killed, and memory stays flat with the simulated time."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import h5netcdf
import numpy as np
import pipelay as pl
import pytest
import xarray as xr
from pipelay import streaming
from pipelay.results import GROUPS, _arrays

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import jensen2009 as paper

LEDGER = ("supplied_work", "dissipated", "pay_out_energy")
SECTION = pl.Section.pipe(0.3, 0.02, contents_density=0.0, drag=(0.1, 1.0), added_mass=(0.0, 1.0))


@pytest.fixture(autouse=True)
def small_segments(monkeypatch: pytest.MonkeyPatch) -> None:
    """Segments of 7 records, so that every run here is streamed in several."""
    monkeypatch.setattr(streaming, "SEGMENT_RECORDS", 7)


def _hanging(position=None, speed=None, elements: int = 20) -> pl.Model:
    """A 100 m pipe hanging in 300 m of water from end B, held by a drive at `position(t)` (default: the origin)."""
    model = pl.Model(pl.Rod.straight((0, 0, 100), (0, 0, 0), elements, SECTION), sea=pl.Sea(300.0))
    model.drive("B", position=position or (lambda t: np.zeros(3)))
    if speed is not None:
        model.pay_out("B", speed=speed)
    return model


def _assert_same(memory: pl.Results, streamed: pl.Results) -> None:
    """Every array of the two results equal, bit for bit (NaN padding included); the energy ledger to its last bit
    (one unit in the last place where re-basing it on a segment's start rounds a tie the other way)."""
    ours, theirs = _arrays(memory), _arrays(streamed)
    assert sorted(ours) == sorted(theirs)
    assert np.array_equal(memory.time, streamed.time)
    for name, value in ours.items():
        if name in LEDGER:
            np.testing.assert_array_max_ulp(value, theirs[name], maxulp=1)
        else:
            assert np.array_equal(value, theirs[name], equal_nan=True), name


@pytest.fixture(scope="module")
def paper_state() -> tuple[pl.Model, pl.State]:
    model = paper.scenario(paper.controllers()["PID"])
    return model, model.static()


def test_streamed_file_equals_the_in_memory_run(paper_state, tmp_path: Path) -> None:
    """The paper's PID scenario (vessel, lay summary), 40.1 s at Δt = 0.25 s recording every 2nd step in segments of
    7 records (the last one not ending on a record): the file holds every record of the in-memory run, with its
    variables, dimensions and attributes; the run returns the last record."""
    model, state = paper_state
    memory = model.simulation(state, dt=0.25)
    expected = memory.run(40.1, progress=False, record_every=2)
    simulation = model.simulation(state, dt=0.25)
    path = tmp_path / "run.nc"
    last = simulation.run(40.1, progress=False, record_every=2, output=path)
    assert simulation.time == memory.time  # the same 161 steps
    assert np.array_equal(simulation.state.positions, memory.state.positions)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc"]  # the .part file renamed
    back = pl.load(path)
    assert len(back) == len(expected) == 81
    _assert_same(expected, back)
    assert back.passivity_margin() == pytest.approx(expected.passivity_margin(), abs=1e-6)
    with xr.open_dataset(path, engine="h5netcdf") as streamed:
        reference = expected.to_xarray()
        assert dict(streamed.sizes) == dict(reference.sizes)
        assert set(streamed.variables) == set(reference.variables)
        for name in reference.variables:
            assert streamed[name].dims == reference[name].dims, name
            assert streamed[name].attrs == reference[name].attrs, name
        assert streamed.attrs["recorded_groups"] == " ".join(GROUPS)
        assert {"time", "node", "element"} <= set(streamed.encoding["unlimited_dims"])
    assert len(last) == 1 and last.time[0] == expected.time[-1]
    assert np.array_equal(last.positions[0], expected.positions[-1])
    assert np.array_equal(last.eta[0], expected.eta[-1])
    assert last.lay_summary()["top_tension"][0] == expected.lay_summary()["top_tension"][-1]
    np.testing.assert_array_max_ulp(last.supplied_work, expected.supplied_work[-1:], maxulp=1)


def test_a_continued_run_carries_its_own_ledger(paper_state, tmp_path: Path) -> None:
    """A simulation already run to 10 s, streamed on to 25 s: the ledger counts from 10 s as the engine's run
    does (supplied work and dissipation non-zero at the start)."""
    model, state = paper_state
    memory, streamed = model.simulation(state, dt=0.25), model.simulation(state, dt=0.25)
    memory.run(10.0, progress=False)
    streamed.run(10.0, progress=False)
    assert streamed.supplied_work != 0.0 and streamed.dissipated > 0.0
    expected = memory.run(25.0, progress=False)
    streamed.run(25.0, progress=False, output=tmp_path / "more.nc")
    back = pl.load(tmp_path / "more.nc")
    assert back.time[0] == 10.0 and back.supplied_work[0] == 0.0 and back.dissipated[0] == 0.0
    _assert_same(expected, back)


def test_a_subset_of_groups_and_bad_names(paper_state, tmp_path: Path) -> None:
    """record=("vessel", "energy"): only those variables (and time) are written; pl.load then says which groups it
    lacks. Dropping only the optional groups loads without them. Unknown groups are InputErrors."""
    model, state = paper_state
    path = tmp_path / "vessel.nc"
    model.simulation(state, dt=0.25).run(5.0, progress=False, output=path, record=("vessel", "energy"))
    with h5netcdf.File(path, "r") as file:
        written = {name for name in file.variables if name in pl.results.LAYOUT}
        # The thrusters' series, the observer's estimate and the passivity observer's exist only with allocation,
        # an observer and a controller that books its passivity.
        optional = {
            "thrust",
            "azimuth",
            "eta_estimate",
            "passivity_reserve",
            "passivity_withheld",
            "passivity_steps",
        }
        assert written == (set(GROUPS["vessel"]) - optional) | set(GROUPS["energy"])
        assert file.dimensions["time"].size == 21
    with pytest.raises(
        pl.InputError, match=r"path: .*without positions, rotations, velocities, section_forces"
    ):
        pl.load(path)
    core = ("positions", "rotations", "velocities", "section_forces", "reactions", "energy")
    path = tmp_path / "core.nc"
    expected = model.simulation(state, dt=0.25).run(5.0, progress=False)
    model.simulation(state, dt=0.25).run(5.0, progress=False, output=path, record=core)
    back = pl.load(path)
    assert back.eta is None and back.lay_summary() is None
    assert np.array_equal(back.positions, expected.positions)
    assert np.array_equal(back.reaction("B"), expected.reaction("B"))
    simulation = model.simulation(state, dt=0.25)
    with pytest.raises(pl.InputError, match=r"record: .*'positions'.*'lay'.*got \('vessel', 'tides'\)"):
        simulation.run(5.0, progress=False, output=tmp_path / "bad.nc", record=("vessel", "tides"))
    with pytest.raises(pl.InputError, match="record: only with an output file"):
        simulation.run(5.0, progress=False, record=("vessel",))
    with pytest.raises(pl.InputError, match="record_every"):
        simulation.run(5.0, progress=False, record_every=0, output=tmp_path / "bad.nc")
    assert simulation.time == 0.0 and not (tmp_path / "bad.nc").exists()
    assert not (tmp_path / "bad.nc.part").exists()


def test_a_failed_run_keeps_every_record_before_the_error(tmp_path: Path) -> None:
    """A drive that fails at t = 1 s: the InputError is raised again, the file is in place (no .part) with every
    record before the error, as the in-memory run's error keeps them; the error's results hold the last one."""

    def position(t: float) -> np.ndarray:
        if t > 1.0 - 1e-9:
            raise RuntimeError("drive lost")
        return np.array([0.5 * np.sin(2.0 * t), 0.0, 0.0])

    model = _hanging(position)
    state = model.static()
    with pytest.raises(pl.InputError) as memory:
        model.simulation(state, dt=0.05).run(3.0, progress=False)
    path = tmp_path / "failed.nc"
    with pytest.raises(pl.InputError) as streamed:
        model.simulation(state, dt=0.05).run(3.0, progress=False, output=path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["failed.nc"]
    expected = memory.value.results
    assert len(expected) == 20 and expected.time[-1] == pytest.approx(0.95)
    _assert_same(expected, pl.load(path))
    assert len(streamed.value.results) == 1 and streamed.value.results.time[0] == expected.time[-1]


def test_ctrl_c_keeps_the_records_so_far(tmp_path: Path) -> None:
    """SIGINT during a streamed run (sent from the drive at t = 1 s): the run stops with the engine's warning, the
    file holds the records up to there and the last one is returned."""
    sent = []

    def position(t: float) -> np.ndarray:
        if t > 1.0 - 1e-9 and not sent:
            sent.append(t)
            os.kill(os.getpid(), signal.SIGINT)
        return np.zeros(3)

    model = _hanging(position)
    path = tmp_path / "stopped.nc"
    with pytest.warns(UserWarning, match="run interrupted"):
        last = model.simulation(model.static(), dt=0.05).run(30.0, progress=False, output=path)
    back = pl.load(path)
    assert 0.9 <= back.time[-1] < 1.5 and len(back) == round(back.time[-1] / 0.05) + 1
    assert last.time[0] == back.time[-1]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["stopped.nc"]


def test_pay_out_grows_the_node_dimension(tmp_path: Path) -> None:
    """Paying out 1 m/s for 8 s splits the end element at 2.55 s and 7.55 s, in the 3rd and 8th segments: the
    file's node dimension grows and the earlier records' extra nodes are NaN, exactly as in memory."""
    model = _hanging(speed=1.0)
    state = model.static()
    expected = model.simulation(state, dt=0.05).run(8.0, progress=False)
    model.simulation(state, dt=0.05).run(8.0, progress=False, output=tmp_path / "paid.nc")
    back = pl.load(tmp_path / "paid.nc")
    assert expected.nodes == back.nodes == 23
    counts = np.sum(~np.isnan(back.positions[:, :, 0]), axis=1)
    assert list(np.unique(counts)) == [21, 22, 23] and counts[50] == 21 and counts[51] == 22
    assert np.isnan(back.section_forces[0, 20:]).all() and not np.isnan(back.positions[-1]).any()
    assert back.length[-1] == pytest.approx(108.0)
    _assert_same(expected, back)


def test_the_part_file_is_readable_while_the_run_goes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Opened from the drive at t = 2 s (step 40, in the 4th segment of 10 records): the .part file holds the 31
    records of the first three segments; the final file does not exist yet."""
    path = tmp_path / "live.nc"
    seen: list[tuple[int, float, bool]] = []

    def position(t: float) -> np.ndarray:
        if t > 2.0 - 1e-9 and not seen:
            with xr.open_dataset(tmp_path / "live.nc.part", engine="h5netcdf") as data:
                seen.append((data.sizes["time"], float(data["time"][-1]), path.exists()))
                assert not np.isnan(data["positions"].values).any()
        return np.array([0.3 * np.sin(t), 0.0, 0.0])

    monkeypatch.setattr(streaming, "SEGMENT_RECORDS", 10)
    model = _hanging(position)
    model.simulation(model.static(), dt=0.05).run(3.0, progress=False, output=path)
    assert seen == [(31, pytest.approx(1.5), False)]
    assert len(pl.load(path)) == 61


KILLED = """
import os, signal
import numpy as np
import pipelay as pl
from pipelay import streaming

streaming.SEGMENT_RECORDS = 10
section = pl.Section.pipe(0.3, 0.02, contents_density=0.0, drag=(0.1, 1.0), added_mass=(0.0, 1.0))
model = pl.Model(pl.Rod.straight((0, 0, 100), (0, 0, 0), 20, section), sea=pl.Sea(300.0))

def position(t):
    if t > 2.0 - 1e-9:
        os.kill(os.getpid(), signal.SIGKILL)
    return np.array([0.3 * np.sin(t), 0.0, 0.0])

model.drive("B", position=position)
model.simulation(model.static(), dt=0.05).run(10.0, progress=False, output={path!r})
"""


def test_a_killed_run_leaves_a_readable_part_file(tmp_path: Path) -> None:
    """SIGKILL in the middle of the 4th segment: the .part file is a valid netCDF file with the 31 records of the
    first three segments."""
    path = tmp_path / "killed.nc"
    done = subprocess.run(
        [sys.executable, "-c", KILLED.format(path=str(path))],
        check=False,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == -signal.SIGKILL, done.stderr
    assert not path.exists()
    with xr.open_dataset(tmp_path / "killed.nc.part", engine="h5netcdf") as data:
        assert data.sizes["time"] == 31 and float(data["time"][-1]) == pytest.approx(1.5)
        assert not np.isnan(data["positions"].values).any()


MEMORY = """
import numpy as np
import pipelay as pl
from pipelay import streaming

streaming.SEGMENT_RECORDS = 50
section = pl.Section.pipe(0.3, 0.02, contents_density=0.0, drag=(0.1, 1.0), added_mass=(0.0, 1.0))
model = pl.Model(pl.Rod.straight((0, 0, 100), (0, 0, 0), 200, section), sea=pl.Sea(300.0))
model.drive("B", position=lambda t: np.array([2.0 * np.sin(0.5 * t), 0.0, 0.0]))
simulation = model.simulation(model.static(), dt=0.1)
simulation.run({t_end}, progress=False, output={output})
# The process's own peak RSS (VmHWM; getrusage's ru_maxrss would report the parent's when it is larger).
print(next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM")) / 1024)
"""


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="peak RSS from /proc (Linux)")
def test_memory_stays_flat_when_streamed(tmp_path: Path) -> None:
    """Peak RSS of a 200-element run, 250 and 1000 records (each in a fresh process): in memory it grows by the
    750 records' ~26 MB; streamed in segments of 50 records by less than 3 MB."""

    def peak(t_end: float, output: Path | None) -> float:
        code = MEMORY.format(t_end=t_end, output=repr(str(output)) if output else None)
        done = subprocess.run(
            [sys.executable, "-c", textwrap.dedent(code)],
            check=False,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert done.returncode == 0, done.stderr
        return float(done.stdout.split()[-1])

    memory = peak(100.0, None) - peak(25.0, None)
    streamed = peak(100.0, tmp_path / "b.nc") - peak(25.0, tmp_path / "a.nc")
    print(f"peak RSS growth from 250 to 1000 records: in memory {memory:.1f} MB, streamed {streamed:.1f} MB")
    assert memory > 20.0
    assert streamed < 3.0
