"""The peer-code case in waves, shared by ``tests/test_moordyn_waves.py`` and
``benches/moordyn_wave_race.py``: the wire rope of ``moordyn_case`` held still at both ends while waves pass
over it, run in pipelay and in MoorDyn v2.

SI units. The line, its section and how the two codes' line models are matched (weight, buoyancy, EA, normal
drag on d with axial drag off, added mass Ca = 1 across and along, EI = 0 in MoorDyn against the cable
element or the EI = 10 N·m² rod in pipelay, no internal damping, RK4 in MoorDyn) are ``moordyn_case``'s. Here:

* the water is 250 m deep in both codes (``WaveCase.water_depth``), so that the waves' dispersion and depth
  profiles are the same: pipelay's ``pl.Sea(250)`` (frame e: e3 down, the seabed level z = 0, the surface
  z = −250), MoorDyn's ``WtrDpth 250`` (z up, the surface at 0, its flat seabed at −250, 50 m below A and out
  of the line's reach: it dips at most ≈ 1 m below A). So (x, y, z)_MoorDyn = (x, y, −250 − z)_e;
* A is pinned 200 m below the surface (pipelay: the rod built from (0, 0, −50)), B held still at its rest
  position 150 m across and 190 m up, 10 m below the surface (pipelay: pinned there; MoorDyn: a coupled
  point given that position and zero velocity at every step). Static top tension 99.13 kN at n = 50;
* waves along +x (direction 0), at full height from t = 0 (pipelay ``ramp=0.0``; MoorDyn has no ramp), to
  t = 25 s. Two seas: ``REGULAR`` (H = 6 m, T = 10 s) and ``JONSWAP`` (Hs = 4 m, Tp = 10 s, γ = 3.3, 25
  components from seed 0: a mild realisation, its crests at most 2.2 m and troughs 2.0 m over the line in
  these 25 s). The top node never leaves the water: the lowest trough is 3.0 m below the mean level;
* both start from the static state in calm water. pipelay's ``model.static()`` has no waves: with the waves
  it gives the calm state bit for bit. MoorDyn never has waves in its initial-condition solve (its log:
  "Water kinematics for IC gen: No Waves or Currents"; they are set up after it); its static state is made
  in a calm system (``WaveKin 0``) and loaded into the run's system (``Init_NoIC`` then ``Deserialize``,
  which also restores its clock, at 0), so that one solve serves the calm run and both seas.

The waves. pipelay (environment/waves.rs): θ_i = k_i(x cos β_i + y sin β_i) − ω_i t + φ_i, η = Σ a_i cos θ_i,
finite-depth Airy kinematics with Wheeler stretching s′ = h s/(h + η) (s the height above the seabed) and
none above the surface. MoorDyn's ``WaveKin 7`` ("summing component waves", Waves/SpectrumKin.cpp) reads
``wave_frequencies.txt`` beside the input file, rows ``ω re im β`` (the first ω = 0), and makes
η = Σ |c| sin(ωt − k x·β̂ + arg c), c = re + i im, with the same stretching; so c = a e^{i(π/2 − φ)}
(``moordyn_frequencies``). Checked (``test_moordyn_has_pipelays_waves``): MoorDyn's elevation equals
pipelay's ``Sea.waves.elevation`` within 1e-13 m (regular) and 6e-9 m (JONSWAP: MoorDyn solves the dispersion
relation to seven digits), and its velocity and acceleration the Airy kinematics of pipelay's components
within 3e-9, at t = 0 and after stepping (the waves travel +x in both). Above the surface (not reached here)
MoorDyn keeps the surface's kinematics where pipelay has none. Both apply the Froude–Krylov and added-mass
load ρ A [(1 + Ca)(u̇ normal to the line) + (1 + Ca_axial)(u̇ along it)]: pipelay on each element, the waves
taken at its midpoint once per step (at the predicted mid-step position), MoorDyn at each node at each of
RK4's four stages.

Why 25 components. MoorDyn sums every component at every node at each of the four stages of every step
(sin, cos, sinh, cosh and small allocations): measured at n = 100 and dt = 1.1e-3 s, a step costs 25 µs in
calm water, 85 µs in the regular wave (its one component and the ω = 0 row) and 594 µs with 25 components,
≈ 22 µs per component; pipelay's default of 200 components would make a 25 s run at n = 400 (MoorDyn's dt
∝ 1/n, its step's cost ∝ n) take ≈ 27 min. 25 components resolve the JONSWAP peak well enough for a peer
comparison and keep the bench's longest run near 4 min.

MoorDyn's static state. Its default stationary initial-condition solver converges slowly: at n = 50 it
leaves the top tension 48 N (60 s) or 14 N (300 s) below equilibrium, and the calm run from there swings by
71 N or 25 N, undamped. The state used here is its dynamic relaxation (``ICgenDynamic 1``) with the drag
scaled by 100 and critical internal damping (BA = −1, in the relaxing system only), for ``IC_TIME`` = 120 s:
its calm run swings by 7.6 N (600 s: 0.85 N). What remains is taken out by comparing wave-induced tensions,
ΔT(t) = T(t) − T_calm(t), MoorDyn's calm run started from the same state (``wave_induced``; pipelay's calm run
stays at its static state, within 3e-5 N). That is not an exact superposition (the waves' drag also damps
the leftover swing), but measured at n = 50 the ΔT from the 120 s relaxation is within 0.04 % of the range of
that from 600 s (from the stationary solve of 300 s: 0.4 %). The calm mean equals pipelay's static tension
within 0.01 N at n = 50.

The ringing, and what is compared. The waves switched on at full height set the undamped line ringing for
the whole run: its transverse modes near 2 Hz (≈ 300 N at first) and its axial modes at 6.3, 11.9, 17.6 Hz
... (the standing waves of the taut line, c/2L = 5.9 Hz; tens of N each). Their phases drift with each code's
time step and mesh: the raw histories of two pipelay runs at n = 100, dt = 2.5 and 1.25 ms, differ by 12 % of
the range in the regular wave, all of it in those modes (below 1 Hz they agree within 0.005 %); MoorDyn's RK4
at its stability limit differs from its half step by 1.2 % raw; pipelay and MoorDyn at n = 50 by 18 % raw.
The wave-frequency top tension converges in both: ``low_pass`` filters a history at ``LOW_PASS`` = 1 Hz (a
zero-phase 4th-order Butterworth filter, the line at rest before t = 0), and ``range_error`` scores the
difference up to t_end − 2 s (after that the backward pass's start shows), relative to the reference's range.

The top tension is |F_B| as in ``moordyn_case``: pipelay's ``reaction("B")`` read at the step midpoints
(``moordyn_case.run_pipelay``'s docstring says why), MoorDyn's force on its coupled point from ``Step``. B
being still, pipelay's reaction has no inertia term here.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import pipelay as pl
from moordyn_case import (
    Case,
    Run,
    _moordyn_system,
    _quiet,
    initial_condition,
    line_section,
    moordyn_file,
    moordyn_point,
    step_moordyn,
    top_tension_run,
)

__all__ = [
    "JONSWAP",
    "LOW_PASS",
    "REGULAR",
    "WAVE_CASE",
    "SeaState",
    "WaveCase",
    "damped_section",
    "low_pass",
    "moordyn_frequencies",
    "moordyn_initial_waves",
    "moordyn_waves_input",
    "moordyn_waves_system",
    "pipelay_waves_model",
    "range_error",
    "run_moordyn_waves",
    "run_pipelay_waves",
    "wave_induced",
]


@dataclass(frozen=True)
class WaveCase(Case):
    """The line and the water: the fields of ``moordyn_case.Case`` (``depth`` is still A's depth below the
    surface; the drive's fields are not used: B is held still at ``x0``, ``rise``) and the water depth."""

    water_depth: float = 250.0  # depth of the sea (m), in both codes' wave kinematics
    t_end: float = 25.0  # simulated time (s)
    zeta: float = 0.0  # axial internal damping as MoorDyn's BA/-zeta (-): ``damped_section``; 0: none

    @property
    def anchor_z(self) -> float:
        """z of A in pipelay's frame e (e3 down, the seabed level z = 0, the surface z = −water_depth) (m)."""
        return self.depth - self.water_depth

    @property
    def top(self) -> tuple[float, float, float]:
        """Position of B in e (m)."""
        return (self.x0, 0.0, self.anchor_z - self.rise)

    @property
    def top_moordyn(self) -> np.ndarray:
        """Position of B in MoorDyn's frame (z up, the surface at z = 0) (m)."""
        return np.array([self.x0, 0.0, self.rise - self.depth])


WAVE_CASE = WaveCase()
LOW_PASS = 1.0  # Hz: the wave-frequency band the histories are compared in (``low_pass``)
REST = 5.0  # s of rest put before t = 0 for the low-pass filter
MARGIN = 2.0  # s at the end of a run left out of the comparison (the backward filter's start)
IC_TIME = 120.0  # s of MoorDyn's dynamic relaxation to its static state (``moordyn_initial_waves``)
RELAX_DRAG = 100.0  # MoorDyn's drag scale during that relaxation (its CdScaleIC)


@dataclass(frozen=True)
class SeaState:
    """A sea along +x (direction 0) at full height from t = 0 (no build-up): a regular wave of crest-to-trough
    ``height`` (m) and ``period`` (s) if ``components`` is 0, else a JONSWAP sea of significant height
    ``height`` (m), peak period ``period`` (s), peak enhancement ``gamma`` and ``components`` components
    drawn from ``seed``."""

    name: str
    height: float
    period: float
    components: int = 0
    gamma: float = 3.3
    seed: int = 0

    @property
    def description(self) -> str:
        """The sea in words and numbers."""
        if self.components == 0:
            return f"regular, H = {self.height:g} m, T = {self.period:g} s"
        return (
            f"JONSWAP, Hs = {self.height:g} m, Tp = {self.period:g} s, γ = {self.gamma:g}, "
            f"{self.components} components, seed {self.seed}"
        )

    def waves(self) -> pl.Waves:
        """The sea state in pipelay, ramp 0."""
        if self.components == 0:
            return pl.Waves.regular(self.height, self.period, direction=0.0, ramp=0.0)
        return pl.Waves.jonswap(
            self.height, self.period, self.gamma, seed=self.seed, components=self.components, ramp=0.0
        )


REGULAR = SeaState("regular", height=6.0, period=10.0)
JONSWAP = SeaState("JONSWAP", height=4.0, period=10.0, components=25, seed=0)


def damped_section(n: int, case: WaveCase = WAVE_CASE) -> pl.Section:
    """``moordyn_case.line_section`` with, if ``case.zeta`` > 0, the axial internal damping MoorDyn gives a line
    of ``n`` segments for ``BA/-zeta`` = −ζ: BA = ζ l √(EA m) (N·s; l = L/n the segment length, m the mass per
    length in air), a fraction ζ of critical damping at the segment's axial frequency 2c/l, c = √(EA/m). In
    pipelay that is the structural damping ζ at the period π l/c (its β = ζ·period/π = BA/EA); a cable's
    axial damping B is then BA."""
    section = line_section(case)
    if case.zeta <= 0.0:
        return section
    period = math.pi * case.length / n / math.sqrt(case.ea / case.mass)
    return section.with_structural_damping(period=period, axial=case.zeta)


def pipelay_waves_model(n: int, sea: SeaState | None, case: WaveCase = WAVE_CASE) -> pl.Model:
    """The pipelay model with ``n`` elements (of cable if ``case.cable``, else of the EI = 10 rod; damped as
    ``damped_section`` says): a straight
    reference from A at (0, 0, ``anchor_z``) along e1, A pinned there, B pinned at ``case.top``, in a sea
    ``case.water_depth`` deep with the waves of ``sea`` (None: calm)."""
    a = (0.0, 0.0, case.anchor_z)
    rod = pl.Rod.straight(a, (case.length, 0.0, case.anchor_z), n, damped_section(n, case))
    waves = None if sea is None else sea.waves()
    water = pl.Sea(case.water_depth, density=case.rho_water, waves=waves)
    model = pl.Model(rod, sea=water, gravity=case.gravity)
    model.pin("A")
    model.pin("B", position=case.top)
    return model


def run_pipelay_waves(
    n: int, dt: float, sea: SeaState | None, case: WaveCase = WAVE_CASE, t_end: float | None = None
) -> Run:
    """Static equilibrium in calm water (``model.static()``, which has no waves), then ``t_end`` s (default
    ``case.t_end``) in the waves of ``sea`` (None: calm) with step ``dt`` (s) on ``n`` elements; the top
    tension read at the step midpoints as ``moordyn_case.run_pipelay`` does (its docstring says why)."""
    t_end = case.t_end if t_end is None else t_end
    return top_tension_run(pipelay_waves_model(n, sea, case), dt, t_end)[0]


def moordyn_frequencies(sea: SeaState) -> str:
    """MoorDyn's ``wave_frequencies.txt`` for ``sea``: rows ``omega re im beta`` (rad/s, m, m, rad), the first
    one ω = 0 as MoorDyn requires. MoorDyn's elevation is Σ |c| sin(ωt − kx + arg c) with c = re + i im,
    pipelay's Σ a cos(kx − ωt + φ) = Σ a sin(ωt − kx + π/2 − φ): c = a e^{i(π/2 − φ)}."""
    amplitude, frequency, direction, phase = sea.waves().components
    rows = ["0.0 0.0 0.0 0.0"]
    for a, w, beta, phi in zip(amplitude, frequency, direction, phase, strict=True):
        c = float(a) * complex(math.cos(0.5 * math.pi - phi), math.sin(0.5 * math.pi - phi))
        rows.append(f"{float(w)!r} {c.real!r} {c.imag!r} {float(beta)!r}")
    return "\n".join(rows) + "\n"


def moordyn_waves_input(
    n: int,
    dt: float,
    waves: bool,
    case: WaveCase = WAVE_CASE,
    ba: float = 0.0,
    ic_time: float = IC_TIME,
    relaxation: bool = False,
) -> str:
    """The MoorDyn v2 input file: ``n`` segments, internal step ``dt`` (s, RK4), internal damping ``ba`` (N·s;
    negative: minus the damping ratio), the water ``case.water_depth`` deep (its seabed, flat, 50 m below A:
    out of the line's reach), A fixed, B a coupled point. With ``waves``, ``WaveKin 7`` (the components of
    ``wave_frequencies.txt`` summed at every node), else calm (``WaveKin 0``). Its initial-condition solve
    runs for at most ``ic_time`` (s): MoorDyn's default stationary solver or, with ``relaxation``, its dynamic
    relaxation (``ICgenDynamic 1``) with the drag scaled by ``RELAX_DRAG`` and critical internal damping
    (BA = −1, which replaces ``ba``), run for all of ``ic_time`` (its convergence threshold is out of
    reach)."""
    top = case.top_moordyn
    if relaxation:
        ba = -1.0
        solver = f"1e-9  threshIC\n1  ICgenDynamic\n{RELAX_DRAG!r}  CdScaleIC"
    else:
        solver = "1e-7  threshIC"
    options = [
        f"{case.water_depth!r}  WtrDpth",
        f"{7 if waves else 0}  WaveKin",
        "0  Currents",
        "1.0  dtIC",
        f"{ic_time!r}  TmaxIC",
        *solver.splitlines(),
    ]
    title = "pipelay peer comparison: steel wire rope between two fixed points in waves"
    points = (moordyn_point("Fixed", (0.0, 0.0, -case.depth)), moordyn_point("Coupled", top))
    return moordyn_file(title, n, case, ba, points, dt, "RK4", options)


@contextlib.contextmanager
def moordyn_waves_system(text: str, sea: SeaState | None) -> Iterator[Any]:
    """A MoorDyn system built from the input file ``text`` and, with ``sea``, its ``wave_frequencies.txt``
    (both written to a temporary folder), closed on exit."""
    beside = {} if sea is None else {"wave_frequencies.txt": moordyn_frequencies(sea)}
    with _moordyn_system(text, beside) as system:
        yield system


def moordyn_initial_waves(
    n: int, dt: float, case: WaveCase = WAVE_CASE, ic_time: float = IC_TIME
) -> tuple[bytes, float]:
    """MoorDyn's static state in calm water for ``n`` segments: its dynamic relaxation
    (``moordyn_waves_input`` with ``relaxation``) at step ``dt`` (s) for ``ic_time`` (s). Returns the
    serialized system, to start ``run_moordyn_waves`` from (the internal damping is not part of the state),
    and the top tension |F_B| (N)."""
    text = moordyn_waves_input(n, dt, False, case, ic_time=ic_time, relaxation=True)
    return initial_condition(text, case.top_moordyn, n, dt)


def run_moordyn_waves(
    n: int,
    dt: float,
    sea: SeaState | None,
    case: WaveCase = WAVE_CASE,
    initial: bytes | None = None,
    t_end: float | None = None,
    ic_time: float = IC_TIME,
) -> Run:
    """MoorDyn (RK4, internal damping ``BA/-zeta`` = −``case.zeta``) on ``n`` segments with step ``dt`` (s) to
    ``t_end`` (s; default ``case.t_end``) in the waves of ``sea`` (None: calm, ``WaveKin 0``), B held still (a coupled point given
    its position and zero velocity at every step). It starts from ``initial`` (a calm system serialized by
    ``moordyn_initial_waves`` for the same ``n``) or, without it, from that calm solve (at most ``ic_time`` s
    at step ``dt``). Raises RuntimeError if MoorDyn fails or its top force stops being finite."""
    import moordyn  # type: ignore[import-untyped]

    t_end = case.t_end if t_end is None else t_end
    if initial is None:
        initial, _ = moordyn_initial_waves(n, dt, case, ic_time)
    steps = round(t_end / dt)
    times = np.arange(steps + 1) * dt
    top = case.top_moordyn.tolist()
    still = [0.0, 0.0, 0.0]
    with moordyn_waves_system(
        moordyn_waves_input(n, dt, sea is not None, case, -case.zeta, ic_time), sea
    ) as system:
        with _quiet():
            err = moordyn.Init_NoIC(system, top, still)
        if err != 0:
            raise RuntimeError(f"MoorDyn's initialisation failed (error {err}), n = {n}, dt = {dt} s")
        moordyn.Deserialize(system, initial)
        static_tension = float(np.linalg.norm(moordyn.Step(system, top, still, 0.0, 0.0)))
        tension = np.empty(steps + 1)
        tension[0] = static_tension
        wall = step_moordyn(system, [top] * steps, [still] * steps, times, tension, n)
    return Run(times, tension, static_tension, wall, steps)


def wave_induced(run: Run, calm: Run | None = None) -> Run:
    """The wave-induced top tension ΔT(t) = T(t) − T_calm(t) of ``run`` (N): ``calm`` is the same code's calm
    run from the same initial state (interpolated at ``run.time``); None: the static tension is subtracted
    (pipelay, whose calm run stays at its static state)."""
    base = run.static_tension if calm is None else np.interp(run.time, calm.time, calm.tension)
    return replace(run, tension=run.tension - base, static_tension=0.0)


def low_pass(run: Run, cutoff: float = LOW_PASS) -> Run:
    """``run`` with its top tension low-passed at ``cutoff`` (Hz): a 4th-order Butterworth filter run forward
    and backward (zero phase) over the samples after t = 0, which are evenly spaced (pipelay's at the step
    midpoints, MoorDyn's at the steps), preceded by ``REST`` s of the value at t = 0: the line was at rest
    before the waves came, so the filter's start needs no padding guess. The sample at t = 0 is kept."""
    if cutoff <= 0.0:
        return run
    from scipy import signal  # type: ignore[import-untyped]

    spacing = float(run.time[2] - run.time[1])
    before = math.ceil(REST / spacing)
    samples = np.concatenate([np.full(before, run.tension[0]), run.tension[1:]])
    sections = signal.butter(4, cutoff, fs=1.0 / spacing, output="sos")
    filtered = signal.sosfiltfilt(sections, samples)[before:]
    return replace(run, tension=np.concatenate([run.tension[:1], filtered]))


def range_error(run: Run, reference: Run, cutoff: float = LOW_PASS, margin: float = MARGIN) -> float:
    """max |T − T_ref| over t ≤ t_end − ``margin`` (s), both histories low-passed at ``cutoff`` (Hz; 0: as
    they are), the reference interpolated at ``run.time``, relative to the range max T_ref − min T_ref of the
    reference as it is (-)."""
    ours, theirs = low_pass(run, cutoff), low_pass(reference, cutoff)
    scored = run.time <= run.time[-1] - margin
    gap = np.abs(ours.tension - np.interp(run.time, theirs.time, theirs.tension))[scored]
    return float(np.max(gap) / np.ptp(reference.tension))
