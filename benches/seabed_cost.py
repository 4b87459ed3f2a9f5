"""Benchmark: statics and time steps of a pipe resting on the seabed, against the number of elements.

Not a test. The touchdown case (``examples/touchdown.toml``): a flooded 0.6 m × 15 mm steel pipe, 1600 m long,
pinned on the seabed at A and at its top (1200, 0, −800) m, about 400 m of it on an elastic seabed
(k = 1e5 Pa/m) with friction 0.5 axial and 0.8 lateral (mobilisation 1 cm), drag 1.2 and added mass 1.
Statics from the catenary resting on the seabed; then 2 s of Δt = 0.05 s with the top driven in surge,
x_B(t) = 1200 + 2.5(1 − cos(2πt/10)) m. The same pipe without a seabed (it then hangs through the bottom)
gives the cost of the contact. Prints a Markdown table.

Usage::

    python benches/seabed_cost.py [--quick]     # --quick stops at n = 1000
"""

from __future__ import annotations

import argparse
import math
import time

import pipelay as pl


def build(elements: int, seabed: bool) -> pl.Model:
    """The touchdown pipe with ``elements`` elements, with or without the seabed, top driven."""
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0, drag=(0.0, 1.2), added_mass=(0.0, 1.0))
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (1600.0, 0.0, 0.0), elements, section)
    bottom = pl.Seabed(stiffness=1e5, friction=(0.5, 0.8), mobilisation=0.01) if seabed else None
    model = pl.Model(rod, sea=pl.Sea(800.0, seabed=bottom))
    model.pin("A")
    omega = 2.0 * math.pi / 10.0
    model.drive(
        "B",
        position=lambda t: (1200.0 + 2.5 * (1.0 - math.cos(omega * t)), 0.0, -800.0),
        velocity=lambda t: (2.5 * omega * math.sin(omega * t), 0.0, 0.0),
    )
    return model


def main(argv: list[str] | None = None) -> int:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at n = 1000")
    args = parser.parse_args(argv)
    sizes = [100, 1000] if args.quick else [100, 1000, 10000]
    dt, t_end = 0.05, 2.0
    print(
        "| n | seabed | statics (s) | Newton iterations | touchdown (m from A) | steps | iterations per step "
        "| ms per step | µs per step and element |"
    )
    print("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in sizes:
        for seabed in (False, True):
            model = build(n, seabed)
            began = time.perf_counter()
            state = model.static()
            statics = time.perf_counter() - began
            touchdown = state.touchdown
            where = f"{touchdown.arc_length:.2f}" if touchdown is not None else "–"
            sim = model.simulation(state=state, dt=dt)
            began = time.perf_counter()
            res = sim.run(t_end, progress=False)
            seconds = time.perf_counter() - began
            steps = len(res) - 1
            per_step = 1e3 * seconds / steps
            print(
                f"| {n} | {'yes' if seabed else 'no'} | {statics:.3f} | {state.iterations} | {where} | {steps} "
                f"| {float(res.iterations[1:].mean()):.2f} | {per_step:.3f} | {1e3 * per_step / n:.2f} |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
