"""The cable limit of the seabed contact (bending stiffness ~0): statics against the elastic catenary with a
laid part (``seabed_reference.py``, closed form), and against MoorPy (PyPI ``moorpy``, a peer code), with and without
seabed friction.

The cable (L, w, EA) is anchored on a nearly rigid flat seabed at A (k = 1e8 Pa/m: w/(kd) = 0.1 mm of
penetration) and pinned at B, XF across and ZF up. MoorPy's ``catenary(XF, ZF, L, EA, W, CB)`` assumes a rigid
seabed and friction CB fully mobilised along the laid part (the tension falls by CB·w per metre towards the
anchor); pipelay's friction is elastic up to its mobilisation distance, here 0.1 mm, so nearly all of it is
mobilised. Agreement measured when written (n = 800, elements h = 1.25 and 2 m): HF and VF within 2e-5 (1e-4
with friction); the laid length within 0.3–1 m (the touchdown of a cable on a penalty seabed is where the
interpolated penetration vanishes, known to about an element); so the anchor tension H − μ w L_b within
μ w h to 2 μ w h with friction (0.08 % of it at μ = 0.3 for the pipe), within 2e-5 of H without.
"""

from __future__ import annotations

import pipelay as pl
import pytest
from seabed_reference import laid_catenary

moorpy_catenary = pytest.importorskip("moorpy.Catenary").catenary

CASES = [
    # (L, XF, ZF, w, EA, d): a chain-like line, and a flooded 0.6 m steel pipe in 800 m of water
    (1000.0, 900.0, 150.0, 1000.0, 1e9, 0.1),
    (1600.0, 1200.0, 800.0, 1846.0, 5.4e9, 0.6),
]


def static_cable(case: tuple[float, ...], elements: int, friction: float) -> pl.State:
    length, span, rise, w, ea, d = case
    section = pl.Section(EA=ea, GA=ea, GJ=1.0, EI=1.0, mass=w / 9.81, outer_diameter=d, displaced_area=0.0)
    rod = pl.Rod.straight((0, 0, 0), (length, 0, 0), elements, section)
    seabed = pl.Seabed(stiffness=1e8, friction=friction, mobilisation=1e-4)
    model = pl.Model(rod, sea=pl.Sea(rise + 10.0, seabed=seabed))
    model.pin("A")
    model.pin("B", position=(span, 0.0, -rise))
    return model.static()


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("friction", [0.0, 0.5])
def test_cable_matches_the_laid_catenary(case: tuple[float, ...], friction: float) -> None:
    """Horizontal tension, laid length and anchor tension against the closed-form elastic catenary with a
    laid part (``seabed_reference.laid_catenary``, itself checked against MoorPy), and second-order
    convergence of H with the mesh."""
    length, span, rise, w, ea, _ = case
    exact = laid_catenary(length, span, rise, w, ea, friction=friction)
    errors = []
    for n in (200, 800):
        state = static_cable(case, n, friction)
        errors.append(abs(-state.reaction("B")[0] / exact.horizontal - 1.0))
    assert errors[1] < (3e-5 if friction == 0.0 else 1e-4)
    if friction == 0.0:
        assert errors[0] / errors[1] > 8.0  # second order: ×16 expected for 4× finer
    element = length / 800
    assert state.laid_length == pytest.approx(exact.laid_length, abs=element)
    tolerance = 3e-5 * exact.horizontal + 2.0 * friction * w * element
    assert state.reaction("A")[0] == pytest.approx(exact.anchor_tension, abs=tolerance)


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("friction", [0.0, 0.3, 1.0])
def test_cable_matches_moorpy(case: tuple[float, ...], friction: float) -> None:
    """Fairlead tension, anchor tension and laid length against MoorPy's catenary with seabed friction CB."""
    length, span, rise, w, ea, _ = case
    a_h, _, b_h, b_v, info = moorpy_catenary(span, rise, length, ea, w, CB=friction, Tol=1e-10, MaxIter=500)
    state = static_cable(case, 800, friction)
    top = state.reaction("B")[:3]  # the cable's pull on B: toward A (−x) and down (+z)
    # Friction's elastic range (0.1 mm) leaves it slightly less mobilised than MoorPy's: 2.3e-5 of HF.
    tolerance = 2e-5 if friction == 0.0 else 1e-4
    assert -top[0] == pytest.approx(-b_h, rel=tolerance)
    assert top[2] == pytest.approx(-b_v, rel=tolerance)
    # T_A = H − μ w L_b: an error of one element in where the laid part ends moves it by μ w h.
    element = length / 800
    assert state.reaction("A")[0] == pytest.approx(a_h, abs=2e-5 * -b_h + 2.0 * friction * w * element)
    assert state.laid_length == pytest.approx(info["LBot"], abs=element)
