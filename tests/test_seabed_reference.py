"""Validation of the seabed catenary reference (``seabed_reference.py``) against MoorPy and against itself.

MoorPy (NREL, ``moorpy.Catenary.catenary``, a port of the FAST v7 / MAP quasi-static line solver) is the peer
code. Its conventions, read from its source (MoorPy 1.3.0, ``moorpy/Catenary.py``)::

    FxA, FzA, FxB, FzB, info = catenary(XF, ZF, L, EA, W, CB=0, ..., Tol=1e-6, nNodes=20, plots=0)

* ``XF`` ≥ 0 is the horizontal distance from end A (anchor) to end B (m); ``ZF`` is the height of B above A,
  positive UP (m) — so ZF = ``rise`` here, whereas our frame e has z down; ``L`` unstretched length (m);
  ``EA`` (N); ``W`` the submerged weight per unstretched length (N/m).
* ``CB`` > 0: axial seabed friction coefficient, fully mobilised, T(s) = max(0, H − CB·W·(L_bot − s)) on the
  laid part (exactly our μ); ``CB`` = 0: end A on the seabed, no friction; ``CB`` < 0: end A lies −CB metres
  ABOVE the seabed (no contact at A).
* The four forces are those the line exerts on its ends, x positive from A to B, z positive UP:
  FxA = H_A (anchor horizontal tension, ≥ 0), FzA = V_A (0 when a part is laid), FxB = −H_F, FzB = −V_F.
  ``info`` holds ``HF``, ``VF`` (tension components at B, positive), ``HA``, ``VA``, ``LBot`` (UNSTRETCHED laid
  length, m) and ``ProfileType``: 1 fully suspended, 2 laid with anchor tension > 0, 3 laid with the anchor
  tension brought to zero by friction, 4 line too long ("bunched" on the seabed, H = 0). With ``plots=1`` it
  also returns the nodal profile ``s``, ``X``, ``Z`` (up), ``Te`` at ``nNodes`` equally spaced points.
* Accuracy: a Newton iteration (``dsolve2``) on (H_F, V_F) that stops as soon as both closure errors
  |x(L) − XF| and |z(L) − ZF| are below ``Tol`` — an ABSOLUTE distance in metres (default 1e-6), not a relative
  force tolerance. Its force error is therefore about (stiffness dH/dXF) × Tol, which at Tol = 1e-9 m (used
  here) is at most 1.7e-10 of H for the laid cases below (``info['stiffnessB']``); Newton's quadratic
  convergence makes the achieved error far smaller. Measured (max over the 9 laid cases, Tol = 1e-9 m, and
  identical at the default 1e-6 m): H 2.2e-13, anchor tension 2.1e-13 of H, T_B 3.4e-14, V_B 2.8e-14, L_bot
  6.1e-15 relative, touchdown x 1.3e-14 of the span, nodal x, z ≤ 6.4e-12 m, nodal tension 6.8e-14 of T_B. The
  fully suspended cases reach 5.6e-14 at Tol = 1e-9 m but only 7.6e-9 (V_A) at the default Tol, hence the
  explicit Tol. The tests assert 1e-9 relative.
* A quirk of MoorPy's nodal profile: with ``CB = 0`` its laid nodes sit at X = s, omitting the stretch H s / EA
  of the laid part (its closure equation and its suspended nodes do include it; with CB > 0 the laid nodes are
  right). The profile test therefore skips the laid nodes' X when CB = 0.

The chain case of the brief, (L, span, rise) = (300, 250, 50) m, is exactly at the limit where the line is
long enough to lie flat to below B and hang vertically from there (250 + 50 = 300 m), and the hanging part's
stretch takes it over that limit: MoorPy returns ProfileType 4 (H = 0) and the reference raises ValueError.
The chain case below therefore has span 260 m.
"""

from __future__ import annotations

import math
from typing import Any

import pytest
from irvine import irvine_catenary
from seabed_reference import LaidCatenary, laid_catenary

moorpy_catenary = pytest.importorskip("moorpy.Catenary").catenary

# (L m, span m, rise m, w N/m, EA N)
CASES: dict[str, tuple[float, float, float, float, float]] = {
    "cable_150m": (1000.0, 900.0, 150.0, 1000.0, 1e9),
    "flooded_pipe_800m": (1600.0, 1200.0, 800.0, 1846.0, 5.4e9),  # 0.6 m steel pipe, flooded, 800 m water
    "chain_50m": (300.0, 260.0, 50.0, 1500.0, 6e8),
}
FRICTIONS = (0.0, 0.3, 1.0)
MOORPY_TOL = 1e-9  # m, MoorPy's absolute closure tolerance
RTOL = 1e-9  # relative agreement asserted with MoorPy


def _moorpy(case: tuple[float, float, float, float, float], mu: float, **kwargs: Any) -> dict[str, Any]:
    """MoorPy's solution for the case, as a dict of the quantities compared (N, m)."""
    length, span, rise, w, ea = case
    fxa, fza, fxb, fzb, info = moorpy_catenary(span, rise, length, ea, w, CB=mu, Tol=MOORPY_TOL, **kwargs)
    h, vb = -fxb, -fzb
    # Stretched touchdown position implied by MoorPy's forces: B minus the extent of the suspended part.
    ls = vb / w
    x_td = span - h / w * math.asinh(vb / h) - h * ls / ea if h > 0.0 else math.nan
    return {
        "horizontal": h,
        "anchor_tension": fxa,
        "anchor_vertical": fza,
        "top_vertical": vb,
        "top_tension": math.hypot(fxb, fzb),
        "laid_length": info["LBot"],
        "touchdown_x": x_td,
        "profile": info["ProfileType"],
        "info": info,
    }


def _rel(a: float, b: float, scale: float | None = None) -> float:
    """|a − b| relative to ``scale`` (default |b|)."""
    return abs(a - b) / (abs(b) if scale is None else scale)


# ----------------------------------------------------------------------------------------------------------
# Against MoorPy
# ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("mu", FRICTIONS)
@pytest.mark.parametrize("name", CASES)
def test_against_moorpy(name: str, mu: float) -> None:
    """H, anchor and top tensions, laid length and touchdown position agree with MoorPy to 1e-9."""
    case = CASES[name]
    ref = laid_catenary(*case, friction=mu)
    mp = _moorpy(case, mu)
    assert ref.touchdown_arc_length is not None
    assert mp["profile"] == (2 if ref.anchor_tension > 0.0 else 3)
    h = ref.horizontal
    assert _rel(mp["horizontal"], h) < RTOL
    assert _rel(mp["anchor_tension"], ref.anchor_tension, scale=h) < RTOL
    assert mp["anchor_vertical"] == 0.0
    assert _rel(mp["top_tension"], ref.top_tension) < RTOL
    assert _rel(mp["top_vertical"], ref.top_vertical) < RTOL
    assert _rel(mp["laid_length"], ref.laid_length) < RTOL
    assert ref.touchdown_x is not None
    assert _rel(mp["touchdown_x"], ref.touchdown_x, scale=case[1]) < RTOL


def test_friction_regimes_are_exercised() -> None:
    """The cases cover anchor tension > 0 with friction (MoorPy type 2) and a zero-tension stretch (type 3)."""
    assert laid_catenary(*CASES["flooded_pipe_800m"], friction=1.0).anchor_tension > 1e5
    chain = laid_catenary(*CASES["chain_50m"], friction=0.3)
    assert chain.anchor_tension == 0.0
    assert chain.laid_length > chain.slack_arc_length > 0.9 * chain.laid_length


@pytest.mark.parametrize("mu", FRICTIONS)
@pytest.mark.parametrize("name", CASES)
def test_profile_against_moorpy(name: str, mu: float) -> None:
    """Positions and tensions at MoorPy's 41 nodes agree (laid nodes' x skipped when CB = 0, see above)."""
    case = CASES[name]
    span = case[1]
    ref = laid_catenary(*case, friction=mu)
    info = _moorpy(case, mu, nNodes=41, plots=1)["info"]
    for s, x_mp, z_mp, t_mp in zip(info["s"], info["X"], info["Z"], info["Te"], strict=True):
        x, z = ref.position(float(s))
        if not (mu == 0.0 and s <= ref.laid_length):
            assert abs(x - x_mp) < RTOL * span
        assert abs(-z - z_mp) < RTOL * span
        assert abs(ref.tension(float(s)) - t_mp) < RTOL * ref.top_tension


# (L m, span m, rise m, w N/m, EA N): a slack line clear of the seabed, and one stretched 2.5 % beyond its chord.
SUSPENDED = {"slack_clear": (950.0, 850.0, 400.0, 1000.0, 1e9), "taut": (890.0, 900.0, 150.0, 1000.0, 1e9)}


@pytest.mark.parametrize("name", SUSPENDED)
def test_fully_suspended_against_moorpy(name: str) -> None:
    """No laid part: Irvine's catenary with an upward pull on the anchor, as MoorPy's ProfileType 1."""
    case = SUSPENDED[name]
    ref = laid_catenary(*case, friction=0.3)
    mp = _moorpy(case, 0.3)
    assert ref.touchdown_arc_length is None and ref.touchdown_x is None
    assert mp["profile"] == 1
    assert ref.anchor_vertical > 0.01 * case[3] * case[0]
    assert _rel(mp["horizontal"], ref.horizontal) < RTOL
    assert _rel(mp["anchor_tension"], ref.anchor_tension) < RTOL
    assert _rel(mp["anchor_vertical"], ref.anchor_vertical) < RTOL
    assert _rel(mp["top_tension"], ref.top_tension) < RTOL
    x, z = ref.position(case[0])
    assert abs(x - case[1]) < 1e-9 * case[1] and abs(z + case[2]) < 1e-9 * case[1]


def test_too_long_line_is_an_error_like_moorpy_type_4() -> None:
    """The brief's chain case (300, 250, 50) m cannot lie straight: ValueError; MoorPy 'bunches' it, H = 0."""
    case = (300.0, 250.0, 50.0, 1500.0, 6e8)
    with pytest.raises(ValueError, match="too long"):
        laid_catenary(*case)
    mp = _moorpy(case, 0.0)
    assert mp["profile"] == 4 and mp["horizontal"] == 0.0


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((1000.0, 900.0, 0.0, 1000.0, 1e9), "above the seabed"),
        ((1000.0, 900.0, -10.0, 1000.0, 1e9), "above the seabed"),
        ((900.0, 900.0, 150.0, 1000.0, math.inf), "cannot reach"),
        ((1000.0, 0.0, 150.0, 1000.0, 1e9), "span > 0"),
        ((1000.0, 900.0, 150.0, -1000.0, 1e9), "weight > 0"),
    ],
)
def test_impossible_input_raises(args: tuple[float, ...], match: str) -> None:
    """Only impossible geometry or parameters raise, with a message saying why."""
    with pytest.raises(ValueError, match=match):
        laid_catenary(*args)
    with pytest.raises(ValueError, match="friction"):
        laid_catenary(1000.0, 900.0, 150.0, 1000.0, 1e9, friction=-0.1)


# ----------------------------------------------------------------------------------------------------------
# Self-checks
# ----------------------------------------------------------------------------------------------------------


def _derivative(ref: LaidCatenary, s: float, step: float) -> tuple[float, float]:
    """dr/ds at s (central, or second-order one-sided at the ends) by finite differences."""
    if s + step > ref.length:
        (x0, z0), (x1, z1), (x2, z2) = (ref.position(s - k * step) for k in (0, 1, 2))
        return (3 * x0 - 4 * x1 + x2) / (2 * step), (3 * z0 - 4 * z1 + z2) / (2 * step)
    (xm, zm), (xp, zp) = ref.position(s - step), ref.position(s + step)
    return (xp - xm) / (2 * step), (zp - zm) / (2 * step)


@pytest.mark.parametrize("mu", FRICTIONS)
@pytest.mark.parametrize("name", CASES)
def test_equilibrium_and_closure(name: str, mu: float) -> None:
    """Closure at B; on the suspended part H constant, V = w (s − s_td) (so V_B = w L_s) and stretch 1 + T/EA;
    on the laid part z = 0, stretch 1 + T/EA and dT/ds = μ w where taut — all from the geometry alone."""
    length, span, rise, w, ea = CASES[name]
    ref = laid_catenary(length, span, rise, w, ea, friction=mu)
    x_b, z_b = ref.position(length)
    assert abs(x_b - span) < 1e-10 * span and abs(z_b + rise) < 1e-10 * span
    assert ref.position(0.0) == (0.0, 0.0)
    s_td = ref.touchdown_arc_length
    assert s_td is not None
    step = 1e-3
    n = 40
    for k in range(1, n + 1):  # suspended part, up to and including B
        s = s_td + (length - s_td) * k / n
        dx, dz = _derivative(ref, s, step)
        stretch = math.hypot(dx, dz)
        t = ref.tension(s)
        assert abs(stretch - (1.0 + t / ea)) < 1e-8
        assert _rel(t * dx / stretch, ref.horizontal) < 1e-7
        assert abs(t * -dz / stretch - w * (s - s_td)) < 1e-7 * t
    assert _rel(ref.top_vertical, w * (length - s_td)) < 1e-14
    assert _rel(ref.tension(length), ref.top_tension) < 1e-14
    s0 = ref.slack_arc_length
    for k in range(1, n):  # laid part
        s = s_td * k / n
        if abs(s - s0) < 2 * step:
            continue
        dx, _ = _derivative(ref, s, step)
        assert ref.position(s)[1] == 0.0
        t = ref.tension(s)
        assert abs(dx - (1.0 + t / ea)) < 1e-9
        dt = (ref.tension(s + step) - ref.tension(s - step)) / (2 * step)
        assert abs(dt - (mu * w if s > s0 else 0.0)) < 1e-6 * w
    # Whole line: H at the touchdown less the friction on the taut laid stretch is the anchor tension.
    assert _rel(ref.anchor_tension, ref.horizontal - mu * w * (s_td - s0), scale=ref.horizontal) < 1e-12
    if mu == 0.0:
        assert ref.touchdown_x is not None
        assert _rel(ref.touchdown_x, s_td * (1.0 + ref.horizontal / ea)) < 1e-14


@pytest.mark.parametrize("mu", FRICTIONS)
@pytest.mark.parametrize("name", CASES)
def test_suspended_part_is_irvine_catenary(name: str, mu: float) -> None:
    """The suspended part, solved as a free Irvine catenary from the touchdown to B, is horizontal at the
    touchdown (V = 0) with the same H (independent solver: nested bisection in ``irvine.py``)."""
    length, span, rise, w, ea = CASES[name]
    ref = laid_catenary(length, span, rise, w, ea, friction=mu)
    assert ref.touchdown_x is not None
    free = irvine_catenary(ref.suspended_length, span - ref.touchdown_x, rise, w, ea)
    assert _rel(free.horizontal, ref.horizontal) < 1e-9
    assert abs(free.vertical_a) < 1e-9 * ref.top_tension


@pytest.mark.parametrize("mu", FRICTIONS)
def test_continuous_at_lift_off(mu: float) -> None:
    """Moving B just past the span at which the laid part vanishes switches to Irvine's catenary continuously."""
    length, _, rise, w, ea = CASES["cable_150m"]
    # Span at which the whole line just reaches B horizontally at A: the suspended-only solution with V_A = 0.
    h = w * (length**2 - (rise - w * length**2 / (2 * ea)) ** 2) / (2 * (rise - w * length**2 / (2 * ea)))
    span0 = h * length / ea + h / w * math.asinh(w * length / h)
    inside = laid_catenary(length, span0 * (1 - 1e-9), rise, w, ea, friction=mu)
    outside = laid_catenary(length, span0 * (1 + 1e-9), rise, w, ea, friction=mu)
    assert inside.touchdown_arc_length is not None and outside.touchdown_arc_length is None
    assert 0.0 < inside.laid_length < 1e-3
    assert _rel(inside.horizontal, h) < 1e-5 and _rel(outside.horizontal, h) < 1e-5
    assert 0.0 <= outside.anchor_vertical < 1e-5 * h
    assert _rel(inside.top_tension, outside.top_tension) < 1e-5
