"""Steady lay: the scenario's `[pay_out]` and `[controller.tension]` tables, a short J-lay that pays pipe out
while the vessel follows a route, and the lay figures (touchdown track, lay accuracy, tension comparison)."""

from __future__ import annotations

import copy
import math
import re
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay import plots
from pipelay.scenario import SmoothStart, load_scenario, parse_scenario

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "steady_lay.toml"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

# A short, cheap J-lay: a 0.3 m × 15 mm empty pipe (323 N/m submerged), 50 elements of 10 m, in 150 m of
# water; the vessel sits where the catenary leaves the tower nearly straight and follows a route along e1 at
# 0.5 m/s from t = 10 s, paying out at the route's speed.
SHORT = """
[pipe]
outer_diameter = 0.3
wall_thickness = 0.015
drag = [0.0, 1.0]
added_mass = [0.0, 1.0]

[rod]
start = [0.0, 0.0, 0.0]
end = [500.0, 0.0, 0.0]
elements = 50

[sea]
depth = 150.0

[sea.seabed]
stiffness = 1e5
friction = [0.5, 0.5]
mobilisation = 0.02

[supports.A]
kind = "pin"

[vessel]
end = "B"
model = "osv"
eta = [440.0, 0.0, -150.0, 0.0, 0.0, 0.0]

[vessel.lay]
kind = "j-lay"
position = [0.0, 0.0, -10.0]
angle = 0.7

[controller]
kp = [2e5, 2e5, 0, 0, 0, 1e7]
kd = [4e6, 4e6, 0, 0, 0, 1e8]

[controller.route]
start = [440.0, 0.0]
speed = 0.5
start_time = 10.0

[pay_out]
speed = "route"

[solver]
dt = 0.2
t_end = 140.0
"""
SPEED, START = 0.5, 10.0  # the route's


def short(**pay_out: Any) -> dict[str, Any]:
    """The short scenario's dict, with `[pay_out]` keys replaced (None removes a key)."""
    data = tomllib.loads(SHORT)
    for key, value in pay_out.items():
        if value is None:
            data["pay_out"].pop(key, None)
        else:
            data["pay_out"][key] = value
    return data


def simulate(data: dict[str, Any]) -> pl.Results:
    scenario = parse_scenario(data)
    state = scenario.model.static()
    assert scenario.t_end is not None
    return scenario.model.simulation(state, dt=scenario.dt).run(scenario.t_end, progress=False)


def paid(t: np.ndarray, speed: float, start: float, ramp: float) -> np.ndarray:
    """∫ speed · smoothstep((τ − start)/ramp) dτ from −∞ to t: speed · ramp · (s³ − s⁴/2) during the ramp,
    speed · (t − start − ramp/2) after it."""
    if ramp == 0.0:
        return speed * np.maximum(t - start, 0.0)
    s = np.clip((t - start) / ramp, 0.0, 1.0)
    during = speed * ramp * (s**3 - 0.5 * s**4)
    return np.where(t > start + ramp, speed * (t - start - 0.5 * ramp), during)


@pytest.fixture(scope="module")
def route_run() -> pl.Results:
    """speed = "route": 0.5 m/s from the route's start time (10 s), the default 60 s ramp; 140 s."""
    return simulate(short())


@pytest.fixture(scope="module")
def current_run() -> pl.Results:
    """As route_run, to 120 s with a sheared cross current (0.5 m/s in +y at the surface) from t = 60 s, and a
    20 s ramp starting 10 s before the route does, so that the length paid out keeps up with the vessel."""
    data = short(start_time=0.0, ramp=20.0)
    data["sea"]["current"] = {"kind": "linear", "surface_velocity": [0.0, 0.5, 0.0], "start": 60.0}
    data["solver"]["t_end"] = 120.0
    return simulate(data)


def test_route_speed_length(route_run: pl.Results) -> None:
    """speed = "route" pays out at the route's speed from its start time with the default 60 s smoothstep
    ramp: at every record the length has grown by the ramped speed's integral, to 1 mm; by 140 s that is
    0.5 · (140 − 10 − 30) = 50 m, and the mesh has grown by a node per 10 m."""
    grown = route_run.length - route_run.length[0]
    expected = paid(route_run.time, SPEED, START, 60.0)
    print(
        f"grown {grown[-1]:.9f} m, expected {expected[-1]:.9f} m, worst {np.abs(grown - expected).max():.2e}"
    )
    assert expected[-1] == pytest.approx(50.0)
    assert np.abs(grown - expected).max() < 1e-3
    assert route_run.nodes == 51 + 5
    smooth = SmoothStart(SPEED, START, 60.0)  # the scenario's speed callable agrees with the integral
    assert [smooth(t) for t in (5.0, 40.0, 80.0)] == pytest.approx([0.0, 0.25, SPEED])
    assert [smooth.distance(t) for t in route_run.time[::50]] == pytest.approx(expected[::50], abs=1e-12)


@pytest.mark.parametrize(
    ("speed", "start_time", "ramp"),
    [(0.45, 15.0, 20.0), (0.3, 10.0, 0.0), (-0.25, 20.0, 30.0)],
    ids=["ramped", "instant", "pay-in"],
)
def test_number_speed_length(speed: float, start_time: float, ramp: float) -> None:
    """A number speed with its own start time and ramp (0: at once; < 0: pay-in, the vessel holding its
    position and the mesh shrinking) over 80 s: the length follows the integral of the ramped speed at every
    record, to 1 mm."""
    data = short(speed=speed, start_time=start_time, ramp=ramp)
    data["solver"]["t_end"] = 80.0
    if speed < 0.0:
        data["controller"]["route"]["speed"] = 0.0
    results = simulate(data)
    grown = results.length - results.length[0]
    expected = paid(results.time, speed, start_time, ramp)
    nodes = np.isfinite(results.positions[:, :, 0]).sum(axis=1)
    print(f"grown {grown[-1]:.9f} m, expected {expected[-1]:.9f} m, nodes {nodes[0]} → {nodes[-1]}")
    assert abs(expected[-1]) > 10.0
    assert nodes[-1] - nodes[0] == round(expected[-1] / 10.0)
    assert np.abs(grown - expected).max() < 1e-3


@pytest.fixture(scope="module")
def steady_run() -> pl.Results:
    """Pay-out ramped over 20 s from t = 0, half a ramp before the route starts (10 s), so that the length paid
    out keeps up with the vessel; 140 s."""
    return simulate(short(start_time=0.0, ramp=20.0))


def test_touchdown_advances_with_the_vessel(steady_run: pl.Results) -> None:
    """With the length paid out keeping up with the vessel, from 80 to 140 s (three element lengths of pay-out,
    so the split cycle does not bias it) the touchdown's speed along x (least squares) is the lay speed within 8 %, the vessel's advance
    which is the route's 30 m to 1 %, and the layback grows by less than 6 % of the lay speed. (Not closer: at
    0.5 m/s the drag on the moving pipe is 12 % of its submerged weight, and the catenary is still settling
    into its dynamic shape; the S-lay at 0.3 m/s of tests/test_pay_out.py settles to 1.3 %.)"""
    time = steady_run.time
    i, j = np.searchsorted(time, [80.0, 140.0])
    eta, touchdown = steady_run.eta, steady_run.touchdown
    assert eta is not None and touchdown is not None
    vessel = eta[j, 0] - eta[i, 0]
    # Least-squares speeds, less sensitive than end points to the touchdown's small oscillation.
    touchdown_speed = np.polyfit(time[i:], touchdown[i:, 0], 1)[0]
    trend = np.polyfit(time[i:], eta[i:, 0] - touchdown[i:, 0], 1)[0]
    print(
        f"vessel {vessel:.3f} m, touchdown speed {touchdown_speed:.4f} m/s "
        f"(ratio {touchdown_speed / SPEED:.4f}), layback {trend:.2e} m/s"
    )
    assert vessel == pytest.approx(SPEED * 60.0, rel=0.01)
    assert touchdown_speed == pytest.approx(SPEED, rel=0.08)
    assert abs(trend) < 0.06 * SPEED


@pytest.mark.parametrize(
    ("pay_out", "key", "says"),
    [
        ({"speed": "fast"}, "pay_out.speed", 'a number (m/s) or "route"'),
        ({"speed": math.nan}, "pay_out.speed", "finite"),
        ({"speed": True}, "pay_out.speed", "true"),
        ({"speed": [0.5]}, "pay_out.speed", "[0.5]"),
        ({"speed": None}, "pay_out.speed", "missing required key"),
        ({"ramp": -1.0}, "pay_out.ramp", ">= 0 s, got -1"),
        ({"ramp": math.inf}, "pay_out.ramp", "finite"),
        ({"start_time": "soon"}, "pay_out.start_time", "'soon'"),
        ({"end": "C"}, "pay_out.end", '"A" or "B"'),
        ({"end": "A"}, "pay_out.end", "clamped or pinned"),
        ({"sped": 0.5}, "pay_out.sped", "did you mean 'speed'"),
    ],
)
def test_bad_pay_out(pay_out: dict[str, Any], key: str, says: str) -> None:
    """Bad `[pay_out]` keys and values raise pl.InputError naming the key, with the value or what is allowed."""
    with pytest.raises(pl.InputError) as caught:
        parse_scenario(short(**pay_out), "lay.toml")
    message = str(caught.value)
    print(message)
    assert message.startswith(f"{key}:")
    assert says in message
    assert message.endswith("(in lay.toml)")


def test_route_speed_needs_a_route() -> None:
    """speed = "route" without `[controller.route]` (a fixed reference instead) is an error naming
    pay_out.speed; a number speed is fine with it; `[pay_out]` that is not a table is an error too."""
    data = short()
    data["controller"].pop("route")
    data["controller"]["reference"] = [440.0, 0, 0, 0, 0, 0]
    with pytest.raises(pl.InputError, match=r"^pay_out\.speed: .*\[controller\.route\]"):
        parse_scenario(copy.deepcopy(data))
    data["pay_out"]["speed"] = 0.2
    parse_scenario(copy.deepcopy(data))
    data["pay_out"] = 0.2
    with pytest.raises(pl.InputError, match=r"^pay_out: must be a table"):
        parse_scenario(data)
    data = short()
    data.pop("vessel")
    data.pop("controller")
    data["supports"]["B"] = {"kind": "pin"}
    data["pay_out"]["speed"] = 0.2
    with pytest.raises(pl.InputError, match=r"^pay_out\.end: .*pinned"):
        parse_scenario(data)


@pytest.mark.parametrize(
    ("tension", "key"),
    [
        ({"gain": 1e-7}, "controller.tension.target"),
        ({"target": 1e5}, "controller.tension.gain"),
        ({"target": 1e5, "gain": 0.0}, "controller.tension.gain"),
        ({"target": 1e5, "gain": 1e-7, "filter": 0.0}, "controller.tension.filter"),
        ({"target": 1e5, "gain": 1e-7, "rate_limit": -0.1}, "controller.tension.rate_limit"),
        ({"target": 1e5, "gain": 1e-7, "tau": 1.0}, "controller.tension.tau"),
    ],
)
def test_bad_tension_loop(tension: dict[str, Any], key: str) -> None:
    """Bad `[controller.tension]` tables raise pl.InputError naming the key."""
    data = short()
    data["controller"]["tension"] = tension
    with pytest.raises(pl.InputError, match=rf"^{re.escape(key)}:"):
        parse_scenario(data)


def test_tension_loop_moves_the_vessel() -> None:
    """`[controller.tension]` builds the lay-tension loop: with a fixed reference and no pay-out, a target 10 kN
    above the static top tension moves the vessel forward (the layback grows, and the tension with it) as the
    first-order loop dx/dt = g (T* − T(x)) does, T(x) linearised from statics at x ± 1 m: ΔT/k (1 − exp(−g k t))
    after t = 100 s, to 10 %; without the loop it stays put."""
    data = short()
    data.pop("pay_out")
    data["controller"].pop("route")
    data["solver"]["t_end"] = 100.0

    def at(x: float) -> dict[str, Any]:
        moved = copy.deepcopy(data)
        moved["vessel"]["eta"][0] = x
        moved["controller"]["reference"] = [x, 0, 0, 0, 0, 0]
        return moved

    def tension(x: float) -> float:
        summary = parse_scenario(at(x)).model.static().lay_summary()
        assert summary is not None
        return float(summary["top_tension"])

    slope = (tension(441.0) - tension(439.0)) / 2.0  # N/m
    gain, error = 2e-6, 1e4
    still = simulate(at(440.0))
    looped = at(440.0)
    looped["controller"]["tension"] = {"target": tension(440.0) + error, "gain": gain, "filter": 5.0}
    moved = simulate(looped)
    assert still.eta is not None and moved.eta is not None
    shift = moved.eta[-1, 0] - moved.eta[0, 0]
    estimate = error / slope * (1.0 - math.exp(-gain * slope * 100.0))
    print(
        f"dT/dx {slope:.1f} N/m; vessel moved {shift:.3f} m with the loop, first-order estimate {estimate:.3f} m"
    )
    assert abs(still.eta[-1, 0] - still.eta[0, 0]) < 0.05
    assert shift == pytest.approx(estimate, rel=0.1)


def test_example_scenario() -> None:
    """examples/steady_lay.toml: a J-lay whose static top tension is within 2 % of its tension loop's target,
    whose tower is where the catenary leaves it nearly straight, and whose pay-out is the route's."""
    scenario = load_scenario(EXAMPLE)
    state = scenario.model.static()
    summary = state.lay_summary()
    assert summary is not None and state.touchdown is not None
    target = scenario.source["controller"]["tension"]["target"]
    print(
        f"top tension {summary['top_tension'] / 1e3:.1f} kN, touchdown x {state.touchdown.position[0]:.1f} m"
    )
    assert summary["top_tension"] == pytest.approx(target, rel=0.02)
    assert scenario.source["pay_out"]["speed"] == "route"
    assert scenario.t_end is not None and scenario.source["sea"]["current"]["start"] == scenario.t_end / 2


def assert_png(path: Path) -> None:
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) > 10_000, len(data)


def test_lay_figures(current_run: pl.Results, route_run: pl.Results, tmp_path: Path) -> None:
    """The lay figures of real runs: the laid pipe's deviation is what lay_deviation computes (0 on the part
    laid before the run away from the touchdown, to starboard (+y) where the cross current pushed the touchdown); the touchdown track
    shows both advances; the tension comparison one raw and one mean curve per run; all_figures adds the lay
    figures for a run with pay-out only."""
    route = ((440.0, 0.0), 0.0)
    along, across = plots.lay_deviation(current_run, route)
    touchdown = current_run.touchdown
    assert touchdown is not None
    assert along[-1] <= touchdown[-1, 0] - 440.0 + 1e-9
    first = along < np.nanmin(touchdown[:, 0]) - 440.0 - 20.0  # never lifted, 20 m or more from the touchdown
    print(
        f"{len(along)} laid nodes; before the run |dev| ≤ {np.abs(across[first]).max():.2e} m, largest {across.max():.3f} m"
    )
    assert first.sum() >= 15
    assert np.abs(across[first]).max() < 0.01
    # The current pushes the touchdown to starboard (+y): the last laid node deviates most, less than it.
    assert 0.05 < across[-1] == across.max() < touchdown[-1, 1]

    figure = plots.lay_accuracy(
        current_run, route=pl.Route((440.0, 0.0), speed=0.5, start_time=10.0), path=tmp_path / "a.png"
    )
    assert_png(tmp_path / "a.png")
    line = figure.axes[0].get_lines()[1]
    assert np.allclose(line.get_xdata(), along) and np.allclose(line.get_ydata(), across)
    assert f"{np.abs(across).max():.2f} m" in figure.axes[0].get_title()

    figure = plots.touchdown_track(current_run, path=tmp_path / "t.png")
    assert_png(tmp_path / "t.png")
    eta = current_run.eta
    assert eta is not None
    vessel_line, touchdown_line = figure.axes[1].get_lines()
    assert np.asarray(vessel_line.get_ydata())[-1] == pytest.approx(eta[-1, 0] - eta[0, 0])
    assert np.asarray(touchdown_line.get_ydata())[-1] == pytest.approx(touchdown[-1, 0] - touchdown[0, 0])

    runs = {"route": route_run, "with current": current_run}
    figure = plots.tension_comparison(runs, target=1.2e5, window=10.0, path=tmp_path / "c.png")
    assert_png(tmp_path / "c.png")
    lines = figure.axes[0].get_lines()
    assert len(lines) == 2 * len(runs) + 1
    summary = current_run.lay_summary()
    assert summary is not None
    last = current_run.time >= current_run.time[-1] - 10.0
    assert np.asarray(lines[3].get_ydata())[-1] == pytest.approx(summary["top_tension"][last].mean() / 1e3)

    written = {path.name for path in plots.all_figures(current_run, tmp_path / "lay")}
    assert {"touchdown_track.png", "lay_accuracy.png"} <= written
    for name in ("touchdown_track.png", "lay_accuracy.png"):
        assert_png(tmp_path / "lay" / name)
    data = short()
    data.pop("pay_out")
    data["solver"]["t_end"] = 2.0
    written = {path.name for path in plots.all_figures(simulate(data), tmp_path / "still")}
    assert "touchdown.png" in written and "lay_accuracy.png" not in written
