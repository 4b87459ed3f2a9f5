"""Benchmark: the cost of a time step with everything on (seabed with friction, current, the stinger's
rollers, the DP vessel and a JONSWAP sea with the vessel's RAOs) against the number of elements.

Not a test. ``examples/s_lay.toml`` (700 m of 0.6 m × 30 mm pipe from a seabed with friction over an OSV's
15-roller stinger, PD station keeping, a current) with the sea of ``examples/j_lay_waves.toml`` added (JONSWAP
Hs 2.5 m, Tp 9 s, 200 components, 30° off the bow, built up over 2 s). Statics from the lay guess, 5 s of
Δt = 0.1 s to pass the start's transient, then 20 steps timed; the same without the waves for their share.
Prints a Markdown table: ms per step, and µs per step and element, which stays flat when the cost is linear
in n.

Usage::

    python benches/full_cost.py [--quick]     # --quick stops at n = 1000
"""

from __future__ import annotations

import argparse
import copy
import time
import tomllib
from pathlib import Path

import pipelay as pl
from pipelay.scenario import parse_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def build(elements: int, waves: bool) -> pl.Model:
    """The S-lay example with `elements` elements, with or without the J-lay example's sea state."""
    data = copy.deepcopy(tomllib.loads((EXAMPLES / "s_lay.toml").read_text()))
    data["rod"]["elements"] = elements
    if waves:
        sea = tomllib.loads((EXAMPLES / "j_lay_waves.toml").read_text())["sea"]["waves"]
        data["sea"]["waves"] = {**sea, "ramp": 2.0}
    return parse_scenario(data, folder=EXAMPLES).model


def measure(elements: int, waves: bool, steps: int = 20) -> tuple[float, float, float]:
    """Statics time (s), cost per step (ms) and Newton iterations per step."""
    model = build(elements, waves)
    began = time.perf_counter()
    state = model.static()
    statics = time.perf_counter() - began
    simulation = model.simulation(state, dt=0.1)
    for _ in range(50):  # past the start's transient
        simulation.step()
    iterations = 0
    began = time.perf_counter()
    for _ in range(steps):
        simulation.step()
        iterations += simulation.state.iterations
    return statics, 1e3 * (time.perf_counter() - began) / steps, iterations / steps


def main(argv: list[str] | None = None) -> int:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="stop at n = 1000")
    args = parser.parse_args(argv)
    sizes = [250, 1000] if args.quick else [250, 1000, 4000]
    print("| n | waves | statics (s) | Newton its per step | ms per step | µs per step and element |")
    print("| ---: | --- | ---: | ---: | ---: | ---: |")
    for n in sizes:
        for waves in (False, True):
            statics, per_step, iterations = measure(n, waves)
            print(
                f"| {n} | {'yes' if waves else 'no'} | {statics:.3f} | {iterations:.2f} | {per_step:.2f} "
                f"| {1e3 * per_step / n:.2f} |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
