"""Benchmark: what an irregular sea costs on top of the same run in calm water, with everything else on.

Not a test. Three models, each run with its JONSWAP sea (200 components, the vessel moving with its RAOs)
and again without the sea (`[sea.waves]` removed), everything else the same (seabed with friction, DP,
rollers or tower):

* the J-lay of ``examples/j_lay_waves.toml`` (140 elements in 800 m, Hs 2.5 m, Tp 9 s);
* the S-lay of ``examples/s_lay.toml`` at n = 250 and n = 1000 with the J-lay's sea (built up over 2 s).

Statics, 50 steps of Δt = 0.1 s past the start, then `--steps` steps timed, the best of `--repeat` runs.
Prints a Markdown table: ms per step with and without the sea and their ratio (the issue's goal: ≤ 1.2), and
the speed over real time of the run with the sea.

Usage::

    python benches/sea_cost.py [--steps 100] [--repeat 3]
"""

from __future__ import annotations

import argparse
import copy
import time
import tomllib
from pathlib import Path
from typing import Any

from machine import machine
from pipelay.scenario import parse_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
DT = 0.1


def j_lay(waves: bool) -> dict[str, Any]:
    """The J-lay example's data, with or without its sea."""
    data = tomllib.loads((EXAMPLES / "j_lay_waves.toml").read_text())
    if not waves:
        del data["sea"]["waves"]
    return data


def s_lay(elements: int, waves: bool) -> dict[str, Any]:
    """The S-lay example with `elements` elements, with or without the J-lay example's sea."""
    data = copy.deepcopy(tomllib.loads((EXAMPLES / "s_lay.toml").read_text()))
    data["rod"]["elements"] = elements
    if waves:
        sea = tomllib.loads((EXAMPLES / "j_lay_waves.toml").read_text())["sea"]["waves"]
        data["sea"]["waves"] = {**sea, "ramp": 2.0}
    return data


def cost(data: dict[str, Any], steps: int, repeat: int) -> float:
    """The best cost per step (ms) over `repeat` runs of `steps` steps after 50 untimed ones."""
    model = parse_scenario(data, folder=EXAMPLES).model
    state = model.static()
    best = float("inf")
    for _ in range(repeat):
        simulation = model.simulation(state, dt=DT)
        for _ in range(50):
            simulation.step()
        began = time.perf_counter()
        for _ in range(steps):
            simulation.step()
        best = min(best, (time.perf_counter() - began) / steps * 1e3)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"`python benches/sea_cost.py --steps {args.steps} --repeat {args.repeat}`; {machine()}")
    print()
    print("| model | calm ms/step | sea ms/step | sea / calm | sea run × real time |")
    print("| --- | --- | --- | --- | --- |")
    cases = [
        ("J-lay, examples/j_lay_waves.toml, n = 140", j_lay),
        ("S-lay, examples/s_lay.toml, n = 250", lambda waves: s_lay(250, waves)),
        ("S-lay, examples/s_lay.toml, n = 1000", lambda waves: s_lay(1000, waves)),
    ]
    for name, build in cases:
        calm = cost(build(False), args.steps, args.repeat)
        sea = cost(build(True), args.steps, args.repeat)
        print(f"| {name} | {calm:.2f} | {sea:.2f} | {sea / calm:.2f} | {DT * 1e3 / sea:.0f} |")


if __name__ == "__main__":
    main()
