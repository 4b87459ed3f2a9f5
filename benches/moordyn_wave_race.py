"""Benchmark: pipelay against MoorDyn v2 in waves, each at its largest accurate time step.

Not a test. The case is ``tests/moordyn_waves_case.py``: the 250 m steel wire rope of the calm race held
still at both ends (A 200 m deep, B 10 m below the surface, 250 m of water) while waves along +x pass over it
from t = 0, 25 s simulated, in two seas: a regular wave (H = 6 m, T = 10 s) and a JONSWAP sea (Hs = 4 m,
Tp = 10 s, 25 components; MoorDyn sums them at every node at each of its RK4's four stages). Three
contenders: pipelay's cable element, pipelay's rod with EI = 10 N·m² imitating a cable, and MoorDyn (RK4,
BA = 0). For each sea and n (elements = MoorDyn segments):

* pipelay, cable and rod alike (implicit energy–momentum integrator): a reference run at dt = 0.01 s, then
  dt = 25 s / k for k = 100, 125, 160, 200, … (dt = 0.25, 0.2, 0.156, … s) until the top-tension history is
  within 1 % of the range (max − min) of the reference's. At the smallest n the reference is itself checked
  against a run at half its dt (printed);
* MoorDyn: one static state per n shared by its runs (its dynamic relaxation in calm water, 60 s at
  dt = l/c, c the axial wave speed, l the segment length; ``moordyn_initial_waves``), then dt from 2 l/c down
  by factors of 1.25 until a run is stable (finishes, finite), checked against a run at half that dt (RK4:
  its error is ≈ 1/16 of the candidate's) and shrunk further until within 1 % of the range. Above n = 200
  that check is skipped (it would double the bench's longest runs): MoorDyn runs at its largest stable dt,
  where at n = 100 it is within 0.001 % of its half step (the table says "not checked").

What "within 1 %" means here. By default the line has no internal damping (BA = 0 in MoorDyn, none in
pipelay), and the waves switched on at full height at t = 0 set it ringing for the whole run: its transverse
modes near 2 Hz and its axial modes (6.3, 11.9, 17.6, … Hz: the standing waves of a taut 250 m line,
c/2L = 5.9 Hz), at tens to hundreds of N. Neither integrator dissipates them, so a step's phase error in them
grows with time: pipelay's second-order scheme (phase error (ωΔt)²/12 a period) cannot follow them over 25 s
at any dt in its list, and at n = 100 its raw history at dt = 2.5 ms still differs from the one at 1.25 ms by
12 % of the range in the regular wave (the wave-frequency part by less than 0.005 %); MoorDyn's RK4 at its
stability limit differs from its half step by 1.2 % raw. MoorDyn's usual damping (``--damping 0.8``) cuts the
ringing by 40 % in both codes alike but does not end it: pipelay's raw reference at dt = 0.01 s is then still
3.3 % of the range from its half step. The accuracy asked of both is therefore that of the wave-frequency top
tension: both histories low-passed at 1 Hz (``moordyn_waves_case.low_pass``: a zero-phase 4th-order
Butterworth filter, the line at rest before t = 0; the last 2 s, where the backward pass starts, are not
scored). The raw error is printed alongside, and ``--lowpass 0`` applies the 1 % to the raw histories
(pipelay then finds no dt in its list). It is the step a smooth start would need too: with the sea built up
over 10 s (pipelay's ramp; MoorDyn's summed components have none), pipelay's raw history at n = 100 is within
1.1 % (regular) and 1.1 % (JONSWAP) of the range of its dt = 5 ms run at dt = 31 ms, the step the low-passed
criterion finds here.

The table reports, for each contender, the dt found, the number of steps, the wall time of that run (the time
integration only: statics / initial condition excluded; a run shorter than 10 s is timed three times and the
best kept), its error against its own reference (low-passed, and raw), its largest difference from MoorDyn's
reference (in the wave-induced tension ΔT = T − T_calm: MoorDyn's calm run from the same static state is
subtracted, which removes what remains of its relaxation; pipelay's calm run stays at its static state; the
codes' discretisations differ, so this falls like 1/n²) and the speed-up, MoorDyn's time over the
contender's, in the waves and against MoorDyn's time at the same dt without waves (``WaveKin 0``). A second
table splits MoorDyn's cost into the line and its wave kinematics.

``--damping ZETA`` gives the line axial internal damping in both codes, matched: MoorDyn's ``BA/-zeta`` =
−ZETA (BA = ζ l √(EA m), a fraction ζ of critical at the segment's axial frequency) and pipelay's structural
damping ζ at the period π l/c, the same BA (``moordyn_waves_case.damped_section``).

Usage::

    python benches/moordyn_wave_race.py [--quick | --sizes N ...] [--check-up-to N] [--verbose] [--lowpass HZ]
                                        [--damping ZETA]
    # --quick: n = 100 only (≈ 1 min); the full run, n = 100, 200, 400: ≈ 10 min; --check-up-to 400 checks
    # MoorDyn's step against its half at n = 400 too (≈ 8 min more)
"""

from __future__ import annotations

import argparse
import math
import platform
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import numpy as np
import pipelay as pl
from machine import machine
from moordyn_case import Run, axial_wave_time, best_of
from moordyn_waves_case import (
    JONSWAP,
    LOW_PASS,
    REGULAR,
    WAVE_CASE,
    SeaState,
    WaveCase,
    moordyn_initial_waves,
    range_error,
    run_moordyn_waves,
    run_pipelay_waves,
    wave_induced,
)

TOLERANCE = 0.01  # max |T − T_ref| / (max T_ref − min T_ref)
PIPELAY_REFERENCE_DT = 0.01  # s
PIPELAY_STEP_COUNTS = [100, 125, 160, 200, 250, 320, 400, 500, 625, 800, 1000, 1250]  # dt = t_end / k
MOORDYN_SHRINK = 1.25
IC_TIME = 60.0  # s of MoorDyn's dynamic relaxation (its cost grows like n²: ≈ 30 s at n = 400)
CHECKED_UP_TO = 200  # MoorDyn's dt is checked against dt/2 up to this n
CABLE = replace(WAVE_CASE, cable=True)  # the same line on pipelay's cable elements


@dataclass
class Found:
    """One contender at one n: the dt (s) it runs at, that run, its error against its own reference (-,
    low-passed as the race asks, and raw; NaN: not checked), the reference, and whether the error is within
    ``TOLERANCE`` (False: no dt in the list was; ``dt`` and ``run`` are then the last tried)."""

    dt: float
    run: Run
    error: float
    raw_error: float
    reference: Run
    within: bool = True


def pipelay_search(n: int, sea: SeaState, case: WaveCase, cutoff: float, log: Callable[[str], None]) -> Found:
    """pipelay's largest dt = t_end / k within ``TOLERANCE`` of its dt = 0.01 s reference, on cable elements
    if ``case.cable``, else on the rod; the errors low-passed at ``cutoff`` (Hz; 0: raw)."""
    name = "pipelay cable" if case.cable else "pipelay rod"
    reference = run_pipelay_waves(n, PIPELAY_REFERENCE_DT, sea, case)
    last: Found | None = None
    for k in PIPELAY_STEP_COUNTS:
        dt = case.t_end / k
        try:
            run = run_pipelay_waves(n, dt, sea, case)
        except pl.ConvergenceError as exc:
            log(f"{sea.name} {name} n={n} dt={dt:.4g}: Newton failed ({exc})")
            continue
        error, raw = range_error(run, reference, cutoff), range_error(run, reference, 0.0, 0.0)
        log(
            f"{sea.name} {name} n={n} dt={dt:.4g}: error {100 * error:.3f} % (raw {100 * raw:.2f} %), "
            f"{run.wall:.2f} s"
        )
        last = Found(dt, run, error, raw, reference, error <= TOLERANCE)
        if last.within:
            last.run = best_of(run, partial(run_pipelay_waves, n, dt, sea, case))
            return last
    if last is None:
        raise RuntimeError(f"{name}: Newton failed at every dt at n={n}")
    log(f"{sea.name} {name} n={n}: no dt down to {last.dt:.4g} s within {100 * TOLERANCE:g} %")
    return last


def moordyn_search(
    n: int,
    sea: SeaState,
    case: WaveCase,
    initial: bytes,
    cutoff: float,
    check: bool,
    log: Callable[[str], None],
) -> Found:
    """MoorDyn's largest stable dt from 2 l/c down by ``MOORDYN_SHRINK``, within ``TOLERANCE`` of a run at
    half that dt (errors low-passed at ``cutoff`` Hz; 0: raw) if ``check``, else as it is (errors NaN, the run
    its own reference). The line's internal damping is ``case``'s (``BA/-zeta`` = −``case.zeta``)."""
    dt = 2.0 * axial_wave_time(n)
    reference: Run | None = None
    for _ in range(40):
        try:
            run = run_moordyn_waves(n, dt, sea, case, initial=initial)
        except RuntimeError as exc:
            log(f"{sea.name} MoorDyn n={n} dt={dt:.4g}: unstable ({str(exc).split(':')[0]})")
            dt /= MOORDYN_SHRINK
            continue
        again = partial(run_moordyn_waves, n, dt, sea, case, initial=initial)
        if not check:
            log(f"{sea.name} MoorDyn n={n} dt={dt:.4g}: stable, not checked against dt/2, {run.wall:.2f} s")
            run = best_of(run, again)
            return Found(dt, run, math.nan, math.nan, run)
        if reference is None or reference.time[1] > dt / 2.0 * (1 + 1e-9):
            reference = run_moordyn_waves(n, dt / 2.0, sea, case, initial=initial)
        error, raw = range_error(run, reference, cutoff), range_error(run, reference, 0.0, 0.0)
        log(
            f"{sea.name} MoorDyn n={n} dt={dt:.4g}: error {100 * error:.4f} % (raw {100 * raw:.3f} %) "
            f"against dt/2, {run.wall:.2f} s (dt/2: {reference.wall:.2f} s)"
        )
        if error <= TOLERANCE:
            return Found(dt, best_of(run, again), error, raw, reference)
        dt /= MOORDYN_SHRINK
    raise RuntimeError(f"MoorDyn: no accurate dt found at n={n} in the {sea.name} sea")


def percent(value: float, digits: int = 3) -> str:
    """A fraction as a percentage, or "not checked" for NaN."""
    return "not checked" if math.isnan(value) else f"{100 * value:.{digits}f}"


def main(argv: list[str] | None = None) -> int:
    """Run the race and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="n = 100 only")
    parser.add_argument(
        "--sizes", type=int, nargs="+", metavar="N", help="the n to race (default 100 200 400)"
    )
    parser.add_argument(
        "--check-up-to",
        type=int,
        default=CHECKED_UP_TO,
        metavar="N",
        help=f"check MoorDyn's dt against dt/2 up to this n (default {CHECKED_UP_TO})",
    )
    parser.add_argument("--verbose", action="store_true", help="print every trial")
    parser.add_argument(
        "--lowpass",
        type=float,
        default=LOW_PASS,
        metavar="HZ",
        help=f"compare the histories low-passed at HZ (default {LOW_PASS:g}; 0: raw)",
    )
    parser.add_argument(
        "--damping",
        type=float,
        default=0.0,
        metavar="ZETA",
        help="axial internal damping in both codes as MoorDyn's BA/-zeta = -ZETA (default 0: none)",
    )
    args = parser.parse_args(argv)
    sizes = [100] if args.quick else (args.sizes or [100, 200, 400])
    checked_up_to = args.check_up_to
    seas = (REGULAR, JONSWAP)
    cutoff = args.lowpass
    cable_case, rod_case = replace(CABLE, zeta=args.damping), replace(WAVE_CASE, zeta=args.damping)

    def log(line: str) -> None:
        if args.verbose:
            print(line, flush=True)

    band = f"low-passed at {cutoff:g} Hz" if cutoff > 0.0 else "raw"
    print(
        f"pipelay {getattr(pl, '__version__', '?')} vs MoorDyn (Python package moordyn), Python "
        f"{platform.python_version()}, {platform.machine()}; case: {WAVE_CASE.length:g} m wire rope held "
        f"still in waves, {WAVE_CASE.t_end:g} s; accuracy target {100 * TOLERANCE:g} % of the top tension's "
        f"range, histories {band}; axial internal damping "
        + (f"BA/-zeta = {-args.damping:g} in both codes" if args.damping > 0.0 else "none")
    )
    skipped = " (skipped above: it would double the longest runs)" if max(sizes) > checked_up_to else ""
    print(
        f"MoorDyn's dt is checked against dt/2 up to n = {checked_up_to}{skipped}; {machine()}\n", flush=True
    )
    began = time.perf_counter()
    rows: dict[str, list[tuple[int, Found, Found, Found, Run]]] = {sea.name: [] for sea in seas}
    for n in sizes:
        initial, md_static = moordyn_initial_waves(n, axial_wave_time(n), ic_time=IC_TIME)
        calm_runs: dict[float, Run] = {}
        for sea in seas:
            cable = pipelay_search(n, sea, cable_case, cutoff, log)
            rod = pipelay_search(n, sea, rod_case, cutoff, log)
            if n == sizes[0]:
                for name, case, found in (("cable", cable_case, cable), ("rod", rod_case, rod)):
                    half = run_pipelay_waves(n, PIPELAY_REFERENCE_DT / 2.0, sea, case)
                    banded = range_error(found.reference, half, cutoff)
                    raw = range_error(found.reference, half, 0.0, 0.0)
                    print(
                        f"{sea.name}, n = {n}: pipelay {name}'s reference (dt = {PIPELAY_REFERENCE_DT:g} s) "
                        f"against dt = {PIPELAY_REFERENCE_DT / 2:g} s: {percent(banded)} % ({band}), "
                        f"{percent(raw, 2)} % raw",
                        flush=True,
                    )
            theirs = moordyn_search(n, sea, rod_case, initial, cutoff, n <= checked_up_to, log)
            if theirs.dt not in calm_runs:
                calm = run_moordyn_waves(n, theirs.dt, None, rod_case, initial=initial)
                calm_runs[theirs.dt] = best_of(
                    calm, partial(run_moordyn_waves, n, theirs.dt, None, rod_case, initial=initial)
                )
            calm = calm_runs[theirs.dt]
            rows[sea.name].append((n, cable, rod, theirs, calm))
            md_delta = wave_induced(theirs.reference, calm)
            between = range_error(wave_induced(cable.reference), md_delta, cutoff)
            print(
                f"{sea.name}, n = {n}: cable dt = {cable.dt:.4g} s (error {percent(cable.error, 2)} %), "
                f"rod dt = {rod.dt:.4g} s (error {percent(rod.error, 2)} %), "
                f"MoorDyn dt = {theirs.dt:.3g} s (error {percent(theirs.error, 4)} %); static top tension {cable.run.static_tension:.1f} / "
                f"{rod.run.static_tension:.1f} N, MoorDyn {md_static:.1f} N after its relaxation, "
                f"{np.mean(calm.tension):.1f} N its calm mean; ΔT range {np.ptp(md_delta.tension):.0f} N; "
                f"references: cable vs MoorDyn {percent(between)} %, cable vs rod "
                f"{percent(range_error(cable.reference, rod.reference, cutoff), 4)} % of the range "
                f"[{time.perf_counter() - began:.0f} s]",
                flush=True,
            )

    for sea in seas:
        print(
            f"\n{sea.name} sea ({sea.description}): errors in % of the top tension's range, {band}; "
            "raw: unfiltered\n"
        )
        print(
            "| n | code | dt (s) | steps | wall (s) | error vs own reference (%) | raw (%) "
            "| vs MoorDyn's reference, ΔT (%) | speed-up vs MoorDyn | vs MoorDyn without waves |"
        )
        print("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for n, cable, rod, theirs, calm in rows[sea.name]:
            md_delta = wave_induced(theirs.reference, calm)
            for name, found in (
                ("pipelay cable", cable),
                ("MoorDyn", theirs),
                ("pipelay rod (EI = 10)", rod),
            ):
                run = found.run
                if found is theirs:
                    against, speed_up, calm_speed_up = percent(found.error), "—", "—"
                else:
                    against = percent(range_error(wave_induced(run), md_delta, cutoff))
                    speed_up = f"{theirs.run.wall / run.wall:.1f}"
                    calm_speed_up = f"{calm.wall / run.wall:.1f}"
                dt = f"{found.dt:.4g}" if found.within else f"{found.dt:.4g} (none within)"
                print(
                    f"| {n} | {name} | {dt} | {run.steps} | {run.wall:.3f} | {percent(found.error)} | "
                    f"{percent(found.raw_error, 2)} | {against} | {speed_up} | {calm_speed_up} |"
                )

    print("\nMoorDyn's cost at its dt, with and without the waves (WaveKin 7 and 0):\n")
    print("| sea | n | dt (s) | µs per step, waves | µs per step, calm | share of the waves' kinematics |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for sea in seas:
        for n, _, _, theirs, calm in rows[sea.name]:
            waves, still = theirs.run.wall / theirs.run.steps, calm.wall / calm.steps
            print(
                f"| {sea.name} | {n} | {theirs.dt:.3g} | {1e6 * waves:.1f} | {1e6 * still:.1f} | "
                f"{100 * (1 - still / waves):.0f} % |"
            )
    print(f"\ntotal benchmark time {time.perf_counter() - began:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
