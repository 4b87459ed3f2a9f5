"""Fatigue of a run: hot-spot stresses, damage along the line and over a scatter diagram, `pipelay fatigue`.

The references: a constant-amplitude bending history whose damage is n/N of the S-N curve by hand; the wall
force at the free end of a pipe hanging in water, −p_e·A_e (Sparks' effective tension, zero there); the
weighting of a scatter diagram, hours · Σ p_i d_i summed by hand from single runs of its sea states.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
import xarray as xr
from dp_in_waves import scenario_text
from pipelay import cli, fatigue
from pipelay.results.netcdf import _arrays
from pipelay.scenario import apply_overrides, parse_scenario

# The tests' DP vessel in waves (tests/dp_in_waves.py): 150 records of 0.4 s, about a second a run.
SCENARIO = scenario_text("fatigue test: DP vessel in waves, pipe on the seabed")
SCATTER = "# two sea states\nhs,tp,heading,probability\n1.5,7.0,0.0,0.3\n3.0,9.0,45.0,0.7\n"
START = 20.0  # s: the waves' ramp and the transient left out


def single_run(case: dict[str, Any]) -> pl.Results:
    """A sea state run here, in memory, the scenario's keys set by hand."""
    scenario = parse_scenario(apply_overrides(tomllib.loads(SCENARIO), case))
    state = scenario.model.static()
    simulation = scenario.model.simulation(state=state, dt=scenario.dt)
    return simulation.run(scenario.t_end, record_every=scenario.record_every)


@pytest.fixture(scope="module")
def run() -> pl.Results:
    return single_run({})


def test_results_carry_the_walls_and_the_sea_through_their_files(run: pl.Results, tmp_path: Path) -> None:
    """A run records its segments' steel walls and its sea, and a file read back has them: what the stresses
    need without the model."""
    assert run.pipe_walls == [(0.6, 0.03)] and run.water == (800.0, 1025.0)
    back = pl.load(run.to_netcdf(tmp_path / "run.nc"))
    assert back.pipe_walls == run.pipe_walls and back.water == run.water
    one = fatigue.damage(run, fatigue.SNCurve.dnv("D", environment="seawater_cp"), start=START)
    two = fatigue.damage(back, fatigue.SNCurve.dnv("D", environment="seawater_cp"), start=START)
    np.testing.assert_array_equal(one.values, two.values)


def sine_results(
    run: pl.Results, amplitude: float, axial: float, periods: int, per_period: int
) -> pl.Results:
    """`run`'s arrays with its section forces replaced: every element carries the axial force `axial` (N) and a
    bending moment M2 = amplitude·cos(2π t / 10 s), sampled `per_period` times a period over `periods`."""
    count = periods * per_period + 1
    arrays = {name: value[:count] for name, value in _arrays(run).items()}
    time = np.arange(count) * 10.0 / per_period
    forces = np.zeros_like(arrays["section_forces"])
    forces[:, :, 0] = axial
    forces[:, :, 4] = amplitude * np.cos(2.0 * np.pi * time / 10.0)[:, None]
    arrays.update(time=time, section_forces=forces)
    results = pl.Results._from_arrays(run.nodes, arrays)
    return results._with_line(run.pipe_walls, None)


def test_a_constant_amplitude_bending_cycle_gives_n_over_n(run: pl.Results) -> None:
    """M2 = M0 cos ωt: at the hot spot θ = 90° the stress range is 2·SCF·M0·r/I and the damage over the
    duration is (cycles in the record)·(duration / record)/N(Δσ), N by hand from DNV-RP-C203's formula; at
    θ = 0 the bending stress is nil (the axial stress is constant) and so is the damage; at 45° the range
    is cos 45° smaller."""
    d, t = 0.6, 0.03
    inner = d - 2 * t
    second_moment = math.pi / 64 * (d**4 - inner**4)
    amplitude, periods, scf = 2.0e6, 15, 1.25
    results = sine_results(run, amplitude, axial=3e5, periods=periods, per_period=8)
    curve = fatigue.SNCurve.dnv("D", environment="air", thickness=t)
    found = fatigue.damage(results, curve, scf=scf, duration=3600.0)
    stress_range = 2 * scf * amplitude * (d / 2) / second_moment / 1e6  # MPa
    factor = (t / 0.025) ** 0.20  # the thickness effect of the D curve, t > 25 mm
    assert stress_range * factor > curve.switch_stress_range  # on the first slope: m = 3, log a = 12.164
    n_cycles = 10.0 ** (12.164 - 3.0 * math.log10(stress_range * factor))
    expected = periods * (3600.0 / (periods * 10.0)) / n_cycles
    angles = np.degrees(found.angles)
    assert found.values.shape == (12, 8) and found.duration == 3600.0 and found.record == periods * 10.0
    np.testing.assert_allclose(found.values[:, angles == 90.0], expected, rtol=1e-12)
    np.testing.assert_allclose(found.values[:, angles == 0.0], 0.0, atol=1e-30)
    low = 10.0 ** (12.164 - 3.0 * math.log10(stress_range * factor * math.cos(math.pi / 4)))
    np.testing.assert_allclose(
        found.values[:, angles == 45.0], periods * 3600.0 / (periods * 10.0) / low, rtol=1e-9
    )
    assert found.max() == pytest.approx(expected, rel=1e-12)
    assert math.degrees(found.worst()[1]) in (90.0, 270.0)  # where sin θ = ±1


def test_the_free_end_of_a_hanging_pipe_has_the_wall_force_minus_pe_ae() -> None:
    """A pipe hanging in water from its top with a free lower end: the effective tension there is ≈ 0, so the
    steel carries the compression −p_e·A_e (Sparks) and the hot-spot stress at the bottom element is
    (S − p_e A_e)/A_s, the same all around (no bending)."""
    d, t, depth, length = 0.4, 0.02, 500.0, 300.0  # end A 350 m deep, end B 50 m below the surface
    section = pl.Section.pipe(outer_diameter=d, wall_thickness=t, contents_density=0.0)
    rod = pl.Rod.straight((0.0, 0.0, -150.0), (0.0, 0.0, -150.0 - length), 30, section)
    model = pl.Model(rod, pl.Sea(depth))
    model.pin("B")
    state = model.static()
    results = model.simulation(state=state, dt=0.05).run(0.5)
    stresses = fatigue.hot_spot_stresses(results)
    bottom = results.section_forces[-1, 0]
    z = 0.5 * (results.positions[-1, 0, 2] + results.positions[-1, 1, 2])
    pressure = 1025.0 * 9.81 * (depth + z)
    area = math.pi / 4 * (d**2 - (d - 2 * t) ** 2)
    expected = (bottom[0] - pressure * math.pi / 4 * d**2) / area
    assert abs(bottom[0]) < 0.01 * pressure * math.pi / 4 * d**2  # S ≈ 0 at the free end
    np.testing.assert_allclose(stresses.stress[-1, 0], expected, rtol=1e-3)
    assert expected < -4e6  # compression of ~ −ρ g z D²/(4 A_s)


def test_dirlik_and_narrow_band_on_a_run_bracket_rainflow(run: pl.Results) -> None:
    """On the run's wave-frequency stresses at the worst element, Dirlik's damage is within 10 % of rainflow's
    (measured: −1.6 %, from a 40 s record of about ten wave cycles) and the narrow-band one above both
    (measured: +5.6 %)."""
    curve = fatigue.SNCurve.dnv("D", environment="seawater_cp")
    counted = fatigue.damage(run, curve, start=START)
    element, _ = counted.worst()
    dirlik = fatigue.damage(run, curve, start=START, method="dirlik")
    narrow = fatigue.damage(run, curve, start=START, method="narrow_band")
    assert counted.max() > 0.0
    assert dirlik.values[element].max() == pytest.approx(counted.values[element].max(), rel=0.10)
    assert narrow.values[element].max() > max(dirlik.values[element].max(), counted.values[element].max())


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("fatigue")
    (path / "scenario.toml").write_text(SCENARIO)
    (path / "scatter.csv").write_text(SCATTER)
    return path


def standby(folder: Path, curve: fatigue.SNCurve) -> fatigue.ScatterDamage:
    """The 72 h standby over SCATTER, its sea states run on one local worker (finished ones reused)."""
    return fatigue.scatter_damage(
        folder / "scenario.toml",
        folder / "scatter.csv",
        curve,
        hours=72.0,
        start=START,
        output=folder / "out",
        workers=1,
        progress=False,
    )


def test_the_scatter_diagram_weights_each_sea_state_by_its_probability(folder: Path) -> None:
    """D = hours · (p1 d1 + p2 d2) at every hot spot, d_i the damage per hour of sea state i run on its own
    (here, in memory); each sea state's run is the scenario with its Hs, Tp and direction."""
    curve = fatigue.SNCurve.dnv("E", environment="seawater_cp", thickness=0.03)
    found = standby(folder, curve)
    by_hand = np.zeros((12, 8))
    for hs, tp, heading, probability in ((1.5, 7.0, 0.0, 0.3), (3.0, 9.0, 45.0, 0.7)):
        case = {"sea.waves.hs": hs, "sea.waves.tp": tp, "sea.waves.direction": math.radians(heading)}
        by_hand += probability * fatigue.damage(single_run(case), curve, start=START, duration=3600.0).values
    np.testing.assert_allclose(found.values, 72.0 * by_hand, rtol=1e-12)
    assert not found.failures and sorted(found.cases) == [0, 1]
    assert found.max() == pytest.approx(72.0 * by_hand.max(), rel=1e-12)
    assert found.hourly[1].max() > found.hourly[0].max()  # the higher sea state does more damage


def test_pipelay_fatigue_prints_and_writes_the_damage(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`pipelay fatigue` runs the scatter diagram (the finished sea states of the API's call reused) and
    writes fatigue.nc, whose damage is the API's with each segment's D curve and thickness effect."""
    code = cli.main(
        [
            "fatigue",
            str(folder / "scenario.toml"),
            "--scatter",
            str(folder / "scatter.csv"),
            "--hours",
            "72",
            "-o",
            str(folder / "out"),
            "--curve",
            "E",
            "--start",
            str(START),
            "--workers",
            "1",
            "--no-progress",
        ]
    )
    printed = capsys.readouterr().out
    assert code == 0
    with xr.open_dataset(folder / "out" / "fatigue.nc", engine="h5netcdf") as written:
        values = written["damage"].values
        assert written["probability"].values.tolist() == [0.3, 0.7]
    curve = fatigue.SNCurve.dnv("E", environment="seawater_cp", thickness=0.03)
    again = standby(folder, curve)
    np.testing.assert_allclose(values, again.values, rtol=1e-12)
    assert f"largest damage {again.max():.4g}" in printed
    assert (folder / "out" / "damage.png").stat().st_size > 10_000


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("hs,tp,probability\n1.5,7.0,0.3\n3.0,9.0,0.6\n", "scatter.probability"),
        ("hs,tp,probability\n-1.5,7.0,0.3\n3.0,9.0,0.7\n", "scatter.hs"),
        ("hs,probability\n1.5,1.0\n", "lacks tp"),
        ("hs,tp,probability\n1.5,seven,1.0\n", "column tp"),
    ],
)
def test_a_bad_scatter_table_is_an_input_error(tmp_path: Path, text: str, named: str) -> None:
    (tmp_path / "scatter.csv").write_text(text)
    with pytest.raises(pl.InputError, match=named):
        fatigue.read_scatter(tmp_path / "scatter.csv")


def test_bad_damage_arguments_are_input_errors(run: pl.Results) -> None:
    curve = fatigue.SNCurve.dnv("D")
    for arguments, named in (
        ({"scf": 0.5}, "scf"),
        ({"duration": -1.0}, "duration"),
        ({"method": "spectral"}, "method"),
        ({"points": 0}, "points"),
        ({"surface": "middle"}, "surface"),
        ({"start": 1e6}, "start"),
        ({"pipe_walls": [(0.6, 0.4)]}, "pipe_walls"),
    ):
        with pytest.raises(pl.InputError, match=named):
            fatigue.damage(run, curve, **arguments)
    with pytest.raises(pl.InputError, match="curve"):
        fatigue.damage(run, "D")  # type: ignore[arg-type]
    bare = pl.Results._from_arrays(run.nodes, {**_arrays(run), "time": run.time})
    with pytest.raises(pl.InputError, match="pipe_walls"):
        fatigue.damage(bare, curve)


def test_a_scatter_table_with_spaces_after_its_commas_reads(tmp_path: Path) -> None:
    """`hs, tp, heading, probability` names the columns hs, tp, heading and probability."""
    (tmp_path / "scatter.csv").write_text(
        "hs, tp, heading, probability\n1.5, 7.0, 30, 0.4\n2.0, 8.0, 0, 0.6\n"
    )
    found = fatigue.read_scatter(tmp_path / "scatter.csv")
    assert found.tp.tolist() == [7.0, 8.0] and found.probability.tolist() == [0.4, 0.6]
    np.testing.assert_allclose(found.heading, [math.radians(30.0), 0.0])
