"""The peer-code case with seabed contact shared by ``tests/test_moordyn_seabed.py``: the 90 mm steel wire rope
of ``moordyn_case``, anchored on a flat seabed, partly laid on it and partly hanging to a moving top point, run
in pipelay and in MoorDyn v2.

SI units. Frames as in ``moordyn_case``: pipelay's frame e has its origin at the anchor A (node 0), e1
horizontal, e3 pointing down and the sea surface at z = −depth; MoorDyn's frame has z up and the surface at
z = 0, with A at (0, 0, −depth), so (x, y, z)_MoorDyn = (x, y, −depth − z)_e. The seabed is the horizontal
plane through A in both: pipelay's default bathymetry (the plane z = 0 of e), MoorDyn's flat seabed at
WtrDpth = depth.

The line (unstretched length 400 m, submerged weight w = 328.4 N/m, EA = 400 MN) is pinned at A on the seabed
in 160 m of water; its top B starts 340 m across and 150 m up (10 m below the surface). Statics (the elastic
catenary with a laid part on a rigid frictionless seabed, ``seabed_reference.laid_catenary``): H = 53.95 kN,
132.1 m laid, top tension 103.21 kN. From rest B is driven as in ``moordyn_case`` (C² ramp over 10 s, 10 s
period, heave 2 m downwards first, phase 1 rad) with a surge of 3 m, to t = 25 s: the top tension swings
between 79 and 131 kN (mean 104 kN), the touchdown runs between 116 and 148 m from A, the tension along the
line never falls below 29 kN (at A). The seabed: kBot = 3 MPa/m, so the laid line's centreline sinks by
w/(kBot d) = 1.2 mm; cBot = 80 kPa·s/m, close to critical damping of a laid line bouncing on the seabed
(cBot = 2√(kBot m_a/d), m_a = m + ρ_w π d²/4 = 46.5 kg/m the mass with the added mass per length: ζ = 1.02);
no friction.

How the seabed contact of the two codes is matched (MoorDyn v2.7.1 source, source/Line.cpp lines 1606–1642,
checked on the installed v2.7.2 against its reported seabed forces):

* MoorDyn's force on node i (all nodes, ends included), while the node is below the seabed, is vertical:
  B_z = (kBot δ_i − cBot ż_i) d ℓ_i, δ_i the depth of the node (the centreline) below the seabed, d the line
  diameter, ℓ_i half the unstretched lengths of the adjacent segments; B = 0 above. pipelay: force per length
  kBot d δ with δ the penetration of the centreline interpolated linearly along each element and integrated
  (the same nodal force on fully laid elements, O(h) different only on the element holding the touchdown),
  and damping −cBot d ℓ_a (n·v) at nodes whose mean penetration over the step is positive. Neither clips the
  total normal force at 0 (a penetrating node rising fast is held back).
* Friction: off. MoorDyn's FrictionCoefficient (default 0) is written as 0; its FricDamp and StatDynFricScale
  then play no part. pipelay: friction = 0.
* Line: as in ``moordyn_case`` (same w, EA, Cd = 1.2 normal, no axial drag, Ca = 1, MoorDyn EI = 0 and BA = 0
  with RK4, pipelay EI = GJ = 10 N·m²). Top force |F_B| as there; pipelay's history at its step midpoints.

Why these numbers. The surge of 8 m of ``moordyn_case`` on a slacker line (B 320 m across, H = 24.5 kN) drives
the tension of the lower line to zero at t ≈ 17 s: the laid part (a straight bar on a frictionless seabed,
undamped axially: no friction, no axial drag, no internal damping) then snaps, and the top tension fills with
noise up to ±40 % of the mean that depends on n and dt in both codes (MoorDyn n = 100 against 200: 80 %).
A tauter line (H = 54 kN) with 3 m of surge stays taut and converges. The touchdown of a cable on a stiff
seabed jumps from node to node (the contact zone, √(H/(kBot d)) ≈ 0.45 m, is shorter than the elements), which
leaves some high-frequency content in the top tension, converging as the mesh is refined. MoorDyn's default
cBot = 300 kPa·s/m (ζ = 3.8) agrees too (1.6 % at n = 200), but pipelay's Newton failed with it at n = 50,
dt = 0.05 s (t = 13.35 s).

Convergence measured when written (max over the run of the top-tension difference relative to the mean
tension; touchdown: max difference of the arc length from A):

* MoorDyn time step: n = 100, dt = 1e-3 / 5e-4 against 2.5e-4 s: 0.20 / 0.09 %; n = 200, 5e-4 against
  2.5e-4 s: 0.04 % (1e-3 s is unstable at n = 200); n = 400, 2.5e-4 against 1.25e-4 s: 0.01 %;
* MoorDyn mesh against n = 400: n = 50 / 100 / 200: 9.1 / 2.5 / 0.61 % (touchdown 4.8 / 1.9 / 0.87 m);
* pipelay time step against 0.005 s: n = 100, dt = 0.025: 2.1 %; n = 200, dt = 0.05 / 0.025 / 0.01:
  0.72 / 0.86 / 0.62 %; n = 400, dt = 0.025: 0.21 %;
* pipelay mesh against n = 800 (dt = 0.01 s): n = 100 / 200 / 400: 2.1 / 0.59 / 0.18 %;
* pipelay against MoorDyn at equal n: n = 100 (0.025 s, 5e-4 s): 2.2 %; n = 200 (0.025 s, 5e-4 s): 0.77 %
  (rms 0.20 %, touchdown 0.97 m, mean 0.11 m); n = 400 (0.01 s, 2.5e-4 s): 0.24 % (touchdown 0.30 m);
* statics (n = 200): MoorDyn 103206.9 N, pipelay 103208.5 N, reference 103208.5 N; touchdown 132.13 m,
  132.22 m, reference 132.11 m (a rigid seabed).

MoorDyn's static state is its own initial-condition solve: 150 s of it at dt = 5e-4 s leave the top tension
within 0.002 % of its 1000 s value at n = 200 and cost ≈ 8 s there (300 s: 0.0006 %, ≈ 15 s).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import pipelay as pl
from moordyn_case import (
    Case,
    Run,
    _moordyn_system,
    _quiet,
    _to_moordyn,
    initial_condition,
    line_section,
    max_relative_error,
    top_position,
    top_tension_run,
    top_velocity,
)
from moordyn_case import (
    moordyn_input as line_input,
)

__all__ = [
    "SEABED_CASE",
    "SeabedCase",
    "SeabedRun",
    "max_relative_error",
    "moordyn_initial",
    "moordyn_input",
    "moordyn_touchdown",
    "pipelay_model",
    "rms_relative_error",
    "run_moordyn",
    "run_pipelay",
    "touchdown_of",
]


@dataclass(frozen=True)
class SeabedCase(Case):
    """The line, the seabed, the sea and the drive: the fields of ``moordyn_case.Case`` (some with new
    values) and the seabed's. Lengths in m, masses in kg, forces in N, times in s."""

    length: float = 400.0  # unstretched length (m)
    depth: float = 160.0  # depth of the anchor A, on the seabed, below the surface (m)
    x0: float = 340.0  # horizontal distance from A to B at rest (m)
    rise: float = 150.0  # height of B above A (and the seabed) at rest (m)
    amp_x: float = 3.0  # surge amplitude (m)
    amp_z: float = 2.0  # heave amplitude, downwards first (m)
    kbot: float = 3.0e6  # seabed stiffness: force per length kbot·d·(penetration of the centreline) (Pa/m)
    cbot: float = 8.0e4  # seabed damping: force per length −cbot·d·(normal velocity), in contact (Pa·s/m)

    @property
    def penetration(self) -> float:
        """Static penetration of the laid line's centreline into the seabed, w/(kbot·d) (m)."""
        return self.submerged_weight / (self.kbot * self.diameter)

    @property
    def damping_ratio(self) -> float:
        """cbot relative to critical damping of a laid line on the seabed, cbot / (2√(kbot m_a / d)), m_a the
        mass per length with the added mass (-)."""
        added = self.mass + self.ca * self.rho_water * math.pi / 4.0 * self.diameter**2
        return self.cbot / (2.0 * math.sqrt(self.kbot * added / self.diameter))


SEABED_CASE = SeabedCase()


@dataclass(frozen=True)
class SeabedRun(Run):
    """A top-tension history (``moordyn_case.Run``) and the touchdown over time: ``touchdown_time`` (K,) in s,
    ``touchdown_arc_length`` (K,) in m (reference arc length from A; NaN: no contact) and ``touchdown``
    (K, 3) in m (position in e; NaN: no contact). Entry 0 is the static touchdown."""

    touchdown_time: np.ndarray | None = None
    touchdown_arc_length: np.ndarray | None = None
    touchdown: np.ndarray | None = None


def touchdown_of(positions: np.ndarray, length: float) -> tuple[float, np.ndarray]:
    """pipelay's touchdown for a line of unstretched ``length`` (m) cut into equal segments, with nodes at
    ``positions`` (N+1, 3) in e (m): the last point, seen from A, where the penetration z (e3 points down, the
    seabed is z = 0) interpolated linearly between the nodes is ≥ 0. Returns its reference arc length from A
    (m) and its position (3,) (m), NaN without contact."""
    penetration = positions[:, 2]
    inside = np.flatnonzero(penetration >= 0.0)
    if inside.size == 0:
        return math.nan, np.full(3, math.nan)
    last = int(inside[-1])
    n = len(positions) - 1
    if last == n:
        return length, positions[n].copy()
    d1, d2 = penetration[last], penetration[last + 1]
    xi = d1 / (d1 - d2) if d1 > 0.0 else 0.0
    return (last + xi) * length / n, positions[last] * (1.0 - xi) + positions[last + 1] * xi


def rms_relative_error(run: Run, reference: Run) -> float:
    """Root mean square over the run of T − T_ref, the reference interpolated at ``run.time``, relative to
    the mean of the reference (-)."""
    ref = np.interp(run.time, reference.time, reference.tension)
    return float(np.sqrt(np.mean((run.tension - ref) ** 2)) / np.mean(reference.tension))


def pipelay_model(n: int, case: SeabedCase = SEABED_CASE) -> pl.Model:
    """The pipelay model with ``n`` elements: A pinned at the origin, on the seabed plane z = 0, B driven along
    ``top_position``; seabed stiffness ``case.kbot`` (Pa/m) and damping ``case.cbot`` (Pa·s/m), both on the
    outer diameter, no friction. The line's section is the driven wire rope's (``line_section``)."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (case.length, 0.0, 0.0), n, line_section(case))
    seabed = pl.Seabed(
        stiffness=case.kbot, damping=case.cbot, friction=0.0, mobilisation=0.01, bathymetry=None
    )
    sea = pl.Sea(case.depth, density=case.rho_water, seabed=seabed)
    model = pl.Model(rod, sea=sea, gravity=case.gravity)
    model.pin("A")
    model.drive("B", position=lambda t: top_position(t, case), velocity=lambda t: top_velocity(t, case))
    return model


def run_pipelay(n: int, dt: float, case: SeabedCase = SEABED_CASE, t_end: float | None = None) -> SeabedRun:
    """Static equilibrium at t = 0, then the drive to ``t_end`` (s; default ``case.t_end``) with step ``dt``
    (s) on ``n`` elements. The top tension is returned at the step midpoints (t = 0, then dt/2, 3dt/2, …; see
    ``moordyn_case.run_pipelay`` for why), the touchdown at the recorded states (t = 0, dt, 2dt, …)."""
    t_end = case.t_end if t_end is None else t_end
    run, res, state = top_tension_run(pipelay_model(n, case), dt, t_end)
    if res.touchdown is None or res.touchdown_arc_length is None:
        raise RuntimeError("pipelay recorded no touchdown: is the seabed in the model?")
    arc = np.array(res.touchdown_arc_length, dtype=float)
    where = np.array(res.touchdown, dtype=float)
    static_touchdown = state.touchdown
    if static_touchdown is not None:  # the static state's own, should the t = 0 record differ
        arc[0] = static_touchdown.arc_length
        where[0] = static_touchdown.position
    return SeabedRun(
        run.time,
        run.tension,
        run.static_tension,
        run.wall,
        run.steps,
        run.iterations,
        touchdown_time=np.asarray(res.time, dtype=float),
        touchdown_arc_length=arc,
        touchdown=where,
    )


def moordyn_input(
    n: int, dt: float, case: SeabedCase = SEABED_CASE, scheme: str = "RK4", ic_time: float = 150.0
) -> str:
    """The MoorDyn v2 input file for ``n`` segments, internal step ``dt`` (s), time scheme ``scheme`` and at
    most ``ic_time`` (s) of simulated time for its initial-condition (static) solve. The seabed is flat at
    WtrDpth = ``case.depth`` (through A) with kBot = ``case.kbot`` (Pa/m), cBot = ``case.cbot`` (Pa·s/m) and
    no friction (FrictionCoefficient 0, MoorDyn's default, written out). No internal damping (BA = 0)."""
    seabed = f"{case.depth!r}  WtrDpth\n{case.kbot!r}  kBot\n{case.cbot!r}  cBot\n0.0  FrictionCoefficient\n"
    return line_input(n, dt, case, scheme=scheme, ic_time=ic_time, seabed=seabed)


def moordyn_touchdown(line: Any, case: SeabedCase = SEABED_CASE) -> tuple[float, np.ndarray]:
    """The touchdown (``touchdown_of``) of MoorDyn line ``line``: reference arc length from A (m) and position
    in e (m)."""
    import moordyn  # type: ignore[import-untyped]

    nodes = np.array([moordyn.GetLineNodePos(line, i) for i in range(moordyn.GetLineN(line) + 1)])
    positions = np.column_stack([nodes[:, 0], nodes[:, 1], -case.depth - nodes[:, 2]])
    return touchdown_of(positions, case.length)


def moordyn_initial(
    n: int, dt: float, case: SeabedCase = SEABED_CASE, ic_time: float = 150.0
) -> tuple[bytes, float]:
    """MoorDyn's own static initial condition for ``n`` segments with B at ``top_position(0)`` (its
    initial-condition solve, at most ``ic_time`` s of simulated time at step ``dt`` s): the serialized system,
    to start ``run_moordyn`` from, and the top tension |F_B| (N)."""
    text = moordyn_input(n, dt, case, ic_time=ic_time)
    return initial_condition(text, _to_moordyn(top_position(0.0, case), case), n, dt)


def run_moordyn(
    n: int,
    dt: float,
    case: SeabedCase = SEABED_CASE,
    t_end: float | None = None,
    scheme: str = "RK4",
    ic_time: float = 150.0,
    initial: bytes | None = None,
    touchdown_every: float = 0.05,
) -> SeabedRun:
    """MoorDyn on ``n`` segments with internal (and coupling) step ``dt`` (s) to ``t_end`` (s; default
    ``case.t_end``) with time scheme ``scheme``, driven as in ``moordyn_case.run_moordyn`` (one ``Step`` per
    ``dt``, secant velocities, so B is on its path at every step). It starts from ``initial`` (serialized by
    ``moordyn_initial`` for the same ``n``) or from its own initial-condition solve (at most ``ic_time`` s).
    The touchdown is read every ``touchdown_every`` s (a whole number of steps; its cost is left out of the
    wall time). Raises RuntimeError if MoorDyn fails (e.g. goes unstable) or the top force stops being
    finite."""
    import moordyn  # type: ignore[import-untyped]

    t_end = case.t_end if t_end is None else t_end
    steps = round(t_end / dt)
    every = max(1, round(touchdown_every / dt))
    times = np.arange(steps + 1) * dt
    path_e = np.array([top_position(float(t), case) for t in times])
    path = np.column_stack([path_e[:, 0], path_e[:, 1], -case.depth - path_e[:, 2]])  # MoorDyn's frame
    velocities = np.diff(path, axis=0) / dt
    x0 = path[0].tolist()
    with _moordyn_system(moordyn_input(n, dt, case, scheme, ic_time)) as system:
        with _quiet():
            err = moordyn.Init_NoIC(system, x0, [0.0] * 3) if initial else moordyn.Init(system, x0, [0.0] * 3)
        if err != 0:
            raise RuntimeError(f"MoorDyn's initialisation failed (error {err}), n = {n}, dt = {dt} s")
        if initial:
            moordyn.Deserialize(system, initial)
        line = moordyn.GetLine(system, 1)
        static_tension = float(np.linalg.norm(moordyn.Step(system, x0, [0.0] * 3, 0.0, 0.0)))
        tension = np.empty(steps + 1)
        tension[0] = static_tension
        arc, point = moordyn_touchdown(line, case)
        sampled, arcs, where = [0], [arc], [point]
        positions = path.tolist()
        speeds = velocities.tolist()
        step = moordyn.Step
        with _quiet():  # an unstable run prints MoorDyn's NaN dump; the error below says what happened
            began = time.perf_counter()
            k = 0
            try:
                for k in range(steps):
                    fx, fy, fz = step(system, positions[k], speeds[k], float(times[k]), dt)
                    tension[k + 1] = math.sqrt(fx * fx + fy * fy + fz * fz)
                    if (k + 1) % every == 0:
                        paused = time.perf_counter()
                        arc, point = moordyn_touchdown(line, case)
                        sampled.append(k + 1)
                        arcs.append(arc)
                        where.append(point)
                        began += time.perf_counter() - paused
            except RuntimeError as exc:
                raise RuntimeError(
                    f"MoorDyn failed at t = {times[k]:.4f} s (n = {n}, dt = {dt} s): {exc}"
                ) from exc
            wall = time.perf_counter() - began
    if not np.all(np.isfinite(tension)):
        raise RuntimeError(f"MoorDyn's top force is not finite (n = {n}, dt = {dt} s)")
    return SeabedRun(
        times,
        tension,
        static_tension,
        wall,
        steps,
        touchdown_time=times[sampled],
        touchdown_arc_length=np.array(arcs),
        touchdown=np.array(where),
    )
