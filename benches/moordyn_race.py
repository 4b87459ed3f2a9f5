"""Benchmark: pipelay against MoorDyn v2 on the peer-comparison case, each at its largest accurate time step.

Not a test. The case is ``tests/moordyn_case.py`` (a 250 m steel wire rope between a fixed point and a top
point driven in surge and heave, 25 s simulated). Three contenders: pipelay's cable element
(``pl.Section.cable``, 3 DOFs per node, as MoorDyn's line), pipelay's rod with EI = 10 N·m² imitating a cable
(6 DOFs per node) and MoorDyn. For each n (elements = MoorDyn segments):

* pipelay, cable and rod alike (implicit energy–momentum integrator; the top's motion given as tables at the
  step times, which the engine interpolates without calling Python): a reference run at dt = 0.01 s, then
  dt = 25 s / k for
  k = 100, 125, 160, 200, … (dt = 0.25, 0.2, 0.156, 0.125, … s) until the top-tension history is within 1 %
  of the reference (max |T − T_ref| over the run / mean T_ref);
* MoorDyn (explicit RK4, BA = 0): one initial-condition solve, shared by its runs at that n (60 s of
  relaxation at dt = l/c, with c = √(EA/(m + Ca ρ_w A)) the axial wave speed and l the segment length; it
  leaves the static top tension within ≈ 0.05 % of equilibrium, which does not matter here since candidate
  and reference start from the same state); then dt from 2 l/c down by factors of 1.25 until a run is stable
  (finishes, finite); a reference at half that dt (RK4: its error is ≈ 1/16 of the candidate's); if the
  candidate is not within 1 %, smaller dt until it is.

The table reports, for each contender, the dt found, the number of steps, the wall time of that run (the time
integration only: statics / initial condition excluded; a run shorter than 10 s is timed three times and the
best kept) and per simulated second, its error against its own reference, its largest difference from
MoorDyn's reference (the codes' discretisations differ: this falls like 1/n²) and the speed-up, MoorDyn's time
over the contender's.
MoorDyn is driven from Python one ``Step`` call per internal step (its coupled point moves linearly within a
call, so this is what meets the prescribed motion at every step); the per-call overhead, measured with dt = 0
calls, is printed: it matters only at the smallest n. A second table gives pipelay's cost per step and per
Newton iteration against n, for the cable and the rod, to show it grows linearly.

Usage::

    python benches/moordyn_race.py [--quick]     # --quick: n = 50, 100 only (the full run takes ≈ 5 min)
"""

from __future__ import annotations

import argparse
import platform
import sys
import time
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import moordyn  # type: ignore[import-untyped]
import pipelay as pl
from moordyn_case import (
    CASE,
    Case,
    Run,
    _moordyn_system,
    _quiet,
    axial_wave_time,
    best_of,
    max_relative_error,
    moordyn_initial,
    moordyn_input,
    run_moordyn,
    run_pipelay,
)

TOLERANCE = 0.01  # max |T − T_ref| / mean T_ref
PIPELAY_REFERENCE_DT = 0.01  # s
PIPELAY_STEP_COUNTS = [100, 125, 160, 200, 250, 320, 400, 500, 625, 800, 1000, 1250]  # dt = t_end / k
MOORDYN_SHRINK = 1.25
IC_TIME = 60.0  # s of MoorDyn initial-condition relaxation
CABLE = replace(CASE, cable=True)  # the same line on pipelay's cable elements


@dataclass
class Found:
    """The largest accurate dt (s) of one code at one n, its run and its error against the reference (-)."""

    dt: float
    run: Run
    error: float
    reference: Run


def pipelay_search(n: int, log: list[str], case: Case = CASE) -> Found:
    """pipelay's largest dt = t_end / k within ``TOLERANCE`` of the dt = 0.01 s reference, on cable elements
    if ``case.cable``, else on the rod."""
    name = "pipelay cable" if case.cable else "pipelay rod"
    reference = run_pipelay(n, PIPELAY_REFERENCE_DT, case, tables=True)
    for k in PIPELAY_STEP_COUNTS:
        dt = CASE.t_end / k
        try:
            run = run_pipelay(n, dt, case, tables=True)
        except pl.ConvergenceError as exc:
            log.append(f"{name} n={n} dt={dt:.4g}: Newton failed ({exc})")
            continue
        error = max_relative_error(run, reference)
        log.append(f"{name} n={n} dt={dt:.4g}: error {100 * error:.3f} %, {run.wall:.2f} s")
        if error <= TOLERANCE:
            run = best_of(run, partial(run_pipelay, n, dt, case, tables=True))
            return Found(dt, run, error, reference)
    raise RuntimeError(
        f"{name}: no dt down to {CASE.t_end / PIPELAY_STEP_COUNTS[-1]} s is within 1 % at n={n}"
    )


def moordyn_search(n: int, log: list[str]) -> tuple[Found, float]:
    """MoorDyn's largest stable dt within ``TOLERANCE`` of a run at half that dt; also its static tension (N)."""
    initial, static_tension = moordyn_initial(n, axial_wave_time(n), ic_time=IC_TIME)
    dt = 2.0 * axial_wave_time(n)
    reference: Run | None = None
    for _ in range(40):
        try:
            run = run_moordyn(n, dt, initial=initial)
        except RuntimeError as exc:
            log.append(f"MoorDyn n={n} dt={dt:.4g}: unstable ({str(exc).split(':')[0]})")
            dt /= MOORDYN_SHRINK
            continue
        if reference is None or reference.time[1] > dt / 2.0 * (1 + 1e-9):
            reference = run_moordyn(n, dt / 2.0, initial=initial)
        error = max_relative_error(run, reference)
        log.append(f"MoorDyn n={n} dt={dt:.4g}: error {100 * error:.4f} % against dt/2, {run.wall:.2f} s")
        if error <= TOLERANCE:
            run = best_of(run, partial(run_moordyn, n, dt, initial=initial))
            return Found(dt, run, error, reference), static_tension
        dt /= MOORDYN_SHRINK
    raise RuntimeError(f"MoorDyn: no accurate dt found at n={n}")


def moordyn_call_overhead(n: int = 50, calls: int = 20000) -> float:
    """Wall time (s) of one Python ``moordyn.Step`` call with dt = 0 (no integration: the call's own cost)."""
    initial, _ = moordyn_initial(n, axial_wave_time(n), ic_time=1.0)
    with _moordyn_system(moordyn_input(n, axial_wave_time(n), ic_time=0.0)) as system:
        x = [CASE.x0, 0.0, -CASE.depth + CASE.rise]
        with _quiet():
            moordyn.Init_NoIC(system, x, [0.0] * 3)
        moordyn.Deserialize(system, initial)
        began = time.perf_counter()
        for _ in range(calls):
            moordyn.Step(system, x, [0.0] * 3, 0.0, 0.0)
        return (time.perf_counter() - began) / calls


def main(argv: list[str] | None = None) -> int:
    """Run the race and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="n = 50, 100 only")
    parser.add_argument("--verbose", action="store_true", help="print every trial")
    args = parser.parse_args(argv)
    sizes = [50, 100] if args.quick else [50, 100, 200, 1000]

    print(
        f"pipelay {getattr(pl, '__version__', '?')} vs MoorDyn (Python package moordyn), Python "
        f"{platform.python_version()}, {platform.machine()}; case: {CASE.length:g} m wire rope, "
        f"{CASE.t_end:g} s driven, accuracy target {100 * TOLERANCE:g} % of the mean top tension\n"
    )
    began = time.perf_counter()
    rows: list[tuple[int, Found, Found, Found]] = []  # n, cable, rod, MoorDyn
    for n in sizes:
        log: list[str] = []
        cable = pipelay_search(n, log, CABLE)
        rod = pipelay_search(n, log)
        theirs, md_static = moordyn_search(n, log)
        rows.append((n, cable, rod, theirs))
        if args.verbose:
            print("\n".join(log), flush=True)
        print(
            f"n = {n}: cable dt = {cable.dt:.4g} s (error {100 * cable.error:.2f} %), rod dt = {rod.dt:.4g} s "
            f"(error {100 * rod.error:.2f} %), MoorDyn dt = {theirs.dt:.3g} s (error {100 * theirs.error:.3f} %); "
            f"static top tension {cable.run.static_tension:.1f} / {rod.run.static_tension:.1f} / {md_static:.1f} N; "
            f"references: cable vs MoorDyn {100 * max_relative_error(cable.reference, theirs.reference):.3f} %, "
            f"cable vs rod {100 * max_relative_error(cable.reference, rod.reference):.4f} % of the mean",
            flush=True,
        )

    print(
        "\n| n | code | dt (s) | steps | wall (s) | wall per simulated s (ms) | error vs own reference (%) "
        "| vs MoorDyn's reference (%) | speed-up vs MoorDyn |"
    )
    print("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n, cable, rod, theirs in rows:
        for name, found in (("pipelay cable", cable), ("MoorDyn", theirs), ("pipelay rod (EI = 10)", rod)):
            run = found.run
            speed_up = "—" if found is theirs else f"{theirs.run.wall / run.wall:.1f}"
            print(
                f"| {n} | {name} | {found.dt:.4g} | {run.steps} | {run.wall:.3f} | "
                f"{1e3 * run.wall / CASE.t_end:.2f} | {100 * found.error:.3f} | "
                f"{100 * max_relative_error(run, theirs.reference):.3f} | {speed_up} |"
            )

    print("\npipelay's cost against n (the timed runs above):\n")
    print(
        "| n | element | steps | Newton iterations | ms per step | µs per step per element | ms per iteration |"
    )
    print("| ---: | --- | ---: | ---: | ---: | ---: | ---: |")
    for n, cable, rod, _ in rows:
        for name, found in (("cable", cable), ("rod", rod)):
            run = found.run
            per_step = run.wall / run.steps
            print(
                f"| {n} | {name} | {run.steps} | {run.iterations} | {1e3 * per_step:.3f} | "
                f"{1e6 * per_step / n:.2f} | {1e3 * run.wall / max(run.iterations, 1):.3f} |"
            )
    print("\nMoorDyn's cost per step (RK4, four evaluations of the line per step):\n")
    print("| n | µs per step | µs per step per segment |")
    print("| ---: | ---: | ---: |")
    for n, _, _, theirs in rows:
        per_step = theirs.run.wall / theirs.run.steps
        print(f"| {n} | {1e6 * per_step:.1f} | {1e6 * per_step / n:.3f} |")
    overhead = moordyn_call_overhead()
    print(f"\nMoorDyn Python call overhead (Step with dt = 0, n = 50): {1e6 * overhead:.2f} µs per call")
    print(f"total benchmark time {time.perf_counter() - began:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
