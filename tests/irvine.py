"""Irvine's elastic catenary, solved independently of the engine (pure Python, no numpy or scipy).

A cable of unstretched length ``L`` (m), weight ``w`` per unstretched length (N/m, positive = downwards),
axial stiffness ``EA`` (N) and no bending stiffness hangs between two supports: A at the origin and B at a
horizontal distance ``span`` (m) and a height ``rise`` (m, positive = B above A). With H the horizontal
tension (N) and V_A the vertical component of the tension at A (N, positive = pulling A upwards), the
Lagrangian coordinate s (m from A, unstretched) gives (Irvine, *Cable Structures*, 1981, §2.2):

    x(s) = H s / EA + (H / w) [asinh(V(s) / H) − asinh(V_A / H)]
    y(s) = (V_A s + w s² / 2) / EA + (H / w) [√(1 + (V(s)/H)²) − √(1 + (V_A/H)²)]

with V(s) = V_A + w s. The two end conditions x(L) = span, y(L) = rise are solved by nested bisection:
for a given H, y(L) increases monotonically with V_A; with V_A so chosen, x(L) increases monotonically
with H. A buoyant line (w < 0) is the mirror image (y → −y) of a heavy one.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["Catenary", "irvine_catenary"]


@dataclass(frozen=True)
class Catenary:
    """Solution of the elastic catenary. Forces in N, angles in rad, lengths in m.

    Vertical components are positive upwards for the tension *in the cable at that end*: ``vertical_a`` is
    the upward pull of the cable on support A (negative if the cable first dips below A), ``vertical_b``
    the downward pull of the cable on support B.
    """

    horizontal: float
    vertical_a: float
    vertical_b: float
    weight: float
    length: float
    ea: float

    @property
    def tension_a(self) -> float:
        """Tension at A (N)."""
        return math.hypot(self.horizontal, self.vertical_a)

    @property
    def tension_b(self) -> float:
        """Tension at B (N)."""
        return math.hypot(self.horizontal, self.vertical_b)

    @property
    def angle_a(self) -> float:
        """Angle of the cable at A above the horizontal (rad)."""
        return math.atan2(self.vertical_a, self.horizontal)

    def point(self, s: float) -> tuple[float, float]:
        """Position (horizontal distance, height above A) of the material point s (m, unstretched)."""
        return _shape(self.horizontal, self.vertical_a, self.weight, s, self.ea)


def _shape(h: float, va: float, w: float, s: float, ea: float) -> tuple[float, float]:
    """(x, y) of the point s of a cable of weight w > 0 with horizontal tension h and end force va."""
    v = va + w * s
    x = h * s / ea + h / w * (math.asinh(v / h) - math.asinh(va / h))
    y = (va * s + 0.5 * w * s * s) / ea + h / w * (math.hypot(1.0, v / h) - math.hypot(1.0, va / h))
    return x, y


def _bisect(f: Callable[[float], float], lo: float, hi: float) -> float:
    """Root of an increasing function f on [lo, hi] with f(lo) < 0 < f(hi), to machine precision."""
    for _ in range(300):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if f(mid) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _bracket_up(f: Callable[[float], float], lo: float, hi: float) -> tuple[float, float]:
    """Widen [lo, hi] (lo may be negative) until an increasing f changes sign inside it."""
    for _ in range(200):
        if f(lo) < 0.0:
            break
        lo = lo - 2.0 * abs(lo) - 1.0
    for _ in range(200):
        if f(hi) > 0.0:
            break
        hi = 2.0 * abs(hi) + 1.0
    return lo, hi


def irvine_catenary(length: float, span: float, rise: float, weight: float, ea: float) -> Catenary:
    """Solve the elastic catenary between A = (0, 0) and B = (span, rise).

    Args:
        length: unstretched length L (m).
        span: horizontal distance from A to B (m), > 0.
        rise: height of B above A (m), either sign.
        weight: weight per unstretched length w (N/m); negative for a buoyant line.
        ea: axial stiffness EA (N).

    Returns:
        The :class:`Catenary` with the horizontal tension and the vertical end forces (N).
    """
    if not (length > 0 and span > 0 and ea > 0 and weight != 0):
        raise ValueError("need length > 0, span > 0, ea > 0 and weight != 0")
    if weight < 0:
        # Buoyant: mirror y -> -y, solve the heavy problem, mirror back.
        mirrored = irvine_catenary(length, span, -rise, -weight, ea)
        return Catenary(
            horizontal=mirrored.horizontal,
            vertical_a=-mirrored.vertical_a,
            vertical_b=-mirrored.vertical_b,
            weight=weight,
            length=length,
            ea=ea,
        )
    w = weight
    scale = w * length

    def vertical_a_for(h: float) -> float:
        def misfit(va: float) -> float:
            return _shape(h, va, w, length, ea)[1] - rise

        lo, hi = _bracket_up(misfit, -scale, scale)
        return _bisect(misfit, lo, hi)

    def span_misfit(h: float) -> float:
        return _shape(h, vertical_a_for(h), w, length, ea)[0] - span

    lo = 1e-9 * scale
    hi = scale
    for _ in range(200):
        if span_misfit(hi) > 0.0:
            break
        hi *= 2.0
    h = _bisect(span_misfit, lo, hi)
    va = vertical_a_for(h)
    return Catenary(horizontal=h, vertical_a=va, vertical_b=va + w * length, weight=w, length=length, ea=ea)
