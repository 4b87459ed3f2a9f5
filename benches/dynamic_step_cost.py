"""Benchmark: cost of one energy–momentum time step against the number of elements.

Not a test. The 1200 m flooded steel pipe of ``examples/hanging_pipe.py`` (pinned at the seabed, top at
(850, 0, −800) m, drag 1.2, added mass 1) starts from its static state; its top is driven in surge,
x_B(t) = 850 + 2.5(1 − cos(2πt/10)) m. Runs 2 s of Δt = 0.05 s at each n and prints a Markdown table: n,
steps, Newton iterations per step, wall time per step (ms) and per step and element (µs).

Usage::

    python benches/dynamic_step_cost.py [--quick]     # --quick stops at n = 1000
"""

from __future__ import annotations

import argparse
import math
import time

import pipelay as pl


def build(elements: int) -> pl.Model:
    """The driven flooded pipe with ``elements`` elements."""
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0, drag=(0.0, 1.2), added_mass=(0.0, 1.0))
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (1200.0, 0.0, 0.0), elements, section)
    model = pl.Model(rod, sea=pl.Sea(800.0))
    model.pin("A")
    omega = 2.0 * math.pi / 10.0
    model.drive(
        "B",
        position=lambda t: (850.0 + 2.5 * (1.0 - math.cos(omega * t)), 0.0, -800.0),
        velocity=lambda t: (2.5 * omega * math.sin(omega * t), 0.0, 0.0),
    )
    return model


def main(argv: list[str] | None = None) -> int:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at n = 1000")
    args = parser.parse_args(argv)
    sizes = [10, 100, 1000] if args.quick else [10, 100, 1000, 10000]
    dt, t_end = 0.05, 2.0
    print("| n | steps | Newton iterations per step | ms per step | µs per step and element |")
    print("| ---: | ---: | ---: | ---: | ---: |")
    for n in sizes:
        sim = build(n).simulation(dt=dt)
        began = time.perf_counter()
        res = sim.run(t_end, progress=False)
        seconds = time.perf_counter() - began
        steps = len(res) - 1
        iterations = float(res.iterations[1:].mean())
        per_step = 1e3 * seconds / steps
        print(f"| {n} | {steps} | {iterations:.2f} | {per_step:.3f} | {1e3 * per_step / n:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
