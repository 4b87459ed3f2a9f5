"""Standby fatigue of the J-lay of examples/j_lay_waves.toml over a small scatter diagram.

The 0.6 m × 25 mm pipe hangs 1400 m from the J-lay tower of the DP vessel in 800 m of water while the lay
waits on weather. Each sea state of ``j_lay_scatter.csv`` (Hs, Tp, heading, probability) is a run of
j_lay_waves.toml with those waves (a sweep on Dask: one worker process a core; finished sea states in
``--out`` are reused). The girth welds' hot spots, eight around the wall of every element, see the axial and
bending stress times an SCF of 1.2 (an assumed allowance for hi-lo misalignment); their cycles are counted by
rainflow from t = 90 s (after the waves' 30 s build-up and the transient) and summed on the DNV-RP-C203 D
curve in seawater with cathodic protection (the 25 mm wall: no thickness effect). The damage per hour of each
sea state, weighted by its probability, is scaled to a 72-hour standby.

Prints the table of sea states (each one's damage per hour at the worst hot spot and its share of the
standby's damage) and where the damage is largest: at the top, where the tower holds the pipe at a fixed angle
and the vessel's pitch and roll bend it (a rigid hang-off: no flex joint), and, two orders of magnitude lower,
in the touchdown zone. Writes ``damage.png`` (the damage along the pipe) and ``fatigue.nc`` to ``--out``.
About a minute on two cores.

Usage::

    python examples/j_lay_fatigue.py [--out DIR] [--hours H] [--workers N]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from pipelay import fatigue

HERE = Path(__file__).resolve().parent
SCENARIO = HERE / "j_lay_waves.toml"
SCATTER = HERE / "j_lay_scatter.csv"
START = 90.0  # s: the waves' build-up and the transient left out
SCF = 1.2


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("j_lay_fatigue"), help="output folder")
    parser.add_argument("--hours", type=float, default=72.0, help="the standby's duration (h)")
    parser.add_argument("--workers", type=int, default=None, help="worker processes (default: one a core)")
    args = parser.parse_args()

    curve = fatigue.SNCurve.dnv("D", environment="seawater_cp", thickness=0.025)
    found = fatigue.scatter_damage(
        SCENARIO,
        SCATTER,
        curve,
        hours=args.hours,
        scf=SCF,
        start=START,
        output=args.out,
        workers=args.workers,
    )
    element, angle = found.worst()
    point = int(np.argmax(found.angles == angle))
    print(
        f"standby of {args.hours:g} h, DNV-RP-C203 D in seawater (CP), SCF {SCF:g}, rainflow from {START:g} s"
    )
    print(f"{'Hs m':>5} {'Tp s':>5} {'heading':>7} {'p':>5} {'damage/h at worst':>18} {'share':>6}")
    for k in range(len(found.scatter)):
        hourly = found.hourly[k, element, point]
        share = found.scatter.probability[k] * hourly * args.hours / found.max()
        heading = (
            math.degrees(float(found.scatter.heading[k])) if found.scatter.heading is not None else math.nan
        )
        print(
            f"{found.scatter.hs[k]:5.1f} {found.scatter.tp[k]:5.1f} {heading:7.0f} "
            f"{found.scatter.probability[k]:5.2f} {hourly:18.3e} {share:6.1%}"
        )
    print(
        f"largest damage {found.max():.3e} at {found.arc_length[element]:.0f} m from the seabed end "
        f"(element {element}), hot spot {math.degrees(angle):.0f}°: a fatigue life of "
        f"{args.hours / found.max() / 24:.3g} days at this rate"
    )
    lower = found.arc_length < 0.5 * found.arc_length[-1]
    touchdown = int(np.nanargmax(np.where(lower, found.per_element, -np.inf)))
    print(
        f"in the lower half of the line (the touchdown zone) the largest is {found.per_element[touchdown]:.3e}, "
        f"at {found.arc_length[touchdown]:.0f} m"
    )
    found.to_xarray().to_netcdf(args.out / "fatigue.nc", engine="h5netcdf")
    found.plot(path=args.out / "damage.png")
    print(f"figure: {args.out / 'damage.png'}; damage: {args.out / 'fatigue.nc'}")


if __name__ == "__main__":
    main()
