"""Roller boxes on the stinger: their geometry on the arc, frictionless V boxes' reactions against the closed form
F/(2 cos θ) in a whole S-lay, the example on V boxes in a 1 m/s beam current (statics, the lay summary's box loads
and tip offset, a dynamic run whose energy ledger closes), and the scenario keys and bad input.

The closed forms of a single box (each roller F/(2 cos θ), the climb-out at a lateral load F tan θ) are tested on
the contact itself in the engine (`contact::rollers::box_tests`)."""

from __future__ import annotations

import copy
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.plots.replay import prepare
from pipelay.report import run_report
from pipelay.scenario import load_scenario, parse_scenario

EXAMPLE = Path(__file__).parent.parent / "examples" / "s_lay_beam_current.toml"
THETA = np.radians(30.0)


def _example(**current: object) -> dict:
    """The beam-current example's document, its current's keys replaced by `current`."""
    data = tomllib.loads(EXAMPLE.read_text())
    data["sea"]["current"].update(current)
    return data


def test_boxes_stand_on_the_stinger_arc_across_it() -> None:
    """Each box's station lies on the arc of radius R; a V's rollers lie in the plane normal to the arc, rising
    at ±θ from b2; with sides the box has four rollers; a box at its own arc length stands there."""
    radius, origin = 200.0, np.array([-40.0, 0.0, -6.0])
    box = pl.RollerBox(kind="v", half_angle=THETA, roller_length=1.2, sides=True)
    stinger = pl.Stinger(radius, 100.0, 5, origin=origin, boxes=[box] * 5)
    assert len(stinger) == 20 and stinger.supports == [b for b in range(5) for _ in range(4)]
    centre = origin + radius * np.array([0.0, 0.0, 1.0])
    assert np.allclose(np.linalg.norm(stinger.stations - centre, axis=1), radius, atol=1e-9)
    axes = stinger.axes
    for b in range(5):
        port, starboard, side_port, side_starboard = axes[4 * b : 4 * b + 4]
        assert np.isclose(abs(port[1]), np.cos(THETA)) and np.isclose(abs(starboard[1]), np.cos(THETA))
        assert port[1] < 0 < starboard[1]
        # The plane of the box holds b2 and the outward normal: no roller runs along the stinger's tangent.
        station = stinger.stations[b]
        tangent = np.cross([0.0, 1.0, 0.0], (station - centre) / radius)
        assert np.allclose(axes[4 * b : 4 * b + 4] @ tangent, 0.0, atol=1e-12)
        assert np.allclose(side_port, side_starboard)
    assert np.allclose(stinger.lengths, 1.2)
    placed = pl.Stinger(radius, 100.0, 5, origin=origin, boxes=[pl.RollerBox(arc_length=30.0)])
    arc = 2 * radius * np.arcsin(np.linalg.norm(placed.stations[0] - origin) / (2 * radius))
    assert len(placed) == 2 and np.isclose(arc, 30.0)


def test_frictionless_v_boxes_share_each_load_as_the_closed_form() -> None:
    """In still water each box of the example carries its load F on two rollers of F/(2 cos θ) each, F the
    box's resultant, which lies in the box's plane along its outward normal."""
    state = parse_scenario(_example(velocity=[0.0, 0.0, 0.0]), "still water").model.static()
    vectors, supports = state.roller_reaction_vectors, np.array(state.roller_supports)
    loaded, worst = 0, 0.0
    for b in range(supports.max() + 1):
        rollers = vectors[supports == b]
        resultant = np.linalg.norm(rollers.sum(axis=0))
        if resultant < 1e3:
            continue
        loaded += 1
        normal = np.linalg.norm(rollers[:2], axis=1)
        worst = max(worst, np.max(np.abs(normal * 2 * np.cos(THETA) / resultant - 1)))
        assert np.all(np.linalg.norm(rollers[2:], axis=1) == 0.0)  # the side rollers stay clear
    assert loaded >= 12
    print(f"largest deviation from F/(2 cos θ): {worst:.2e}")
    assert worst < 1e-5
    loads = pl.support_loads(state)
    assert loads is not None and loads.boxes and loads.stays_in_boxes
    assert np.all(np.abs(loads.lateral) < 1e-6 * np.maximum(loads.vertical, 1.0) + 1e-6)
    assert abs(loads.tip_offset) < 1e-6


def test_s_lay_in_a_beam_current_on_v_boxes_solves_with_lateral_loads() -> None:
    """The example: statics converge with the current; the boxes push the pipe back against it (to port) in
    total, the pipe sits to starboard at the tip and stays in its boxes. A frictionless V holds at most tan θ
    of a box's load along its outward normal sideways, and exactly that where the pipe rides on one roller."""
    state = load_scenario(EXAMPLE).model.static()
    loads = pl.support_loads(state)
    assert loads is not None and loads.stays_in_boxes
    assert loads.lateral.sum() < -50e3, loads.lateral
    assert 0.05 < loads.tip_offset < 0.6, loads.tip_offset
    # The stinger's outward normal at each box: from the arc's centre (200 m below the origin) to the station.
    stations = pl.Stinger(200.0, 100.0, 15, origin=[-40.0, 0.0, -6.0]).positions
    up = (stations - np.array([-40.0, 0.0, 194.0])) / 200.0
    supports = np.array(state.roller_supports)
    one_roller = 0
    for b in range(15):
        rollers = state.roller_reaction_vectors[supports == b]
        resultant = rollers.sum(axis=0)
        along_normal, lateral = resultant @ up[b], resultant[1]
        assert abs(lateral) <= np.tan(THETA) * along_normal * (1 + 1e-4) + 1e-6, b
        if np.count_nonzero(np.linalg.norm(rollers[:2], axis=1)) == 1:
            one_roller += 1
            assert abs(lateral) == pytest.approx(np.tan(THETA) * along_normal, rel=1e-4), b
    assert one_roller >= 3


def test_the_beam_current_run_keeps_the_pipe_in_its_boxes_and_the_ledger_exact(tmp_path: Path) -> None:
    """From still water, the 1 m/s beam current starting at 5 s pushes the pipe toward starboard on the boxes
    in a 20 s run: it stays in them, its tip offset grows from 0, and the energy ledger closes to 1e-8 of the
    stored energy. The run records the rollers' reaction vectors, the report tabulates each box's loads, and
    the replay draws the boxes' rollers."""
    scenario = parse_scenario(_example(start=5.0), "beam current from 5 s")
    simulation = scenario.model.simulation(dt=0.2)
    results = simulation.run(20.0, progress=False)
    lay = results.lay_summary()
    assert lay is not None
    assert np.all(lay["boxes_left"] == 0)
    assert lay["tip_offset"][0] == pytest.approx(0.0, abs=1e-6) and np.max(lay["tip_offset"]) > 0.02
    energy = results.energy["total"]
    balance = energy[-1] - energy[0] - (results.supplied_work[-1] - results.dissipated[-1])
    assert abs(balance) < 1e-8 * abs(energy[0]), balance
    # The run records each roller's reaction vector, whose size is its normal force.
    vectors = results.roller_reaction_vectors
    assert vectors is not None and vectors.shape == (len(results.time), 60, 3)
    assert np.allclose(np.linalg.norm(vectors, axis=2), results.roller_reactions, rtol=1e-12, atol=1e-6)
    # The report's table gives each box's largest lateral load over the run.
    report = run_report(results, tmp_path / "report.html", model=scenario.model, replay=False).read_text()
    supports = np.array(simulation.state.roller_supports)
    lateral = [vectors[:, supports == b, 1].sum(axis=1) for b in range(15)]
    tip = lateral[13][np.argmax(np.abs(lateral[13]))]
    assert 'id="roller-boxes"' in report and f'data-value="{float(tip / 1e3)!r}"' in report
    # The replay draws each box's rollers as lines 1.2 m long, in the vessel's frame as it moves.
    scene = prepare(results, scenario.model, "tension", 5)
    assert scene.equipment is not None and scene.equipment[0] == "roller boxes"
    lines = scene.equipment[1][-1].reshape(60, 3, 3)
    assert np.allclose(np.linalg.norm(lines[:, 1] - lines[:, 0], axis=1), 1.2, atol=0.011)
    assert np.all(np.isnan(lines[:, 2]))


def test_pipelay_static_prints_each_boxs_loads() -> None:
    """`pipelay static` on the example names the lift-off box, the tip offset, whether the pipe stays in its
    boxes and each box's vertical and lateral load."""
    out = subprocess.run(
        [sys.executable, "-m", "pipelay", "static", str(EXAMPLE)], capture_output=True, text=True, check=True
    ).stdout
    assert "lay: lift-off box" in out and "of 15" in out
    assert "lay: pipe in its boxes  yes" in out
    assert "roller box loads on the pipe (kN, vertical up / lateral to starboard), boxes 1 to 15" in out
    offset = float(out.split("lay: tip offset")[1].split("m")[0])
    assert 0.05 < offset < 0.6


def test_scenario_boxes_and_bad_input_are_refused_clearly() -> None:
    """`boxes` places each box; `box` and `boxes` together, a box's arc length beyond the stinger, an unknown
    kind, a half-angle of 90° and a negative friction are refused, naming the key or argument."""
    data = _example()
    stinger = data["vessel"]["lay"]["stinger"]
    box = stinger.pop("box")
    placed = copy.deepcopy(data)
    placed["vessel"]["lay"]["stinger"]["boxes"] = [dict(box, arc_length=s) for s in (60.0, 80.0, 100.0)]
    model = parse_scenario(placed, "three boxes").model
    assert model is not None
    both = copy.deepcopy(data)
    both["vessel"]["lay"]["stinger"].update(box=box, boxes=[box])
    with pytest.raises(pl.InputError, match="box"):
        parse_scenario(both, "both")
    beyond = copy.deepcopy(data)
    beyond["vessel"]["lay"]["stinger"]["boxes"] = [dict(box, arc_length=120.0)]
    with pytest.raises(pl.InputError, match="arc_length.*120"):
        parse_scenario(beyond, "beyond")
    with pytest.raises(pl.InputError, match="kind"):
        pl.RollerBox(kind="w")
    with pytest.raises(pl.InputError, match="half_angle"):
        pl.RollerBox(half_angle=np.pi / 2)
    with pytest.raises(pl.InputError, match="friction"):
        pl.RollerBox(friction=-0.2)
    with pytest.raises(pl.InputError, match="boxes"):
        pl.Stinger(200.0, 100.0, 15, boxes=[pl.RollerBox()] * 3)
