"""The ``pipelay`` command line end to end, in subprocesses: run, static, check, plot; exit codes; broken
scenario files (exit 2, the key named, no traceback); Ctrl-C keeping the results; resuming a run."""

from __future__ import annotations

import argparse
import itertools
import os
import re
import signal
import subprocess
import sys
import time
from importlib import metadata
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.cli import _parser
from pipelay.scenario import load_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PAPER = (EXAMPLES / "jensen2009.toml").read_text()


def cli(*args: str | Path, timeout: float = 120.0) -> subprocess.CompletedProcess[str]:
    """Runs ``python -m pipelay.cli ARGS``."""
    command = [sys.executable, "-m", "pipelay.cli", *map(str, args)]
    return subprocess.run(command, check=False, capture_output=True, text=True, timeout=timeout)


def printed(stdout: str, label: str) -> str:
    """What the summary line starting with `label` says after it."""
    return next(line for line in stdout.splitlines() if line.startswith(label))[len(label) :].strip()


def static_state(path: Path) -> pl.State:
    """The static state of a scenario file, solved here as `pipelay static` solves it."""
    found = load_scenario(path)
    return found.model.static(steps=found.static_steps, start=found.static_start)


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
    """Without a vessel the top tension is the effective axial force of the element at end B, printed beside
    the reaction's magnitude |F_B| (a standalone solve of the same file)."""
    done = cli("static", EXAMPLES / "hanging_pipe.toml", "--plots", tmp_path)
    assert done.returncode == 0, done.stderr
    state = static_state(EXAMPLES / "hanging_pipe.toml")
    assert state.lay_summary() is None
    assert (
        printed(done.stdout, "top tension")
        == f"{state.tension[-1] / 1e3:.1f} kN (effective, the element at end B)"
    )
    assert (
        printed(done.stdout, "reaction at B |F_B|")
        == f"{np.linalg.norm(state.reaction('B')[:3]) / 1e3:.1f} kN"
    )
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
    "vessel below the seabed": (
        PAPER.replace("eta = [730.0, 0.0, -800.0", "eta = [730.0, 0.0, 800.0"),
        "vessel.eta",
    ),
    "vessel above the sea": (
        PAPER.replace("eta = [730.0, 0.0, -800.0", "eta = [730.0, 0.0, -850.0"),
        "vessel.eta",
    ),
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


def test_version_is_the_installed_package_version() -> None:
    done = cli("--version")
    assert done.returncode == 0, done.stderr
    assert done.stdout == f"pipelay {metadata.version('pipelay')}\n"
    assert pl.__version__ == metadata.version("pipelay")


def test_help_describes_every_subcommand() -> None:
    """Every subcommand has a one-line description (argparse lists a subcommand without one bare, and gives it
    no entry in `_choices_actions`), and `pipelay --help` prints it beside the name."""
    commands = next(a for a in _parser()._actions if isinstance(a, argparse._SubParsersAction))
    described = {action.dest: action.help for action in commands._choices_actions}
    assert set(described) == set(commands.choices)
    done = cli("--help")
    assert done.returncode == 0, done.stderr
    flat = " ".join(done.stdout.split())
    for name, text in described.items():
        assert text and f"{name} {' '.join(str(text).split())}" in flat, name


def test_plots_directories_are_made_with_their_parents(tmp_path: Path) -> None:
    """`--plots DIR` of static, run and plot makes DIR and its parents; a file in its way fails with exit 2
    before solving."""
    figures = tmp_path / "new" / "static"
    done = cli("static", EXAMPLES / "s_lay_concrete.toml", "--plots", figures)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in figures.iterdir()) == ["lay_configuration.png", "tension_bending.png"]
    assert all(p.stat().st_size > 10_000 for p in figures.iterdir())
    path = scenario(tmp_path, short_paper(1.0))
    run = cli("run", path, "-o", tmp_path / "out.nc", "--plots", tmp_path / "new" / "run", "--no-progress")
    assert run.returncode == 0, run.stderr
    assert len(list((tmp_path / "new" / "run").iterdir())) == 5
    plotted = cli("plot", tmp_path / "out.nc", "--plots", tmp_path / "again" / "plot")
    assert plotted.returncode == 0, plotted.stderr
    assert len(list((tmp_path / "again" / "plot").iterdir())) == 5
    (tmp_path / "taken").write_text("")
    blocked = cli("static", EXAMPLES / "s_lay_concrete.toml", "--plots", tmp_path / "taken" / "figures")
    assert blocked.returncode == 2 and "Traceback" not in blocked.stderr
    assert "taken" in blocked.stderr and "static equilibrium" not in blocked.stdout


def test_the_s_lay_summary_numbers_the_rollers_from_1() -> None:
    """examples/s_lay_concrete.toml: the lift-off roller is printed as its number counted from 1, and is the
    last roller carrying a load in the reactions printed and in `roller_reactions` of a standalone solve; the
    top tension is lay_summary()["top_tension"], the reaction line |F_B|, the tip clearance lay_summary's."""
    done = cli("static", EXAMPLES / "s_lay_concrete.toml")
    assert done.returncode == 0, done.stderr
    state = static_state(EXAMPLES / "s_lay_concrete.toml")
    summary, reactions = state.lay_summary(), state.roller_reactions
    assert summary is not None and reactions is not None
    last_loaded = int(np.flatnonzero(reactions > 0)[-1]) + 1
    assert summary["liftoff_roller"] == last_loaded - 1  # Python's index into roller_reactions is 0-based
    assert printed(done.stdout, "lay: lift-off roller") == f"{last_loaded} of {len(reactions)}"
    lines = done.stdout.splitlines()
    header = next(i for i, line in enumerate(lines) if line.startswith("lay: roller reactions (kN)"))
    block = " ".join(itertools.takewhile(lambda line: line.startswith(" "), lines[header + 1 :]))
    loads = {int(k): float(v) for k, v in re.findall(r"(\d+):\s*(-?\d+\.\d)", block)}
    assert sorted(loads) == list(range(1, len(reactions) + 1))
    np.testing.assert_allclose([loads[k] for k in sorted(loads)], reactions / 1e3, atol=0.05 + 1e-9)
    assert loads[last_loaded] > 0 and all(loads[k] == 0 for k in loads if k > last_loaded)
    assert printed(done.stdout, "top tension") == (
        f"{summary['top_tension'] / 1e3:.1f} kN (effective, at the vessel's hold point)"
    )
    assert (
        printed(done.stdout, "reaction at B |F_B|")
        == f"{np.linalg.norm(state.reaction('B')[:3]) / 1e3:.1f} kN"
    )
    assert printed(done.stdout, "lay: tip clearance").startswith(
        f"{summary['tip_clearance']:.3f} m at roller {len(reactions)}"
    )
    assert printed(done.stdout, "lay: overbend strain") == f"{100 * summary['overbend_strain']:.4f} %"


def test_a_j_lay_summary_has_no_stinger_quantities() -> None:
    """examples/j_lay_dp.toml: a tower, no stinger: no overbend strain, lift-off roller, roller reactions or
    tip clearance; the departure angle, sagbend strain and top tension are the standalone solve's."""
    done = cli("static", EXAMPLES / "j_lay_dp.toml")
    assert done.returncode == 0, done.stderr
    state = static_state(EXAMPLES / "j_lay_dp.toml")
    summary = state.lay_summary()
    assert summary is not None and state.roller_reactions is None
    for absent in ("overbend", "lift-off", "roller", "tip clearance"):
        assert absent not in done.stdout, absent
    assert printed(done.stdout, "lay: departure angle") == (
        f"{np.degrees(summary['departure_angle']):.2f}° below horizontal"
    )
    assert printed(done.stdout, "lay: sagbend strain") == f"{100 * summary['sagbend_strain']:.4f} %"
    assert printed(done.stdout, "top tension") == (
        f"{summary['top_tension'] / 1e3:.1f} kN (effective, at the vessel's hold point)"
    )
    assert (
        printed(done.stdout, "reaction at B |F_B|")
        == f"{np.linalg.norm(state.reaction('B')[:3]) / 1e3:.1f} kN"
    )
