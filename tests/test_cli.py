"""The ``pipelay`` command line end to end, in subprocesses: run, static, check, plot; exit codes; broken
scenario files (exit 2, the key named, no traceback); Ctrl-C keeping the results; resuming a run."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PAPER = (EXAMPLES / "jensen2009.toml").read_text()


def cli(*args: str | Path, timeout: float = 120.0) -> subprocess.CompletedProcess[str]:
    """Runs ``python -m pipelay.cli ARGS``."""
    command = [sys.executable, "-m", "pipelay.cli", *map(str, args)]
    return subprocess.run(command, check=False, capture_output=True, text=True, timeout=timeout)


def scenario(tmp_path: Path, text: str, name: str = "scenario.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def short_paper(t_end: float, dt: float = 0.5) -> str:
    """The paper's scenario cut to `t_end` seconds at step `dt`."""
    cut = PAPER.replace("dt = 0.25", f"dt = {dt}").replace("t_end = 200.0", f"t_end = {t_end}")
    return cut.replace("plot_times = [0.0, 30.0, 200.0]", f"plot_times = [0.0, {t_end}]")


def test_the_console_script_is_installed() -> None:
    script = Path(sys.executable).parent / "pipelay"
    assert script.exists()
    done = subprocess.run([str(script), "--help"], check=False, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "run" in done.stdout and "static" in done.stdout


def test_run_writes_results_plots_and_a_checkpoint(tmp_path: Path) -> None:
    """`pipelay run` on the paper's scenario (40 s): exit 0, a netCDF file pl.load reads, five figures."""
    path = scenario(tmp_path, short_paper(40.0))
    done = cli("run", path, "-o", tmp_path / "out.nc", "--plots", tmp_path / "plots", "--no-progress",
               "--checkpoint", tmp_path / "state.npz")  # fmt: skip
    assert done.returncode == 0, done.stderr
    results = pl.load(tmp_path / "out.nc")
    assert results.time[-1] == pytest.approx(40.0) and len(results) == 81
    assert results.eta[-1, 0] > 740.0  # the PD has started pulling the vessel towards x = 780 m
    figures = sorted(p.name for p in (tmp_path / "plots").iterdir())
    assert figures == [
        "energy.png",
        "shape.png",
        "tension_bending.png",
        "top_tension.png",
        "vessel_motion.png",
    ]
    assert all((tmp_path / "plots" / f).stat().st_size > 10_000 for f in figures)
    assert (tmp_path / "state.npz").stat().st_size > 0
    again = cli("plot", tmp_path / "out.nc", "--plots", tmp_path / "again")
    assert again.returncode == 0, again.stderr
    assert len(list((tmp_path / "again").iterdir())) == 5


def test_resumed_run_equals_the_uninterrupted_one(tmp_path: Path) -> None:
    """20 s, checkpoint, then 20 → 40 s with --resume: the same records as one 40 s run."""
    first = cli("run", scenario(tmp_path, short_paper(20.0), "a.toml"), "-o", tmp_path / "a.nc", "--no-progress",
                "--checkpoint", tmp_path / "a.npz")  # fmt: skip
    assert first.returncode == 0, first.stderr
    second = cli("run", scenario(tmp_path, short_paper(40.0), "b.toml"), "-o", tmp_path / "b.nc", "--no-progress",
                 "--resume", tmp_path / "a.npz")  # fmt: skip
    assert second.returncode == 0, second.stderr
    whole = cli(
        "run", scenario(tmp_path, short_paper(40.0), "c.toml"), "-o", tmp_path / "c.nc", "--no-progress"
    )
    assert whole.returncode == 0, whole.stderr
    resumed, uninterrupted = pl.load(tmp_path / "b.nc"), pl.load(tmp_path / "c.nc")
    tail = slice(40, None)  # records from t = 20 s
    assert np.array_equal(resumed.time, uninterrupted.time[tail])
    assert np.array_equal(resumed.positions, uninterrupted.positions[tail])
    assert np.array_equal(resumed.eta, uninterrupted.eta[tail])


def test_static_and_check(tmp_path: Path) -> None:
    done = cli("static", EXAMPLES / "hanging_pipe.toml", "--plots", tmp_path)
    assert done.returncode == 0, done.stderr
    assert "top tension" in done.stdout and "2917.7 kN" in done.stdout
    assert (tmp_path / "tension_bending.png").stat().st_size > 10_000
    checked = cli("check", EXAMPLES / "jensen2009.toml")
    assert checked.returncode == 0 and "valid" in checked.stdout


BROKEN = {
    "negative diameter": (PAPER.replace("outer_diameter = 0.60", "outer_diameter = -0.6"), "outer_diameter"),
    "wrong type": (PAPER.replace("elements = 10", 'elements = "ten"'), "rod.elements"),
    "wrong shape": (
        PAPER.replace("eta = [730.0, 0.0, -800.0, 0.0, 0.0, 0.0]", "eta = [730.0, 0.0]"),
        "vessel.eta",
    ),
    "unknown key": (PAPER.replace("depth = 800.0", "depht = 800.0"), "sea.depht"),
    "unknown section": (PAPER.replace("[solver]", "[solvr]"), "solvr"),
    "missing key": (PAPER.replace("depth = 800.0\n", ""), "sea.depth"),
    "bad current kind": (PAPER.replace('kind = "linear"', 'kind = "tidal"'), "sea.current.kind"),
    "bad support kind": (PAPER.replace('kind = "clamp"', 'kind = "weld"'), "supports.A.kind"),
    "nan": (PAPER.replace("t_end = 200.0", "t_end = nan"), "solver.t_end"),
    "syntax error": (PAPER.replace("[sea]", "[sea"), "line"),
    "bad end": (PAPER.replace('end = "B"', 'end = "C"'), "vessel.end"),
    "negative time step": (PAPER.replace("dt = 0.25", "dt = -0.25"), "solver.dt"),
}


@pytest.mark.parametrize("kind", sorted(BROKEN))
def test_broken_scenarios_exit_2_naming_the_key(tmp_path: Path, kind: str) -> None:
    text, key = BROKEN[kind]
    path = scenario(tmp_path, text)
    for command in (("check", path), ("run", path, "-o", tmp_path / "out.nc", "--no-progress")):
        done = cli(*command)
        assert done.returncode == 2, (kind, done.stdout, done.stderr)
        assert key in done.stderr, (kind, done.stderr)
        assert "Traceback" not in done.stderr
    assert not (tmp_path / "out.nc").exists()


def test_missing_files_exit_2(tmp_path: Path) -> None:
    done = cli("run", tmp_path / "none.toml", "-o", tmp_path / "out.nc")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    done = cli("plot", tmp_path / "none.nc", "--plots", tmp_path)
    assert done.returncode == 2 and "Traceback" not in done.stderr


@pytest.mark.skipif(os.name != "posix", reason="SIGINT delivery")
def test_ctrl_c_keeps_the_results_so_far(tmp_path: Path) -> None:
    """SIGINT during a long run: exit 130, and the results computed so far are written."""
    long = short_paper(100000.0, dt=0.25).replace("elements = 10", "elements = 200")
    path = scenario(tmp_path, long)
    command = [
        sys.executable,
        "-m",
        "pipelay.cli",
        "run",
        str(path),
        "-o",
        str(tmp_path / "out.nc"),
        "--no-progress",
    ]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(4.0)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=120)
    assert process.returncode == 130, stderr
    assert "interrupted" in stderr and "Traceback" not in stderr
    results = pl.load(tmp_path / "out.nc")
    assert 1 < len(results) and results.time[-1] < 100000.0
