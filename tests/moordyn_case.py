"""The peer-code case shared by ``tests/test_moordyn.py`` and ``benches/moordyn_race.py``: one mooring line
(a 90 mm steel wire rope) hanging between a fixed point and a moving one, run in pipelay and in MoorDyn v2.

SI units. pipelay's frame e: origin at the fixed end A (node 0), e1 horizontal, e3 pointing down, the sea
surface at z = −depth. MoorDyn's frame: z up, the surface at z = 0; the fixed end is at (0, 0, −depth) and
the two frames are related by (x, y, z)_MoorDyn = (x, y, −depth − z)_e.

The line (unstretched length 250 m) is pinned at A and its top end B starts at 150 m horizontally and 190 m
above A, 10 m below the surface (static top tension ≈ 99.1 kN). From rest, B is driven in surge and heave
at a 10 s period, the amplitudes growing over the first 10 s by a C² ramp (zero velocity and acceleration at
t = 0, so the start is smooth and the initial velocity consistent):

    x_B(t) = x0 + A_x r(t) sin(ωt),   z_B(t) = z0 + A_z r(t) sin(ωt + φ),
    r(t) = 10 s³ − 15 s⁴ + 6 s⁵,  s = min(t / T_ramp, 1),

with A_x = 8 m, A_z = 2 m (downwards first: e3 points down), ω = 2π/10 s, φ = 1 rad, run to t = 25 s.
The top tension then swings between 64 and 228 kN (mean 115 kN); the line's lowest tension is ≈ 5 kN.

How the two models are matched:

* weight and buoyancy: both use w = (m − ρ_w π/4 d²) g = 328.4 N/m, the line fully submerged;
* drag: normal Cd = 1.2 on the diameter d in both; axial drag off in both (pipelay refers its axial Cd to d,
  MoorDyn to πd, so zero is the one value that means the same);
* added mass: Ca = 1 across and along the line in both (MoorDyn: Ca = CaAx = 1); `Case.ca_axial` sets the axial one;
* bending: MoorDyn's line has EI = 0. pipelay's rod needs EI > 0: it gets EI = GJ = 10 N·m², whose bending
  length √(EI/T) ≤ 5 cm even at the lowest tension (≈ 5 kN) is far below the shortest element used (0.25 m at
  n = 1000), so the line behaves as a cable. GA = EA. With ``Case(cable=True)`` pipelay uses its cable element
  instead (``pl.Section.cable``: tension only, no bending or torsion, 3 DOFs per node, as MoorDyn's line),
  with the same d, mass, EA, drag and added mass;
* internal damping: none. MoorDyn's default RK2 scheme is unstable without internal damping (BA = 0 blows up
  within 3 s), so MoorDyn runs with its RK4 scheme and BA = 0, the same undamped physics as pipelay. (MoorDyn's
  usual BA/-zeta = −0.8 changes the top tension by at most 0.10 % of the mean at n = 50, with RK2 or RK4.);
* seabed: no contact in either code. pipelay has none; MoorDyn's seabed is put 50 m below A (the line's
  lowest point dips at most ≈ 1 m below A during the motion);
* the top force is |F_B|, the magnitude of the force of the line on the support at B: pipelay's
  ``reaction("B")``, MoorDyn's force on its coupled point. Both include the end node's half-segment weight
  and drag; pipelay's also includes the end node's lumped inertia (m + Ca ρ_w A) l/2 · a_B, MoorDyn's does
  not. That term is at most 69 N at n = 100 (0.06 % of the mean tension), vanishes like 1/n and is left in.

MoorDyn is driven one internal step per ``Step`` call: at each call it gets the position of B at the start
of the step and the secant velocity to the position at the end (MoorDyn moves a coupled point linearly within
a call), so the prescribed motion is met exactly at every step. Its static state is its own initial-condition
solve (a pseudo-dynamic relaxation), which converges slowly: 300 s of relaxation leave the top tension within
≈ 0.01 % of equilibrium at n ≤ 200; ``moordyn_initial`` lets several runs share one such solve.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import pipelay as pl

__all__ = [
    "CASE",
    "Case",
    "Run",
    "axial_wave_time",
    "best_of",
    "initial_condition",
    "line_section",
    "max_relative_error",
    "moordyn_file",
    "moordyn_initial",
    "moordyn_input",
    "moordyn_point",
    "pipelay_model",
    "run_moordyn",
    "run_pipelay",
    "step_moordyn",
    "top_position",
    "top_tension_run",
    "top_velocity",
]


@dataclass(frozen=True)
class Case:
    """The line, the sea and the drive. Lengths in m, masses in kg, forces in N, times in s."""

    length: float = 250.0  # unstretched length (m)
    diameter: float = 0.09  # outer (volume-equivalent) diameter (m)
    mass: float = 40.0  # mass per unit length in air (kg/m)
    ea: float = 4.0e8  # axial stiffness (N)
    ei: float = 10.0  # pipelay's (small) bending stiffness (N·m²) of the rod; MoorDyn uses 0
    cable: bool = False  # pipelay: the cable element (pl.Section.cable) instead of the rod with EI = ``ei``
    cd_normal: float = 1.2  # normal drag coefficient on d (-)
    ca: float = 1.0  # added-mass coefficient normal to the line (-)
    ca_axial: float | None = None  # added-mass coefficient along the line (-); None: ``ca``
    rho_water: float = 1025.0  # sea-water density (kg/m³)
    gravity: float = 9.81  # (m/s²)
    depth: float = 200.0  # depth of the fixed end A below the surface (m)
    x0: float = 150.0  # horizontal distance from A to B at rest (m)
    rise: float = 190.0  # height of B above A at rest (m)
    amp_x: float = 8.0  # surge amplitude (m)
    amp_z: float = 2.0  # heave amplitude, downwards first (m)
    period: float = 10.0  # drive period (s)
    phase: float = 1.0  # heave phase lead over surge (rad)
    ramp: float = 10.0  # duration of the amplitude ramp (s)
    t_end: float = 25.0  # simulated time (s)

    @property
    def omega(self) -> float:
        """Drive angular frequency (rad/s)."""
        return 2.0 * math.pi / self.period

    @property
    def axial_added_mass(self) -> float:
        """The added-mass coefficient along the line (-)."""
        return self.ca if self.ca_axial is None else self.ca_axial

    @property
    def submerged_weight(self) -> float:
        """(m − ρ_w π/4 d²) g (N/m)."""
        return (self.mass - self.rho_water * math.pi / 4.0 * self.diameter**2) * self.gravity


CASE = Case()


@dataclass(frozen=True)
class Run:
    """A top-tension history: ``time`` (T,) in s, ``tension`` (T,) = |F_B| in N (``tension[0]`` is the static
    value), the static top tension (N), the wall time of the time integration alone (s; statics and set-up
    excluded), the number of steps and, for pipelay, the number of Newton iterations (0 for MoorDyn)."""

    time: np.ndarray
    tension: np.ndarray
    static_tension: float
    wall: float
    steps: int
    iterations: int = 0


def _ramp(t: float, case: Case) -> tuple[float, float]:
    """The C² amplitude ramp r(t) (-) and its rate r'(t) (1/s)."""
    s = min(max(t / case.ramp, 0.0), 1.0)
    r = s**3 * (10.0 - 15.0 * s + 6.0 * s * s)
    rate = 30.0 * s * s * (1.0 - s) ** 2 / case.ramp
    return r, rate


def top_position(t: float, case: Case = CASE) -> tuple[float, float, float]:
    """Position of B at time t (s), in pipelay's frame e (m)."""
    r, _ = _ramp(t, case)
    w = case.omega
    return (
        case.x0 + case.amp_x * r * math.sin(w * t),
        0.0,
        -case.rise + case.amp_z * r * math.sin(w * t + case.phase),
    )


def top_velocity(t: float, case: Case = CASE) -> tuple[float, float, float]:
    """Velocity of B at time t (s), in pipelay's frame e (m/s)."""
    r, rate = _ramp(t, case)
    w = case.omega
    return (
        case.amp_x * (rate * math.sin(w * t) + r * w * math.cos(w * t)),
        0.0,
        case.amp_z * (rate * math.sin(w * t + case.phase) + r * w * math.cos(w * t + case.phase)),
    )


def drive_tables(dt: float, t_end: float, case: Case = CASE) -> tuple[np.ndarray, np.ndarray]:
    """``top_position`` and ``top_velocity`` as tables of rows [t, x, y, z] at the step times k·dt up to t_end."""
    times = np.arange(round(t_end / dt) + 1) * dt
    position = np.column_stack([times, [top_position(t, case) for t in times]])
    velocity = np.column_stack([times, [top_velocity(t, case) for t in times]])
    return position, velocity


def line_section(case: Case) -> pl.Section:
    """The line's section: a cable's if ``case.cable``, else the rod with EI = GJ = ``case.ei`` (GA = EA) that
    behaves as one; normal drag and added mass (axial, normal) as the case gives them."""
    d, m = case.diameter, case.mass
    drag, added_mass = (0.0, case.cd_normal), (case.axial_added_mass, case.ca)
    if case.cable:
        return pl.Section.cable(d, m, case.ea, drag=drag, added_mass=added_mass)
    return pl.Section(
        EA=case.ea,
        GA=case.ea,
        GJ=case.ei,
        EI=case.ei,
        mass=m,
        inertia=(m * d * d / 4.0, m * d * d / 8.0, m * d * d / 8.0),
        outer_diameter=d,
        drag=drag,
        added_mass=added_mass,
    )


def pipelay_model(n: int, case: Case = CASE, tables: tuple[np.ndarray, np.ndarray] | None = None) -> pl.Model:
    """The pipelay model with ``n`` elements (of cable if ``case.cable``, else of rod): A pinned at the origin,
    B driven along ``top_position`` (by the callables, or by ``tables`` from ``drive_tables``, which the engine
    interpolates without calling Python)."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (case.length, 0.0, 0.0), n, line_section(case))
    model = pl.Model(rod, sea=pl.Sea(case.depth, density=case.rho_water), gravity=case.gravity)
    model.pin("A")
    if tables is None:
        model.drive("B", position=lambda t: top_position(t, case), velocity=lambda t: top_velocity(t, case))
    else:
        model.drive("B", position=tables[0], velocity=tables[1])
    return model


def run_pipelay(
    n: int, dt: float, case: Case = CASE, t_end: float | None = None, tables: bool = False
) -> Run:
    """Static equilibrium at t = 0, then the drive to ``t_end`` (s; default ``case.t_end``) with step ``dt`` (s)
    on ``n`` elements; with ``tables``, the drive is given as tables at the step times.

    Two things about pipelay's recorded reactions (this version): the sample recorded at t = 0 is zero (the
    simulation's initial state carries no reaction), so the static reaction takes its place; and the sample
    recorded at t_{k+1} is the energy–momentum scheme's algorithmic force of the step (time-centred: built on
    the average of the start- and end-of-step strains), which is second-order accurate at the step's midpoint
    t_k + dt/2 but only first-order at t_{k+1}. The history is therefore returned at the midpoints (t = 0 then
    dt/2, 3dt/2, …). Measured here (n = 50): read at t_{k+1}, the dt = 0.05 s history is off by 2.7 % of the
    mean against dt = 0.01 s; both read at the midpoints, by 0.35 %."""
    t_end = case.t_end if t_end is None else t_end
    model = pipelay_model(n, case, drive_tables(dt, t_end, case) if tables else None)
    return top_tension_run(model, dt, t_end)[0]


def top_tension_run(model: pl.Model, dt: float, t_end: float) -> tuple[Run, pl.Results, pl.State]:
    """`model`'s static equilibrium, then its simulation to ``t_end`` (s) with step ``dt`` (s), every step
    recorded and the integration timed: the top tension |F_B| at the step midpoints (t = 0, then dt/2, 3dt/2,
    …, as ``run_pipelay`` explains; the static value at t = 0), the results and the static state."""
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
    return Run(times, tension, static_tension, wall, len(res.time) - 1, iterations), res, state


def axial_wave_time(n: int, case: Case = CASE) -> float:
    """Segment length over the axial wave speed, l/c (s), c = √(EA/(m + Ca ρ_w A)): MoorDyn's stable step is
    about twice it."""
    area = math.pi / 4.0 * case.diameter**2
    speed = math.sqrt(case.ea / (case.mass + case.ca * case.rho_water * area))
    return case.length / n / speed


def best_of(found: Run, again: Callable[[], Run], below: float = 10.0, runs: int = 3) -> Run:
    """`found` with the best wall time of itself and, if it took less than `below` (s), of `runs` − 1 more
    runs by `again` (a shared machine's timings of a short run vary by tens of %)."""
    if found.wall >= below:
        return found
    walls = [found.wall] + [again().wall for _ in range(runs - 1)]
    return replace(found, wall=min(walls))


def moordyn_file(
    title: str,
    n: int,
    case: Case,
    ba: float,
    points: tuple[str, str],
    dt: float,
    scheme: str,
    options: list[str],
) -> str:
    """A MoorDyn v2 input file: one line of ``case``'s rope in ``n`` segments with internal damping ``ba`` (N·s;
    negative: minus the damping ratio) from point 1 to point 2, each given as its attachment and position in
    MoorDyn's frame (``moordyn_point``); OPTIONS: no log, the step ``dt`` (s) of the time scheme ``scheme``,
    ``case``'s gravity and water density, the lines ``options`` (each "value  name"), no output files."""
    head = [
        "0  writeLog",
        f"{dt!r}  dtM",
        f"{scheme}  tScheme",
        f"{case.gravity!r}  g",
        f"{case.rho_water!r}  rho",
    ]
    lines = "\n".join([*head, *options, "1  disableOutput", "1  disableOutTime"])
    return f"""--------------------- MoorDyn Input File ------------------------------------
{title}
---------------------- LINE TYPES ------------------------------------------------------
TypeName  Diam  Mass/m  EA  BA/-zeta  EI  Cd  Ca  CdAx  CaAx
(name)  (m)  (kg/m)  (N)  (N-s/-)  (N-m^2)  (-)  (-)  (-)  (-)
rope  {case.diameter!r}  {case.mass!r}  {case.ea!r}  {ba!r}  0.0  {case.cd_normal!r}  {case.ca!r}  0.0  {case.axial_added_mass!r}
---------------------- POINTS ----------------------------------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(#)  (word/ID)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
1  {points[0]}  0  0  0  0
2  {points[1]}  0  0  0  0
---------------------- LINES -----------------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)  (name)  (ID)  (ID)  (m)  (-)  (-)
1  rope  1  2  {case.length!r}  {n}  -
---------------------- OPTIONS ---------------------------------------------------------
{lines}
------------------------- need this line -----------------------------------------------
"""


def moordyn_point(attachment: str, position: Any) -> str:
    """A point's attachment ("Fixed", "Coupled") and position (x, y, z) in MoorDyn's frame (m), as its row."""
    return f"{attachment}  {position[0]!r}  {position[1]!r}  {position[2]!r}"


def moordyn_input(
    n: int,
    dt: float,
    case: Case = CASE,
    scheme: str = "RK4",
    ba: float = 0.0,
    ic_time: float = 300.0,
    seabed: str | None = None,
) -> str:
    """The MoorDyn v2 input file for ``n`` segments, internal step ``dt`` (s), time scheme ``scheme``, internal
    damping ``ba`` (N·s; negative: minus the damping ratio) and at most ``ic_time`` (s) of simulated time for
    its initial-condition (static) solve. ``seabed``: the OPTIONS lines of the seabed (WtrDpth, kBot, ...);
    default: a seabed 50 m below A, out of the line's reach."""
    top = _to_moordyn(top_position(0.0, case), case)
    if seabed is None:
        seabed = f"{case.depth + 50.0!r}  WtrDpth\n"
    points = (moordyn_point("Fixed", (0.0, 0.0, -case.depth)), moordyn_point("Coupled", top))
    options = [*seabed.splitlines(), "1.0  dtIC", f"{ic_time!r}  TmaxIC", "1e-7  threshIC"]
    title = "pipelay peer comparison: steel wire rope between a fixed point and a driven one"
    return moordyn_file(title, n, case, ba, points, dt, scheme, options)


def _to_moordyn(p: tuple[float, float, float], case: Case) -> np.ndarray:
    """A position in e (m) in MoorDyn's frame (z up, the surface at z = 0) (m)."""
    return np.array([p[0], p[1], -case.depth - p[2]])


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Silence the C library's own prints on file descriptors 1 and 2 (MoorDyn's banner, log and NaN dumps)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, devnull):
            os.close(fd)


@contextlib.contextmanager
def _moordyn_system(text: str, beside: dict[str, str] | None = None) -> Iterator[Any]:
    """A MoorDyn system built from the input file ``text`` (written to a temporary folder with the files
    ``beside`` it, name: text), closed on exit."""
    import moordyn  # type: ignore[import-untyped]

    with tempfile.TemporaryDirectory(prefix="pipelay-moordyn-") as folder:
        path = os.path.join(folder, "line.txt")
        for name, content in {"line.txt": text, **(beside or {})}.items():
            with open(os.path.join(folder, name), "w", encoding="utf-8") as handle:
                handle.write(content)
        with _quiet():
            system = moordyn.Create(path)
        try:
            yield system
        finally:
            moordyn.Close(system)


def moordyn_initial(n: int, dt: float, case: Case = CASE, ic_time: float = 300.0) -> tuple[bytes, float]:
    """MoorDyn's own static initial condition for ``n`` segments with B at ``top_position(0)``, found by its
    initial-condition solver (a pseudo-dynamic relaxation run with step ``dt`` (s) for at most ``ic_time`` (s)
    of simulated time): the serialized system, to start ``run_moordyn`` from, and the top tension |F_B| (N)."""
    text = moordyn_input(n, dt, case, ic_time=ic_time)
    return initial_condition(text, _to_moordyn(top_position(0.0, case), case), n, dt)


def initial_condition(text: str, top: np.ndarray, n: int, dt: float) -> tuple[bytes, float]:
    """MoorDyn's initial-condition solve of the system described by the input file `text`, its coupled point
    at `top` (MoorDyn's frame, m): the serialized system and the top tension |F_B| (N). `n` and `dt` only name
    the run in the error raised if the solve fails."""
    import moordyn  # type: ignore[import-untyped]

    with _moordyn_system(text) as system:
        with _quiet():
            err = moordyn.Init(system, top, np.zeros(3))
        if err != 0:
            raise RuntimeError(
                f"MoorDyn's initial-condition solve failed (error {err}), n = {n}, dt = {dt} s"
            )
        force = moordyn.Step(system, top, np.zeros(3), 0.0, 0.0)
        return moordyn.Serialize(system), float(np.linalg.norm(force))


def run_moordyn(
    n: int,
    dt: float,
    case: Case = CASE,
    t_end: float | None = None,
    scheme: str = "RK4",
    ba: float = 0.0,
    ic_time: float = 300.0,
    initial: bytes | None = None,
) -> Run:
    """MoorDyn on ``n`` segments with internal (and coupling) step ``dt`` (s) to ``t_end`` (s; default
    ``case.t_end``), time scheme ``scheme`` and internal damping ``ba`` (see ``moordyn_input``).

    It starts from ``initial`` (a system serialized by ``moordyn_initial`` for the same ``n``) or, without it,
    from its own initial-condition solve (at most ``ic_time`` s of simulated time at step ``dt``). Then one
    ``Step`` per ``dt``. Raises RuntimeError if MoorDyn fails (e.g. it goes unstable: NaN) or if the top force
    stops being finite."""
    import moordyn  # type: ignore[import-untyped]

    t_end = case.t_end if t_end is None else t_end
    steps = round(t_end / dt)
    times = np.arange(steps + 1) * dt
    path_e = np.array([top_position(float(t), case) for t in times])
    path = np.column_stack([path_e[:, 0], path_e[:, 1], -case.depth - path_e[:, 2]])  # MoorDyn's frame
    velocities = np.diff(path, axis=0) / dt  # secant velocities: B lands on the path at every step
    x0 = path[0].tolist()
    with _moordyn_system(moordyn_input(n, dt, case, scheme, ba, ic_time)) as system:
        with _quiet():
            err = moordyn.Init_NoIC(system, x0, [0.0] * 3) if initial else moordyn.Init(system, x0, [0.0] * 3)
        if err != 0:
            raise RuntimeError(f"MoorDyn's initialisation failed (error {err}), n = {n}, dt = {dt} s")
        if initial:
            moordyn.Deserialize(system, initial)
        static_tension = float(np.linalg.norm(moordyn.Step(system, x0, [0.0] * 3, 0.0, 0.0)))
        tension = np.empty(steps + 1)
        tension[0] = static_tension
        wall = step_moordyn(system, path.tolist(), velocities.tolist(), times, tension, n)
    return Run(times, tension, static_tension, wall, steps)


def step_moordyn(
    system: Any,
    positions: Sequence[Sequence[float]],
    velocities: Sequence[Sequence[float]],
    times: np.ndarray,
    tension: np.ndarray,
    n: int,
) -> float:
    """MoorDyn's ``Step`` from each ``times[k]`` to ``times[k + 1]`` with its coupled point at ``positions[k]``
    (m) moving at ``velocities[k]`` (m/s), the top tension |F_B| after it written to ``tension[k + 1]`` (N):
    the wall time of the steps (s). Raises RuntimeError naming where MoorDyn failed (on a line of ``n``
    segments) or if a tension is not finite."""
    import moordyn  # type: ignore[import-untyped]

    dt = float(times[1] - times[0])
    step = moordyn.Step
    with _quiet():  # an unstable run prints MoorDyn's NaN dump; the error below says what happened
        began = time.perf_counter()
        try:
            for k in range(len(times) - 1):
                fx, fy, fz = step(system, positions[k], velocities[k], float(times[k]), dt)
                tension[k + 1] = math.sqrt(fx * fx + fy * fy + fz * fz)
        except RuntimeError as exc:
            raise RuntimeError(
                f"MoorDyn failed at t = {times[k]:.4f} s (n = {n}, dt = {dt} s): {exc}"
            ) from exc
        wall = time.perf_counter() - began
    if not np.all(np.isfinite(tension)):
        raise RuntimeError(f"MoorDyn's top force is not finite (n = {n}, dt = {dt} s)")
    return wall


def max_relative_error(run: Run, reference: Run) -> float:
    """max |T − T_ref| over the run, the reference interpolated at ``run.time``, relative to the mean of
    the reference (-)."""
    ref = np.interp(run.time, reference.time, reference.tension)
    return float(np.max(np.abs(run.tension - ref)) / np.mean(reference.tension))
