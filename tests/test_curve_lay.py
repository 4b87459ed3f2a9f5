"""Lay on a curve: a pipe on the seabed along an arc of radius R, pulled along its tangents at both ends with the
residual bottom tension H, holds when R > H/(μ_l W) and slides inward when not. Time-domain runs find the
threshold within 2 % of that formula (within 0.3 %: the arc's ends pull with 2H sin(Φ/2), a little less than
the H Φ its length holds against, a factor Φ/(2 sin(Φ/2)) = 1.0017 for Φ = 0.2 rad); the held pipe's lateral
friction utilisation is H/(R μ_l W) along the arc's middle, and its deviation from the planned arc is the
friction's elastic slip."""

from __future__ import annotations

import numpy as np
import pipelay as pl
import pytest

RADIUS, ANGLE, FRICTION, DEPTH = 200.0, 0.2, 0.5, 100.0
SECTION = pl.Section.pipe(0.4064, 0.02, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0))
ELEMENTS = 20
THETA = np.linspace(-ANGLE / 2, ANGLE / 2, ELEMENTS + 1)
# The arc, centred at (0, R): its middle at the origin, bulging toward −y; the pipe's centre on the seabed.
ARC = np.column_stack([RADIUS * np.sin(THETA), RADIUS - RADIUS * np.cos(THETA)])


def _weight() -> float:
    """The pipe's submerged weight W (N/m)."""
    return SECTION.submerged_weight


def _run(fraction: float) -> tuple[pl.Results, pl.State]:
    """The arc on a flat seabed (μ = 0.5 both ways, mobilisation 1 cm), settled for 10 s, its end tensions ramped to
    `fraction` of μ_l W R over 20 s and held to t = 60 s."""
    nodes = np.column_stack([ARC, np.zeros(ELEMENTS + 1)])
    seabed = pl.Seabed(stiffness=1e5, damping=2e4, friction=[FRICTION, FRICTION], mobilisation=0.01)
    model = pl.Model(pl.Rod(nodes, SECTION), sea=pl.Sea(DEPTH, seabed=seabed))
    tension = fraction * FRICTION * _weight() * RADIUS
    for node, angle, sign in ((0, THETA[0], -1.0), (ELEMENTS, THETA[-1], 1.0)):
        tangent = np.array([np.cos(angle), np.sin(angle), 0.0])
        model.point_load(
            node, force=tuple(sign * tension * tangent), scale=lambda t: np.clip((t - 10.0) / 20.0, 0, 1)
        )
    simulation = model.simulation(state=model.rest(), dt=0.1)
    results = simulation.run(60.0, progress=False)
    return results, simulation.state


def _slides(fraction: float) -> bool:
    """Whether the arc's middle moves inward by more than 10 cm over the 30 s after the tension is in."""
    results, _ = _run(fraction)
    middle = results.positions[:, ELEMENTS // 2, 1]
    held = results.time >= 30.0
    return bool(middle[-1] - middle[held][0] > 0.1)


def test_the_curve_slides_at_the_tension_the_formula_gives() -> None:
    """Bisection on H between 0.9 and 1.1 of μ_l W R brackets the sliding threshold within 0.3 % of the formula,
    on the side the arc's end geometry puts it."""
    low, high = 0.9, 1.1
    assert not _slides(low) and _slides(high)
    while high - low > 0.002:
        middle = 0.5 * (low + high)
        low, high = (low, middle) if _slides(middle) else (middle, high)
    ends = ANGLE / (2 * np.sin(ANGLE / 2))
    print(f"the arc slides between H = {low:.4f} and {high:.4f} of μ_l W R (ends' factor {ends:.4f})")
    assert low <= ends + 0.002 and high >= ends - 0.002
    assert abs(0.5 * (low + high) - 1.0) < 0.02


def test_held_curve_reports_its_friction_utilisation_and_deviation() -> None:
    """At 0.95 μ_l W R the arc holds: its middle third uses 0.95 of its lateral friction (within 2 %), and it lies
    within the friction's elastic slip (1 cm mobilisation) of the planned arc."""
    _, state = _run(0.95)
    utilisation = pl.curve_lay.lateral_friction_utilisation(state, FRICTION)
    third = slice(ELEMENTS // 3, 2 * ELEMENTS // 3 + 1)
    print(f"utilisation along the middle third: {np.round(utilisation[third], 3)}")
    assert np.allclose(utilisation[third], 0.95, rtol=0.02)
    deviation = pl.curve_lay.route_deviation(state, ARC)
    assert np.max(deviation) < 0.011, np.max(deviation)
    assert pl.curve_lay.minimum_radius(
        0.95 * FRICTION * _weight() * RADIUS, _weight(), FRICTION
    ) == pytest.approx(0.95 * RADIUS)


def test_bad_input_names_the_argument() -> None:
    with pytest.raises(pl.InputError, match="lateral_friction"):
        pl.curve_lay.minimum_radius(1e5, 500.0, 0.0)
    with pytest.raises(pl.InputError, match="route"):
        pl.curve_lay.route_deviation(
            pl.Model(pl.Rod.straight((0, 0, 0), (1, 0, 0), 1, SECTION)).rest(), [[0, 0]]
        )
