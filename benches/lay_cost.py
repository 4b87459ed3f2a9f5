"""Benchmark: statics and time steps of the S-lay example against the number of elements, with and without
the stinger's rollers.

Not a test. ``examples/s_lay.toml``: a 0.6 m × 30 mm steel pipe (empty), 700 m, pinned at A on a seabed with
friction, held by an OSV's tensioner over a 200 m-radius, 100 m stinger of 15 rollers, in 150 m of water,
the vessel held by its static thrust. The same model held without rollers at the tensioner's position at the
example's departure angle (a J-lay whose tower leans 62° from vertical) gives the rollers' cost. Statics from the lay guess;
then 2 s of Δt = 0.1 s. Prints a Markdown table.

Usage::

    python benches/lay_cost.py [--quick]     # --quick stops at n = 1000
"""

from __future__ import annotations

import argparse
import copy
import time
import tomllib
from pathlib import Path

import pipelay as pl
from machine import machine
from pipelay.scenario import parse_scenario

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "s_lay.toml"


def build(elements: int, rollers: bool) -> pl.Model:
    """The example with `elements` elements, with or without its stinger, no controller."""
    data = tomllib.loads(EXAMPLE.read_text())
    data = copy.deepcopy(data)
    data["rod"]["elements"] = elements
    data.pop("controller")
    if not rollers:
        data["vessel"]["lay"] = {"kind": "j-lay", "position": [10.0, 0.0, -6.3], "angle": 1.08}
    return parse_scenario(data).model


def measure(elements: int, rollers: bool) -> tuple[float, float, int]:
    """Statics time (s), cost per step (ms) and Newton iterations per step."""
    model = build(elements, rollers)
    start = time.perf_counter()
    state = model.static()
    statics = time.perf_counter() - start
    simulation = model.simulation(state, dt=0.1)
    simulation.step()  # warm-up
    steps = 20
    start = time.perf_counter()
    iterations = 0
    for _ in range(steps):
        simulation.step()
        iterations += simulation.state.iterations
    return statics, 1e3 * (time.perf_counter() - start) / steps, iterations // steps


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at n = 1000")
    args = parser.parse_args(argv)
    sizes = (280, 1000) if args.quick else (280, 1000, 3000)
    print(f"`python benches/lay_cost.py{' --quick' if args.quick else ''}`; {machine()}")
    print(
        "| n | statics, rollers (s) | step, rollers (ms) | Newton its | statics, no rollers (s) | step, no rollers (ms) | ratio |"
    )
    print("|---|---|---|---|---|---|---|")
    for n in sizes:
        with_statics, with_step, its = measure(n, True)
        without_statics, without_step, _ = measure(n, False)
        print(
            f"| {n} | {with_statics:.3f} | {with_step:.2f} | {its} | {without_statics:.3f} | {without_step:.2f} "
            f"| {with_step / without_step:.2f} |"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
