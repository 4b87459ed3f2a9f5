"""A stiff pipe (a flooded 0.6 m × 15 mm steel pipe, EI = 2.44e8 N·m²) hanging onto the seabed: the sagbend's
boundary layer against its classical estimates, mesh convergence of the touchdown and of the largest moment,
and the cable limit.

The case: L = 1600 m, anchored (pinned) on the seabed at A, pinned at B 1200 m across and 800 m up; seabed
k = 1e5 Pa/m, no friction. Classical estimates (e.g. Palmer et al. 1974; Dixon & Rutledge 1968): near the
touchdown the bending stiffness matters over the boundary-layer length λ = √(EI/H); above it the pipe follows
the catenary, whose curvature at the touchdown is w/H, so the largest sagbend moment is about EI·w/H,
reached a few λ above the touchdown (where the boundary layer has grown and the catenary's curvature, which
falls as w H/T², has not yet fallen). Measured when written: M_max = 493.76 kN m = 0.973 EI w/H, 4.0 λ above
the touchdown; second-order convergence of M_max with n; the touchdown converged to 1e-5 of L at n = 800.
"""

from __future__ import annotations

import math

import numpy as np
import pipelay as pl
import pytest
from seabed_bvp import stiff_pipe_on_seabed

LENGTH, SPAN, RISE = 1600.0, 1200.0, 800.0


def static(elements: int, ei: float | None = None) -> tuple[pl.State, pl.Model]:
    """The hanging pipe on the seabed with `elements` elements (EI: the steel pipe's unless given)."""
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0)
    if ei is not None:
        section = pl.Section(
            EA=section.EA,
            GA=section.GA,
            GJ=1.3 * ei,
            EI=ei,
            mass=section.mass,
            inertia=section.inertia,
            outer_diameter=0.6,
        )
    rod = pl.Rod.straight((0, 0, 0), (LENGTH, 0, 0), elements, section)
    model = pl.Model(rod, sea=pl.Sea(RISE, seabed=pl.Seabed(stiffness=1e5)))
    model.pin("A")
    model.pin("B", position=(SPAN, 0.0, -RISE))
    return model.static(), model


def largest_moment(state: pl.State, elements: int) -> tuple[float, float]:
    """The largest bending moment (N m) and the reference arc length of its element's midpoint (m)."""
    moment = np.hypot(state.section_forces[:, 4], state.section_forces[:, 5])
    worst = int(np.argmax(moment))
    return float(moment[worst]), (worst + 0.5) * LENGTH / elements


def test_stiff_pipe_matches_the_boundary_value_solution() -> None:
    """Against the planar boundary-value solution (``seabed_bvp.py``, scipy's solve_bvp, written independently
    of the finite elements): largest sagbend moment, touchdown, horizontal and top tension, and their mesh
    convergence. Measured when written: at n = 200 / 800 / 1600 the moment is off by 5.8e-4 / 1.8e-7 /
    1.3e-5 (the element-midpoint sampling of the peak), the touchdown by 3.6 / 1.1 / 0.4 cm, H by 7.9e-6 /
    3.7e-7 / 5.7e-8."""
    state, model = static(200)
    section = model.rod.section
    reference = stiff_pipe_on_seabed(
        LENGTH, SPAN, RISE, model.submerged_weight, section.EA, section.EI[0], 1e5, section.outer_diameter
    )
    coarse = abs(largest_moment(state, 200)[0] / reference.max_moment - 1.0)
    for n in (800, 1600):
        state, _ = static(n)
        moment, where = largest_moment(state, n)
        assert abs(moment / reference.max_moment - 1.0) < 3e-5
        assert abs(moment / reference.max_moment - 1.0) < 0.1 * coarse
        assert abs(where - reference.max_moment_arc_length) < 2.0 * LENGTH / n
        assert state.touchdown.arc_length == pytest.approx(reference.touchdown_arc_length, abs=0.02)  # type: ignore[union-attr]
        assert state.reaction("A")[0] == pytest.approx(reference.horizontal, rel=1e-6)
        top = float(np.linalg.norm(state.reaction("B")[:3]))
        assert top == pytest.approx(reference.top_tension, rel=1e-6)


def test_sagbend_moment_matches_the_boundary_layer_estimates() -> None:
    """M_max ≈ EI w/H (within 5 %), a few boundary-layer lengths λ = √(EI/H) above the touchdown."""
    n = 1600
    state, model = static(n)
    ei = model.rod.section.EI[0]
    w = model.submerged_weight
    horizontal = state.reaction("A")[0]  # no friction: H reaches the anchor
    moment, where = largest_moment(state, n)
    touchdown = state.touchdown
    assert touchdown is not None
    estimate = ei * w / horizontal
    boundary_layer = math.sqrt(ei / horizontal)
    assert 0.95 < moment / estimate < 1.0
    assert 2.0 * boundary_layer < where - touchdown.arc_length < 6.0 * boundary_layer
    # On the seabed from 100 to 300 m, away from the touchdown and from A's boundary layer (A is pinned at
    # z = 0 while the pipe rests 3 cm into the seabed), the pipe lies straight and carries no moment.
    bending = np.hypot(state.section_forces[:, 4], state.section_forces[:, 5])
    assert np.max(bending[n * 100 // 1600 : n * 300 // 1600]) < 1e-4 * moment


def test_touchdown_and_moment_converge_with_the_mesh() -> None:
    """Largest moment: second-order convergence (error ratios ≈ 4 per halving against n = 6400); touchdown:
    within 1e-5 of L from n = 800 on."""
    sizes = [400, 800, 1600, 3200]
    finest_state, _ = static(6400)
    finest_moment, _ = largest_moment(finest_state, 6400)
    finest_touchdown = finest_state.touchdown.arc_length  # type: ignore[union-attr]
    errors = []
    for n in sizes:
        state, _ = static(n)
        errors.append(abs(largest_moment(state, n)[0] - finest_moment))
        if n >= 800:
            assert state.touchdown.arc_length == pytest.approx(finest_touchdown, abs=1e-5 * LENGTH)  # type: ignore[union-attr]
    order = math.log(errors[0] / errors[2]) / math.log(4.0)
    assert order > 1.8, (errors, order)


def test_cable_limit_is_the_catenary_and_bending_only_shifts_the_touchdown_a_little() -> None:
    """From EI = 1 N m² (a cable) to the steel pipe's EI the horizontal tension changes by < 0.2 % and the
    touchdown moves by less than one boundary-layer length."""
    n = 800
    cable, _ = static(n, ei=1.0)
    pipe, model = static(n)
    h_cable, h_pipe = cable.reaction("A")[0], pipe.reaction("A")[0]
    assert abs(h_pipe / h_cable - 1.0) < 2e-3
    boundary_layer = math.sqrt(model.rod.section.EI[0] / h_pipe)
    shift = cable.touchdown.arc_length - pipe.touchdown.arc_length  # type: ignore[union-attr]
    assert 0.0 < shift < boundary_layer
