"""Reel-lay of a 16-inch X65 pipe: its bending from the reel to the straightener, and the straightener setting
that leaves it straight.

The pipe (0.4064 m × 20.6 mm, X65 as Ramberg–Osgood with its SMYS at 0.5 % total strain) is spooled onto a reel
whose pipe centreline has an 8 m radius (about 2.5 % strain at its outer fibre), unspooled straight, bent over a
9 m aligner and reverse-bent by the straightener. Without a straightener it leaves with a residual curvature;
`pl.design_straightener` finds the setting that leaves it straight. Prints both, the accumulated plastic strain
of the reeling (the share a strain-based design counts), and writes ``reel_lay.png`` (the moment–curvature path)
to ``--out``. About a second.

Usage::

    python examples/reel_lay.py [--out DIR] [--reel METRES] [--aligner METRES]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pipelay as pl

STAGES = ("reel", "unspooled", "aligner", "straightener", "released")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("."), help="where reel_lay.png goes")
    parser.add_argument("--reel", type=float, default=8.0, help="the reel's centreline radius (m)")
    parser.add_argument("--aligner", type=float, default=9.0, help="the aligner's centreline radius (m)")
    args = parser.parse_args()
    section = pl.Section.pipe(0.4064, 0.0206, grade="X65", material=pl.Material.grade("X65"))
    bare = pl.ReelLay(args.reel, args.aligner).history(section)
    straightener = pl.design_straightener(section, args.reel, args.aligner)
    straight = pl.ReelLay(args.reel, args.aligner, straightener).history(section)
    print(f"reel {args.reel:g} m, aligner {args.aligner:g} m (pipe centreline radii)")
    print(f"largest strain on the reel          {100 * bare['strain'].max():8.3f} %")
    print(
        f"residual curvature, no straightener {bare['residual_curvature']:12.4e} 1/m "
        f"(radius {1 / abs(bare['residual_curvature']):.1f} m)"
    )
    print(f"straightener curvature              {straightener.curvature:12.4e} 1/m")
    print(f"residual curvature, straightened    {straight['residual_curvature']:12.4e} 1/m")
    print(f"accumulated plastic strain          {100 * straight['accumulated_plastic_strain']:8.3f} %")
    figure, axis = plt.subplots(figsize=(7, 5))
    for k, name in enumerate(STAGES):
        points = straight["stage"] == k
        axis.plot(straight["curvature"][points], straight["moment"][points] / 1e3, ".-", label=name)
    axis.set_xlabel("curvature (1/m)")
    axis.set_ylabel("bending moment (kN m)")
    axis.set_title("16-inch X65 through reel, aligner and straightener")
    axis.legend()
    axis.grid(True, alpha=0.3)
    args.out.mkdir(parents=True, exist_ok=True)
    figure.savefig(args.out / "reel_lay.png", dpi=120, bbox_inches="tight")
    print(f"wrote {args.out / 'reel_lay.png'}")


if __name__ == "__main__":
    main()
