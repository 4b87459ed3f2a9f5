"""Benchmark: static solve of the 1200 m hanging steel pipe at n = 10, 100, 1000 and 10 000 elements.

Not a test. The pipe and supports are those of ``examples/hanging_pipe.py``: Section.pipe(0.6, 0.015) flooded
with sea water (submerged weight 1845.7 N/m), pinned at A = (0, 0, 0) and at B = (850, 0, −800) m in 800 m of
water, solved two ways: from Irvine's elastic catenary (``start="auto"``, the default) and from the straight
horizontal stress-free reference with load stepping (``start="reference"``). Only ``model.static()`` is timed
(the model is built afresh before each run). Prints a Markdown table: elements, start, wall time (s; best of 3
runs, 1 run for 10 000), Newton iterations, accepted load steps and the reaction at B |F_B| (kN).

Usage::

    python benches/static_hanging.py [--quick]     # --quick stops at n = 1000
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np
import pipelay as pl

LENGTH = 1200.0  # m
DEPTH = 800.0  # m
TOP = (850.0, 0.0, -DEPTH)  # m


def build(elements: int) -> pl.Model:
    """The pinned–pinned flooded pipe with ``elements`` elements."""
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0)
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (LENGTH, 0.0, 0.0), elements, section)
    model = pl.Model(rod, sea=pl.Sea(DEPTH))
    model.pin("A")
    model.pin("B", position=TOP)
    return model


def run(elements: int, start: str, repeats: int) -> tuple[float, pl.State]:
    """Best wall time (s) of ``repeats`` static solves from ``start``, and the last state."""
    best = float("inf")
    state = None
    for _ in range(repeats):
        model = build(elements)
        began = time.perf_counter()
        state = model.static(start=start)
        best = min(best, time.perf_counter() - began)
    assert state is not None
    return best, state


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at n = 1000")
    args = parser.parse_args(argv)

    sizes = [10, 100, 1000] if args.quick else [10, 100, 1000, 10000]
    print(
        f"static hanging pipe, pipelay {getattr(pl, '__version__', '?')}, Python {platform.python_version()}, "
        f"{platform.machine()}"
    )
    print()
    print("| n | start | wall time (s) | Newton iterations | load steps | reaction at B \\|F_B\\| (kN) |")
    print("| ---: | --- | ---: | ---: | ---: | ---: |")
    for n in sizes:
        for start in ("auto", "reference"):
            repeats = 1 if n >= 10000 else 3
            seconds, state = run(n, start, repeats)
            top = float(np.linalg.norm(state.reaction("B")[:3])) / 1e3
            row = f"| {n} | {start} | {seconds:.4f} | {state.iterations} | {state.steps} | {top:.1f} |"
            print(row, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
