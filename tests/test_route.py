"""A moving DP reference: the PID follows a lay route (pl.Route) or a reference given as a callable of time."""

from __future__ import annotations

import math

import numpy as np
import pipelay as pl
import pytest

KP, KD = 2e5, 2e6


def _follower(reference: object, **pid: object) -> pl.Model:
    """The OSV carrying a light 10 m rod (no drag) under PD control about `reference`."""
    section = pl.Section(EA=1e7, GA=1e7, GJ=1e4, EI=1e4, mass=1.0, outer_diameter=0.1)
    model = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 2, section), pl.Sea(100.0))
    controller = pl.PID(kp=[KP, KP, 0, 0, 0, 1e8], kd=[KD, KD, 0, 0, 0, 1e9], reference=reference, **pid)
    model.attach_vessel("B", pl.Vessel.osv(), eta=[10, 0, -100, 0, 0, 0.0], controller=controller)
    return model


def _run(model: pl.Model, t_end: float = 600.0) -> pl.Results:
    return model.simulation(model.static(), dt=0.5).run(t_end, progress=False)


@pytest.mark.parametrize("heading", [0.0, 0.5])
def test_route_is_followed_with_the_pd_lag(heading: float) -> None:
    """At constant lay speed v the PD's steady state is a lag e = D₁₁ v / K_p behind the route (the surge
    damping balanced by the proportional thrust, the derivative term seeing the route's rate), nothing across
    it, and the vessel at the route's speed and heading."""
    speed = 1.0
    route = pl.Route((10.0, 0.0), heading=heading, speed=speed)
    results = _run(_follower(route))
    t = results.time[-1]
    pose, rate = route.at(t)
    assert np.allclose(rate[:2], speed * np.array([math.cos(heading), math.sin(heading)]))
    offset = results.eta[-1, :2] - pose[:2]
    along = offset @ [math.cos(heading), math.sin(heading)]
    across = offset @ [-math.sin(heading), math.cos(heading)]
    expected = -pl.Vessel.osv().D[0, 0] * speed / KP
    print(f"heading {heading}: lag {along:.9f} m (expected {expected:.9f}), across {across:.2e} m")
    assert along == pytest.approx(expected, rel=1e-5)
    assert abs(across) < 1e-5
    assert results.nu[-1, 0] == pytest.approx(speed, rel=1e-6)
    assert results.eta[-1, 5] == pytest.approx(heading, abs=1e-7)


def test_callable_reference_matches_the_route() -> None:
    """The same route as callables of time: with its rate the runs agree to round-off; with the rate left to
    central differences (exact for a straight line) they agree as well."""
    route = pl.Route((10.0, 0.0), heading=0.3, speed=0.8, start_time=20.0)
    reference = _run(_follower(route), 200.0)
    pose = lambda t: route.at(t)[0]
    rate = lambda t: route.at(t)[1]
    with_rate = _run(_follower(pose, reference_rate=rate), 200.0)
    differenced = _run(_follower(pose), 200.0)
    assert np.abs(with_rate.eta - reference.eta).max() < 1e-9
    # Central differences straddle the route's start at 20 s only within a millisecond of it.
    assert np.abs(differenced.eta - reference.eta).max() < 1e-3


def test_reference_callables_that_fail_name_themselves() -> None:
    """A reference that turns NaN stops the run with an InputError naming `reference` and the time; bad
    routes and a rate without a callable are rejected when built."""
    model = _follower(lambda t: [10.0 + t, 0, 0, 0, 0, math.nan if t > 5.0 else 0.0])
    with pytest.raises(pl.InputError, match=r"reference.*t = 5\.\d+ s"):
        _run(model, 10.0)
    with pytest.raises(pl.InputError, match="speed"):
        pl.Route((0.0, 0.0), speed=math.nan)
    with pytest.raises(pl.InputError, match="reference_rate"):
        pl.PID(kp=[1] * 6, kd=[1] * 6, reference=[0] * 6, reference_rate=lambda t: [0] * 6)


def test_scenario_route() -> None:
    """[controller.route] builds the same PID reference as pl.Route; with `reference` as well it is an error
    naming both."""
    import tomllib
    from pathlib import Path

    from pipelay.scenario import parse_scenario

    path = Path(__file__).resolve().parent.parent / "examples" / "s_lay.toml"
    data = tomllib.loads(path.read_text())
    data["controller"].pop("reference")
    data["controller"]["route"] = {"start": [660.0, 0.0], "speed": 0.5, "start_time": 10.0}
    scenario = parse_scenario(data)
    state = scenario.model.static()
    results = scenario.model.simulation(state, dt=0.2).run(2.0, progress=False)
    assert len(results.time) == 11
    route = pl.Route((660.0, 0.0), speed=0.5, start_time=10.0)
    assert np.allclose(route.at(30.0)[0], [670.0, 0, 0, 0, 0, 0])
    data["controller"]["reference"] = [660.0, 0, 0, 0, 0, 0]
    with pytest.raises(pl.InputError, match="controller.reference"):
        parse_scenario(data)
    data["controller"].pop("reference")
    data["controller"]["route"]["speed"] = "fast"
    with pytest.raises(pl.InputError, match="controller.route.speed"):
        parse_scenario(data)


def test_stages_move_the_set_point_and_the_route() -> None:
    """Stages move the DP reference: a new set-point (x, y, ψ) is where the PD brings the vessel (no other
    load: to 1 mm after 400 s); a route speed then moves it on along ψ from there, and the vessel follows with
    the PD's lag D₁₁v/K_p behind the ramped route (travelled 1 m/s · 300 s less half the 10 s ramp: 295 m; to
    5 mm). A set-point that is not finite names the key; one without a controller names the stage's key."""
    model = _follower([10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    stages = pl.Stages(
        [
            pl.Stage("hold", duration=50.0),
            pl.Stage("move", duration=400.0, setpoint=(30.0, 5.0, 0.0)),
            pl.Stage("sail", duration=300.0, route_speed=1.0),
        ]
    )
    results = model.simulation(model.static(), dt=0.5, stages=stages).run(progress=False)
    eta = results.eta
    assert eta is not None
    moved = np.flatnonzero(results.stage == 1)[-1]
    print(f"\nat the set-point {eta[moved, :2]}, end {eta[-1, :2]}")
    np.testing.assert_allclose(eta[moved, :2], [30.0, 5.0], atol=1e-3)
    lag = pl.Vessel.osv().D[0, 0] * 1.0 / KP
    assert eta[-1, 0] == pytest.approx(30.0 + 295.0 - lag, abs=5e-3)
    assert eta[-1, 1] == pytest.approx(5.0, abs=1e-3)
    with pytest.raises(pl.InputError, match="setpoint"):
        pl.Stage("bad", duration=1.0, setpoint=(0.0, math.nan, 0.0))
    free = pl.Model(
        pl.Rod.straight((0, 0, 0), (10, 0, 0), 2, pl.Section(EA=1e7, GA=1e7, GJ=1e4, EI=1e4, mass=1.0)),
        pl.Sea(100.0),
    )
    free.attach_vessel("B", pl.Vessel.osv(), eta=[10, 0, -100, 0, 0, 0.0])
    with pytest.raises(pl.InputError, match=r"stages\[0\]\.setpoint"):
        free.simulation(
            free.rest(), dt=0.5, stages=pl.Stages([pl.Stage("a", duration=1.0, setpoint=(1.0, 0.0, 0.0))])
        )


def test_a_route_of_legs_turns_on_arcs_and_the_vessel_follows_it() -> None:
    """`Route.legs`: 300 m east, a left turn of 90° on an arc of R = 200 m, 300 m north, at 1 m/s. The reference
    lies on the arc about (110, 200) with heading and yaw rate v/R there, and stops at the end; the PD-controlled
    vessel follows it within 0.5 m once past the start's step in speed, its heading D₆₆(v/R)/K_p behind in the
    turn (within 1 %: sway and yaw couple through the turn's centripetal terms)."""
    radius, speed = 200.0, 1.0
    route = pl.Route.legs([(10.0, 0.0), (310.0, 0.0), (310.0, 300.0)], radius=radius, speed=speed)
    quarter = 0.5 * math.pi * radius
    for t in np.linspace(100.5, 100.0 + quarter - 0.5, 7):
        pose, rate = route.at(t)
        assert np.hypot(pose[0] - 110.0, pose[1] - 200.0) == pytest.approx(radius, rel=1e-12)
        assert pose[5] == pytest.approx((t - 100.0) / radius, abs=1e-12)
        assert rate[5] == pytest.approx(speed / radius, rel=1e-12)
        assert np.hypot(*rate[:2]) == pytest.approx(speed, rel=1e-12)
    end, stopped = route.at(1e4)
    assert np.allclose(end[:2], [310.0, 300.0]) and np.all(stopped == 0.0)
    results = _run(_follower(route), 100.0 + quarter + 50.0)
    track = [route.at(t)[0] for t in results.time]
    error = np.array([np.hypot(*(eta[:2] - pose[:2])) for eta, pose in zip(results.eta, track, strict=True)])
    lag = np.array([eta[5] - pose[5] for eta, pose in zip(results.eta, track, strict=True)])
    # In the turn the PD holds the yaw rate v/R a steady lag D₆₆(v/R)/K_p behind, as it holds the surge speed.
    expected = -pl.Vessel.osv().D[5, 5] * speed / radius / 1e8
    at_arc_end = results.time == 400.0
    print(
        f"largest distance from the reference after the start {error[results.time > 60].max():.3f} m; yaw lag at "
        f"the arc's end {np.degrees(lag[at_arc_end][0]):.3f}° (expected {np.degrees(expected):.3f}°)"
    )
    assert error[results.time > 60].max() < 0.5
    assert lag[at_arc_end][0] == pytest.approx(expected, rel=0.01)


def test_a_route_of_legs_refuses_an_arc_its_legs_cannot_hold() -> None:
    with pytest.raises(pl.InputError, match="radius.*too large for leg"):
        pl.Route.legs([(0, 0), (100, 0), (100, 100)], radius=150.0, speed=1.0)
    with pytest.raises(pl.InputError, match="waypoints"):
        pl.Route.legs([(0, 0)], radius=10.0)
    with pytest.raises(pl.InputError, match="radius"):
        pl.Route.legs([(0, 0), (100, 0), (100, 100)], speed=1.0)
