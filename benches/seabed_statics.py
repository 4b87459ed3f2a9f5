"""Benchmark: statics that find the touchdown, over pipe length, water depth and mesh.

Not a test. A flooded 0.6 m × 15 mm steel pipe (submerged weight 1846 N/m) of length L is anchored (pinned) on
the seabed (k = 1e5 Pa/m) at A and pinned at B, `depth` above A at the sea surface, where the catenary with a
laid part would have the horizontal tension H = w·depth (shallower: H = 0.3 w depth when that leaves too
little pipe on the seabed) — so that about the same share of pipe lies on the seabed in every case. Prints a
Markdown table: L, depth, n, friction, wall time, Newton iterations, reaction at B |F_B|, touchdown.

Usage::

    python benches/seabed_statics.py [--quick]     # --quick stops at n = 1000
"""

from __future__ import annotations

import argparse
import math
import time

import pipelay as pl


def build(length: float, depth: float, elements: int, friction: float) -> pl.Model:
    """The pipe on the seabed with its top at the surface, placed as in the module docstring."""
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0)
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (length, 0.0, 0.0), elements, section)
    model = pl.Model(rod, sea=pl.Sea(depth, seabed=pl.Seabed(stiffness=1e5, friction=friction)))
    w = model.submerged_weight
    horizontal = w * depth
    suspended = math.sqrt(depth * (depth + 2 * horizontal / w))
    if suspended > 0.95 * length:
        horizontal = 0.3 * w * depth
        suspended = math.sqrt(depth * (depth + 2 * horizontal / w))
    span = length - suspended + horizontal / w * math.asinh(w * suspended / horizontal)
    model.pin("A")
    model.pin("B", position=(span, 0.0, -depth))
    return model


def main(argv: list[str] | None = None) -> int:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at n = 1000")
    args = parser.parse_args(argv)
    sizes = [100, 1000] if args.quick else [100, 1000, 10000]
    cases = [(1000, 100), (1000, 500), (2000, 100), (2000, 1000), (3000, 100), (3000, 1500), (3000, 2500)]
    print(
        "| L (m) | depth (m) | n | friction | statics (s) | Newton iterations | reaction at B \\|F_B\\| (kN) | touchdown (m from A) |"
    )
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for length, depth in cases:
        for n in sizes:
            for friction in (0.0, 0.5):
                if friction > 0.0 and n > 1000 and depth < 200:
                    continue  # slow: strong friction in shallow water at n = 1e4 (see the README)
                model = build(length, depth, n, friction)
                began = time.perf_counter()
                try:
                    state = model.static()
                except pl.ConvergenceError as error:
                    print(f"| {length} | {depth} | {n} | {friction} | failed: {error} | | | |", flush=True)
                    continue
                seconds = time.perf_counter() - began
                top = math.hypot(*state.reaction("B")[:3]) / 1e3
                touchdown = state.touchdown
                where = f"{touchdown.arc_length:.2f}" if touchdown is not None else "–"
                print(
                    f"| {length} | {depth} | {n} | {friction} | {seconds:.3f} | {state.iterations} | {top:.1f} "
                    f"| {where} |",
                    flush=True,
                )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
