"""The stages of a lay in one run: a J-lay laydown in 800 m of water from a 30° tower, and its recovery.

The run (module fixture, ~17 s): the 0.6 m × 25 mm pipe, 2000 m in 10 m elements, pinned at its seabed end,
hangs from the tower of the OSV under DP. Stages: the vessel moves off 180 m to where the tower's angle
matches the catenary's (the tower's clamp moment falls from 4.1 MN·m to ~0.1); 60 s of normal lay (pay-out
and route at 0.5 m/s); the hand-over to the A&R winch 5 m up the tower (its wire: 80 mm, EA 550 MN; a 5 t
laydown head on the pipe's end); the laydown (winch and route at 1 m/s) until the head lands and the wire lies
on the seabed; a rest; the recovery (haul-in and the vessel moving back at 1 m/s).

References: the axial force passed at the hand-over (the wire is stretched to carry the pipe's axial force);
the statics of the final configuration (pipe, head and wire, pinned at the winch's final position) for the
head's landing place; the catenary's vertical balance for the wire at rest on the seabed (the winch carries the
suspended wire's submerged weight); the discrete energy ledger E(t) − E(0) = W(t) − D(t) through every stage,
hand-over and landing; the ramped pay-out speeds' integral for the length paid out.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.analysis.stages import head_positions

DEPTH = 800.0
ANGLE = math.radians(30.0)
EXIT = np.array([0.0, 0.0, -10.0])
TOWER = np.array([math.sin(ANGLE), 0.0, -math.cos(ANGLE)])
PIPE = pl.Section.pipe(
    outer_diameter=0.6, wall_thickness=0.025, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0)
)
WIRE = pl.Section.cable(diameter=0.08, mass=28.0, EA=5.5e8, drag=(0.0, 1.2), added_mass=(0.0, 1.0))
HEAD = pl.Clump(mass=5000.0, volume=0.8, drag_area=1.0, added_mass=1.0)
DT, EVERY = 0.5, 4
SPEED = 1.0


def _j_lay(eta_x: float = 1480.0, winch: pl.Winch | None = None) -> pl.Model:
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (2000.0, 0.0, 0.0), 200, PIPE)
    sea = pl.Sea(DEPTH, seabed=pl.Seabed(stiffness=1e5, friction=0.5, mobilisation=0.02))
    model = pl.Model(rod, sea)
    model.pin("A")
    eta = [eta_x, 0.0, -DEPTH, 0.0, 0.0, 0.0]
    controller = pl.PID(kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=eta)
    if winch is None:
        winch = pl.Winch(EXIT + 5.0 * TOWER, tension_limit=2e6, wire=WIRE, element_length=10.0, head=HEAD)
    lay = pl.JLay(position=tuple(EXIT), angle=ANGLE)
    model.attach_vessel("B", pl.Vessel.osv(), eta=eta, lay=lay, controller=controller, winch=winch)
    return model


STAGES = pl.Stages(
    [
        pl.Stage("move-off", duration=360.0, route_speed=0.5, ramp=20.0),
        pl.Stage("normal lay", duration=60.0, pay_out=0.5, route_speed=0.5),
        pl.Stage("hand-over", duration=30.0, hold="winch", route_speed=0.0, winch_speed=0.0),
        pl.Stage("laydown", duration=1500.0, winch_speed=SPEED, route_speed=SPEED, ramp=20.0),
        pl.Stage("slacken", duration=120.0, winch_speed=0.5, route_speed=0.0),
        pl.Stage("rest", duration=60.0, winch_speed=0.0),
        pl.Stage("pick-up", duration=120.0, winch_speed=-0.5),
        pl.Stage("recovery", duration=600.0, winch_speed=-SPEED, route_speed=-SPEED, ramp=20.0),
    ]
)


@pytest.fixture(scope="module")
def laydown() -> tuple[pl.Model, pl.Simulation, pl.Results]:
    model = _j_lay()
    simulation = model.simulation(model.static(), dt=DT, stages=STAGES)
    with pytest.warns(pl.PhysicsWarning):  # the tower's clamp moment strains the pipe beyond yield at first
        results = simulation.run(progress=False, record_every=EVERY)
    return model, simulation, results


def _last(results: pl.Results, stage: int) -> int:
    return int(np.flatnonzero(results.stage == stage)[-1])


def _top_element(row: np.ndarray) -> int:
    return int(np.flatnonzero(np.isfinite(row))[-1])


def test_records_are_marked_with_their_stage_and_the_length_follows_the_ramps(
    laydown: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """Each stage has duration/(dt·record_every) records (the first record opens stage 0); the pipe paid out
    in normal lay is the ramped speed's integral, 0.5 m/s for 60 s less half the 10 s ramp: 27.5 m; the
    hand-over adds the 5 m of wire between the pipe's end and the winch, less its stretch under the pipe's
    axial force, and the winch carries on at the speed it took over."""
    _, simulation, results = laydown
    counts = np.bincount(results.stage)
    expected = np.array([360, 60, 30, 1500, 120, 60, 120, 600]) / (DT * EVERY)
    expected[0] += 1
    np.testing.assert_array_equal(counts, expected)
    assert simulation.stages_end == pytest.approx(2850.0)
    np.testing.assert_allclose(results.stage_starts, np.cumsum([0, 360, 60, 30, 1500, 120, 60, 120, 600]))
    before = results.length[_last(results, 1)]
    assert before - 2000.0 == pytest.approx(27.5, abs=1e-9)
    # The hand-over adds the wire between the pipe's end and the winch (5 m, stretched by the pipe's force).
    handed = results.length[_last(results, 1) + 1]
    force = simulation.hand_over_tension
    assert force is not None
    # The winch carries on at the tensioner's 0.5 m/s, ramping to rest over 10 s: 0.9 m in the record's 2 s.
    assert handed - before == pytest.approx(5.0 / (1.0 + force / 5.5e8) + 0.9, rel=1e-9)


def test_the_wire_takes_the_tensioners_axial_force_at_the_hand_over(
    laydown: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """At the hand-over the wire takes on the top element's axial force exactly (it is stretched to carry it);
    over the 30 s hand-over stage (the vessel and winch ramping to rest, the tower letting go of the pipe's
    shear and moment) the wire's tension stays within 15 % of the tensioner's at the hand-over (measured 11 %)."""
    _, simulation, results = laydown
    k = _last(results, 1)
    top = _top_element(results.section_forces[k, :, 0])
    tensioner = results.section_forces[k, top, 0]
    assert simulation.hand_over_tension == pytest.approx(tensioner, rel=1e-12)
    tension = results.lay_summary()["top_tension"]
    swing = np.abs(tension[results.stage == 2] / tensioner - 1.0).max()
    print(f"\nhand-over at {tensioner / 1e3:.1f} kN: the wire within {swing:.2%} of it over the stage")
    assert swing < 0.15


def test_the_head_lands_where_the_final_statics_puts_it(
    laydown: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """After the rest stage the head lies on the seabed within one element (10 m) of where statics of the final
    configuration puts it: the pipe and wire as paid out, the head, the wire pinned at the winch's final
    position (measured 2 cm apart); it lands (head height < 0.5 m) during the laydown."""
    model, _, results = laydown
    k = _last(results, 5)
    heads = head_positions(results, model)
    pipe_length = results.length[_last(results, 1)]
    wire_length = results.length[k] - pipe_length
    winch = results.positions[k, np.flatnonzero(np.isfinite(results.positions[k, :, 0]))[-1]]
    segments = [pl.Segment(pipe_length, PIPE, elements=203), pl.Segment(wire_length, WIRE, elements=156)]
    final = pl.Model(
        pl.Rod.segments((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), segments),
        pl.Sea(DEPTH, seabed=pl.Seabed(stiffness=1e5)),
    )
    final.pin("A")
    final.pin("B", position=winch)
    final.attach(pipe_length, HEAD)
    predicted = final.static().positions[203]
    gap = np.linalg.norm(heads[k] - predicted)
    landed = results.time[np.flatnonzero(-heads[:, 2] < 0.5)[0]]
    print(f"\nhead at {heads[k]}, statics {predicted}: {gap:.3f} m apart; landed at t = {landed:.0f} s")
    assert gap < 10.0
    assert results.stage[np.flatnonzero(results.time == landed)[0]] == 3


def test_after_landing_the_winch_carries_the_suspended_wires_weight(
    laydown: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """At rest with the head on the seabed, the wire's vertical pull on the vessel is the submerged weight of
    the wire between its touchdown and the winch, w·s (w = (28 − 1025·π/4·0.08²)·9.81 N/m): to 1 % (measured
    0.1 %); and the top tension has fallen from the pipe's ~1 MN to under
    0.4 of it."""
    _, _, results = laydown
    k = _last(results, 5)
    positions = results.positions[k]
    nodes = np.flatnonzero(np.isfinite(positions[:, 0]))
    segment = results.segment[k]
    wire = np.flatnonzero(segment == segment[_top_element(segment)])
    joint = wire[0]
    chain = positions[joint : nodes[-1] + 1]
    lifted = np.flatnonzero(-chain[:, 2] > 0.0)[0] - 1  # the last wire node in the seabed (it sinks 3 cm)
    suspended = np.sum(np.linalg.norm(np.diff(chain[lifted:], axis=0), axis=1))
    w = (28.0 - 1025.0 * math.pi / 4 * 0.08**2) * 9.81
    vertical = results.reaction("B")[k, 2]
    print(
        f"\nwinch's vertical pull {vertical / 1e3:.2f} kN, suspended wire {suspended:.1f} m × w = {w * suspended / 1e3:.2f} kN"
    )
    assert vertical == pytest.approx(w * suspended, rel=0.01)
    tension = results.lay_summary()["top_tension"]
    assert tension[k] < 0.4 * tension[_last(results, 1)]


def test_recovery_reverses_the_laydown(laydown: tuple[pl.Model, pl.Simulation, pl.Results]) -> None:
    """Hauled in with the vessel moving back, the head lifts off again and climbs (to over 100 m by the end);
    at the same head heights (20–100 m) the winch's tension is that of the laydown within 20 % (measured 16 %:
    the drag on the line moving at 1 m/s, some 50 kN on the wire alone, reverses with the motion); the head
    lies within 1 m of one place while on the seabed."""
    model, _, results = laydown
    heads = head_positions(results, model)
    height = -heads[:, 2]
    tension = results.lay_summary()["top_tension"]
    down = results.stage == 3
    up = results.stage == 7
    assert height[up][-1] > 100.0
    levels = np.linspace(20.0, 100.0, 9)
    order_down = np.argsort(height[down])
    order_up = np.argsort(height[up])
    at_down = np.interp(levels, height[down][order_down], tension[down][order_down])
    at_up = np.interp(levels, height[up][order_up], tension[up][order_up])
    worst = np.abs(at_up / at_down - 1.0).max()
    print(f"\nlaydown {np.round(at_down / 1e3)} kN, recovery {np.round(at_up / 1e3)} kN: {worst:.1%}")
    assert worst < 0.20
    on_seabed = height < 0.5
    assert np.ptp(heads[on_seabed, 0]) < 1.0


def test_the_energy_ledger_closes_through_every_stage(
    laydown: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """E(t) − E(0) = W(t) − D(t) at every record through the stage changes, the hand-over (the wire and head
    brought in are booked with pay-out's energy, in W), the landing and the recovery: to 1e-9 of the energy
    (measured 1e-11)."""
    _, _, results = laydown
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    print(f"\nbalance {np.abs(balance).max():.3e} J of {np.abs(energy).max():.3e} J")
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()
    assert np.all(np.diff(results.dissipated) >= 0.0)


def test_stage_summary_has_each_stages_extremes(laydown: tuple[pl.Model, pl.Simulation, pl.Results]) -> None:
    """The summary's rows are the stages; its extremes are those of the records of each stage: the top tension,
    the wire's tension (none before the hand-over), the touchdown and the head's final place."""
    model, _, results = laydown
    summary = results.stage_summary(model, checks={"grade": "X65"})
    assert list(summary["name"]) == STAGES.names
    tension = results.lay_summary()["top_tension"]
    for k in range(len(STAGES)):
        assert summary["top_tension_max"][k] == pytest.approx(tension[results.stage == k].max(), rel=1e-12)
    assert np.isnan(summary["wire_tension_max"][:2]).all() and (summary["wire_tension_max"][2:] > 0).all()
    heads = head_positions(results, model)
    assert summary["head_x"][5] == pytest.approx(heads[_last(results, 5), 0], rel=1e-12)
    assert (summary["utilisation_max"] > 0).all()
    print("\n" + summary.to_string())
    # Held by the winch, the line departs along the wire's top chord (a cable's node has no rotation of its own).
    k = _last(results, 5)
    nodes = np.flatnonzero(np.isfinite(results.positions[k, :, 0]))
    chord = results.positions[k, nodes[-1]] - results.positions[k, nodes[-2]]
    departure = math.atan2(-chord[2], np.hypot(chord[0], chord[1]))
    assert results.lay_summary()["departure_angle"][k] == pytest.approx(departure, abs=1e-12)


# --- resume and bad input, on a short J-lay ---------------------------------------------------------------


def _short(winch: bool = True, controller: bool = True, tension_limit: float | None = None) -> pl.Model:
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (600.0, 0.0, 0.0), 60, PIPE)
    model = pl.Model(rod, pl.Sea(150.0, seabed=pl.Seabed(stiffness=1e5, friction=0.5, mobilisation=0.02)))
    model.pin("A")
    tower = np.array([math.sin(0.2), 0.0, -math.cos(0.2)])
    eta = [480.0, 0.0, -150.0, 0.0, 0.0, 0.0]
    pid = (
        pl.PID(kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=eta)
        if controller
        else None
    )
    a_r = (
        pl.Winch(EXIT + 5.0 * tower, tension_limit, wire=WIRE, element_length=10.0, head=HEAD)
        if winch
        else None
    )
    model.attach_vessel(
        "B", pl.Vessel.osv(), eta=eta, lay=pl.JLay(position=tuple(EXIT), angle=0.2), controller=pid, winch=a_r
    )
    return model


SHORT = pl.Stages(
    [
        pl.Stage("lay", duration=20.0, pay_out=0.3, route_speed=0.3),
        pl.Stage("hand-over", duration=10.0, hold="winch"),
        pl.Stage("lower", duration=30.0, winch_speed=0.5, route_speed=0.5),
    ]
)


@pytest.mark.parametrize("stop", [12.0, 25.0, 47.0])
def test_a_run_resumed_in_the_middle_of_a_stage_is_bit_identical(tmp_path: Path, stop: float) -> None:
    """Checkpointed in normal lay, in the hand-over stage (after the wire joined) and while lowering, and resumed
    on the model as built through the same stages, the run ends bit for bit where the uninterrupted one does."""
    model = _short()
    state = model.static()
    whole = model.simulation(state, dt=DT, stages=SHORT).run(progress=False)
    first = model.simulation(state, dt=DT, stages=SHORT)
    first.run(stop, progress=False)
    path = first.checkpoint(tmp_path / "stop.npz")
    resumed = pl.resume(model, path, stages=SHORT).run(progress=False)
    np.testing.assert_array_equal(resumed.positions[-1], whole.positions[-1])
    np.testing.assert_array_equal(resumed.section_forces[-1], whole.section_forces[-1])
    assert resumed.supplied_work[-1] + first.supplied_work == pytest.approx(
        whole.supplied_work[-1], rel=1e-12
    )
    np.testing.assert_array_equal(resumed.stage, _short_stage_of(resumed.time))


def _short_stage_of(time: np.ndarray) -> np.ndarray:
    """The stage of each record of the short run: boundaries at 20 and 30 s, a boundary record closing its stage."""
    return np.searchsorted(np.array([20.0, 30.0]) + 1e-9, time)


def test_results_files_keep_the_stages(tmp_path: Path) -> None:
    """to_netcdf and streaming both write the stages; pl.load reads them back."""
    model = _short()
    results = model.simulation(model.static(), dt=DT, stages=SHORT).run(progress=False)
    back = pl.load(results.to_netcdf(tmp_path / "r.nc"))
    assert back.stage_names == SHORT.names
    np.testing.assert_array_equal(back.stage, results.stage)
    streamed = model.simulation(model.static(), dt=DT, stages=SHORT)
    streamed.run(output=tmp_path / "s.nc", progress=False)
    loaded = pl.load(tmp_path / "s.nc")
    np.testing.assert_array_equal(loaded.stage, results.stage)
    np.testing.assert_array_equal(loaded.positions[-1], results.positions[-1])


def _simulate(model: pl.Model, stages: list[pl.Stage], rest: bool = False) -> pl.Simulation:
    state = model.rest() if rest else model.static()
    return model.simulation(state, dt=DT, stages=pl.Stages(stages))


@pytest.mark.parametrize(
    ("build", "key"),
    [
        (lambda: pl.Stage("no duration"), "duration"),
        (lambda: pl.Stage("negative", duration=-1.0), "duration"),
        (lambda: pl.Stage("crane", duration=1.0, hold="crane"), "hold"),
        (lambda: pl.Stage("ramp", duration=1.0, ramp=5.0), "ramp"),
        (lambda: pl.Stages([pl.Stage("a", duration=1.0), "b"]), r"stages\[1\]"),
        (
            lambda: _simulate(
                _short(winch=False),
                [pl.Stage("a", duration=1.0), pl.Stage("b", duration=1.0, winch_speed=0.5)],
            ),
            r"stages\[1\]\.winch_speed",
        ),
        (
            lambda: _simulate(
                _short(winch=False), [pl.Stage("a", duration=1.0), pl.Stage("b", duration=1.0, hold="winch")]
            ),
            r"stages\[1\]\.hold",
        ),
        (
            lambda: _simulate(_short(), [pl.Stage("a", duration=1.0, winch_speed=0.5)]),
            r"stages\[0\]\.winch_speed",
        ),
        (
            lambda: _simulate(
                _short(),
                [pl.Stage("a", duration=1.0, hold="winch"), pl.Stage("b", duration=1.0, pay_out=0.2)],
            ),
            r"stages\[1\]\.pay_out",
        ),
        (
            lambda: _simulate(_short(), [pl.Stage("a", duration=1.0, winch_tension=5e5)]),
            r"stages\[0\]\.winch_tension",
        ),
        (lambda: _simulate(_short(), [pl.Stage("a", duration=1.25)]), r"stages\[0\]\.duration"),
        (
            lambda: _simulate(
                _short(controller=False), [pl.Stage("a", duration=1.0, route_speed=0.5)], rest=True
            ),
            r"stages\[0\]\.route_speed",
        ),
        (lambda: pl.Winch((0.0, 0.0, 0.0), tension_limit=-1.0), "tension_limit"),
        (lambda: _j_lay(winch=pl.Winch((0.0, 5.0, -10.0), wire=WIRE)), "winch position"),
        (lambda: _j_lay(winch=pl.Winch(EXIT + 5.0 * TOWER, wire=PIPE)), "wire"),
        (lambda: _j_lay(winch=pl.Winch(EXIT + 5.0 * TOWER)), r"winch\.wire"),
    ],
)
def test_bad_stages_and_winches_name_their_key(build: object, key: str) -> None:
    with pytest.raises(pl.InputError, match=key):
        build()  # type: ignore[operator]


def test_a_constant_tension_winch_hauling_past_the_head_stops_with_an_input_error() -> None:
    """A winch holding more tension than the line pulls hauls in at full speed; in constant-tension mode it
    does not stop at the hold point for the hand-back (that is a commanded haul-in's), so reaching the pipe's
    end stops the run with an InputError saying so; the records before it are kept on the error."""
    model = _short()
    stages = [
        pl.Stage("hand-over", duration=2.0, hold="winch"),
        pl.Stage("haul", duration=30.0, winch_tension=5e6),
    ]
    simulation = _simulate(model, stages)
    with pytest.raises(pl.InputError, match="hauls its wire in past the pipe's end") as caught:
        simulation.run(progress=False)
    kept = caught.value.results  # type: ignore[attr-defined]
    assert kept.time[-1] > 2.0


def test_a_wire_beyond_the_winchs_limit_is_warned_of() -> None:
    """The winch runs at its speed whatever the tension: a wire pulled beyond its tension_limit is reported as a
    PhysicsWarning naming the tension, the time and the limit; within the limit, nothing is said."""
    limited = _short(tension_limit=1e4)
    with pytest.warns(
        pl.PhysicsWarning, match=r"A&R wire's tension .* exceeds the winch's tension_limit 10\.0 kN"
    ):
        limited.simulation(limited.static(), dt=DT, stages=SHORT).run(progress=False)
    ample = _short(tension_limit=1e8)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ample.simulation(ample.static(), dt=DT, stages=SHORT).run(progress=False)
    assert not [w for w in caught if "tension_limit" in str(w.message)]


def test_a_stage_can_start_from_statics_of_its_configuration() -> None:
    """A stage with statics=True starts from the line and vessel brought to rest in equilibrium where they
    are: one step after it the pipe's kinetic energy is down from 10 kJ to a twentieth (the DP, whose reference
    the vessel lagged, now pushes it on), the line is where an independent static solve with the vessel at
    that pose puts it to 0.1 m (measured 6.5 cm: the vessel's surge over that step) with the vessel's heave and
    pitch to 1 mm and 1e-3 rad, and the ledger closes with the restart booked as work supplied."""

    def build(eta: list[float]) -> pl.Model:
        rod = pl.Rod.straight((0.0, 0.0, 0.0), (600.0, 0.0, 0.0), 60, PIPE)
        model = pl.Model(rod, pl.Sea(150.0, seabed=pl.Seabed(stiffness=1e5)))
        model.pin("A")
        pid = pl.PID(
            kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=[520.0, 0, -150, 0, 0, 0]
        )
        lay = pl.JLay(position=(0.0, 0.0, -10.0), angle=0.2)
        model.attach_vessel("B", pl.Vessel.osv(), eta=eta, lay=lay, controller=pid)
        return model

    model = build([520.0, 0.0, -150.0, 0.0, 0.0, 0.0])
    stages = pl.Stages(
        [
            pl.Stage("pull", duration=20.0, route_speed=0.5),
            pl.Stage("statics", duration=10.0, statics=True, route_speed=0.0),
        ]
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        results = model.simulation(model.static(), dt=DT, stages=stages).run(progress=False)
        k = int(np.flatnonzero(results.stage == 0)[-1])
        eta = results.eta
        assert eta is not None
        static = build([eta[k, 0], eta[k, 1], -150.0, 0.0, 0.0, eta[k, 5]]).static()
    kinetic = results.energy["pipe_kinetic"]
    print(f"\nkinetic {kinetic[k]:.0f} J before, {kinetic[k + 1]:.0f} J one step after the restart")
    assert kinetic[k + 1] < 0.1 * kinetic[k]
    assert np.abs(results.positions[k + 1] - static.positions).max() < 0.1
    assert static.eta is not None
    assert abs(eta[k + 1, 2] - static.eta[2]) < 1e-3 and abs(eta[k + 1, 4] - static.eta[4]) < 1e-3
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()


def test_a_stage_restarting_from_statics_during_pay_out_ramps_the_pay_out_up_from_rest() -> None:
    """Statics bring the line to rest, so a stage that restarts from them while the tensioner pays out ramps
    the pay-out up from zero over its ramp (a pipe at rest fed at 0.5 m/s would take an axial shock of
    √(EA·m)·0.5 ≈ 0.6 MN): a J-lay of the 16-inch pipe in 500 m paying out at 0.5 m/s, restarted from statics
    at 20 s, pays out 0.5 · (20 − 10/2) = 7.5 m over the next 20 s, and its top tension stays within 5 % of its
    value before the restart."""
    rod = pl.Rod.straight(
        (0.0, 0.0, 0.0), (1000.0, 0.0, 0.0), 100, pl.Section.pipe(0.4064, 0.0206, contents_density=0.0)
    )
    sea = pl.Sea(500.0, seabed=pl.Seabed(stiffness=1e5, friction=0.5, mobilisation=0.02))
    model = pl.Model(rod, sea)
    model.pin("A")
    model.attach_vessel(
        "B",
        pl.Vessel.osv(),
        eta=[700.0, 0.0, -500.0, 0.0, 0.0, 0.0],
        lay=pl.JLay((-30.0, 0.0, -5.0), angle=0.2),
    )
    stages = pl.Stages(
        [pl.Stage("lay", 20.0, pay_out=0.5), pl.Stage("restart", 20.0, pay_out=0.5, statics=True, ramp=10.0)]
    )
    results = model.simulation(model.static(), dt=0.2, stages=stages).run(progress=False)
    restart = int(np.flatnonzero(results.stage == 1)[0])
    paid = results.length[-1] - results.length[restart - 1]
    tension = results.lay_summary()["top_tension"]
    swing = np.abs(tension[restart:] / tension[restart - 1] - 1.0).max()
    print(
        f"paid out {paid:.6f} m after the restart; top tension within {swing:.2%} of {tension[restart - 1]:.0f} N"
    )
    assert paid == pytest.approx(7.5, rel=1e-9)
    assert swing < 0.05


def test_a_winch_stage_can_start_from_statics_after_a_violent_start() -> None:
    """A stage held by the winch starts from statics too: after the winch jumps to 1 m/s in a second and pays
    out 60 m (the wire at 536 kN, the line moving with 0.41 MJ of kinetic energy), statics=True brings the
    line, its wire and head to rest in equilibrium: one step later its kinetic energy is below 1 J (measured
    1e-15 J, the vessel held still), the wire within 20 % of the hand-over's tension (measured 848 against
    999 kN: 60 m of wire more), and the ledger closes."""
    model = _j_lay(1660.0)
    stages = pl.Stages(
        [
            pl.Stage("hand-over", duration=30.0, hold="winch", winch_speed=0.0),
            pl.Stage("lower fast", duration=60.0, winch_speed=1.0, ramp=1.0),
            pl.Stage("settle", duration=20.0, statics=True, winch_speed=0.0),
        ]
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        simulation = model.simulation(model.static(), dt=DT, stages=stages)
        results = simulation.run(progress=False)
    k = int(np.flatnonzero(results.stage == 1)[-1])
    kinetic = results.energy["pipe_kinetic"]
    tension = results.lay_summary()["top_tension"]
    print(
        f"\nbefore: {kinetic[k]:.3e} J, {tension[k] / 1e3:.0f} kN; after one step: {kinetic[k + 1]:.3e} J, "
        f"{tension[k + 1] / 1e3:.0f} kN"
    )
    assert kinetic[k] > 1e5 and kinetic[k + 1] < 1.0
    assert simulation.hand_over_tension is not None
    assert tension[k + 1] == pytest.approx(simulation.hand_over_tension, rel=0.2)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()
