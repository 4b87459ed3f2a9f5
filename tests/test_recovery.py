"""Recovery through the hand-back, as `examples/j_lay_recovery.toml` runs it: the 0.6 m pipe, laid down on the
seabed in 800 m of water by the A&R winch from a 30° J-lay tower, is recovered: the winch hauls its 1560 m of
wire in while the vessel moves back, the head climbs the catenary, the winch slows down and stops with the
pipe's end at the tower clamp, which takes the pipe back (the hand-back), and normal lay resumes (module
fixture: ~20 s, a record every step).

References: the pipe's own length (the wire comes off whole: the line is the pipe that was handed over); the
tension through the hand-back against the stage's own step-to-step swing; the discrete energy ledger
E(t) − E(0) = W(t) − D(t) through the hand-back (the wire and head taken off booked with pay-out's energy); the
ramped pay-out's integral after it; a resumed run, bit for bit.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.analysis.stages import head_positions
from pipelay.scenario import Scenario, load_scenario
from test_winch import _j_lay

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "j_lay_recovery.toml"
ON_BOARD = 8  # the stage the hand-back happens in


@pytest.fixture(scope="module")
def recovery() -> tuple[Scenario, pl.Simulation, pl.Results]:
    scenario = load_scenario(EXAMPLE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        simulation = scenario.model.simulation(
            scenario.model.static(), dt=scenario.dt, stages=scenario.stages
        )
        results = simulation.run(progress=False)
    return scenario, simulation, results


def _hand_back_record(simulation: pl.Simulation, results: pl.Results) -> int:
    """The record at the hand-back's time: the last with the wire."""
    assert simulation.hand_back_time is not None
    return int(np.flatnonzero(np.isclose(results.time, simulation.hand_back_time))[0])


def test_the_tensioner_takes_back_the_pipe_it_handed_over(
    recovery: tuple[Scenario, pl.Simulation, pl.Results],
) -> None:
    """The hand-back happens in the "on board" stage, when the wire is hauled in to its length at the hand-over:
    the line is then the pipe as it was handed over (2027.5 m: 2000 m and 27.5 m of normal lay), without the wire's
    node or the head; normal lay then pays out the ramped 0.5 m/s for 120 s, 57.5 m."""
    scenario, simulation, results = recovery
    k = _hand_back_record(simulation, results)
    print(f"\nhand-back at t = {simulation.hand_back_time} s")
    assert results.stage[k] == ON_BOARD
    handed_over = results.length[np.flatnonzero(results.stage == 1)[-1]]
    assert handed_over == pytest.approx(2027.5, abs=1e-9)
    assert results.length[k + 1] == pytest.approx(handed_over, abs=1e-9)
    nodes = np.isfinite(results.positions[:, :, 0]).sum(axis=1)
    assert nodes[k + 1] == nodes[k] - 1
    heads = head_positions(results, scenario.model)
    assert np.isfinite(heads[k, 2]) and np.isnan(heads[k + 1 :, 2]).all()
    assert results.length[-1] - handed_over == pytest.approx(57.5, abs=1e-9)


def test_the_tension_passes_the_hand_back_within_the_stages_swing(
    recovery: tuple[Scenario, pl.Simulation, pl.Results],
) -> None:
    """The tower clamp takes the pipe where its end is, with its rotation, so the top tension passes from the
    wire to the clamp without a jump beyond the stage's own: the change over the hand-back's step is less than
    the largest step-to-step change in the stage before it (measured 54 against 88 kN), and over the stage
    after it the tension stays within the stage's range before it widened by half its swing (measured
    958 … 1175 kN after, 1025 … 1232 kN before)."""
    _, simulation, results = recovery
    k = _hand_back_record(simulation, results)
    tension = results.lay_summary()["top_tension"]
    stage = results.stage == ON_BOARD
    before = stage & (results.time <= results.time[k])
    after = stage & (results.time > results.time[k])
    low, high = tension[before].min(), tension[before].max()
    steps = np.abs(np.diff(tension[before])).max()
    jump = abs(tension[k + 1] - tension[k])
    print(
        f"\nhand-back: {tension[k] / 1e3:.1f} → {tension[k + 1] / 1e3:.1f} kN; before {low / 1e3:.0f} … "
        f"{high / 1e3:.0f} kN (steps ≤ {steps / 1e3:.1f}); after {tension[after].min() / 1e3:.0f} … "
        f"{tension[after].max() / 1e3:.0f} kN"
    )
    assert jump < steps
    margin = 0.5 * (high - low)
    assert low - margin < tension[after].min() and tension[after].max() < high + margin


def test_the_ledger_closes_through_the_hand_back(
    recovery: tuple[Scenario, pl.Simulation, pl.Results],
) -> None:
    """E(t) − E(0) = W(t) − D(t) at every record, through the laydown, the landing, the recovery and the
    hand-back, to 1e-9 of the energy (measured 4e-13): the wire and the 5 t head taken off (with the head's
    potential 800 m above the seabed) are booked in the pay-out energy at the hand-back."""
    _, simulation, results = recovery
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    k = _hand_back_record(simulation, results)
    taken_off = results.pay_out_energy[k + 1] - results.pay_out_energy[k]
    print(
        f"\nbalance {np.abs(balance).max():.3e} J of {np.abs(energy).max():.3e} J; taken off {taken_off:.4e} J"
    )
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()
    assert taken_off < 0.0


# --- the hand-back on a short recovery: resume and bad input ---------------------------------------------------


def _short_recovery(raise_for: float = 140.0) -> pl.Stages:
    return pl.Stages(
        [
            pl.Stage("hand-over", duration=30.0, hold="winch", winch_speed=0.0),
            pl.Stage("lower", duration=100.0, winch_speed=0.5, route_speed=0.5, ramp=20.0),
            pl.Stage("rest", duration=20.0, winch_speed=0.0, route_speed=0.0),
            pl.Stage("raise", duration=raise_for, winch_speed=-0.5, route_speed=-0.5, ramp=20.0),
            pl.Stage("lay again", duration=40.0, hold="tensioner", pay_out=0.5, route_speed=0.5, ramp=20.0),
        ]
    )


@pytest.mark.parametrize("stop", [250.0, 270.0])
def test_a_run_resumed_around_the_hand_back_is_bit_identical(tmp_path: Path, stop: float) -> None:
    """Checkpointed before the hand-back (at 259 s) and after it, and resumed, the run ends bit for bit where the
    uninterrupted one does: the checkpoint keeps the clamp the hand-back made."""
    model = _j_lay()
    stages = _short_recovery()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        whole = model.simulation(model.static(), dt=0.5, stages=stages)
        results = whole.run(progress=False)
        first = model.simulation(model.static(), dt=0.5, stages=stages)
        first.run(stop, progress=False)
        path = first.checkpoint(tmp_path / "stop.npz")
        resumed = pl.resume(model, path, stages=stages).run(progress=False)
    assert whole.hand_back_time == pytest.approx(259.0)
    # The records are padded to the most nodes a run had: compare the line's own.
    nodes = np.isfinite(results.positions[-1, :, 0])
    assert np.isfinite(resumed.positions[-1, :, 0]).sum() == nodes.sum()
    np.testing.assert_array_equal(resumed.positions[-1, : nodes.sum()], results.positions[-1, nodes])
    forces = results.section_forces[-1, : nodes.sum() - 1]
    np.testing.assert_array_equal(resumed.section_forces[-1, : nodes.sum() - 1], forces)


def test_a_tensioner_stage_before_the_head_is_back_names_its_key() -> None:
    """Hauled in for too short a time, the head is still below the tower when the tensioner should hold the pipe
    again: an InputError names the stage's hold and how much wire is still out; the records are kept."""
    model = _j_lay()
    simulation = model.simulation(model.static(), dt=0.5, stages=_short_recovery(raise_for=100.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        with pytest.raises(pl.InputError, match=r"stages\[4\]\.hold.* m of wire is still out") as caught:
            simulation.run(progress=False)
    kept = caught.value.results  # type: ignore[attr-defined]
    assert kept.time[-1] == pytest.approx(250.0)
