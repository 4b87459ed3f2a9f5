"""The seabed through the tool: scenario keys, the command line's printouts, results files and figures."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay import plots
from pipelay.scenario import load_scenario, parse_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
TOUCHDOWN = (EXAMPLES / "touchdown.toml").read_text()


def cli(*args: str | Path) -> subprocess.CompletedProcess[str]:
    command = [sys.executable, "-m", "pipelay.cli", *map(str, args)]
    return subprocess.run(command, check=False, capture_output=True, text=True, timeout=300)


def short_touchdown(t_end: float = 6.0, elements: int = 100) -> str:
    """The touchdown example, coarser and shorter."""
    return (
        TOUCHDOWN.replace("t_end = 60.0", f"t_end = {t_end}")
        .replace("elements = 400", f"elements = {elements}")
        .replace("plot_times = [0.0, 21.0, 27.0]", f"plot_times = [0.0, {t_end}]")
    )


def test_scenario_builds_the_seabed_and_the_drive() -> None:
    """[sea.seabed] and a driven top: the static state touches down where the Python model does."""
    scenario = parse_scenario(tomllib.loads(short_touchdown()))
    seabed = scenario.model.sea.seabed  # type: ignore[union-attr]
    assert seabed is not None and seabed.friction == (0.5, 0.8) and seabed.mobilisation == 0.01
    state = scenario.model.static()
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0)
    rod = pl.Rod.straight((0, 0, 0), (1600, 0, 0), 100, section)
    model = pl.Model(rod, sea=pl.Sea(800.0, seabed=pl.Seabed(friction=(0.5, 0.8))))
    model.pin("A")
    model.pin("B", position=(1200, 0, -800))
    direct = model.static()
    assert state.touchdown.arc_length == direct.touchdown.arc_length  # type: ignore[union-attr]


GRID = """
[sea.seabed.bathymetry]
kind = "grid"
x = [0.0, 1000.0, 2000.0]
y = [-100.0, 100.0]
z = [[0.0, 0.0], [1.0, 1.0], [-2.0, -2.0]]
"""

BROKEN = {
    "negative stiffness": (("stiffness = 1e5", "stiffness = -1e5"), "sea.seabed.stiffness"),
    "unknown seabed key": (("mobilisation = 0.01", "mobilization = 0.01"), "sea.seabed.mobilization"),
    "negative friction": (("friction = [0.5, 0.8]", "friction = [0.5, -0.8]"), "sea.seabed.friction[1]"),
    "zero mobilisation": (("mobilisation = 0.01", "mobilisation = 0.0"), "sea.seabed.mobilisation"),
    "grid shape": (
        ("z = [[0.0, 0.0], [1.0, 1.0], [-2.0, -2.0]]", "z = [[0.0, 0.0], [1.0, 1.0]]"),
        "bathymetry.z",
    ),
    "grid order": (("x = [0.0, 1000.0, 2000.0]", "x = [0.0, 2000.0, 1000.0]"), "sea.seabed.bathymetry.x"),
    "above surface": (
        ("z = [[0.0, 0.0], [1.0, 1.0], [-2.0, -2.0]]", "z = [[0.0, 0.0], [1.0, 1.0], [-900.0, -2.0]]"),
        "sea.seabed.bathymetry",
    ),
    "drive without period": (("period = 12.0\n", ""), "supports.B.period"),
    "amplitude on a pin": (
        ('kind = "pin"\n', 'kind = "pin"\namplitude = [1.0, 0.0, 0.0]\n'),
        "supports.A.amplitude",
    ),
}


@pytest.mark.parametrize("kind", sorted(BROKEN))
def test_broken_seabed_keys_exit_2_naming_the_key(tmp_path: Path, kind: str) -> None:
    (old, new), key = BROKEN[kind]
    text = short_touchdown().replace("mobilisation = 0.01       # m", "mobilisation = 0.01") + GRID
    assert old in text, kind
    path = tmp_path / "broken.toml"
    path.write_text(text.replace(old, new, 1))
    done = cli("check", path)
    assert done.returncode == 2, (kind, done.stdout, done.stderr)
    assert key in done.stderr, (kind, done.stderr)
    assert "Traceback" not in done.stderr


def test_static_and_run_print_the_touchdown(tmp_path: Path) -> None:
    """`pipelay static` prints touchdown, laid length and the largest moment; `pipelay run` their ranges, writes
    the touchdown to netCDF and draws it."""
    path = tmp_path / "touchdown.toml"
    path.write_text(short_touchdown())
    static = cli("static", path)
    assert static.returncode == 0, static.stderr
    for text in ("touchdown", "laid length", "largest bending moment"):
        assert text in static.stdout, static.stdout
    done = cli("run", path, "-o", tmp_path / "run.nc", "--plots", tmp_path / "figures", "--no-progress")
    assert done.returncode == 0, done.stderr
    assert "touchdown (from A)" in done.stdout
    assert (tmp_path / "figures" / "touchdown.png").stat().st_size > 10_000
    results = pl.load(tmp_path / "run.nc")
    assert results.touchdown is not None and results.touchdown.shape == (len(results), 3)
    assert np.all(np.isfinite(results.touchdown_arc_length))


def test_netcdf_round_trip_keeps_the_seabed_series(tmp_path: Path) -> None:
    """Touchdown, its arc length, the laid length and the seabed energy come back bit for bit."""
    scenario = load_scenario(EXAMPLES / "touchdown.toml")
    model = scenario.model
    results = model.simulation(state=model.static(), dt=0.2).run(2.0, progress=False)
    back = pl.load(results.to_netcdf(tmp_path / "run.nc"))
    for name in ("touchdown", "touchdown_arc_length", "laid_length"):
        np.testing.assert_array_equal(getattr(back, name), getattr(results, name))
    np.testing.assert_array_equal(back.energy["seabed"], results.energy["seabed"])
    figure = plots.touchdown_path(back)
    assert len(figure.axes) == 2
    with pytest.raises(ValueError, match="seabed"):
        plots.touchdown_path(pl.load(_run_without_seabed(tmp_path)))


def _run_without_seabed(tmp_path: Path) -> Path:
    rod = pl.Rod.straight((0, 0, 0), (100, 0, 0), 5, pl.Section.pipe(0.3, 0.01, contents_density=1025.0))
    model = pl.Model(rod, sea=pl.Sea(100.0))
    model.pin("A")
    model.pin("B", position=(90, 0, -30))
    return model.simulation(dt=0.5).run(1.0, progress=False).to_netcdf(tmp_path / "plain.nc")
