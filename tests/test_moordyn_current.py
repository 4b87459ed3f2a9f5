"""Statics in a 3-D current against MoorDyn v2: a line between two fixed points in a steady current across
the vertical plane of its ends, pipelay's ``model.static()`` (the cable element, and the rod with
EI = GJ = 10 N·m² that imitates it) against MoorDyn's own static solution of the same line.

The case (``moordyn_current_case.py`` has every number, how MoorDyn takes the current, why its static solution
is its time integration relaxed to rest in the current, and the two small modelling differences left): the
250 m, 90 mm wire rope of ``moordyn_case`` pinned at A, 200 m deep, and at B, 150 m across and 180 m up, in

* a uniform 1.0 m/s current straight across the plane of A and B (the line swings 8.72 m downstream at
  mid-length, 5.8 % of the span), and
* a linearly sheared current at 45° to that plane, 1.5 m/s at the surface to zero at A's depth (1.89 m).

Resolution: n = 50 in both codes (5 m elements); MoorDyn RK4 at dt = 1e-3 s, relaxed until no node moves by
1e-5 m in 5 s (175 s of simulated time in the uniform current, 50 s in the sheared one). Runtime ≈ 10 s,
nearly all of it MoorDyn's relaxation, done once per case for the module.

Measured when written (``python tests/moordyn_current_case.py`` prints the study; relative differences,
pipelay's cable − MoorDyn; the rod's are the same to the digits shown):

| quantity | uniform, n = 50 / 100 | sheared, n = 50 / 100 | each code's change n = 50 → 100 |
| --- | --- | --- | --- |
| top tension (magnitude of F_B) | −5.0e-6 / 6.3e-7 | 1.0e-5 / 4.7e-6 | 1.0e-4 to 1.1e-4 |
| anchor force (magnitude of ΔF_A over F_A's) | 1.9e-5 / 1.9e-5 | 9.2e-5 / 3.1e-5 | 3.3e-4 to 3.9e-4 |
| lateral offset at mid-length | 1.1e-4 / 1.1e-4 | 1.1e-3 / 4.0e-4 | 1.8e-4 to 5.5e-4 |
| largest lateral offset | 1.1e-4 / 1.1e-4 | 1.0e-3 / 3.7e-4 | |
| shape, largest node distance | 4.0e-6 L / 4.1e-6 L | 8.8e-6 L / 3.2e-6 L | 3.5e-5 L to 3.6e-5 L |

The two codes share their discretisation (straight segments, loads lumped at the nodes), so at equal n they
agree far better than either agrees with the continuum: at n = 50 each is 1.3e-4 to 1.5e-4 below pipelay's
n = 800 top tension, 5e-4 of |F_A| from its anchor force (the end node's lumped weight) and 4.8e-5 L from its
shape. The tolerances are set from that mesh error, the error two independent discretisations could each
have, and not from the closer agreement at equal n: 5e-4 for |F_B| and 1e-3 of |F_A| for the anchor force
(about twice the mesh error of each), 1e-4 L for the shape, and 1 % for the lateral offsets (the sheared
current's 1.1e-3 is the codes' largest difference, the current sampled at mid-depth against at the nodes;
1 % of the offset is 1 % of the current's drag, half a percent of its speed). What they catch: the current
raises the top tension by 1.1 % (uniform) and 1.7 % (sheared), so 5e-4 is 4 % or 3 % of the current's
effect. Measured against this MoorDyn run, pipelay with its normal drag 2 % high (or the current 1 % fast)
is off by 1.9–2.1 % in the lateral offsets and in the anchor's cross-current force, 1.4e-3 to 4.1e-3 of |F_A|
in the anchor force and 1.8e-4 L to 7.1e-4 L in the shape, each beyond its tolerance (the top tension, 4e-4,
is not); the current ignored, mirrored across the plane, or uniform instead of sheared fails every
comparison of the lateral offset and shape by far. MoorDyn's own convergence is not what limits the
tolerances: relaxed to 1e-7 m instead of 1e-5 m, its state moves by 2e-5 m and 0.01 N.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from moordyn_current_case import (
    SHEARED,
    UNIFORM,
    CurrentCase,
    Static,
    lateral_offsets,
    run_moordyn,
    run_pipelay,
)

ELEMENTS = 50
DT_MOORDYN = 1e-3  # s
SETTLE = 1e-5  # m: MoorDyn has settled when no node moves by this much in a 5 s window
TOP_TENSION = 5e-4  # relative tolerance on |F_B|
ANCHOR_FORCE = 1e-3  # tolerance on |F_A − F_A,MoorDyn| relative to |F_A,MoorDyn|
LATERAL = 0.01  # relative tolerance on the lateral offsets
SHAPE = 1e-4  # tolerance on the largest distance between the two shapes, relative to the line's length
CASES = {"uniform": UNIFORM, "sheared": SHEARED}
SMALLEST_OFFSET = {"uniform": 0.05, "sheared": 0.01}  # the lateral offset at mid-length must pass, x span


@pytest.fixture(scope="module", params=list(CASES))
def solved(request: pytest.FixtureRequest) -> tuple[str, CurrentCase, Static, Static, Static]:
    """One case solved three ways at n = 50: its name, the case, pipelay's cable and rod, and MoorDyn."""
    pytest.importorskip("moordyn")
    name = request.param
    case = CASES[name]
    cable = run_pipelay(ELEMENTS, replace(case, cable=True))
    rod = run_pipelay(ELEMENTS, case)
    theirs = run_moordyn(ELEMENTS, DT_MOORDYN, case, settle=SETTLE)
    return name, case, cable, rod, theirs


def test_moordyn_settled_in_the_current(solved: tuple[str, CurrentCase, Static, Static, Static]) -> None:
    """MoorDyn relaxed for more than one window, and in its last 5 s no node moved by 1e-5 m: its state is its
    static equilibrium to about 2e-5 m (see ``moordyn_current_case``)."""
    *_, theirs = solved
    assert theirs.relaxed > 5.0, theirs.relaxed
    assert theirs.last_motion < SETTLE, theirs.last_motion


def test_top_tension_agrees(solved: tuple[str, CurrentCase, Static, Static, Static]) -> None:
    """|F_B| of pipelay's cable and rod within 5e-4 of MoorDyn's (measured: −5.0e-6 uniform, 1.0e-5 sheared;
    each code's own mesh error at n = 50: 1.5e-4)."""
    _, _, cable, rod, theirs = solved
    reference = float(np.linalg.norm(theirs.force_b))
    for ours in (cable, rod):
        top = float(np.linalg.norm(ours.force_b))
        assert abs(top / reference - 1.0) < TOP_TENSION, (top, reference)


def test_anchor_force_agrees(solved: tuple[str, CurrentCase, Static, Static, Static]) -> None:
    """The anchor force F_A (N, in e) of pipelay's cable and rod within 1e-3 of |F_A| of MoorDyn's, as a
    vector (measured: 1.9e-5 uniform, 9.2e-5 sheared; mesh error at n = 50: 5e-4), and its cross-current
    component, the anchor's share of the current's load, within 1 % (measured: 7e-5, 1.5e-3)."""
    _, _, cable, rod, theirs = solved
    size = float(np.linalg.norm(theirs.force_a))
    for ours in (cable, rod):
        gap = float(np.linalg.norm(ours.force_a - theirs.force_a))
        assert gap < ANCHOR_FORCE * size, (ours.force_a, theirs.force_a)
        assert abs(ours.force_a[1] / theirs.force_a[1] - 1.0) < LATERAL, (ours.force_a, theirs.force_a)


def test_lateral_offset_agrees(solved: tuple[str, CurrentCase, Static, Static, Static]) -> None:
    """The line's offset across the plane of A and B, at mid-length and at its largest, within 1 % of
    MoorDyn's (measured: 1.1e-4 uniform, 1.1e-3 sheared), and large enough in both codes that a current
    ignored or turned would fail: more than 5 % of the span in the uniform current (measured 5.8 %), 1 % in
    the sheared one (1.26 %)."""
    name, case, cable, rod, theirs = solved
    theirs_middle, theirs_largest = lateral_offsets(theirs, case.length)
    assert theirs_middle > SMALLEST_OFFSET[name] * case.x0, theirs_middle
    for ours in (cable, rod):
        middle, largest = lateral_offsets(ours, case.length)
        assert middle > SMALLEST_OFFSET[name] * case.x0, middle
        assert abs(middle / theirs_middle - 1.0) < LATERAL, (middle, theirs_middle)
        assert abs(largest / theirs_largest - 1.0) < LATERAL, (largest, theirs_largest)


def test_shape_agrees(solved: tuple[str, CurrentCase, Static, Static, Static]) -> None:
    """Node positions at the same reference arc lengths (both codes put node i at i L/n) within 1e-4 L of
    MoorDyn's (measured: 4.0e-6 L uniform, 8.8e-6 L sheared; mesh error at n = 50: 4.8e-5 L), while the
    current moves MoorDyn's line from its still-water shape (pipelay's) by more than 50 times the tolerance of
    25 mm somewhere (measured: 9.2 m uniform, 2.2 m sheared)."""
    _, case, cable, rod, theirs = solved
    for ours in (cable, rod):
        gap = float(np.max(np.linalg.norm(ours.positions - theirs.positions, axis=1)))
        assert gap < SHAPE * case.length, gap / case.length
    still = run_pipelay(ELEMENTS, replace(case, current=(0.0, 0.0, 0.0), cable=True))
    moved = float(np.max(np.linalg.norm(theirs.positions - still.positions, axis=1)))
    assert moved > 50.0 * SHAPE * case.length, moved


def test_cable_and_rod_agree(solved: tuple[str, CurrentCase, Static, Static, Static]) -> None:
    """The cable and the rod with EI = GJ = 10 N·m² that imitates it, on the same mesh: top and anchor forces
    within 1e-6 and node positions within 1e-6 L (measured: forces 1.5e-7, positions 3.4e-8 L; what remains is
    the rod's bending stiffness)."""
    _, case, cable, rod, _ = solved
    for cable_force, rod_force in ((cable.force_b, rod.force_b), (cable.force_a, rod.force_a)):
        gap = float(np.linalg.norm(cable_force - rod_force) / np.linalg.norm(cable_force))
        assert gap < 1e-6, (cable_force, rod_force)
    gap = float(np.max(np.linalg.norm(cable.positions - rod.positions, axis=1)))
    assert gap < 1e-6 * case.length, gap / case.length
