"""S-lay abandonment, as `examples/s_lay_abandonment.toml` runs it: the 24-inch pipe in 150 m of water is handed
over from the tensioner to the A&R winch (10 m forward of it on the firing line) with a 5 t head, 3 m long, on
its end, and the winch pays the wire out as the vessel moves on at 1 m/s, so that the head runs aft over the
stinger's 15 rollers (the default 1e7 N/m), leaves its tip and goes down the catenary to the seabed, with the
solver's high-frequency damping ξ = 0.1 (module fixture: ~15 s).

References: the normal lay's roller loads (their static values and the dynamic margin the run itself shows
before the hand-over) for the head's passage over the rollers; the laid pipe's length for where the head lands;
the discrete energy ledger through the stages.
"""

from __future__ import annotations

import math
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.analysis.stages import head_positions
from pipelay.scenario import Scenario, load_scenario, parse_scenario

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "s_lay_abandonment.toml"
STINGER_TIP = -40.0 - 200.0 * math.sin(100.0 / 200.0)  # body x of the stinger's last roller top (m)


@pytest.fixture(scope="module")
def abandonment() -> tuple[Scenario, pl.State, pl.Results]:
    scenario = load_scenario(EXAMPLE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        state = scenario.model.static()
        simulation = scenario.simulation(state)
        results = simulation.run(progress=False, record_every=scenario.record_every)
    return scenario, state, results


def _head_along_vessel(results: pl.Results, heads: np.ndarray) -> np.ndarray:
    """The head's distance forward of CO along the vessel's heading (m), records (T,)."""
    eta = results.eta
    assert eta is not None
    offset = heads[:, :2] - eta[:, :2]
    return offset[:, 0] * np.cos(eta[:, 5]) + offset[:, 1] * np.sin(eta[:, 5])


def test_the_head_runs_over_the_rollers_within_the_normal_lays_loads(
    abandonment: tuple[Scenario, pl.State, pl.Results],
) -> None:
    """The head's padeye starts 3 m forward of the tensioner (13 m forward of CO, less the winch's last
    creep) and runs aft past every roller to the stinger's tip (body x = −135.9 m) and beyond. While it crosses
    the stinger's first 11 rollers (forward of −100 m) no roller carries more than the normal lay's largest load
    (the static 113 kN plus the margin of the normal lay's own dynamics, measured 8 %) by more than 50 %
    (measured 31 %: the head's taper rides over each roller at 1 m/s). Over the last rollers the stiff pipe's
    end pivots on the tip roller with the pipe hanging below it: that roller's load peaks at 2.4 times the
    static (275 kN), still below the wire's tension there (819 kN: a deflection under 60°). The wire never goes
    slack (its least tension 168 kN, a fifth of its largest)."""
    scenario, state, results = abandonment
    heads = head_positions(results, scenario.model)
    along = _head_along_vessel(results, heads)
    rollers = results.roller_reactions
    assert rollers is not None and state.roller_reactions is not None
    static = state.roller_reactions.max()
    normal = rollers[results.stage == 0].max()
    margin = normal / static - 1.0
    seen = np.isfinite(along)
    ahead = seen & (along > -100.0)
    passing = rollers[ahead].max()
    tip = seen & (along <= -100.0) & (along > STINGER_TIP - 10.0)
    peak = int(np.flatnonzero(tip)[np.argmax(rollers[tip, -1])])
    tension = results.lay_summary()["top_tension"]
    print(
        f"\nstatic {static / 1e3:.1f} kN, normal lay {normal / 1e3:.1f} kN (margin {margin:.1%}); head ahead of "
        f"the last rollers {passing / 1e3:.1f} kN; tip roller at the head's pivot {rollers[peak, -1] / 1e3:.1f} kN "
        f"(wire {tension[peak] / 1e3:.1f} kN)"
    )
    assert along[seen][0] == pytest.approx(13.0, abs=1.5)
    assert along[seen].min() < STINGER_TIP - 100.0
    assert np.all(np.diff(along[ahead]) < 0.5)  # aft, record after record (the vessel moving on)
    assert 0.0 < margin < 0.5
    assert passing <= 1.5 * normal
    assert normal < rollers[peak, -1] < tension[peak]
    summary = results.stage_summary(scenario.model)
    assert summary["wire_tension_min"][2] > 0.1 * summary["wire_tension_max"][2]
    # The stage summary's tip clearance is the lay summary's least in each stage; the head's pivot closes it.
    clearance = results.lay_summary()["tip_clearance"]
    for k in range(len(summary)):
        assert summary["tip_clearance_min"][k] == pytest.approx(
            np.nanmin(clearance[results.stage == k]), abs=1e-12
        )
    assert clearance[peak] < 0.0


def test_the_head_lands_at_the_laid_pipes_end(abandonment: tuple[Scenario, pl.State, pl.Results]) -> None:
    """The head lands during the abandonment stage and rests on the seabed (sunk by its weight, a few cm) at
    the laid pipe's length from the pile: the 700 m of pipe and the 27.5 m paid out in normal lay (0.5 m/s for
    60 s less half the 10 s ramp), plus the head's 3 m to its padeye, stretched by its residual tension (within
    one 5 m element; measured 3.02 m beyond the pipe's length)."""
    scenario, _, results = abandonment
    heads = head_positions(results, scenario.model)
    pipe_length = 700.0 + 0.5 * 60.0 - 0.5 * 0.5 * 10.0
    handed = int(np.flatnonzero(results.stage == 1)[0])
    assert results.length[handed - 1] == pytest.approx(pipe_length, abs=1e-9)
    landed = np.flatnonzero(-heads[:, 2] < 0.2)
    assert results.stage[landed[0]] == 2
    final = heads[-1]
    print(f"\nhead lands at t = {results.time[landed[0]]:.0f} s, rests at {final}")
    assert abs(final[0] - pipe_length - 3.0) < 5.0
    assert abs(final[1]) < 1e-6 and 0.0 < final[2] < 0.2


def test_the_ledger_closes_through_the_abandonment(
    abandonment: tuple[Scenario, pl.State, pl.Results],
) -> None:
    """E(t) − E(0) = W(t) − D(t) through the hand-over, the head's passage over the rollers and its landing, the
    high-frequency damping's work in D: to 1e-9 of the energy (measured 2e-11). Once the head has reached the
    stinger's last rollers the wire on them takes some steps in substeps (measured 119 records of 336, at most 8
    substeps a step)."""
    _, _, results = abandonment
    split = results.substeps > 1
    assert 0 < np.count_nonzero(split)
    assert results.substeps[0] == 1 and results.substeps.max() <= 32
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    print(f"\nbalance {np.abs(balance).max():.2e} J of {np.abs(energy).max():.2e} J")
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()


def test_the_substeps_are_kept_in_the_file(
    abandonment: tuple[Scenario, pl.State, pl.Results], tmp_path: Path
) -> None:
    """`results.substeps` goes to the netCDF file and comes back from it."""
    _, _, results = abandonment
    loaded = pl.load(results.to_netcdf(tmp_path / "abandonment.nc"))
    assert np.array_equal(loaded.substeps, results.substeps)


@pytest.fixture(scope="module")
def stopped() -> tuple[Scenario, pl.Results]:
    """The example's abandonment for 200 s (the head has left the stinger's tip and hangs 26 m below it), then
    the vessel stopped for 150 s while the winch lowers the head on at 0.5 m/s, at the example's Δt = 0.5 s (~8 s)."""
    data = tomllib.loads(EXAMPLE.read_text())
    data["stages"][2]["duration"] = 200.0
    data["stages"][3] = {"name": "stopped", "duration": 150.0, "winch_speed": 0.5, "route_speed": 0.0}
    scenario = parse_scenario(data, origin=str(EXAMPLE))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        state = scenario.model.static()
        results = scenario.simulation(state).run(progress=False, record_every=scenario.record_every)
    return scenario, results


def test_the_head_is_lowered_on_with_the_vessel_stopped(stopped: tuple[Scenario, pl.Results]) -> None:
    """With the vessel stopped while the head hangs below the stinger's tip, the winch lowers it on: the head
    goes down at every record (2 s) of the stopped stage, by more than the 75 m of wire paid out at 0.5 m/s in
    150 s less 10 % (measured 89.4 m: the wire swings down under the vessel as well); the wire never goes slack
    (least tension 125 kN, a seventh of the stage's largest) and the ledger closes to 1e-9 of the energy."""
    scenario, results = stopped
    heads = head_positions(results, scenario.model)
    depth = heads[results.stage == 3, 2]  # z down, 0 on the seabed
    tension = results.lay_summary()["top_tension"][results.stage == 3]
    print(
        f"\nhead lowered {depth[-1] - depth[0]:.1f} m; wire {tension.min() / 1e3:.0f}–{tension.max() / 1e3:.0f} kN"
    )
    assert np.all(np.diff(depth) > 0.0)
    assert depth[-1] - depth[0] > 0.9 * 0.5 * 150.0
    assert tension.min() > 0.1 * tension.max()
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()
