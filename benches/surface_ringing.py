"""Benchmark: does the top tension of a line whose top element leaves the water converge as the step is halved,
with and without axial structural damping?

Not a test. The wire rope of ``tests/moordyn_waves_case.py`` (250 m, 90 mm, A 200 m deep in 250 m of water),
its top B held still 1 m below the mean surface instead of 10 m, in the regular wave (H = 6 m, T = 10 s) built
up over 10 s: the troughs (3 m) lay the top element bare once a period. pipelay's rod (EI = 10 N·m²) at
n = 100, 30 s, against its own run at dt = 5 ms: the largest |T − T_ref| over the range of T_ref, for dt from
0.2 s down, without damping and with axial structural damping at the given ratios (MoorDyn's convention, a
fraction of critical at the segment's axial frequency: ``moordyn_waves_case.damped_section``).

Usage::

    python benches/surface_ringing.py [--zeta 0 0.8 4]
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import numpy as np
import pipelay as pl
from machine import machine
from moordyn_case import Run
from moordyn_waves_case import WAVE_CASE, SeaState, run_pipelay_waves

ELEMENTS = 100
REFERENCE_DT = 0.005  # s
STEP_COUNTS = [150, 300, 600, 1200, 2400]  # dt = t_end / k
SURFACE = replace(WAVE_CASE, rise=199.0, t_end=30.0)  # B 1 m below the mean level


class BuiltUp(SeaState):
    """The regular wave of ``moordyn_waves_case.REGULAR`` built up over 10 s."""

    def waves(self) -> pl.Waves:
        return pl.Waves.regular(self.height, self.period, direction=0.0, ramp=10.0)


SEA = BuiltUp("regular, built up over 10 s", height=6.0, period=10.0)


def error(run: Run, reference: Run) -> float:
    """max |T − T_ref| over the run / (max T_ref − min T_ref) (-)."""
    gap = np.abs(run.tension - np.interp(run.time, reference.time, reference.tension))
    return float(gap.max() / np.ptp(reference.tension))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--zeta", type=float, nargs="+", default=[0.0, 0.8, 4.0])
    args = parser.parse_args()
    print(f"`python benches/surface_ringing.py --zeta {' '.join(f'{z:g}' for z in args.zeta)}`; {machine()}")
    print()
    header = " | ".join(f"Δt = {SURFACE.t_end / k:.4g} s" for k in STEP_COUNTS)
    print(f"| damping ζ | range of T (kN) | {header} |")
    print("| ---: | ---: |" + " ---: |" * len(STEP_COUNTS))
    for zeta in args.zeta:
        case = replace(SURFACE, zeta=zeta)
        reference = run_pipelay_waves(ELEMENTS, REFERENCE_DT, SEA, case)
        cells = []
        for k in STEP_COUNTS:
            try:
                run = run_pipelay_waves(ELEMENTS, case.t_end / k, SEA, case)
                cells.append(f"{100 * error(run, reference):.2f} %")
            except pl.ConvergenceError:
                cells.append("Newton failed")
        print(f"| {zeta:g} | {np.ptp(reference.tension) / 1e3:.2f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
