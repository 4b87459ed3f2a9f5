"""Checks of the independent reference ``seabed_bvp``: a stiff pipe hanging onto a flat elastic seabed, solved
as a two-segment boundary-value problem with scipy's ``solve_bvp`` (no pipelay here).

The main case: a flooded 0.6 m steel pipe, wall 15 mm (E = 207 GPa, steel 7850 kg/m³, sea water 1025 kg/m³:
EA = 5.706e9 N, EI = 2.443e8 N·m², w = 1845.7 N/m), L = 1600 m, B 1200 m across and 800 m up, seabed
k = 1e5 Pa/m under d = 0.6 m (w/(kd) = 31 mm of penetration of the laid part).

Measured when written (solve_bvp tolerance 1e-8, 2770 nodes, 0.3 s): H = 887 950.78 N, top tension
|F(B)| = 2 364 155 N, touchdown s_t = 408.2644 m from A (x = 408.3278 m), largest |M| = 493 770.03 N·m at
s = 476.0018 m, i.e. 67.74 m = 4.08 λ above the touchdown, with EI·w/H = 507 748 N·m (ratio 0.972) and
λ = √(EI/H) = 16.59 m. The nearly flexible pipe (EI = 1e4 N·m², λ = 0.11 m) matches the laid catenary on the
elastic seabed to 5e-7 in H and 4e-6 in the touchdown; the steel pipe's H is 0.16 % and its touchdown 1.9 %
(8 m) below the catenary's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("scipy")

from irvine import irvine_catenary
from seabed_bvp import (
    SeabedBVP,
    boundary_layer_estimates,
    laid_catenary,
    stiff_pipe_on_seabed,
)

E_STEEL = 207e9  # Young's modulus (Pa)
OUTER, INNER = 0.6, 0.57  # diameters (m)
AREA = math.pi / 4 * (OUTER**2 - INNER**2)  # steel area (m²)
INERTIA = math.pi / 64 * (OUTER**4 - INNER**4)  # second moment of area (m⁴)
MASS = 7850.0 * AREA + 1025.0 * math.pi / 4 * INNER**2  # steel + flooded contents (kg/m)
WEIGHT = (MASS - 1025.0 * math.pi / 4 * OUTER**2) * 9.81  # submerged weight (N/m)
EA, EI = E_STEEL * AREA, E_STEEL * INERTIA
LENGTH, SPAN, RISE = 1600.0, 1200.0, 800.0  # m
STIFFNESS, DIAMETER = 1e5, OUTER  # Pa/m, m
FLEXIBLE_EI = 1e4  # N·m²: λ = 0.11 m; far smaller EI leaves the residual of θ' = M/EI at round-off level


def solve(ei: float = EI, tolerance: float = 1e-8, **kwargs: float) -> SeabedBVP:
    """The main case with bending stiffness `ei` (N·m²)."""
    return stiff_pipe_on_seabed(
        LENGTH, SPAN, RISE, WEIGHT, EA, ei, STIFFNESS, DIAMETER, tolerance=tolerance, **kwargs
    )


@pytest.fixture(scope="module")
def steel() -> SeabedBVP:
    return solve()


@pytest.fixture(scope="module")
def flexible() -> SeabedBVP:
    return solve(FLEXIBLE_EI, tolerance=1e-5)


def gauss_points(result: SeabedBVP, upto: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """5-point Gauss–Legendre points and weights (m) on every mesh interval of `result` (up to s = upto):
    exact for the cubic interpolant and for k d z on the laid part."""
    s = result.s if upto is None else result.s[result.s <= upto]
    g, gw = np.polynomial.legendre.leggauss(5)
    a, b = s[:-1, None], s[1:, None]
    return (0.5 * (a + b) + 0.5 * (b - a) * g).ravel(), (0.5 * (b - a) * gw).ravel()


def test_section_of_the_main_case() -> None:
    assert WEIGHT == pytest.approx(1845.73, abs=0.01)
    assert EA == pytest.approx(5.7065e9, rel=1e-4)
    assert EI == pytest.approx(2.4427e8, rel=1e-4)


def test_laid_catenary_reference_against_irvine() -> None:
    """The suspended part of the reference, from its vertex (w/(2kd) below the seabed plane) to B, is the
    catenary that ``irvine_catenary`` finds between those two points: zero vertical force at the vertex."""
    cat = laid_catenary(LENGTH, SPAN, RISE, WEIGHT, EA, STIFFNESS, DIAMETER)
    vertex_x = cat.vertex_arc_length * (1.0 + cat.horizontal / EA)
    hanging = irvine_catenary(
        LENGTH - cat.vertex_arc_length, SPAN - vertex_x, RISE + cat.vertex_depth, WEIGHT, EA
    )
    assert hanging.horizontal == pytest.approx(cat.horizontal, rel=1e-9)
    assert abs(hanging.vertical_a) < 1e-6 * WEIGHT * LENGTH
    assert cat.laid_depth == pytest.approx(WEIGHT / (STIFFNESS * DIAMETER), rel=1e-12)
    # The touchdown is ℓ = √(H/((1 + H/EA) k d)) past the vertex (small-slope boundary layer).
    ell = math.sqrt(cat.horizontal / ((1.0 + cat.horizontal / EA) * STIFFNESS * DIAMETER))
    assert cat.touchdown_arc_length - cat.vertex_arc_length == pytest.approx(ell, rel=1e-3)


def test_flexible_limit_matches_the_laid_catenary(flexible: SeabedBVP) -> None:
    """(a) EI → 0: H and the touchdown of the BVP are those of the elastic catenary on the elastic seabed
    (measured 5e-7 and 4e-6), and the peak moment is EI·w/H, the catenary's curvature at its vertex."""
    cat = laid_catenary(LENGTH, SPAN, RISE, WEIGHT, EA, STIFFNESS, DIAMETER)
    assert flexible.horizontal == pytest.approx(cat.horizontal, rel=1e-5)
    assert flexible.top_tension == pytest.approx(cat.top_tension, rel=1e-5)
    assert flexible.touchdown_arc_length == pytest.approx(cat.touchdown_arc_length, rel=2e-5)
    assert flexible.touchdown_x == pytest.approx(cat.touchdown_x, rel=2e-5)
    estimate = boundary_layer_estimates(FLEXIBLE_EI, flexible.horizontal, WEIGHT)
    assert flexible.max_moment == pytest.approx(estimate.moment, rel=1e-3)
    # The laid part sinks to w/(kd) midway.
    middle = 0.5 * flexible.touchdown_arc_length
    assert flexible.position(middle)[1] == pytest.approx(cat.laid_depth, rel=1e-6)


def test_steel_pipe_sagbend_moment_and_boundary_layer(steel: SeabedBVP) -> None:
    """(b) The peak sagbend moment is EI·w/H within ±30 % (measured 0.972 of it), a few λ = √(EI/H) above the
    touchdown (measured 4.08 λ), in the suspended part; bending lowers H and pulls the touchdown toward A."""
    estimate = boundary_layer_estimates(EI, steel.horizontal, WEIGHT, STIFFNESS, DIAMETER)
    ratio = steel.max_moment / estimate.moment
    assert 0.7 < ratio < 1.3
    assert ratio == pytest.approx(0.9725, abs=2e-3)
    distance = steel.max_moment_arc_length - steel.touchdown_arc_length
    assert 2.0 * estimate.length < distance < 6.0 * estimate.length
    assert distance / estimate.length == pytest.approx(4.08, abs=0.02)
    assert estimate.length == pytest.approx(16.59, abs=0.01)
    # The peak is a maximum of |M| with zero shear force, and the moment is that of the sagbend (θ' < 0).
    assert abs(float(steel.shear_force(steel.max_moment_arc_length))) < 1e-6 * steel.max_moment
    assert float(steel.bending_moment(steel.max_moment_arc_length)) == pytest.approx(-steel.max_moment)
    assert np.abs(steel.moment).max() <= steel.max_moment * (1 + 1e-12)
    cat = laid_catenary(LENGTH, SPAN, RISE, WEIGHT, EA, STIFFNESS, DIAMETER)
    assert steel.horizontal / cat.horizontal - 1.0 == pytest.approx(-1.59e-3, abs=0.02e-3)
    assert steel.touchdown_arc_length - cat.touchdown_arc_length == pytest.approx(-7.98, abs=0.01)


def test_main_case_values(steel: SeabedBVP) -> None:
    """Regression values of the reference (see the module docstring)."""
    assert steel.horizontal == pytest.approx(887950.78, rel=1e-8)
    assert steel.top_tension == pytest.approx(2364155.05, rel=1e-8)
    assert steel.touchdown_arc_length == pytest.approx(408.26436, rel=1e-7)
    assert steel.touchdown_x == pytest.approx(408.32776, rel=1e-7)
    assert steel.max_moment == pytest.approx(493770.03, rel=1e-7)
    assert steel.max_moment_arc_length == pytest.approx(476.00181, rel=1e-7)


def test_contact_is_consistent_with_the_segments(steel: SeabedBVP, flexible: SeabedBVP) -> None:
    """The laid segment lies in the seabed (z > 0 inside it), the suspended one above it (z < 0), checked on
    a dense grid of the interpolant; the touchdown is a crossing of the seabed plane."""
    for result in (steel, flexible):
        st = result.touchdown_arc_length
        laid = np.linspace(0.0, st, 100_001)[1:-1]
        hanging = np.linspace(st, LENGTH, 100_001)[1:]
        assert result.position(laid)[1].min() > 0.0
        assert result.position(hanging)[1].max() < 0.0
        assert result.laid_min_depth > -1e-12 * LENGTH
        assert result.suspended_max_depth < 0.0
        assert abs(float(result.position(st)[1])) < 1e-12 * LENGTH
        assert float(result.angle(st)) < 0.0  # rising toward B at the touchdown
    # The hinges: positions and zero moments.
    x, z = steel.position(np.array([0.0, LENGTH]))
    assert np.allclose([x[0], z[0], x[1], z[1]], [0.0, 0.0, SPAN, -RISE], rtol=0.0, atol=1e-10 * LENGTH)
    assert np.abs(steel.bending_moment(np.array([0.0, LENGTH]))).max() < 1e-9 * steel.max_moment


def test_tolerance_convergence(steel: SeabedBVP) -> None:
    """(c) A solve to 1e-9 agrees with the one to 1e-8 to better than 1e-5 (measured ~1e-12) in the
    touchdown, the peak moment and its place, H and the top tension."""
    fine = solve(tolerance=1e-9)
    assert fine.nodes > steel.nodes
    for name in (
        "touchdown_arc_length",
        "touchdown_x",
        "max_moment",
        "max_moment_arc_length",
        "horizontal",
        "top_tension",
    ):
        assert getattr(fine, name) == pytest.approx(getattr(steel, name), rel=1e-5), name


def test_continuation_in_ei_reaches_the_same_solution(steel: SeabedBVP) -> None:
    """Continuation from EI = 1e-6 H L² (λ = 1e-3 L) in 3 steps lands on the directly solved pipe."""
    continued = solve(steps=3)
    assert continued.touchdown_arc_length == pytest.approx(steel.touchdown_arc_length, rel=1e-7)
    assert continued.max_moment == pytest.approx(steel.max_moment, rel=1e-7)
    assert continued.horizontal == pytest.approx(steel.horizontal, rel=1e-9)


def test_global_equilibrium(steel: SeabedBVP, flexible: SeabedBVP) -> None:
    """(d) Reactions of the hinges + total weight − total seabed reaction = 0 (forces, and moments about A),
    with the seabed reaction integrated independently over the interpolated shape."""
    for result in (steel, flexible):
        total_weight = WEIGHT * LENGTH
        points, weights = gauss_points(result)
        seabed = float(np.sum(weights * result.seabed_reaction(points)))
        (ax, az), (bx, bz) = result.reaction_a, result.reaction_b
        assert abs(ax + bx) < 1e-8 * total_weight
        assert abs(az + bz + total_weight - seabed) < 1e-8 * total_weight
        # Moments about A (sense e1 → e3, a × b = a_x b_z − a_z b_x): r_B × R_B + ∫ r × (0, w − q) ds = 0.
        x, _ = result.position(points)
        moment = (
            SPAN * bz + RISE * bx + float(np.sum(weights * x * (WEIGHT - result.seabed_reaction(points))))
        )
        assert abs(moment) < 1e-8 * total_weight * SPAN
        # The seabed carries the laid weight: about w s_t, less what the hinge at A holds up.
        assert seabed == pytest.approx(WEIGHT * result.touchdown_arc_length, rel=0.05)
    # The laid pipe would sink to w/(kd) but A is pinned at z = 0: the hinge holds it up (R_A points −e3).
    assert steel.reaction_a[1] < 0.0
    # The axial force: H on the laid part (frictionless), the top tension near B.
    assert steel.axial[1] == pytest.approx(steel.horizontal, rel=1e-4)
    assert steel.axial[-1] == pytest.approx(steel.top_tension, rel=1e-4)
