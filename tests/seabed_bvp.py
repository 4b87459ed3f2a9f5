"""A stiff pipe hanging from a top point onto a flat elastic seabed: a planar boundary-value problem solved with
scipy's ``solve_bvp``, independently of pipelay (a reference for its finite elements with seabed contact).

SI units throughout. Frame e: origin at end A, e1 horizontal toward the top end B, e3 pointing DOWN (gravity
along +e3); the seabed is the plane z = 0 through A, water above it (z < 0). B is pinned at (span, −rise).

The pipe has unstretched length L (m), axial stiffness EA (N), bending stiffness EI (N·m²) and submerged weight
w (N per unstretched metre, along +e3). It is a planar, shear-rigid, extensible and geometrically exact rod.
With s ∈ [0, L] the unstretched arc length from A (m):

* r(s) = (x, z) the centreline (m); θ(s) the angle of the tangent t = (cos θ, sin θ), measured from e1 toward
  e3 (rad; θ < 0 where the pipe rises toward B); n = (−sin θ, cos θ) the normal.
* F(s) = (Fx, Fz) the internal force (N) that the part beyond s exerts on the part before it, so a tension
  pulls toward B: F = N t + Q n with N = F·t the axial (effective) force (N, > 0 in tension) and Q = F·n the
  shear force (N).
* M(s) the bending moment (N·m) that the part beyond s exerts on the part before it, positive in the sense of
  θ (rotating e1 toward e3); with a × b := a_x b_z − a_z b_x, moments of forces are r × F.
* q(s) the seabed reaction per unstretched length (N/m), pushing up (−e3): q = k d max(0, z) with z the
  centreline's penetration below the seabed plane, k the seabed stiffness (Pa/m) and d the outer diameter (m);
  no friction.

The distributed load on the element ds is f ds with f = (0, w − q). Equilibrium of the element [s, s + ds]
(forces F(s + ds) − F(s) + f ds = 0; moments about r(s): M(s + ds) − M(s) + r' ds × F = 0) and the
constitutive laws (stretch 1 + N/EA, Euler–Bernoulli bending M = EI θ') give

    x' = (1 + N/EA) cos θ,        z' = (1 + N/EA) sin θ,        N = Fx cos θ + Fz sin θ,
    θ' = M / EI,                  M' = −(x' Fz − z' Fx) = −(1 + N/EA) Q,    Q = Fz cos θ − Fx sin θ,
    Fx' = 0,                      Fz' = −w + q,

(' = d/ds). Fx = H is the horizontal tension, constant (no friction). On a suspended catenary the pipe rises
toward B, so Fz < 0 there (the pull of B is upward) and decreases by w per metre toward B. The supports react
on the pipe with R_A = −F(0) at A and R_B = F(L) at B, and the global balance of forces
R_A + R_B + (0, wL) − (0, ∫q ds) = 0 is the integral of Fz' = −w + q.

Boundary conditions (both ends hinged): x(0) = z(0) = 0, M(0) = 0 and x(L) = span, z(L) = −rise, M(L) = 0.

Because q has a kink at z = 0, the problem is posed on two segments joined at the touchdown s_t, an unknown
parameter: the laid segment [0, s_t] with the seabed active and the suspended segment [s_t, L] without it, all
six states continuous at s_t and z(s_t) = 0 — 6 + 6 + 1 = 13 conditions for 12 states and one parameter. Both
segments are mapped onto τ ∈ [0, 1] starting at the touchdown (s = s_t (1 − τ) and s = s_t + (L − s_t) τ), so
that the boundary layers of both at the touchdown share mesh nodes near τ = 0, those at the ends near τ = 1.
The laid segment keeps the contact as k d max(0, z), so a dip of its centreline above the seabed (z < 0)
would feel no reaction; the solution is checked afterwards: z ≥ 0 on [0, s_t] is reported as
``laid_min_depth`` and z ≤ 0 on [s_t, L] as ``suspended_max_depth``.

Internally s, x and z are scaled by L, forces by wL and the curvature θ' by 1/L, so that the states are of
order one (the penetration w/(kd) ~ 1e-5 L excepted, but k d z/w is) and solve_bvp's relative tolerance means
much the same for all of them; the Jacobian is analytic. The start is the elastic catenary resting on the
elastic seabed (:func:`laid_catenary`) with the bending boundary layers at the hinges built in, on a mesh
graded into every boundary layer (λ = √(EI/H), the cable's √(H/(kd)) at the touchdown and the foundation's
(4EI/(kd))^(1/4) at A) and uniform elsewhere with as many nodes as the stiff equation θ' = M/EI needs. The
target EI is solved directly from it; if that fails, by continuation in EI (geometric steps from a nearly
flexible line, λ = 1e-3 L).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from irvine import Catenary
from scipy.integrate import solve_bvp
from scipy.optimize import OptimizeResult, brentq

__all__ = [
    "BoundaryLayer",
    "LaidCatenary",
    "SeabedBVP",
    "boundary_layer_estimates",
    "laid_catenary",
    "stiff_pipe_on_seabed",
]

_X, _Z, _THETA, _KAPPA, _FX, _FZ = range(6)


@dataclass(frozen=True)
class LaidCatenary:
    """The elastic catenary (EI = 0) resting on the elastic seabed. Lengths in m (arc lengths unstretched,
    from A), forces in N.

    ``suspended`` is Irvine's catenary of the hanging part from its vertex (zero vertical force there) to B;
    the vertex lies ``vertex_depth`` = w/(2kd) below the seabed plane, ``vertex_arc_length`` from A, and the
    centreline crosses the seabed plane (the touchdown, z = 0) ``touchdown_arc_length`` from A.
    """

    horizontal: float
    top_tension: float
    vertex_arc_length: float
    vertex_depth: float
    touchdown_arc_length: float
    touchdown_x: float
    laid_depth: float
    suspended: Catenary


@dataclass(frozen=True)
class BoundaryLayer:
    """Classic estimates of bending near the touchdown of a tensioned pipe (N·m and m).

    ``moment`` = EI·w/H: EI times the catenary's curvature at its vertex, w/H (1/m).
    ``length`` λ = √(EI/H): the length over which bending stiffness matters next to the touchdown.
    ``foundation_length`` = (4 EI / (k d))^(1/4): the characteristic length of a beam on an elastic foundation
    (1/β of Hetényi's solution), the length of the bending zone on the laid side; ``inf`` without a seabed.
    """

    moment: float
    length: float
    foundation_length: float


def boundary_layer_estimates(
    ei: float, horizontal: float, weight: float, stiffness: float = 0.0, diameter: float = 0.0
) -> BoundaryLayer:
    """Boundary-layer estimates of the sagbend bending near the touchdown.

    Args:
        ei: bending stiffness EI (N·m²).
        horizontal: horizontal tension H (N).
        weight: submerged weight w (N/m).
        stiffness: seabed stiffness k (Pa/m), optional.
        diameter: outer diameter d (m), optional.

    Returns:
        The :class:`BoundaryLayer`: moment EI·w/H (N·m), λ = √(EI/H) (m), (4EI/(kd))^(1/4) (m).
    """
    kd = stiffness * diameter
    return BoundaryLayer(
        moment=ei * weight / horizontal,
        length=math.sqrt(ei / horizontal),
        foundation_length=(4.0 * ei / kd) ** 0.25 if kd > 0 else math.inf,
    )


def laid_catenary(
    length: float, span: float, rise: float, weight: float, ea: float, stiffness: float, diameter: float
) -> LaidCatenary:
    """The elastic catenary with a laid part on a flat elastic seabed, from Irvine's formulas.

    The laid part, frictionless, carries N = H: it is straight, stretched by 1 + H/EA and sinks to z = w/(kd)
    away from its ends. Where it meets the suspended part the small-slope cable equation (H/ν) z'' = −w + k d z
    (ν = 1 + H/EA) has the exponential solution z = (w/kd)(1 − e^(−u/ℓ)), ℓ = √(H/(ν k d)), on the laid side
    (u the arc length from the touchdown) and a parabola on the suspended side; matching slopes at z = 0 puts
    the vertex of the parabola (the catenary's point of zero vertical force) ℓ before the touchdown, at the
    depth w/(2kd) below the seabed plane. So the suspended part is Irvine's catenary from a vertex at
    z = w/(2kd), rising rise + w/(2kd) to B, and the laid part from A to the vertex is straight; the errors are
    of second order in the slope at the touchdown, √(w/(kd)·w/H) (≈ 0.01 for the pipe of the tests).

    Args:
        length: unstretched length L (m).
        span: horizontal distance from A to B (m).
        rise: height of B above the seabed at A (m), > 0.
        weight: submerged weight w (N/m), > 0.
        ea: axial stiffness EA (N).
        stiffness: seabed stiffness k (Pa/m), > 0.
        diameter: outer diameter d (m), > 0.

    Returns:
        The :class:`LaidCatenary`.
    """
    w = weight
    vertex_depth = w / (2.0 * stiffness * diameter)
    height = rise + vertex_depth

    def lift(h: float, s: float) -> float:
        """Height of the point s of a catenary above its vertex (Irvine), m."""
        return w * s * s / (2.0 * ea) + (math.hypot(h, w * s) - h) / w

    def horizontal_for(suspended: float) -> float:
        return brentq(
            lambda h: lift(h, suspended) - height,
            1e-12 * w * length,
            1e3 * w * length,
            xtol=1e-14,
            rtol=1e-15,
        )

    def span_misfit(suspended: float) -> float:
        h = horizontal_for(suspended)
        x_hanging = h * suspended / ea + h / w * math.asinh(w * suspended / h)
        return (length - suspended) * (1.0 + h / ea) + x_hanging - span

    shortest = brentq(lambda s: s + w * s * s / (2.0 * ea) - height, 0.0, length, xtol=1e-14)
    suspended = brentq(span_misfit, shortest * (1.0 + 1e-9), length, xtol=1e-13, rtol=1e-15)
    h = horizontal_for(suspended)
    hanging = Catenary(
        horizontal=h, vertical_a=0.0, vertical_b=w * suspended, weight=w, length=suspended, ea=ea
    )
    vertex = length - suspended
    to_touchdown = brentq(lambda s: lift(h, s) - vertex_depth, 0.0, suspended, xtol=1e-14, rtol=1e-15)
    return LaidCatenary(
        horizontal=h,
        top_tension=hanging.tension_b,
        vertex_arc_length=vertex,
        vertex_depth=vertex_depth,
        touchdown_arc_length=vertex + to_touchdown,
        touchdown_x=vertex * (1.0 + h / ea) + hanging.point(to_touchdown)[0],
        laid_depth=2.0 * vertex_depth,
        suspended=hanging,
    )


@dataclass(frozen=True)
class SeabedBVP:
    """The solution of the stiff pipe on the elastic seabed. Lengths in m (arc lengths unstretched, from A),
    forces in N, moments in N·m, angles in rad; signs as in the module docstring (z and Fz positive DOWN).

    The arrays ``s``, ``x``, …, ``axial`` hold the states at the nodes of solve_bvp's final mesh (both
    segments, s increasing, the touchdown node once); :meth:`state` and the other methods evaluate the C1 cubic
    interpolant of the collocation solution at any s.
    """

    length: float
    span: float
    rise: float
    weight: float
    ea: float
    ei: float
    stiffness: float
    diameter: float
    tolerance: float
    touchdown_arc_length: float
    touchdown_x: float
    horizontal: float
    top_tension: float
    max_moment: float
    max_moment_arc_length: float
    laid_min_depth: float
    suspended_max_depth: float
    nodes: int
    s: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    z: np.ndarray = field(repr=False)
    theta: np.ndarray = field(repr=False)
    moment: np.ndarray = field(repr=False)
    fx: np.ndarray = field(repr=False)
    fz: np.ndarray = field(repr=False)
    axial: np.ndarray = field(repr=False)
    _interpolant: Callable[[np.ndarray], np.ndarray] = field(repr=False, compare=False)

    def state(self, s: float | np.ndarray) -> np.ndarray:
        """States (x, z, θ, M, Fx, Fz) at the arc lengths s (m): shape (6,) or (6, n), SI units."""
        return self._interpolant(np.asarray(s, dtype=float))

    def position(self, s: float | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Centreline (x, z) at s (m); z is the depth below the seabed plane (m, positive down)."""
        y = self.state(s)
        return y[_X], y[_Z]

    def angle(self, s: float | np.ndarray) -> np.ndarray:
        """Tangent angle θ from e1 toward e3 (down) at s (rad)."""
        return self.state(s)[_THETA]

    def bending_moment(self, s: float | np.ndarray) -> np.ndarray:
        """Bending moment M = EI θ' at s (N·m)."""
        return self.state(s)[_KAPPA]

    def force(self, s: float | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Internal force (Fx, Fz) exerted by the part beyond s on the part before it (N, Fz positive down)."""
        y = self.state(s)
        return y[_FX], y[_FZ]

    def axial_force(self, s: float | np.ndarray) -> np.ndarray:
        """Axial (effective) force N = F·t at s (N, positive in tension)."""
        y = self.state(s)
        return y[_FX] * np.cos(y[_THETA]) + y[_FZ] * np.sin(y[_THETA])

    def shear_force(self, s: float | np.ndarray) -> np.ndarray:
        """Shear force Q = F·n at s, n = (−sin θ, cos θ) (N); M' = −(1 + N/EA) Q."""
        y = self.state(s)
        return y[_FZ] * np.cos(y[_THETA]) - y[_FX] * np.sin(y[_THETA])

    def seabed_reaction(self, s: float | np.ndarray) -> np.ndarray:
        """Seabed reaction per unstretched length q = k d max(0, z) on the laid part, 0 beyond (N/m)."""
        s = np.asarray(s, dtype=float)
        z = self.state(s)[_Z]
        return np.where(
            s <= self.touchdown_arc_length, self.stiffness * self.diameter * np.maximum(z, 0.0), 0.0
        )

    @property
    def reaction_a(self) -> tuple[float, float]:
        """Force of the hinge A on the pipe, (horizontal, down) components (N): −F(0)."""
        fx, fz = self.force(0.0)
        return -float(fx), -float(fz)

    @property
    def reaction_b(self) -> tuple[float, float]:
        """Force of the hinge B on the pipe, (horizontal, down) components (N): F(L)."""
        fx, fz = self.force(self.length)
        return float(fx), float(fz)


class _Scaled:
    """The scaled two-segment problem: s, x, z by L, forces by wL, curvature θ' by 1/L."""

    def __init__(self, length: float, weight: float, ea: float, ei: float, kd: float) -> None:
        self.a = weight * length / ea  # N/EA = a·F̃
        self.b = weight * length**3 / ei  # κ̃' = −b ν Q̃
        self.c = kd * length / weight  # F̃z' = −1 + c max(0, z̃)

    def rates(self, y: np.ndarray, seabed: bool) -> np.ndarray:
        """d/ds̃ of the 6 states of one segment."""
        cos, sin = np.cos(y[_THETA]), np.sin(y[_THETA])
        fx, fz = y[_FX], y[_FZ]
        nu = 1.0 + self.a * (fx * cos + fz * sin)
        shear = fz * cos - fx * sin
        load = -1.0 + (self.c * np.maximum(y[_Z], 0.0) if seabed else 0.0)
        return np.array([nu * cos, nu * sin, y[_KAPPA], -self.b * nu * shear, 0.0 * fx, load + 0.0 * fx])

    def jacobian(self, y: np.ndarray, seabed: bool) -> np.ndarray:
        """∂(rates)/∂(states), shape (6, 6, m)."""
        a, b = self.a, self.b
        cos, sin = np.cos(y[_THETA]), np.sin(y[_THETA])
        fx, fz = y[_FX], y[_FZ]
        axial = fx * cos + fz * sin
        shear = fz * cos - fx * sin
        nu = 1.0 + a * axial
        jac = np.zeros((6, 6, y.shape[1]))
        jac[_X, _THETA] = a * shear * cos - nu * sin
        jac[_X, _FX] = a * cos * cos
        jac[_X, _FZ] = a * sin * cos
        jac[_Z, _THETA] = a * shear * sin + nu * cos
        jac[_Z, _FX] = a * cos * sin
        jac[_Z, _FZ] = a * sin * sin
        jac[_THETA, _KAPPA] = 1.0
        jac[_KAPPA, _THETA] = -b * (a * shear * shear - nu * axial)
        jac[_KAPPA, _FX] = -b * (a * cos * shear - nu * sin)
        jac[_KAPPA, _FZ] = -b * (a * sin * shear + nu * cos)
        if seabed:
            jac[_FZ, _Z] = self.c * (y[_Z] > 0.0)
        return jac


def _start(
    length: float,
    weight: float,
    ea: float,
    ei: float,
    kd: float,
    catenary: LaidCatenary,
    nodes: int,
) -> tuple[np.ndarray, np.ndarray, float]:
    """Initial mesh τ (`nodes` uniform ones, plus nodes graded into every boundary layer), scaled guess
    (12 × m) and s̃_t from the laid catenary, with the bending boundary layers (zero moment at the hinges)
    built in."""
    w, h = weight, catenary.horizontal
    nu = 1.0 + h / ea
    ell = math.sqrt(h / (nu * kd))  # the cable's layer on the elastic seabed
    layer = boundary_layer_estimates(ei, h, w, kd, 1.0)
    lam = layer.length
    st = catenary.touchdown_arc_length
    tau = [np.linspace(0.0, 1.0, nodes)]
    for scale in (ell, lam, layer.foundation_length):
        for segment in (st, length - st):
            if scale < segment / 400.0:
                graded = scale / segment * np.geomspace(0.02, 40.0, 40)
                tau += [graded[graded < 0.5], 1.0 - graded[graded < 0.5]]
    tau = np.unique(np.concatenate(tau))
    y = np.zeros((12, tau.size))
    # Laid segment, s = s_t (1 − τ): z = (w/kd)(1 − e^(−u/ℓ))(1 − e^(−s/ℓ)), u = s_t − s.
    s = st * (1.0 - tau)
    u = st - s
    eu, es = np.exp(-u / ell), np.exp(-s / ell)
    depth = w / kd
    z = depth * (1.0 - eu) * (1.0 - es)
    dz = depth * (-eu * (1.0 - es) + (1.0 - eu) * es) / ell
    ddz = depth * (-eu * (1.0 - es) - 2.0 * eu * es - (1.0 - eu) * es) / ell**2
    y[_X] = nu * s / length
    y[_Z] = z / length
    y[_THETA] = np.arctan(dz / nu)
    y[_KAPPA] = ddz / nu * length * (1.0 - np.exp(-s / min(lam, layer.foundation_length)))
    y[_FX] = h / (w * length)
    y[_FZ] = h * dz / nu / (w * length)
    # Suspended segment, s = s_t + (L − s_t) τ: Irvine's catenary, σ = s − s_vertex from its vertex.
    sigma = st - catenary.vertex_arc_length + (length - st) * tau
    hanging = catenary.suspended
    xz = np.array([hanging.point(float(v)) for v in sigma])
    vertical = w * sigma
    y[6 + _X] = (catenary.vertex_arc_length * nu + xz[:, 0]) / length
    y[6 + _Z] = (catenary.vertex_depth - xz[:, 1]) / length
    y[6 + _THETA] = -np.arctan2(vertical, h)
    y[6 + _KAPPA] = (
        -w * h / (h * h + vertical * vertical) * length * (1.0 - np.exp(-(length - st) * (1.0 - tau) / lam))
    )
    y[6 + _FX] = h / (w * length)
    y[6 + _FZ] = -vertical / (w * length)
    return tau, y, st / length


def _solve(
    problem: _Scaled,
    span: float,
    rise: float,
    tau: np.ndarray,
    y: np.ndarray,
    st: float,
    tolerance: float,
    max_nodes: int,
) -> OptimizeResult:
    """One solve_bvp call on the scaled two-segment problem (span, rise scaled by L)."""

    def fun(t: np.ndarray, yy: np.ndarray, p: np.ndarray) -> np.ndarray:
        return np.vstack([-p[0] * problem.rates(yy[:6], True), (1.0 - p[0]) * problem.rates(yy[6:], False)])

    def fun_jac(t: np.ndarray, yy: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        jac = np.zeros((12, 12, t.size))
        jac[:6, :6] = -p[0] * problem.jacobian(yy[:6], True)
        jac[6:, 6:] = (1.0 - p[0]) * problem.jacobian(yy[6:], False)
        dp = np.vstack([-problem.rates(yy[:6], True), -problem.rates(yy[6:], False)])
        return jac, dp[:, None, :]

    def bc(ya: np.ndarray, yb: np.ndarray, p: np.ndarray) -> np.ndarray:
        return np.concatenate(
            [
                ya[:6] - ya[6:],  # continuity at the touchdown
                [ya[_Z]],  # z(s_t) = 0
                [yb[_X], yb[_Z], yb[_KAPPA]],  # hinge at A
                [yb[6 + _X] - span, yb[6 + _Z] + rise, yb[6 + _KAPPA]],  # hinge at B
            ]
        )

    return solve_bvp(
        fun, bc, tau, y, p=np.array([st]), fun_jac=fun_jac, tol=tolerance, max_nodes=max_nodes, bc_tol=1e-12
    )


def stiff_pipe_on_seabed(
    length: float,
    span: float,
    rise: float,
    weight: float,
    ea: float,
    ei: float,
    stiffness: float,
    diameter: float,
    tolerance: float = 1e-8,
    max_nodes: int = 100_000,
    steps: int = 0,
    first_ei: float | None = None,
) -> SeabedBVP:
    """Solve the stiff pipe hanging from B onto the elastic seabed (the problem of the module docstring).

    The start is the laid catenary with the bending boundary layers built in; by default the target EI is
    solved directly from it, and if that fails, by continuation in EI over 6 geometric steps from
    EI = 1e-6 H L² (λ = √(EI/H) = 1e-3 L). Intermediate steps are solved to max(tolerance, 1e-5).

    Args:
        length: unstretched length L (m).
        span: horizontal distance from A to B (m).
        rise: height of B above the seabed plane through A (m), > 0.
        weight: submerged weight w (N per unstretched m), > 0.
        ea: axial stiffness EA (N).
        ei: bending stiffness EI (N·m²), > 0. The relative residual of M' = −(1 + N/EA) Q, with the shear Q a
            difference of O(wL) forces, cannot fall below about ε·wL³/EI (ε the machine epsilon): keep
            tolerance ≳ 10 ε wL³/EI (for the tests' pipe, EI ≥ 1e3 N·m² at tolerance 1e-5).
        stiffness: seabed stiffness k (Pa/m): q = k d max(0, z).
        diameter: outer diameter d (m).
        tolerance: solve_bvp's tolerance on the relative collocation residual of the final solve.
        max_nodes: solve_bvp's limit on the number of mesh nodes.
        steps: continuation steps in EI (geometric, from `first_ei`); 0 = solve the target directly first.
        first_ei: EI of the first continuation step (N·m²); default 1e-6 H L².

    Returns:
        The :class:`SeabedBVP`.

    Raises:
        RuntimeError: if solve_bvp does not converge.
    """
    if not (length > 0 and span > 0 and rise > 0 and weight > 0 and ea > 0 and ei > 0):
        raise ValueError("need length, span, rise, weight, ea and ei > 0")
    if not (stiffness > 0 and diameter > 0):
        raise ValueError("need stiffness > 0 and diameter > 0")
    kd = stiffness * diameter
    catenary = laid_catenary(length, span, rise, weight, ea, stiffness, diameter)
    if first_ei is None:
        first_ei = 1e-6 * catenary.horizontal * length**2
    path = np.geomspace(min(first_ei, ei), ei, steps + 1) if steps > 0 and first_ei < ei else np.array([ei])
    # Uniform mesh fine enough that the smooth parts meet the tolerance at once: the residual of the stiff
    # equation θ' = M/EI grows like (wL³/EI)·h⁴ (an error of the cubic θ times the factor of the shear).
    b = weight * length**3 / path[0]
    nodes = int(min(max(401, 0.35 * (b / tolerance) ** 0.25), max_nodes // 4))
    tau, y, st = _start(length, weight, ea, float(path[0]), kd, catenary, nodes)
    for i, ei_step in enumerate(path):
        problem = _Scaled(length, weight, ea, float(ei_step), kd)
        tol = tolerance if i == len(path) - 1 else max(tolerance, 1e-5)
        solution = _solve(problem, span / length, rise / length, tau, y, st, tol, max_nodes)
        if not solution.success:
            if steps == 0:
                return stiff_pipe_on_seabed(
                    length, span, rise, weight, ea, ei, stiffness, diameter, tolerance, max_nodes, 6, first_ei
                )
            raise RuntimeError(f"solve_bvp failed at EI = {ei_step:.4g} N·m²: {solution.message}")
        tau, y, st = solution.x, solution.y, float(solution.p[0])
    return _result(solution, length, span, rise, weight, ea, ei, stiffness, diameter, tolerance)


def _result(
    solution: OptimizeResult,
    length: float,
    span: float,
    rise: float,
    weight: float,
    ea: float,
    ei: float,
    stiffness: float,
    diameter: float,
    tolerance: float,
) -> SeabedBVP:
    """Unscale the solve_bvp solution into a :class:`SeabedBVP`."""
    st = float(solution.p[0])
    sol = solution.sol
    force = weight * length
    units = np.array([length, length, 1.0, ei / length, force, force])[:, None]

    def interpolant(s: np.ndarray) -> np.ndarray:
        flat = np.atleast_1d(s)
        out = np.empty((6, flat.size))
        laid = flat <= st * length
        if laid.any():
            out[:, laid] = sol(1.0 - flat[laid] / (st * length))[:6]
        if (~laid).any():
            out[:, ~laid] = sol((flat[~laid] / length - st) / (1.0 - st))[6:]
        out *= units
        return out[:, 0] if np.ndim(s) == 0 else out

    tau, y = solution.x, solution.y
    s = np.concatenate([st * (1.0 - tau[::-1]), st + (1.0 - st) * tau[1:]]) * length
    states = np.hstack([y[:6, ::-1], y[6:, 1:]]) * units
    axial = states[_FX] * np.cos(states[_THETA]) + states[_FZ] * np.sin(states[_THETA])

    # Largest |M|: the node of largest |M|, refined to the zero of the shear force M' = −ν Q beside it.
    worst = int(np.argmax(np.abs(states[_KAPPA])))

    def shear(arc: float) -> float:
        yy = interpolant(np.array(arc))
        return float(yy[_FZ] * math.cos(yy[_THETA]) - yy[_FX] * math.sin(yy[_THETA]))

    peak = float(s[worst])
    lo, hi = s[max(worst - 1, 0)], s[min(worst + 1, s.size - 1)]
    if 0 < worst < s.size - 1 and shear(lo) * shear(hi) < 0.0:
        peak = brentq(shear, lo, hi, xtol=1e-12 * length, rtol=1e-15)
    laid = s <= st * length
    return SeabedBVP(
        length=length,
        span=span,
        rise=rise,
        weight=weight,
        ea=ea,
        ei=ei,
        stiffness=stiffness,
        diameter=diameter,
        tolerance=tolerance,
        touchdown_arc_length=st * length,
        touchdown_x=float(sol(0.0)[_X]) * length,
        horizontal=float(y[6 + _FX, -1]) * force,
        top_tension=float(math.hypot(y[6 + _FX, -1], y[6 + _FZ, -1])) * force,
        max_moment=float(abs(interpolant(np.array(peak))[_KAPPA])),
        max_moment_arc_length=peak,
        laid_min_depth=float(states[_Z, laid].min()),
        suspended_max_depth=float(states[_Z, ~laid].max()),
        nodes=int(tau.size),
        s=s,
        x=states[_X],
        z=states[_Z],
        theta=states[_THETA],
        moment=states[_KAPPA],
        fx=states[_FX],
        fz=states[_FZ],
        axial=axial,
        _interpolant=interpolant,
    )
