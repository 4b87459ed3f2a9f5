"""DP capability (pipelay.analysis.capability over pl._core.dp_capability_wind): the OSV's envelope is
symmetric, shrinks with the pipe's pull where the main propellers bind, is zero beyond the thrusters' own
limit, sits where the allocation saturates, holds in the time domain, and reads models, scenarios and bad
input; the polar plot, the table and the ``pipelay capability`` command."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from matplotlib.figure import Figure
from pipelay import plots
from pipelay.analysis import Capability, dp_capability
from pipelay.scenario import load_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
S_LAY = EXAMPLES / "s_lay.toml"
HEADINGS = np.radians(np.arange(0.0, 360.0, 15.0))
MAX_WIND = 60.0
TUNNELS = 4 * 200e3  # N: the OSV's sway capacity (its four tunnel thrusters; the mains push fore and aft)
MAINS = 2 * 798.72e3  # N: its surge capacity (the two main propellers)
BISECTION = 1e-3  # m/s: the engine's tolerance on the envelope's wind speed


@pytest.fixture(scope="module")
def osv() -> pl.Vessel:
    return pl.Vessel.osv()


@pytest.fixture(scope="module")
def bare(osv: pl.Vessel) -> Capability:
    """The OSV alone (no pipe), every 15°, 0.75 m/s current."""
    return dp_capability(osv, HEADINGS)


def _aft(tension: float) -> np.ndarray:
    """A pipe pulling the vessel straight aft with `tension` (N): its force on the vessel, body frame."""
    return np.array([-tension, 0.0, 0.0, 0.0, 0.0, 0.0])


def test_the_envelope_is_symmetric_port_and_starboard(bare: Capability) -> None:
    """The OSV's thrusters, wind, current and drift tables are mirror images port/starboard, so without a pipe
    the envelope at heading h equals that at 360° − h to 1e-6 (measured: equal to the bit). It is finite
    where it should be: 39.18 m/s from the beam (90°), capped at 60 m/s head-on and from astern."""
    speeds = bare.wind_speed
    for k in range(1, len(HEADINGS) // 2):
        assert speeds[k] == pytest.approx(speeds[-k], rel=1e-6), np.degrees(HEADINGS[k])
    beam = speeds[6]
    print(f"beam envelope {beam:.4f} m/s; head-on {speeds[0]:.1f}, astern {speeds[12]:.1f} m/s")
    assert 35.0 < beam < 45.0
    assert speeds[0] == MAX_WIND and speeds[12] == MAX_WIND


def test_the_pipes_pull_shrinks_the_envelope_where_the_mains_bind(osv: pl.Vessel, bare: Capability) -> None:
    """A pipe pulling aft with 100 kN and with 300 kN: the envelope is nowhere larger than without it (to
    the bisection's 1 mm/s), and 300 kN nowhere larger than 100 kN. Where the four tunnels' 800 kN of sway
    are what runs out (the environment's sway at the envelope is 800 kN, 75°–135° each side) the mains take
    100 kN of pull changing the envelope by less than 0.05 m/s (measured ≤ 0.024 m/s, where the drift's surge
    brings the mains in); where the cap (60 m/s) or the tunnels do not decide it, it shrinks by more than
    0.05 m/s and by more at 300 kN."""
    pulled = {t: dp_capability(osv, HEADINGS, pipe_load=_aft(t)).wind_speed for t in (100e3, 300e3)}
    assert np.all(pulled[100e3] <= bare.wind_speed + BISECTION)
    assert np.all(pulled[300e3] <= pulled[100e3] + BISECTION)
    sway = np.array(
        [abs(pl._core.environment_load(osv, v, h)[1]) for v, h in zip(bare.wind_speed, HEADINGS, strict=True)]
    )
    capped = bare.wind_speed >= MAX_WIND
    sway_bound = ~capped & (sway >= 0.999 * TUNNELS)
    free = ~capped & ~sway_bound
    shrink = {t: bare.wind_speed - speeds for t, speeds in pulled.items()}
    print(
        "headings free of the cap and the tunnels:",
        np.degrees(HEADINGS[free]).tolist(),
        "shrink at 100 kN:",
        np.round(shrink[100e3][free], 3).tolist(),
    )
    assert free.sum() >= 4 and sway_bound.sum() >= 4
    assert np.all(shrink[100e3][free] > 0.05) and np.all(shrink[300e3][free] > shrink[100e3][free])
    assert np.all(np.abs(shrink[100e3][sway_bound]) < 0.05)


def test_zero_environment_gives_the_pipe_loads_own_limit(osv: pl.Vessel) -> None:
    """The largest pull aft the thrusters hold alone, by bisection on allocate((T, 0, …)) not saturated:
    the two mains' 2 × 798.72 kN (to the allocation's 1e-4 saturation threshold; measured +5.0e-5). With
    no current (so that calm is no environment at all), a pull of 0.999 T_max leaves an envelope > 0 at every
    heading, 60 m/s (the cap) from astern, where the environment pushes the vessel forward against the pipe,
    and a few m/s head-on (measured 3.9 m/s); 1.001 T_max cannot be held even in calm: 0 at every heading."""
    low, high = 0.0, 4.0 * MAINS
    while high - low > 1.0:
        middle = 0.5 * (low + high)
        if osv.allocate([middle, 0, 0, 0, 0, 0]).saturated:
            high = middle
        else:
            low = middle
    limit = low
    print(f"T_max = {limit / 1e3:.3f} kN ({limit / MAINS - 1.0:+.2e} of the mains')")
    assert limit == pytest.approx(MAINS, rel=1e-4)
    below = dp_capability(osv, HEADINGS, current=0.0, pipe_load=_aft(0.999 * limit)).wind_speed
    above = dp_capability(osv, HEADINGS, current=0.0, pipe_load=_aft(1.001 * limit)).wind_speed
    print("0.999 T_max:", np.round(below, 2).tolist())
    assert np.all(below > 0.0)
    assert below[12] == MAX_WIND  # 180°: from astern
    assert 0.0 < below[0] < 10.0
    assert np.all(above == 0.0)


@pytest.mark.parametrize(("heading_deg", "tension"), [(90.0, 0.0), (45.0, 300e3), (60.0, 100e3)])
def test_the_envelope_is_where_the_allocation_saturates(
    osv: pl.Vessel, heading_deg: float, tension: float
) -> None:
    """At the envelope's speed V* the allocation of −(environment + pipe) delivers it: X, Y and N/L (L = 83
    m) within 1e-3 of the largest of them (measured ≤ 7.2e-5), unsaturated, some thruster at its limit (to
    1e-3); at 0.999 V* unsaturated, at 1.02 V* saturated. (90°, no pipe: V* = 39.18 m/s, the four tunnels at
    200 kN.)"""
    heading = np.radians(heading_deg)
    pipe = _aft(tension)
    speed = float(dp_capability(osv, [heading], pipe_load=pipe).wind_speed[0])
    assert 0.0 < speed < MAX_WIND

    def load(v: float) -> np.ndarray:
        return pl._core.environment_load(osv, v, heading) + pipe

    assert osv.length is not None
    planar = np.array([1.0, 1.0, 1.0 / osv.length])
    at = osv.allocate(-load(speed))
    error = np.abs((at.tau + load(speed))[[0, 1, 5]] * planar).max()
    scale = np.abs(load(speed)[[0, 1, 5]] * planar).max()
    limits = np.array([t.max_thrust for t in osv.thrusters])
    print(f"{heading_deg}°, {tension / 1e3:g} kN: V* = {speed:.4f} m/s, delivered to {error / scale:.1e}")
    assert error <= 1e-3 * scale
    assert not at.saturated
    assert np.max(np.abs(at.thrust) / limits) >= 0.999
    assert not osv.allocate(-load(0.999 * speed)).saturated
    assert osv.allocate(-load(1.02 * speed)).saturated


def _vessel_on_a_short_rod(sea: pl.Sea, controller: pl.PID) -> pl.Model:
    """The OSV at (10, 0) holding a light 10 m rod (1 kg/m, 0.1 m): a pipe load of a few hundred newtons."""
    section = pl.Section(EA=1e7, GA=1e7, GJ=1e4, EI=1e4, mass=1.0, outer_diameter=0.1)
    model = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 2, section), sea)
    model.attach_vessel(
        "B", pl.Vessel.osv(), eta=[10, 0, -100, 0, 0, 0.0], controller=controller, hull_loads=True
    )
    return model


def test_a_point_of_the_envelope_holds_in_the_time_domain(osv: pl.Vessel) -> None:
    """From the beam (90°), steady wind at 70 % of the envelope (27.42 m/s) and the 0.75 m/s current with it,
    on the hull through its tables; PID with QP allocation, 300 s at Δt = 0.5 s. The vessel holds station:
    largest low-frequency offset 1 m over the run (measured 0.57 m in the first 20 s), 0.25 m after 100 s
    (measured 0.09 m), heading within 0.5° (measured 0.24°); no thruster ever above its limit. Over the last
    100 s the delivered sway and yaw balance the tables' wind and current load on the hull, −357 kN and
    −2.81 MN·m, to 1 %. The sea of that wind is left out (the steady load is the point here)."""
    heading = np.pi / 2
    speed = 0.7 * float(dp_capability(osv, [heading]).wind_speed[0])
    toward = heading + np.pi  # the vessel's ψ = 0: the direction the wind and current go, in e
    flow = np.array([np.cos(toward), np.sin(toward)])
    sea = pl.Sea(
        100.0,
        current=pl.Current.uniform([0.75 * flow[0], 0.75 * flow[1], 0.0]),
        wind=pl.Wind(speed, toward, spectrum=None),
    )
    controller = pl.PID(
        kp=[5e5, 5e5, 0, 0, 0, 5e8],
        kd=[5e6, 5e6, 0, 0, 0, 3e9],
        ki=[1e4, 1e4, 0, 0, 0, 1e7],
        reference=[10, 0, 0, 0, 0, 0.0],
        allocation="qp",
    )
    model = _vessel_on_a_short_rod(sea, controller)
    results = model.simulation(model.static(), dt=0.5).run(300.0, progress=False)
    assert results.eta_low_frequency is not None and results.thrust is not None and results.tau is not None
    pose = results.eta_low_frequency
    offset = np.hypot(pose[:, 0] - 10.0, pose[:, 1])
    late = results.time >= 100.0
    last = results.time >= 200.0
    print(
        f"wind {speed:.2f} m/s; offset {offset.max():.3f} m, after 100 s {offset[late].max():.3f} m; "
        f"heading {np.degrees(np.abs(pose[:, 5]).max()):.3f}°"
    )
    assert offset.max() < 1.0
    assert offset[late].max() < 0.25
    assert np.degrees(np.abs(pose[:, 5]).max()) < 0.5
    limits = np.array([t.max_thrust for t in osv.thrusters])
    assert np.all(np.abs(results.thrust) <= limits * (1.0 + 1e-9))
    assert osv.wind_coefficients is not None and osv.current_coefficients is not None
    hull = osv.wind_coefficients.load(1.226, speed * flow) + osv.current_coefficients.load(
        1025.0, 0.75 * flow
    )
    delivered = results.tau[last].mean(axis=0)
    print(f"delivered Y {delivered[1] / 1e3:.2f} kN, N {delivered[5] / 1e6:.4f} MN m; hull {hull[[1, 5]]}")
    assert delivered[1] == pytest.approx(-hull[1], rel=0.01)
    assert delivered[5] == pytest.approx(-hull[5], rel=0.01)


def test_a_scenario_gives_its_static_pipe_load(osv: pl.Vessel) -> None:
    """The S-lay example (1069 kN top tension): the envelope of the file uses the static state's χ (the pipe
    pulls the vessel aft by 876 kN), is the vessel's envelope with that load, and is labelled with the file's
    title; the parsed scenario and its model (with the vessel passed) give the same. The pull shrinks the
    envelope at 8 headings of 24 (at 60° by more than 1 m/s, measured 40.60 → 36.17 m/s)
    and nowhere enlarges it beyond 1 mm/s; head-on it is still held to 60 m/s (392 kN of wind, current and
    drift plus 876 kN of pipe, within the mains' 1597 kN)."""
    scenario = load_scenario(S_LAY)
    chi = scenario.model.static().chi
    found = dp_capability(S_LAY, HEADINGS)
    np.testing.assert_allclose(found.pipe_load, chi, rtol=1e-9)
    assert found.pipe_load[0] < -8e5
    assert found.label == scenario.source["title"]
    np.testing.assert_array_equal(found.wind_speed, dp_capability(osv, HEADINGS, pipe_load=chi).wind_speed)
    np.testing.assert_array_equal(dp_capability(scenario, HEADINGS).wind_speed, found.wind_speed)
    model = dp_capability(scenario.model, HEADINGS, vessel=osv)
    np.testing.assert_array_equal(model.wind_speed, found.wind_speed)
    bare = dp_capability(osv, HEADINGS)
    assert found.wind_speed[4] < bare.wind_speed[4] - 1.0  # 60°: measured 36.17 against 40.60 m/s
    assert int((found.wind_speed < bare.wind_speed - 0.05).sum()) >= 6  # measured 8
    assert np.all(found.wind_speed <= bare.wind_speed + BISECTION)


def test_table_and_plot(bare: Capability, tmp_path: Path) -> None:
    """The table has a row per heading (deg, m/s); the figure is polar, 0° at the top, clockwise, the pipe
    load in the title, saved as PNG; several envelopes go on one figure, labelled."""
    table = bare.table()
    assert list(table.columns) == ["heading_deg", "wind_speed"] and len(table) == 24
    np.testing.assert_allclose(table["heading_deg"], np.arange(0.0, 360.0, 15.0))
    np.testing.assert_array_equal(table["wind_speed"], bare.wind_speed)
    figure = bare.plot(path=tmp_path / "capability.png")
    assert isinstance(figure, Figure)
    axis = figure.axes[0]
    assert axis.name == "polar"
    assert axis.get_theta_offset() == pytest.approx(np.pi / 2) and axis.get_theta_direction() == -1
    assert "no pipe load" in axis.get_title()
    assert (tmp_path / "capability.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pulled = dp_capability(pl.Vessel.osv(), HEADINGS, pipe_load=_aft(1e6), label="1000 kN aft")
    both = plots.capability({"no pipe": bare, "1000 kN aft": pulled})
    labels = [t.get_text() for t in both.axes[0].get_legend().get_texts()]
    assert labels[:2] == ["no pipe", "1000 kN aft"]
    assert "X = -1000 kN" in pulled.plot().axes[0].get_title()


@pytest.mark.parametrize(
    ("arguments", "argument"),
    [
        ({"headings": [0.0, np.nan]}, "headings"),
        ({"headings": []}, "headings"),
        ({"current": -0.1}, "current"),
        ({"max_wind": 0.0}, "max_wind"),
        ({"pipe_load": [1.0, 2.0]}, "pipe_load"),
        ({"pipe_load": [np.inf, 0, 0, 0, 0, 0]}, "pipe_load"),
    ],
)
def test_bad_arguments_name_themselves(osv: pl.Vessel, arguments: dict[str, object], argument: str) -> None:
    with pytest.raises(pl.InputError, match=f"^{argument}: "):
        dp_capability(osv, **arguments)  # type: ignore[arg-type]


def test_bad_subjects_name_the_argument(osv: pl.Vessel) -> None:
    """A model with no vessel, a vessel without thrusters, a scenario without a vessel, something else; a model
    gives its own vessel (the same envelope as with `vessel=` given)."""
    model = load_scenario(S_LAY).model
    headings = HEADINGS[:4]
    np.testing.assert_array_equal(
        dp_capability(model, headings).wind_speed, dp_capability(model, headings, vessel=osv).wind_speed
    )
    section = pl.Section(EA=1e7, GA=1e7, GJ=1e4, EI=1e4, mass=1.0, outer_diameter=0.1)
    free = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 2, section), pl.Sea(100.0))
    free.clamp("A")
    with pytest.raises(pl.InputError, match="^model_or_scenario: .*no vessel"):
        dp_capability(free, vessel=osv)
    bare_hull = pl.Vessel(osv.M, osv.D, osv.G)
    with pytest.raises(pl.InputError, match="^vessel: "):
        dp_capability(bare_hull)
    with pytest.raises(pl.InputError, match="^model_or_scenario: has no vessel"):
        dp_capability(EXAMPLES / "hanging_pipe.toml")
    with pytest.raises(pl.InputError, match="^model_or_scenario: "):
        dp_capability(42)  # type: ignore[arg-type]


def test_the_command_prints_the_table_and_saves_the_plot(tmp_path: Path) -> None:
    """`pipelay capability examples/s_lay.toml --headings-step 90 --plot FILE`: exit 0, the pipe load in kN,
    four rows 0, 90, 180, 270°, the 180° row held to the limit, the PNG written; a bad step exits 2 naming
    the option."""
    figure = tmp_path / "capability.png"
    command = [sys.executable, "-m", "pipelay.cli", "capability", str(S_LAY), "--headings-step", "90"]
    done = subprocess.run(
        [*command, "--plot", str(figure)], check=False, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    rows = [line.split() for line in done.stdout.splitlines() if line[:11].strip().replace(".", "").isdigit()]
    assert [float(r[0]) for r in rows] == [0.0, 90.0, 180.0, 270.0]
    assert "held to --max-wind" in " ".join(rows[2])
    assert "X -876" in done.stdout
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    bad = subprocess.run([*command[:-1], "0"], check=False, capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "--headings-step" in bad.stderr
