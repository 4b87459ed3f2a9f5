"""Elastic catenary with a laid part on a flat rigid seabed, with axial seabed friction (pure Python).

An independent analytic reference for the engine's seabed contact; it shares nothing with the engine and
uses only :mod:`math` and the sibling reference ``irvine.py``.

Conventions (SI units throughout)
---------------------------------
Frame e: origin at the anchor, end A, which lies ON the flat rigid seabed z = 0; e1 horizontal toward the top
end B; e3 points DOWN (gravity = +g e3). B lies at a horizontal distance ``span`` (m) from A and a height
``rise`` (m) above the seabed, i.e. at (x, z) = (span, −rise). The cable has no bending stiffness, an
unstretched length L (m), an axial stiffness EA (N) and a submerged weight w > 0 (N per *unstretched* metre).
s ∈ [0, L] is the unstretched (Lagrangian) arc length from A (m). Tensions are in N.

The line lies on the seabed from A to the touchdown s_td (unstretched laid length L_b = s_td) and is suspended
from there to B (unstretched suspended length L_s = L − s_td). At the touchdown the suspended part is
horizontal: its vertical tension is zero there, its horizontal tension H is constant along it.

Suspended part, s_td ≤ s ≤ L (Irvine, *Cable Structures*, 1981, §2.2, with V_A = 0 at the touchdown).
With u = s − s_td and V(u) = w u the vertical tension component (N):

    x(s) = x_td + H u / EA + (H / w) asinh(w u / H)
   −z(s) = w u² / (2 EA) + (H / w) [√(1 + (w u / H)²) − 1]
    T(s) = √(H² + (w u)²)

so the top tension is T_B = √(H² + (w L_s)²), its vertical component V_B = w L_s.

Laid part, 0 ≤ s ≤ s_td (z = 0). Fully mobilised axial friction of coefficient μ ≥ 0 (the model of
MoorPy and of classical mooring analysis) lets the tension fall from H at the touchdown toward A by μ w per
unstretched metre, and never below zero:

    T(s) = max(0, H − μ w (s_td − s)),     s_0 = max(0, s_td − H / (μ w))   (s_0 = 0 when μ = 0)
    x(s) = s + (1 / EA) ∫₀ˢ T(σ) dσ = s + (s − s_0) [T(s_0) + T(s)] / (2 EA)   for s ≥ s_0,   x(s) = s below

(the tension is linear between s_0 and s_td, so the trapezoid is exact). The anchor tension, horizontal, is
T_A = max(0, H − μ w s_td); without friction T = H on the whole laid part, T_A = H.

Solution
--------
The height condition −z(L) = rise has a closed-form solution for H given L_s: with
r = rise − w L_s² / (2 EA) (the inextensible part of the rise),

    H(L_s) = w (L_s² − r²) / (2 r),

which increases from 0 at L_s = L_0 = 2 rise / (1 + √(1 + 2 w rise / EA)) (the suspended part hangs vertically
and stretches) to ∞ at L_s = √(2 EA rise / w) (r → 0). The span condition

    F(L_s) = x_td(H, L − L_s) + H L_s / EA + (H / w) asinh(w L_s / H) − span = 0

is then one scalar equation, increasing in L_s, solved by bisection to machine precision. Regimes:

* F(L_0) = L − L_0 − span ≥ 0: the line is so slack that, even at zero tension, its laid part reaches B: no
  straight laid equilibrium (it would double back; MoorPy's "ProfileType 4"): :class:`ValueError`.
* L ≤ L_0, or F(L) < 0 with L below √(2 EA rise / w): no laid part; the line hangs clear of the seabed and is
  Irvine's elastic catenary through A and B (:func:`irvine.irvine_catenary`), with an upward pull V_A ≥ 0 on
  the anchor. The touchdown is then ``None``.
* otherwise a laid part of length L − L_s.

Only an impossible geometry is an error: B not above the seabed, an inextensible line (``ea = math.inf``)
shorter than the chord, or the over-long line above. A taut line simply stretches.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from irvine import Catenary, irvine_catenary

__all__ = ["LaidCatenary", "laid_catenary"]


@dataclass(frozen=True)
class LaidCatenary:
    """Solution of the cable on the seabed. Lengths in m, forces in N, angles in rad; frame e (z down).

    Attributes:
        length: unstretched length L (m).
        span: horizontal distance from A to B (m).
        rise: height of B above the seabed and A (m).
        weight: submerged weight w (N per unstretched m).
        ea: axial stiffness EA (N).
        friction: axial seabed friction coefficient μ (-).
        horizontal: horizontal tension H of the suspended part (N).
        touchdown_arc_length: unstretched arc length s_td from A to the touchdown (m), or ``None`` when the line
            is fully suspended.
        anchor_vertical: upward pull of the cable on A (N); 0 when a part of the line is laid.
    """

    length: float
    span: float
    rise: float
    weight: float
    ea: float
    friction: float
    horizontal: float
    touchdown_arc_length: float | None
    anchor_vertical: float = 0.0

    @property
    def laid_length(self) -> float:
        """Unstretched length resting on the seabed (m); 0 when fully suspended."""
        return 0.0 if self.touchdown_arc_length is None else self.touchdown_arc_length

    @property
    def suspended_length(self) -> float:
        """Unstretched suspended length L − s_td (m)."""
        return self.length - self.laid_length

    @property
    def anchor_tension(self) -> float:
        """Horizontal tension at A (N): max(0, H − μ w s_td) when laid, H when fully suspended."""
        if self.touchdown_arc_length is None:
            return self.horizontal
        return max(0.0, self.horizontal - self.friction * self.weight * self.touchdown_arc_length)

    @property
    def slack_arc_length(self) -> float:
        """Unstretched arc length s_0 from A over which friction has brought the tension to zero (m)."""
        if self.touchdown_arc_length is None or self.friction == 0.0:
            return 0.0
        return max(0.0, self.touchdown_arc_length - self.horizontal / (self.friction * self.weight))

    @property
    def touchdown_x(self) -> float | None:
        """Stretched position of the touchdown along e1 (m), or ``None`` when fully suspended."""
        if self.touchdown_arc_length is None:
            return None
        s_td = self.touchdown_arc_length
        return _laid_x(self.horizontal, s_td, s_td, self.friction, self.weight, self.ea)

    @property
    def top_vertical(self) -> float:
        """Vertical tension component at B (N, the cable pulls B downward): V_A + w × suspended length."""
        return self.anchor_vertical + self.weight * self.suspended_length

    @property
    def top_tension(self) -> float:
        """Magnitude of the tension at B (N)."""
        return math.hypot(self.horizontal, self.top_vertical)

    @property
    def top_angle(self) -> float:
        """Angle of the cable at B above the horizontal (rad)."""
        return math.atan2(self.top_vertical, self.horizontal)

    def tension(self, s: float) -> float:
        """Tension magnitude (N) at the unstretched arc length s (m) from A."""
        self._check_s(s)
        s_td = self.touchdown_arc_length
        if s_td is None:
            return math.hypot(self.horizontal, self.anchor_vertical + self.weight * s)
        if s <= s_td:
            return _laid_tension(self.horizontal, s_td, s, self.friction, self.weight)
        return math.hypot(self.horizontal, self.weight * (s - s_td))

    def position(self, s: float) -> tuple[float, float]:
        """Position (x, z) in frame e (m, z down, seabed z = 0) of the material point s (m, unstretched)."""
        self._check_s(s)
        s_td = self.touchdown_arc_length
        h, w, ea = self.horizontal, self.weight, self.ea
        if s_td is None:
            va = self.anchor_vertical
            x, y = Catenary(h, va, va + w * self.length, w, self.length, ea).point(s)
            return x, -y
        if s <= s_td:
            return _laid_x(h, s_td, s, self.friction, w, ea), 0.0
        u = s - s_td
        x_s, height = _suspended(h, u, w, ea)
        return _laid_x(h, s_td, s_td, self.friction, w, ea) + x_s, -height

    def _check_s(self, s: float) -> None:
        if not 0.0 <= s <= self.length:
            raise ValueError(f"arc length s = {s} m outside [0, {self.length}] m")


def _laid_tension(h: float, s_td: float, s: float, mu: float, w: float) -> float:
    """Tension (N) at s on the laid part: H less the fully mobilised friction μ w (s_td − s), floored at 0."""
    return max(0.0, h - mu * w * (s_td - s))


def _laid_x(h: float, s_td: float, s: float, mu: float, w: float, ea: float) -> float:
    """Stretched position x(s) = s + ∫₀ˢ T/EA (m) of a point s ≤ s_td of the laid part; H = h at s_td."""
    s0 = max(0.0, s_td - h / (mu * w)) if mu > 0.0 else 0.0
    if s <= s0:
        return s
    t0 = _laid_tension(h, s_td, s0, mu, w)
    t1 = _laid_tension(h, s_td, s, mu, w)
    return s + (s - s0) * (t0 + t1) / (2.0 * ea)


def _suspended(h: float, u: float, w: float, ea: float) -> tuple[float, float]:
    """(Δx, height) (m) of the point u (m, unstretched) past the touchdown of a catenary of tension h (N)."""
    q = w * u / h
    dx = h * u / ea + h / w * math.asinh(q)
    height = w * u * u / (2.0 * ea) + h / w * (q * q / (math.sqrt(1.0 + q * q) + 1.0))
    return dx, height


def _horizontal_for(ls: float, rise: float, w: float, ea: float) -> float:
    """Closed-form H (N) for which a suspended length ls (m), horizontal at the seabed, reaches ``rise`` (m)."""
    r = rise - w * ls * ls / (2.0 * ea)
    if r <= 0.0:
        return math.inf
    return w * (ls - r) * (ls + r) / (2.0 * r)


def _bisect(f: Callable[[float], float], lo: float, hi: float) -> float:
    """Root of an increasing f on [lo, hi] with f(lo) < 0 < f(hi), to machine precision (f(hi) not evaluated)."""
    for _ in range(400):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if f(mid) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def laid_catenary(
    length: float, span: float, rise: float, weight: float, ea: float, friction: float = 0.0
) -> LaidCatenary:
    """Solve the elastic catenary hanging from B = (span, −rise) with its end A anchored on the seabed.

    Args:
        length: unstretched length L (m), > 0.
        span: horizontal distance from A to B (m), > 0.
        rise: height of B above the seabed (m), > 0.
        weight: submerged weight w (N per unstretched m), > 0.
        ea: axial stiffness EA (N), > 0 (``math.inf`` for an inextensible line).
        friction: axial seabed friction coefficient μ (-), ≥ 0.

    Returns:
        The :class:`LaidCatenary`; its ``touchdown_arc_length`` is ``None`` when no part of the line is laid.

    Raises:
        ValueError: for invalid parameters or an impossible geometry (B not above the seabed, an inextensible
            line shorter than the chord AB, or a line so long that its laid part reaches B at zero tension).
    """
    if not (length > 0.0 and span > 0.0 and weight > 0.0 and ea > 0.0 and friction >= 0.0):
        raise ValueError("need length > 0, span > 0, weight > 0, ea > 0 and friction >= 0")
    if not rise > 0.0:
        raise ValueError(f"end B must lie above the seabed (rise = {rise} m must be > 0)")
    if math.isinf(ea) and length <= math.hypot(span, rise):
        raise ValueError(
            f"an inextensible line of length {length} m cannot reach B at distance {math.hypot(span, rise)} m"
        )
    w, mu = weight, friction
    ls_min = 2.0 * rise / (1.0 + math.sqrt(1.0 + 2.0 * w * rise / ea))  # hanging vertically, H = 0
    ls_max = math.sqrt(2.0 * ea * rise / w)  # H -> infinity

    def span_misfit(ls: float) -> float:
        h = _horizontal_for(ls, rise, w, ea)
        lb = length - ls
        if (
            not h > 0.0
        ):  # rounding at the vertical limit: nothing hangs sideways, the laid part is unstretched
            return lb - span
        if math.isinf(h):
            return math.inf
        return _laid_x(h, lb, lb, mu, w, ea) + _suspended(h, ls, w, ea)[0] - span

    if length > ls_min:
        if length - ls_min >= span:
            raise ValueError(
                f"line too long: {length - ls_min} m of it would lie slack on the seabed, beyond B at {span} m "
                "(no straight laid equilibrium)"
            )
        if length >= ls_max or span_misfit(length) >= 0.0:
            ls = _bisect(span_misfit, ls_min, min(length, ls_max))
            h = _horizontal_for(ls, rise, w, ea)
            return LaidCatenary(length, span, rise, w, ea, mu, horizontal=h, touchdown_arc_length=length - ls)
    cat = irvine_catenary(length, span, rise, w, ea)
    if cat.vertical_a < -1e-9 * w * length:
        raise RuntimeError(f"fully suspended solution dips below the seabed (V_A = {cat.vertical_a} N)")
    return LaidCatenary(
        length,
        span,
        rise,
        w,
        ea,
        mu,
        horizontal=cat.horizontal,
        touchdown_arc_length=None,
        anchor_vertical=max(0.0, cat.vertical_a),
    )
