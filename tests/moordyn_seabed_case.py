"""The peer-code case with seabed contact shared by ``tests/test_moordyn_seabed.py``: a mooring line (the
90 mm steel wire rope of ``moordyn_case``) anchored on a flat seabed, partly laid on it and partly hanging to a
moving top point, run in pipelay and in MoorDyn v2.

SI units. Frames as in ``moordyn_case``: pipelay's frame e has its origin at the anchor A (node 0), e1
horizontal, e3 pointing down and the sea surface at z = −depth; MoorDyn's frame has z up and the surface at
z = 0, with A at (0, 0, −depth), so (x, y, z)_MoorDyn = (x, y, −depth − z)_e. The seabed is the plane through
A in both: pipelay's default flat bathymetry z = 0 in e, MoorDyn's flat seabed at WtrDpth = depth.

The line is the 90 mm wire rope (submerged weight 328.4 N/m), 400 m long, A on the seabed 160 m below the
surface, B 320 m across and 150 m up; kBot = 3e6 Pa/m (1.2 mm of penetration under the line's weight),
cBot = 3e5 Pa·s/m, no friction; B driven in surge (8 m) and heave (2 m) at a 10 s period, ramped in. At
n = 100: static top tension 103 203.0 N (pipelay) and 103 199.8 N (MoorDyn); the touchdown swings over
about 32 m.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import pipelay as pl
from moordyn_case import Case, Run, _moordyn_system, _quiet, _to_moordyn, top_position, top_velocity

__all__ = [
    "SEABED_CASE",
    "SeabedCase",
    "SeabedRun",
    "max_relative_error",
    "moordyn_initial",
    "moordyn_input",
    "moordyn_touchdown",
    "pipelay_model",
    "run_moordyn",
    "run_pipelay",
    "touchdown_of",
]


@dataclass(frozen=True)
class SeabedCase(Case):
    """The line, the seabed, the sea and the drive (the fields of ``moordyn_case.Case``, with new values,
    plus the seabed's). Lengths in m, masses in kg, forces in N, times in s."""

    length: float = 400.0  # unstretched length (m)
    depth: float = 160.0  # depth of the anchor A, on the seabed, below the surface (m)
    x0: float = 340.0  # horizontal distance from A to B at rest (m)
    rise: float = 150.0  # height of B above A (and the seabed) at rest (m)
    amp_x: float = 3.0  # surge amplitude (m)
    amp_z: float = 2.0  # heave amplitude, downwards first (m)
    kbot: float = 3.0e6  # seabed stiffness: normal force per length kbot·d·penetration (Pa/m)
    cbot: float = 8.0e4  # seabed damping: normal force per length −cbot·d·normal velocity (Pa·s/m)

    @property
    def penetration(self) -> float:
        """Static penetration of the laid line's centreline into the seabed, w/(kbot·d) (m)."""
        return self.submerged_weight / (self.kbot * self.diameter)


SEABED_CASE = SeabedCase()


@dataclass(frozen=True)
class SeabedRun(Run):
    """A top-tension history (see ``moordyn_case.Run``) with the touchdown over time: ``touchdown_time`` (K,)
    in s, ``touchdown_arc_length`` (K,) in m (reference arc length from A, NaN: no contact) and
    ``touchdown`` (K, 3) in m (position in e). Entry 0 is the static touchdown."""

    touchdown_time: np.ndarray | None = None
    touchdown_arc_length: np.ndarray | None = None
    touchdown: np.ndarray | None = None


def touchdown_of(positions: np.ndarray, length: float) -> tuple[float, np.ndarray]:
    """pipelay's definition of the touchdown, for equal segments of a line of unstretched ``length`` (m) with
    nodes at ``positions`` (N+1, 3) in e (m): the last point, seen from A, where the penetration z (e3 points
    down, the seabed is z = 0) interpolated linearly between the nodes is ≥ 0. Returns its reference arc length from A (m; NaN: no
    contact) and its position (3,) (m; NaN: no contact)."""
    depth = positions[:, 2]
    inside = np.flatnonzero(depth >= 0.0)
    if inside.size == 0:
        return math.nan, np.full(3, math.nan)
    last = int(inside[-1])
    n = len(positions) - 1
    if last == n:
        return length, positions[n].copy()
    d1, d2 = depth[last], depth[last + 1]
    xi = d1 / (d1 - d2) if d1 > 0.0 else 0.0
    arc = (last + xi) * length / n
    return arc, positions[last] * (1.0 - xi) + positions[last + 1] * xi


def pipelay_model(n: int, case: SeabedCase = SEABED_CASE) -> pl.Model:
    """The pipelay model with ``n`` elements: A pinned at the origin on the seabed plane z = 0, B driven along
    ``top_position``; seabed stiffness ``case.kbot`` and damping ``case.cbot`` on the outer diameter, no
    friction."""
    d, m = case.diameter, case.mass
    section = pl.Section(
        EA=case.ea,
        GA=case.ea,
        GJ=case.ei,
        EI=case.ei,
        mass=m,
        inertia=(m * d * d / 4.0, m * d * d / 8.0, m * d * d / 8.0),
        outer_diameter=d,
        drag=(0.0, case.cd_normal),
        added_mass=(case.ca, case.ca),
    )
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (case.length, 0.0, 0.0), n, section)
    seabed = pl.Seabed(
        stiffness=case.kbot, damping=case.cbot, friction=0.0, mobilisation=0.01, bathymetry=None
    )
    sea = pl.Sea(case.depth, density=case.rho_water, seabed=seabed)
    model = pl.Model(rod, sea=sea, gravity=case.gravity)
    model.pin("A")
    model.drive("B", position=lambda t: top_position(t, case), velocity=lambda t: top_velocity(t, case))
    return model


def run_pipelay(n: int, dt: float, case: SeabedCase = SEABED_CASE, t_end: float | None = None) -> SeabedRun:
    """Static equilibrium at t = 0, then the drive to ``t_end`` (s; default ``case.t_end``) with step ``dt`` (s)
    on ``n`` elements. The top tension is returned at the step midpoints (t = 0, then dt/2, 3dt/2, …; see
    ``moordyn_case.run_pipelay`` for why), the touchdown at the recorded states (t = 0, dt, 2dt, …)."""
    t_end = case.t_end if t_end is None else t_end
    model = pipelay_model(n, case)
    state = model.static()
    static_tension = float(np.linalg.norm(state.reaction("B")[:3]))
    sim = model.simulation(state=state, dt=dt)
    steps = round(t_end / dt)
    began = time.perf_counter()
    res = sim.run(steps * dt, progress=False, record_every=1)
    wall = time.perf_counter() - began
    tension = np.linalg.norm(res.reaction("B")[:, :3], axis=1)
    tension[0] = static_tension
    times = np.asarray(res.time) - 0.5 * dt
    times[0] = 0.0
    iterations = int(np.sum(res.iterations))
    arc = np.array(res.touchdown_arc_length, dtype=float)
    where = np.array(res.touchdown, dtype=float)
    static_touchdown = state.touchdown
    if static_touchdown is not None:  # the recorded t = 0 sample is the static state's
        arc[0] = static_touchdown.arc_length
        where[0] = static_touchdown.position
    return SeabedRun(
        times,
        tension,
        static_tension,
        wall,
        len(res.time) - 1,
        iterations,
        touchdown_time=np.asarray(res.time, dtype=float),
        touchdown_arc_length=arc,
        touchdown=where,
    )


def moordyn_input(
    n: int, dt: float, case: SeabedCase = SEABED_CASE, scheme: str = "RK4", ic_time: float = 300.0
) -> str:
    """The MoorDyn v2 input file for ``n`` segments, internal step ``dt`` (s), time scheme ``scheme`` and at
    most ``ic_time`` (s) of simulated time for its initial-condition (static) solve. The seabed is flat at
    WtrDpth = ``case.depth`` (through A), with kBot = ``case.kbot``, cBot = ``case.cbot`` and no friction
    (FrictionCoefficient 0, MoorDyn's default, given explicitly). No internal damping (BA = 0)."""
    top = _to_moordyn(top_position(0.0, case), case)
    return f"""--------------------- MoorDyn Input File ------------------------------------
pipelay peer comparison: steel wire rope laid on a flat seabed and driven at the top
---------------------- LINE TYPES ------------------------------------------------------
TypeName  Diam  Mass/m  EA  BA/-zeta  EI  Cd  Ca  CdAx  CaAx
(name)  (m)  (kg/m)  (N)  (N-s/-)  (N-m^2)  (-)  (-)  (-)  (-)
rope  {case.diameter!r}  {case.mass!r}  {case.ea!r}  0.0  0.0  {case.cd_normal!r}  {case.ca!r}  0.0  {case.ca!r}
---------------------- POINTS ----------------------------------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(#)  (word/ID)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
1  Fixed  0.0  0.0  {-case.depth!r}  0  0  0  0
2  Coupled  {top[0]!r}  {top[1]!r}  {top[2]!r}  0  0  0  0
---------------------- LINES -----------------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)  (name)  (ID)  (ID)  (m)  (-)  (-)
1  rope  1  2  {case.length!r}  {n}  -
---------------------- OPTIONS ---------------------------------------------------------
0  writeLog
{dt!r}  dtM
{scheme}  tScheme
{case.gravity!r}  g
{case.rho_water!r}  rho
{case.depth!r}  WtrDpth
{case.kbot!r}  kBot
{case.cbot!r}  cBot
0.0  FrictionCoefficient
1.0  dtIC
{ic_time!r}  TmaxIC
1e-7  threshIC
1  disableOutput
1  disableOutTime
------------------------- need this line -----------------------------------------------
"""


def moordyn_touchdown(line: object, case: SeabedCase = SEABED_CASE) -> tuple[float, np.ndarray]:
    """The touchdown (``touchdown_of``) of a MoorDyn line: reference arc length from A (m) and position in e
    (m)."""
    import moordyn  # type: ignore[import-untyped]

    nodes = np.array([moordyn.GetLineNodePos(line, i) for i in range(moordyn.GetLineN(line) + 1)])
    positions = np.column_stack([nodes[:, 0], nodes[:, 1], -case.depth - nodes[:, 2]])
    return touchdown_of(positions, case.length)


def moordyn_initial(
    n: int, dt: float, case: SeabedCase = SEABED_CASE, ic_time: float = 300.0
) -> tuple[bytes, float]:
    """MoorDyn's own static initial condition for ``n`` segments with B at ``top_position(0)`` (its
    initial-condition solve, at most ``ic_time`` s of simulated time at step ``dt`` s): the serialized system,
    to start ``run_moordyn`` from, and the top tension |F_B| (N)."""
    import moordyn  # type: ignore[import-untyped]

    x = _to_moordyn(top_position(0.0, case), case)
    with _moordyn_system(moordyn_input(n, dt, case, ic_time=ic_time)) as system:
        with _quiet():
            err = moordyn.Init(system, x, np.zeros(3))
        if err != 0:
            raise RuntimeError(
                f"MoorDyn's initial-condition solve failed (error {err}), n = {n}, dt = {dt} s"
            )
        force = moordyn.Step(system, x, np.zeros(3), 0.0, 0.0)
        return moordyn.Serialize(system), float(np.linalg.norm(force))


def run_moordyn(
    n: int,
    dt: float,
    case: SeabedCase = SEABED_CASE,
    t_end: float | None = None,
    scheme: str = "RK4",
    ic_time: float = 300.0,
    initial: bytes | None = None,
    touchdown_every: float = 0.05,
) -> SeabedRun:
    """MoorDyn on ``n`` segments with internal (and coupling) step ``dt`` (s) to ``t_end`` (s; default
    ``case.t_end``) with time scheme ``scheme``, driven as in ``moordyn_case.run_moordyn`` (one ``Step`` per
    ``dt``, secant velocities). It starts from ``initial`` (serialized by ``moordyn_initial`` for the same
    ``n``) or from its own initial-condition solve (at most ``ic_time`` s). The touchdown is read every
    ``touchdown_every`` s (rounded to a whole number of steps). Raises RuntimeError if MoorDyn fails."""
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
        samples = list(range(0, steps + 1, every))
        arcs = np.empty(len(samples))
        where = np.empty((len(samples), 3))
        arcs[0], where[0] = moordyn_touchdown(line, case)
        positions = path.tolist()
        speeds = velocities.tolist()
        step = moordyn.Step
        wall = 0.0
        with _quiet():  # an unstable run prints MoorDyn's NaN dump; the error below says what happened
            began = time.perf_counter()
            k = 0
            try:
                for j in range(1, len(samples) + 1):
                    stop = samples[j] if j < len(samples) else steps
                    while k < stop:
                        fx, fy, fz = step(system, positions[k], speeds[k], float(times[k]), dt)
                        tension[k + 1] = math.sqrt(fx * fx + fy * fy + fz * fz)
                        k += 1
                    if j < len(samples):
                        paused = time.perf_counter()
                        arcs[j], where[j] = moordyn_touchdown(line, case)
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
        touchdown_time=times[samples],
        touchdown_arc_length=arcs,
        touchdown=where,
    )


def max_relative_error(run: Run, reference: Run) -> float:
    """max |T − T_ref| over the run, the reference interpolated at ``run.time``, relative to the mean of
    the reference (-)."""
    ref = np.interp(run.time, reference.time, reference.tension)
    return float(np.max(np.abs(run.tension - ref)) / np.mean(reference.tension))
