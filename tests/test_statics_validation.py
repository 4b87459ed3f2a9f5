"""Validation ladder for statics: analytic solutions, the literature, and the hanging pipe.

Conventions (see ``shared/API.md``): SI units; frame e with e3 pointing DOWN (gravity = +g e3), the sea surface
at z = −depth; end "A" = node 0, "B" = node n; ``state.reaction(end)`` is the force and moment (in e) that the
rod exerts on that support.

Rungs:

* roll-up of a cantilever under an end moment (Euler's elastica: an exact circle) and its convergence order;
* a cantilever under a small tip load against Timoshenko beam theory, with and without a shear term that matters;
* the 45° bend of Bathe & Bolourchi (1979) against Simo & Vu-Quoc (1986);
* a hanging line with negligible bending stiffness against Irvine's elastic catenary (our own solver, ``irvine.py``);
* the 1200 m steel pipe of the paper's scenario, pinned or clamped, converging from a straight reference.
"""

from __future__ import annotations

import math

import numpy as np
import pipelay as pl
import pytest
from irvine import irvine_catenary

# ----------------------------------------------------------------------------------------------------------
# Helpers
# ----------------------------------------------------------------------------------------------------------

RHO_WATER = 1025.0  # kg/m³
G = 9.81  # m/s²


def rot_e3(angle: float) -> np.ndarray:
    """Rotation by ``angle`` (rad) about e3, as a 3×3 matrix."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def beam_section(ea: float, ga: float, gj: float, ei: float) -> pl.Section:
    """A weightless-in-practice section (mass 1 kg/m, used with gravity = 0) of the given stiffnesses (N, N·m²)."""
    return pl.Section(EA=ea, GA=ga, GJ=gj, EI=ei, mass=1.0, inertia=(1.0, 0.5, 0.5))


def cantilever(length: float, elements: int, section: pl.Section) -> pl.Model:
    """A straight rod from the origin along e1, clamped at A, no gravity and no sea."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (length, 0.0, 0.0), elements, section)
    model = pl.Model(rod, gravity=0.0)
    model.clamp("A")
    return model


def observed_order(elements: list[int], errors: list[float]) -> tuple[float, list[float]]:
    """Least-squares slope of −log(error) against log(n), and the orders of successive refinements."""
    x = np.log(np.asarray(elements, dtype=float))
    y = np.log(np.asarray(errors, dtype=float))
    slope = -float(np.polyfit(x, y, 1)[0])
    pairwise = [
        math.log(errors[i] / errors[i + 1]) / math.log(elements[i + 1] / elements[i])
        for i in range(len(errors) - 1)
    ]
    return slope, pairwise


def assert_converged(state: pl.State) -> None:
    """The solver reports a full load factor and integer counters."""
    assert state.load_factor == pytest.approx(1.0, abs=1e-12)
    assert isinstance(state.iterations, int) and state.iterations >= 1
    assert isinstance(state.steps, int) and state.steps >= 1


# ----------------------------------------------------------------------------------------------------------
# The reference solver itself
# ----------------------------------------------------------------------------------------------------------


def test_irvine_helper_closes_and_matches_the_inextensible_catenary() -> None:
    """Our Irvine solver meets its end conditions to 1e-9 m and, for level supports and a stiff cable,
    the closed form L = (2H/w) sinh(w l / 2H) of the inextensible catenary to 1e-9 relative."""
    cat = irvine_catenary(length=1200.0, span=850.0, rise=800.0, weight=1845.7, ea=5.7e9)
    x, y = cat.point(1200.0)
    assert x == pytest.approx(850.0, abs=1e-9)
    assert y == pytest.approx(800.0, abs=1e-9)
    assert cat.vertical_b - cat.vertical_a == pytest.approx(1845.7 * 1200.0, rel=1e-12)

    w, span, length = 10.0, 100.0, 120.0
    level = irvine_catenary(length=length, span=span, rise=0.0, weight=w, ea=1e16)
    h = level.horizontal
    assert 2.0 * h / w * math.sinh(w * span / (2.0 * h)) == pytest.approx(length, rel=1e-9)
    assert level.vertical_a == pytest.approx(-0.5 * w * length, rel=1e-9)  # symmetric: half the weight each

    # A buoyant line is the mirror image of a heavy one: same tensions, vertical forces reversed.
    heavy = irvine_catenary(1200.0, 850.0, -800.0, 720.0, 5.7e9)
    light = irvine_catenary(1200.0, 850.0, 800.0, -720.0, 5.7e9)
    assert light.horizontal == pytest.approx(heavy.horizontal, rel=1e-12)
    assert light.vertical_a == pytest.approx(-heavy.vertical_a, rel=1e-12)


# ----------------------------------------------------------------------------------------------------------
# Roll-up under an end moment: the exact solution is a circle of radius EI/M
# ----------------------------------------------------------------------------------------------------------

ROLL_L = 10.0  # m
ROLL_EI = 1.0e4  # N·m²


def rollup(turns: float, elements: int) -> tuple[pl.State, float, float]:
    """Clamp at A, a moment M = 2π·turns·EI/L about e3 at B; returns (state, M in N·m, radius EI/M in m)."""
    section = beam_section(ea=1.0e8, ga=1.0e8, gj=1.0e4, ei=ROLL_EI)
    model = cantilever(ROLL_L, elements, section)
    moment = 2.0 * math.pi * turns * ROLL_EI / ROLL_L
    model.point_load("B", moment=(0.0, 0.0, moment))
    return model.static(), moment, ROLL_EI / moment


@pytest.mark.parametrize("turns", [0.5, 1.0], ids=["half-circle", "full-circle"])
def test_rollup_under_end_moment_is_a_circle(turns: float) -> None:
    """M = π EI/L (half) and 2π EI/L (full circle), 20 elements.

    Asserts: tip on the exact circle, |tip − exact| < 1e-3 L (full circle: the tip is back at the root);
    every node within 1 % of ρ = EI/M of the centre (0, ρ, 0); the tip frame rotated by θ = ML/EI about e3
    relative to the clamped root frame (to 1e-6); |m| = M at every element midpoint (1e-6 relative), no
    force resultant (|n| < 1e-5 M/L) and zero tension.
    """
    n = 20
    state, moment, radius = rollup(turns, n)
    assert_converged(state)
    theta = moment * ROLL_L / ROLL_EI
    expected_tip = np.array([radius * math.sin(theta), radius * (1.0 - math.cos(theta)), 0.0])
    tip = state.positions[-1]
    assert np.linalg.norm(tip - expected_tip) < 1e-3 * ROLL_L
    if turns == 1.0:
        assert np.linalg.norm(tip - state.positions[0]) < 1e-3 * ROLL_L

    centre = np.array([0.0, radius, 0.0])
    distance = np.linalg.norm(state.positions - centre, axis=1)
    assert np.max(np.abs(distance - radius)) < 1e-2 * radius
    assert np.max(np.abs(state.positions[:, 2])) < 1e-9 * ROLL_L  # stays in the plane

    relative = state.rotations[-1] @ state.rotations[0].T
    np.testing.assert_allclose(relative, rot_e3(theta), atol=1e-6)

    forces = state.section_forces
    assert forces.shape == (n, 6)
    np.testing.assert_allclose(np.linalg.norm(forces[:, 3:], axis=1), moment, rtol=1e-6)
    assert np.max(np.linalg.norm(forces[:, :3], axis=1)) < 1e-5 * moment / ROLL_L
    assert np.max(np.abs(state.tension)) < 1e-5 * moment / ROLL_L


def test_rollup_convergence_order() -> None:
    """Half-circle roll-up tip error at n = 4, 8, 16, 32: observed order of convergence in [1.8, 2.2]
    (linear elements, one-point integration: second order), and the error at n = 4 is not already zero."""
    elements = [4, 8, 16, 32]
    errors = []
    for n in elements:
        state, _, radius = rollup(0.5, n)
        exact = np.array([0.0, 2.0 * radius, 0.0])
        errors.append(float(np.linalg.norm(state.positions[-1] - exact)))
    assert errors[0] > 1e-4 * ROLL_L
    slope, pairwise = observed_order(elements, errors)
    assert 1.8 <= slope <= 2.2, (errors, pairwise)
    assert all(1.8 <= p <= 2.2 for p in pairwise), (errors, pairwise)


# ----------------------------------------------------------------------------------------------------------
# Small-load cantilever: Timoshenko beam theory δ = P L³/(3 EI) + P L/(GA)
# ----------------------------------------------------------------------------------------------------------


def timoshenko_tip(length: float, ei: float, ga: float, elements: int, relative_deflection: float = 1e-5):
    """Tip deflection (m) of a cantilever along e1 under a fixed tip force P e2 small enough that
    δ/L = ``relative_deflection``; returns (state, P in N, exact Timoshenko δ in m)."""
    compliance = length**3 / (3.0 * ei) + length / ga
    force = relative_deflection * length / compliance
    model = cantilever(length, elements, beam_section(ea=1.0e3 * ga, ga=ga, gj=ei, ei=ei))
    model.point_load("B", force=(0.0, force, 0.0))
    return model.static(), force, force * compliance


def test_timoshenko_cantilever_slender() -> None:
    """L = 2 m, EI = 1e4 N·m², GA = 1e6 N (shear is 0.75 % of δ), n = 32.

    Asserts: tip deflection within 1e-3 relative of P L³/(3EI) + P L/(GA), and farther than 5e-3 from the
    Euler–Bernoulli value P L³/(3EI) (so GA counts); reaction at A = (0, P, 0) to 1e-5 P and (0, 0, P L) to
    1e-6 P L; the moment
    |m| at element midpoints = P (L − S) to 1e-6 P L; the force |n| = P to 1e-6.
    """
    length, ei, ga, n = 2.0, 1.0e4, 1.0e6, 32
    state, force, exact = timoshenko_tip(length, ei, ga, n)
    assert_converged(state)
    deflection = state.positions[-1, 1]
    assert deflection == pytest.approx(exact, rel=1e-3)
    euler_bernoulli = force * length**3 / (3.0 * ei)
    assert abs(deflection - euler_bernoulli) > 5e-3 * exact

    # The reaction's axial component is EA·ε with ε at round-off (EA = 1e9 N, ε ~ 1e-16): about 1e-7 N, so the
    # force is checked to 1e-5 P (P = 0.074 N here).
    reaction = state.reaction("A")
    np.testing.assert_allclose(reaction[:3], [0.0, force, 0.0], atol=1e-5 * force)
    np.testing.assert_allclose(reaction[3:], [0.0, 0.0, force * length], atol=1e-6 * force * length)

    midpoints = (np.arange(n) + 0.5) * length / n
    moments = np.linalg.norm(state.section_forces[:, 3:], axis=1)
    np.testing.assert_allclose(moments, force * (length - midpoints), atol=1e-6 * force * length)
    np.testing.assert_allclose(np.linalg.norm(state.section_forces[:, :3], axis=1), force, rtol=1e-6)


def test_timoshenko_stubby_beam_shear_doubles_the_deflection() -> None:
    """L = 1 m, EI = 1e4 N·m², GA = 3e4 N: bending and shear parts are equal. n = 32.

    Asserts: δ within 1e-3 relative of P L³/(3EI) + P L/(GA) and δ / (P L³/3EI) within 1e-3 of 2.
    """
    length, ei, ga = 1.0, 1.0e4, 3.0e4
    state, force, exact = timoshenko_tip(length, ei, ga, 32)
    assert_converged(state)
    deflection = state.positions[-1, 1]
    assert deflection == pytest.approx(exact, rel=1e-3)
    assert deflection / (force * length**3 / (3.0 * ei)) == pytest.approx(2.0, rel=1e-3)


def test_timoshenko_convergence_order() -> None:
    """Slender cantilever (L = 2 m, EI = 1e4, GA = 1e6) at n = 4, 8, 16, 32: the error of the tip deflection
    decreases with observed order in [1.8, 2.2] (fit and each refinement)."""
    length, ei, ga = 2.0, 1.0e4, 1.0e6
    elements = [4, 8, 16, 32]
    errors = []
    for n in elements:
        state, _, exact = timoshenko_tip(length, ei, ga, n)
        errors.append(abs(state.positions[-1, 1] - exact) / exact)
    assert errors[0] > 1e-4
    slope, pairwise = observed_order(elements, errors)
    assert 1.8 <= slope <= 2.2, (errors, pairwise)
    assert all(1.8 <= p <= 2.2 for p in pairwise), (errors, pairwise)


# ----------------------------------------------------------------------------------------------------------
# The 45° bend (Bathe & Bolourchi 1979; Simo & Vu-Quoc 1986)
# ----------------------------------------------------------------------------------------------------------

# Published tip positions with 8 linear elements: Simo & Vu-Quoc, "A three-dimensional finite-strain rod model.
# Part II: Computational aspects", CMAME 58 (1986) 79–116, Example 7.5 (table of the 45° bend), quoted there as
# (22.33, 58.84, 40.08) at P = 300 and (15.79, 47.23, 53.37) at P = 600 in a frame where the bend starts along y
# and curves towards +x. The same numbers in a frame where the bend starts along x and curves towards +y,
# x = R sin φ, y = R(1 − cos φ), z = 0, clamped at the origin and loaded by +P e_z at the tip, are
# (58.84, 22.33, 40.08), (52.32, 18.62, 48.39) at P = 450 and (47.23, 15.79, 53.37): so quoted as the
# reference values in Exudyn's test of ObjectBeamGeometricallyExact (geometricallyExactBeamCurvedTest.py,
# which also reports 32 elements at P = 600: (46.90, 15.56, 53.60)) and in SPHinXsys's beam test
# (beam_arc_rotation, reference `pos_ref` with `tip_pos = R (sin 45°, 1 − cos 45°, 0)`).
# Bathe & Bolourchi (1979) give (22.5, 59.2, 39.5) and (15.9, 47.2, 53.4) in Simo & Vu-Quoc's frame.
# Our e1, e2, e3 form a right-handed frame like (x, y, z), so the mapping is the identity: the arc lies in the
# horizontal plane e1–e2 and the tip force +P e3 points down; the tip moves down (z > 0).
BEND_REFERENCE = {
    300.0: (58.84, 22.33, 40.08),
    600.0: (47.23, 15.79, 53.37),
}
BEND_R = 100.0
BEND_E = 1.0e7


def bend45(force: float, elements: int = 8) -> pl.State:
    """The 45° bend: radius 100, unit square section, E = 1e7, G = E/2; a fixed-direction tip force +P e3."""
    phi = np.linspace(0.0, math.pi / 4.0, elements + 1)
    nodes = np.column_stack([BEND_R * np.sin(phi), BEND_R * (1.0 - np.cos(phi)), np.zeros_like(phi)])
    shear = 0.5 * BEND_E
    section = pl.Section(
        EA=BEND_E * 1.0,
        GA=shear * 1.0,
        GJ=shear / 6.0,  # polar moment of the unit square, J = 2I = 1/6
        EI=BEND_E / 12.0,
        mass=1.0,
        inertia=(1.0 / 6.0, 1.0 / 12.0, 1.0 / 12.0),
    )
    model = pl.Model(pl.Rod(nodes, section), gravity=0.0)
    model.clamp("A")
    model.point_load("B", force=(0.0, 0.0, force))
    return model.static()


@pytest.mark.parametrize("force", sorted(BEND_REFERENCE))
def test_bend45_against_simo_vu_quoc(force: float) -> None:
    """8 elements as in the literature. Asserts: |tip − published| ≤ 1 % of the published tip displacement
    (about 0.5 at P = 300, 0.6 at P = 600), the clamp takes the whole load (reaction force = (0, 0, P) to 1e-6)."""
    state = bend45(force)
    assert_converged(state)
    reference = np.array(BEND_REFERENCE[force])
    start = np.array([BEND_R * math.sin(math.pi / 4), BEND_R * (1.0 - math.cos(math.pi / 4)), 0.0])
    displacement = np.linalg.norm(reference - start)
    error = np.linalg.norm(state.positions[-1] - reference)
    assert error <= 0.01 * displacement, (state.positions[-1], reference)
    np.testing.assert_allclose(state.reaction("A")[:3], [0.0, 0.0, force], atol=1e-6 * force)


# ----------------------------------------------------------------------------------------------------------
# Hanging lines: Irvine's elastic catenary, and the paper's 1200 m steel pipe
# ----------------------------------------------------------------------------------------------------------

PIPE_LENGTH = 1200.0  # m
DEPTH = 800.0  # m
TOP = (850.0, 0.0, -800.0)  # B at the surface, 850 m from A horizontally
OD, WT = 0.6, 0.015  # m
STEEL_DENSITY, YOUNG, POISSON = 7850.0, 207e9, 0.3
STEEL_AREA = math.pi / 4.0 * (OD**2 - (OD - 2.0 * WT) ** 2)  # 0.027567 m²
BORE_AREA = math.pi / 4.0 * (OD - 2.0 * WT) ** 2
OUTER_AREA = math.pi / 4.0 * OD**2
PIPE_EA = YOUNG * STEEL_AREA

# Submerged weight per unit length (N/m) by our own arithmetic, not the engine's:
# flooded (contents = sea water) = (ρ_s − ρ_w) A g, the paper's "(m_P − ρ_w A) g" (1845.7 N/m);
# empty = (ρ_s A − ρ_w π/4 OD²) g = −720.1 N/m: an empty 0.6 m × 15 mm steel pipe FLOATS, so it arches upwards.
PIPE_WEIGHT = {
    "flooded": (STEEL_DENSITY * STEEL_AREA + RHO_WATER * BORE_AREA - RHO_WATER * OUTER_AREA) * G,
    "empty": (STEEL_DENSITY * STEEL_AREA - RHO_WATER * OUTER_AREA) * G,
}
PIPE_CONTENTS = {"flooded": RHO_WATER, "empty": 0.0}


def hanging_model(section: pl.Section, elements: int, support: str) -> pl.Model:
    """The 1200 m line from a straight horizontal reference, A at the origin (seabed) and B moved to TOP."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (PIPE_LENGTH, 0.0, 0.0), elements, section)
    model = pl.Model(rod, sea=pl.Sea(DEPTH))
    if support == "pinned":
        model.pin("A")
        model.pin("B", position=TOP)
    else:
        model.clamp("A")
        model.clamp("B", position=TOP, rotation=np.eye(3))
    return model


def test_catenary_with_negligible_bending_matches_irvine() -> None:
    """EI = GJ = 1 N·m², real EA and GA, buoyancy on the steel area (w = 1845.7 N/m), pinned, n = 100.

    Asserts against our Irvine solution: horizontal tension (from both reactions, with their signs), top and
    bottom tension, vertical reactions, and the axial force at every element midpoint within 0.5 %; node
    positions within 1e-3 L of the catenary's material points; B where it was put (1e-9 m).
    """
    n = 100
    weight = (STEEL_DENSITY - RHO_WATER) * STEEL_AREA * G
    section = pl.Section(
        EA=PIPE_EA,
        GA=0.5 * YOUNG / (2.0 * (1.0 + POISSON)) * STEEL_AREA,
        GJ=1.0,
        EI=1.0,
        mass=STEEL_DENSITY * STEEL_AREA,
        displaced_area=STEEL_AREA,
        outer_diameter=OD,
    )
    state = hanging_model(section, n, "pinned").static()
    assert_converged(state)
    ref = irvine_catenary(PIPE_LENGTH, TOP[0], -TOP[2], weight, PIPE_EA)

    np.testing.assert_allclose(state.positions[0], [0.0, 0.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(state.positions[-1], TOP, atol=1e-9)

    force_a = state.reaction("A")[:3]
    force_b = state.reaction("B")[:3]
    # The rod pulls A up and towards B, and pulls B down and back towards A (e3 down).
    assert force_a[0] == pytest.approx(ref.horizontal, rel=5e-3)
    assert -force_b[0] == pytest.approx(ref.horizontal, rel=5e-3)
    assert -force_a[2] == pytest.approx(ref.vertical_a, rel=5e-3)
    assert force_b[2] == pytest.approx(ref.vertical_b, rel=5e-3)
    assert np.linalg.norm(force_b) == pytest.approx(ref.tension_b, rel=5e-3)
    assert np.linalg.norm(force_a) == pytest.approx(ref.tension_a, rel=5e-3)

    s_mid = (np.arange(n) + 0.5) * PIPE_LENGTH / n
    expected_tension = np.hypot(ref.horizontal, ref.vertical_a + weight * s_mid)
    np.testing.assert_allclose(state.tension, expected_tension, rtol=5e-3)

    s_nodes = np.arange(n + 1) * PIPE_LENGTH / n
    expected = np.array([ref.point(s) for s in s_nodes])  # (horizontal, height above A)
    shape_error = np.hypot(state.positions[:, 0] - expected[:, 0], -state.positions[:, 2] - expected[:, 1])
    assert np.max(shape_error) < 1e-3 * PIPE_LENGTH
    assert np.max(np.abs(state.positions[:, 1])) < 1e-9 * PIPE_LENGTH


@pytest.mark.parametrize("elements", [10, 100])
@pytest.mark.parametrize("support", ["pinned", "clamped"])
@pytest.mark.parametrize("contents", ["flooded", "empty"])
def test_hanging_steel_pipe(contents: str, support: str, elements: int) -> None:
    """``Section.pipe(0.6, 0.015)`` (flooded: contents_density = 1025, the paper's submerged weight; empty: the
    pipe floats), 1200 m from a straight reference, A at the seabed origin, B at (850, 0, −800).

    Asserts: convergence (load factor 1); the supports hold (1e-9 m; clamped: the frame at B is the identity
    and t1 at A stays along e1, to 1e-9); global equilibrium F_A + F_B = w L e3 (the rod hands its submerged weight to the supports) within
    1e-6 of |w L|, w computed here from the geometry; pinned: |F_B| within 2 % of Irvine's top tension (the
    real EI is not negligible) and the horizontal components within 2 % of Irvine's H.
    """
    section = pl.Section.pipe(OD, WT, contents_density=PIPE_CONTENTS[contents])
    model = hanging_model(section, elements, support)
    state = model.static()
    assert_converged(state)
    weight = PIPE_WEIGHT[contents]

    np.testing.assert_allclose(state.positions[0], [0.0, 0.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(state.positions[-1], TOP, atol=1e-9)
    if support == "clamped":
        np.testing.assert_allclose(state.rotations[-1], np.eye(3), atol=1e-9)
        np.testing.assert_allclose(state.rotations[0][:, 0], [1.0, 0.0, 0.0], atol=1e-9)  # t1 stays along e1

    force_a = state.reaction("A")[:3]
    force_b = state.reaction("B")[:3]
    total_weight = np.array([0.0, 0.0, weight * PIPE_LENGTH])
    np.testing.assert_allclose(force_a + force_b, total_weight, atol=1e-6 * abs(weight) * PIPE_LENGTH)

    if support == "pinned":
        ref = irvine_catenary(PIPE_LENGTH, TOP[0], -TOP[2], weight, PIPE_EA)
        assert np.linalg.norm(force_b) == pytest.approx(ref.tension_b, rel=0.02)
        assert force_a[0] == pytest.approx(ref.horizontal, rel=0.02)
        assert -force_b[0] == pytest.approx(ref.horizontal, rel=0.02)
