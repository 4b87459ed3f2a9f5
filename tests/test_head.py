"""The laydown head as a body: `pl.Winch(..., head=pl.Clump(...), head_length=, head_diameter=)`.

The line: the 0.6 m pipe of test_winch.py in 800 m of water on the 30° J-lay tower that matches its catenary,
handed over to the A&R winch 5 m up the tower, lowered 50 m, hauled back and handed back to the tower clamp.
The head: 5 t, 0.8 m³, 3 m long, 0.6 m across at the pipe's end, tapering to the wire's 80 mm at its padeye.

References: the same run with the head as a point body of the same mass, volume, drag and added mass (the
line's tension the same to the head's own dynamics); the discrete energy ledger; the mesh (the head is one
element of its own section, and comes off with the wire at the hand-back). The rollers' view of the taper is
tested in the engine (`a_tapered_element_touches_a_roller_where_its_gap_is_least`).
"""

from __future__ import annotations

import warnings

import numpy as np
import pipelay as pl
import pytest
from test_stages import ANGLE, DEPTH, EXIT, HEAD, PIPE, TOWER, WIRE

BODY = {"head_length": 3.0, "head_diameter": 0.6}


def _j_lay(body: dict[str, float]) -> pl.Model:
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (2000.0, 0.0, 0.0), 200, PIPE)
    model = pl.Model(rod, pl.Sea(DEPTH, seabed=pl.Seabed(stiffness=1e5, friction=0.5, mobilisation=0.02)))
    model.pin("A")
    eta = [1660.0, 0.0, -DEPTH, 0.0, 0.0, 0.0]
    controller = pl.PID(kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=eta)
    winch = pl.Winch(EXIT + 5.0 * TOWER, wire=WIRE, element_length=10.0, head=HEAD, **body)
    lay = pl.JLay(position=tuple(EXIT), angle=ANGLE)
    model.attach_vessel("B", pl.Vessel.osv(), eta=eta, lay=lay, controller=controller, winch=winch)
    return model


STAGES = pl.Stages(
    [
        pl.Stage("hand-over", duration=30.0, hold="winch", winch_speed=0.0),
        pl.Stage("lower", duration=100.0, winch_speed=0.5, route_speed=0.5, ramp=20.0),
        pl.Stage("raise", duration=140.0, winch_speed=-0.5, route_speed=-0.5, ramp=20.0),
        pl.Stage("lay", duration=40.0, hold="tensioner", pay_out=0.5, route_speed=0.5, ramp=20.0),
    ]
)


def _run(body: dict[str, float]) -> tuple[pl.Simulation, pl.Results]:
    model = _j_lay(body)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        simulation = model.simulation(model.static(), dt=0.5, stages=STAGES)
        return simulation, simulation.run(progress=False)


@pytest.fixture(scope="module")
def runs() -> tuple[tuple[pl.Simulation, pl.Results], tuple[pl.Simulation, pl.Results]]:
    return _run({}), _run(BODY)


def test_the_head_body_is_an_element_of_the_line_until_the_hand_back(
    runs: tuple[tuple[pl.Simulation, pl.Results], tuple[pl.Simulation, pl.Results]],
) -> None:
    """At the hand-over the head joins the line as one element (3 m, of its own segment) between the pipe's
    end and the wire, so the winch holds one node more than with a point head; at the hand-back both come off,
    and the line is the pipe again (2000 m, then the 15 m of lay)."""
    (_, point), (simulation, body) = runs
    nodes = np.isfinite(body.positions[:, :, 0]).sum(axis=1)
    point_nodes = np.isfinite(point.positions[:, :, 0]).sum(axis=1)
    # Over the hand-over stage (the brake on: no wire paid out, no remeshing).
    handed = (body.stage == 0) & (body.time > 0.0)
    assert (nodes[handed] == point_nodes[handed] + 1).all()
    k = int(np.flatnonzero(handed)[0])
    top = nodes[k] - 2  # the wire's element; the head's is the one before it
    segments = body.segment[k, : nodes[k] - 1]
    assert segments[top - 1] not in (segments[0], segments[top])
    chord = np.linalg.norm(body.positions[k, top] - body.positions[k, top - 1])
    assert chord == pytest.approx(3.0, rel=1e-3)
    assert simulation.hand_back_time is not None
    assert nodes[-1] == point_nodes[-1]
    assert body.length[-1] == pytest.approx(2015.0, abs=1e-9)


def test_the_line_pulls_as_with_a_point_head_of_the_same_mass(
    runs: tuple[tuple[pl.Simulation, pl.Results], tuple[pl.Simulation, pl.Results]],
) -> None:
    """The head's mass, buoyancy, drag and added mass spread over its 3 m instead of one node: the hand-over
    passes the same axial force, and the top tension of each stage spans the point head's to 5 % (measured
    3.3 %); the ledger closes to 1e-9 of the energy with the head body too."""
    (point_simulation, point), (simulation, body) = runs
    assert simulation.hand_over_tension == pytest.approx(point_simulation.hand_over_tension, rel=1e-12)
    tension, point_tension = body.lay_summary()["top_tension"], point.lay_summary()["top_tension"]
    for stage in range(len(STAGES)):
        ours, theirs = tension[body.stage == stage], point_tension[point.stage == stage]
        low, high = abs(ours.min() / theirs.min() - 1.0), abs(ours.max() / theirs.max() - 1.0)
        print(
            f"\n{STAGES[stage].name}: {ours.min() / 1e3:.0f} … {ours.max() / 1e3:.0f} kN against "
            f"{theirs.min() / 1e3:.0f} … {theirs.max() / 1e3:.0f} kN",
            end="",
        )
        assert low < 0.05 and high < 0.05
    energy = body.energy["total"]
    balance = energy - energy[0] - body.supplied_work + body.dissipated
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()


@pytest.mark.parametrize(
    ("arguments", "key"),
    [
        ({"head_length": 3.0}, "head_diameter"),
        ({"head_diameter": 0.6}, "head_length"),
        ({"head_length": -3.0, "head_diameter": 0.6}, "head_length"),
        ({"head_length": 3.0, "head_diameter": 0.6, "head": None}, "head_length"),
    ],
)
def test_a_bad_head_body_names_its_key(arguments: dict[str, float | None], key: str) -> None:
    given = {"head": HEAD, **arguments}
    with pytest.raises(pl.InputError, match=key):
        pl.Winch(EXIT + 5.0 * TOWER, wire=WIRE, **given)  # type: ignore[arg-type]


def test_a_head_that_leaves_no_wire_to_the_winch_is_refused() -> None:
    """The winch 5 m up the tower cannot take a 4.5 m head: less than 1 m of wire would be left."""
    with pytest.raises(pl.InputError, match="head_length.*1 m of wire"):
        _j_lay({"head_length": 4.5, "head_diameter": 0.6})
