"""Results files that say what is wrong with them: `pl.load` refuses a file that is not a pipelay results file
(text, empty, netCDF-3, another netCDF or HDF5 file), a truncated one and one of a newer format with an
`InputError` naming the file and the problem; both writers mark their files with the format
(`pipelay_format`); a file without it (an older pipelay's) and the `.part` file of a killed streamed run
load."""

from __future__ import annotations

import re
import signal
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import h5py
import numpy as np
import pipelay as pl
import pytest
import xarray as xr
from pipelay.results import netcdf
from test_streaming import KILLED  # the same killed run, loaded here

SECTION = pl.Section.pipe(0.3, 0.02, contents_density=0.0, drag=(0.1, 1.0), added_mass=(0.0, 1.0))


def _hanging(position: Callable[[float], np.ndarray] | None = None) -> pl.Model:
    """A 100 m pipe of 20 elements hanging in 300 m of water from end B, driven at 0.3·sin(t) m along e1."""
    model = pl.Model(pl.Rod.straight((0, 0, 100), (0, 0, 0), 20, SECTION), sea=pl.Sea(300.0))
    model.drive("B", position=position or (lambda t: np.array([0.3 * np.sin(t), 0.0, 0.0])))
    return model


@pytest.fixture(scope="module")
def run() -> pl.Results:
    """2 s at Δt = 0.05 s: 41 records."""
    model = _hanging()
    return model.simulation(model.static(), dt=0.05).run(2.0, progress=False)


@pytest.fixture
def good(run: pl.Results, tmp_path: Path) -> Path:
    return run.to_netcdf(tmp_path / "good.nc")


def _same(a: pl.Results, b: pl.Results) -> None:
    for name in ("time", "positions", "rotations", "velocities", "section_forces", "supplied_work"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


def test_both_writers_mark_the_format_and_a_good_file_round_trips(run: pl.Results, good: Path) -> None:
    """to_netcdf and a streamed run write pipelay_format = 1 (the reader's FORMAT) and the pipelay version;
    both load back bit for bit."""
    assert netcdf.FORMAT == 1
    with h5py.File(good, "r") as file:
        assert int(np.asarray(file.attrs["pipelay_format"]).item()) == 1
        assert file.attrs["pipelay_version"] == pl.__version__
    _same(run, pl.load(good))
    model = _hanging()
    streamed = good.with_name("streamed.nc")
    model.simulation(model.static(), dt=0.05).run(2.0, progress=False, output=streamed)
    with xr.open_dataset(streamed, engine="h5netcdf") as data:
        assert int(data.attrs["pipelay_format"]) == 1 and data.attrs["pipelay_version"] == pl.__version__
    _same(run, pl.load(streamed))


def test_a_file_without_a_format_from_an_older_pipelay_loads(run: pl.Results, tmp_path: Path) -> None:
    dataset = run.to_xarray()
    del dataset.attrs["pipelay_format"], dataset.attrs["pipelay_version"]
    path = tmp_path / "old.nc"
    dataset.to_netcdf(path, engine="h5netcdf")
    _same(run, pl.load(path))


def _text(path: Path, good: Path) -> None:
    path.write_text("time,tension\n0.0,1e5\n")


def _empty(path: Path, good: Path) -> None:
    path.write_bytes(b"")


def _netcdf3(path: Path, good: Path) -> None:
    xr.Dataset({"temperature": ("x", np.arange(3.0))}).to_netcdf(path, engine="scipy")


def _other_netcdf(path: Path, good: Path) -> None:
    xr.Dataset({"temperature": ("x", np.arange(3.0))}).to_netcdf(path, engine="h5netcdf")


def _plain_hdf5(path: Path, good: Path) -> None:
    with h5py.File(path, "w") as file:
        file["samples"] = np.arange(4.0)


def _half(path: Path, good: Path) -> None:
    data = good.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def _signature_only(path: Path, good: Path) -> None:
    path.write_bytes(good.read_bytes()[:5])


def _attribute(value: object) -> Callable[[Path, Path], None]:
    """A good file with its pipelay_format set to `value`."""

    def write(path: Path, good: Path) -> None:
        with xr.open_dataset(good, engine="h5netcdf") as data:
            dataset = data.load()
        dataset.attrs["pipelay_format"] = value
        dataset.to_netcdf(path, engine="h5netcdf")

    return write


def _mismatched(path: Path, good: Path) -> None:
    """A pipelay file whose series do not agree: positions for 5 nodes, the rest for 21."""
    with xr.open_dataset(good, engine="h5netcdf") as data:
        dataset = data.load()
    dataset.isel(node=slice(0, 5)).to_netcdf(path, engine="h5netcdf")


BAD_FILES = {
    "text": (_text, r"is not a pipelay results file: not a netCDF-4 \(HDF5\) file \(it starts with b'time,"),
    "empty": (_empty, r"is empty \(0 bytes\), not a pipelay results file"),
    "netCDF-3": (_netcdf3, r"is a netCDF-3 \(classic\) file, not a pipelay results file"),
    "other netCDF": (
        _other_netcdf,
        (
            r"is a netCDF-4 \(HDF5\) file but not a pipelay results file: it has none of the variables "
            r"positions, .* \(its variables: temperature\)"
        ),
    ),
    "plain HDF5": (_plain_hdf5, r"but not a pipelay results file: .*\(its variables: samples\)"),
    "half": (_half, r"is truncated: it has (\d+) of the (\d+) bytes its header announces"),
    "5 bytes": (_signature_only, r"is truncated: 5 bytes, the start of an HDF5 signature"),
    "newer": (
        _attribute(2),
        (
            r"the file's format 2 is newer than this pipelay reads \(1\); upgrade pipelay to read '.*', "
            r"written by pipelay"
        ),
    ),
    "format text": (_attribute("two"), r"has a pipelay_format attribute that is not a format number .*'two'"),
    "format 0": (_attribute(0), r"has a pipelay_format attribute that is not a format number .*got 0"),
    "mismatched": (_mismatched, r"is not a valid pipelay results file: its arrays do not make a Results"),
}


@pytest.mark.parametrize("case", BAD_FILES)
def test_a_bad_file_is_an_input_error_naming_the_file_and_the_problem(
    case: str, good: Path, tmp_path: Path
) -> None:
    write, problem = BAD_FILES[case]
    path = tmp_path / "bad.nc"
    write(path, good)
    with pytest.raises(pl.InputError) as raised:
        pl.load(path)
    message = str(raised.value)
    assert message.startswith("path: ") and repr(str(path)) in message, message
    found = re.search(problem, message)
    assert found, message
    if case == "half":  # half the bytes of the file, which its header gives whole
        assert int(found.group(1)) == good.stat().st_size // 2
        assert int(found.group(2)) == good.stat().st_size


def test_pipelay_plot_of_a_bad_file_exits_2_naming_it(
    good: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`pipelay plot` of a truncated file: exit 2 and the error, no traceback."""
    from pipelay.cli import main

    path = tmp_path / "half.nc"
    _half(path, good)
    assert main(["plot", str(path), "--plots", str(tmp_path / "figures")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"pipelay: error: path: {str(path)!r} is truncated") and "Traceback" not in err, err


def test_every_cut_of_a_file_is_an_input_error(good: Path, tmp_path: Path) -> None:
    """A file cut anywhere (at 40 places from byte 1 to its last byte but one) is an InputError naming it."""
    data = good.read_bytes()
    path = tmp_path / "cut.nc"
    for size in np.unique(np.geomspace(1, len(data) - 1, 40).astype(int)):
        path.write_bytes(data[:size])
        with pytest.raises(pl.InputError, match=re.escape(repr(str(path)))):
            pl.load(path)


def test_the_part_file_of_a_killed_run_loads(run: pl.Results, tmp_path: Path) -> None:
    """SIGKILL in the 4th segment of 10 records: pl.load reads the .part file's 31 records (0 to 1.5 s), equal
    to the in-memory run's first 31."""
    path = tmp_path / "killed.nc"
    done = subprocess.run(
        [sys.executable, "-c", KILLED.format(path=str(path))],
        check=False,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == -signal.SIGKILL, done.stderr
    back = pl.load(tmp_path / "killed.nc.part")
    assert len(back) == 31 and back.time[-1] == pytest.approx(1.5)
    assert np.array_equal(back.time, run.time[:31])
    assert np.array_equal(back.positions, run.positions[:31])
    assert np.array_equal(back.section_forces, run.section_forces[:31])


def test_a_file_of_pipelay_run_keeps_its_scenario_and_its_line(tmp_path: Path) -> None:
    """`pipelay run` writes the scenario into its results file: `scenario_of_results` builds the same model
    again (the same static state, to the bit) and keeps the table paths working from another folder; the file
    also records the pipe's wall and the sea. A file written from the API holds no scenario (None)."""
    from pipelay import cli
    from pipelay.scenario import load_scenario, scenario_of_results

    example = Path(__file__).resolve().parents[1] / "examples" / "j_lay_waves.toml"
    text = example.read_text().replace("t_end = 1290.0", "t_end = 1.0").replace("645.0, 1290.0", "0.5, 1.0")
    (tmp_path / "short.toml").write_text(text)
    assert (
        cli.main(["run", str(tmp_path / "short.toml"), "-o", str(tmp_path / "run.nc"), "--no-progress"]) == 0
    )
    stored = scenario_of_results(tmp_path / "run.nc")
    assert stored is not None and stored.origin == str(tmp_path / "short.toml")
    assert stored.source == load_scenario(tmp_path / "short.toml").source
    again = stored.model.static(steps=stored.static_steps, start=stored.static_start)
    first = load_scenario(tmp_path / "short.toml").model.static()
    assert np.array_equal(again.positions, first.positions)
    results = pl.load(tmp_path / "run.nc")
    assert results.pipe_walls == [(0.6, 0.025)] and results.water == (800.0, 1025.0)
    assert (
        scenario_of_results(
            _hanging().simulation(dt=0.05).run(0.1, progress=False).to_netcdf(tmp_path / "api.nc")
        )
        is None
    )
    with pytest.raises(pl.InputError, match="no results file"):
        scenario_of_results(tmp_path / "missing.nc")
