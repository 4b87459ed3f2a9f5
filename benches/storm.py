"""Benchmark: a 3-hour JONSWAP storm on the J-lay of ``examples/j_lay_waves.toml``, its speed over real time and
the accuracy of its time step against a run at half the step.

Not a test. The example (140 elements in 800 m, seabed, DP, the OSV's RAOs, Hs 2.5 m, Tp 9 s, 200 components)
run for 3 h (10 800 s) of storm after its 90 s start, at Δt = `--dt` and at Δt/2, each recorded every 0.2 s
(every Δt for a longer step).
Prints the speed of each over real time, and for the reaction at B |F_B| (the pipe's pull on the tower) and the
hang-off bending moment (the top element's |M|): the largest (and for the tension the smallest) value, the
standard deviation and the response spectrum's peak and m0, at both steps and their difference.

Usage::

    python benches/storm.py [--dt 0.2] [--hours 3]
"""

from __future__ import annotations

import argparse
import time
import tomllib
from pathlib import Path

import numpy as np
from machine import machine
from pipelay.analysis.statistics import response_spectrum
from pipelay.scenario import parse_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
START = 90.0  # s: the waves' build-up and the transient, left out of the statistics
RECORD = 0.2  # s between records, at least


def storm(dt: float, seconds: float, record: float) -> tuple[float, dict[str, np.ndarray]]:
    """The run at step `dt` (s) for `seconds` of storm after START, recorded every `record` (s): its wall time
    (s, statics included) and the recorded reaction at B |F_B| (kN) and hang-off moment (kN·m) after START."""
    data = tomllib.loads((EXAMPLES / "j_lay_waves.toml").read_text())
    model = parse_scenario(data, folder=EXAMPLES).model
    began = time.perf_counter()
    state = model.static()
    every = round(record / dt)
    results = model.simulation(state, dt=dt).run(START + seconds, progress=False, record_every=every)
    wall = time.perf_counter() - began
    keep = results.time >= START - 1e-9
    forces = results.section_forces[keep]
    series = {
        "reaction at B \\|F_B\\| (kN)": np.linalg.norm(results.reaction("B")[keep, :3], axis=1) / 1e3,
        "hang-off moment (kN m)": np.hypot(forces[:, -1, 4], forces[:, -1, 5]) / 1e3,
    }
    return wall, series


def describe(values: np.ndarray, record: float) -> dict[str, float]:
    """Largest, smallest, standard deviation, spectral peak frequency (Hz) and m0 of a series recorded every
    `record` (s)."""
    spectrum = response_spectrum(values, record, segment=min(600.0, record * (len(values) - 1)))
    frequency, density = spectrum
    return {
        "max": float(values.max()),
        "min": float(values.min()),
        "std": float(values.std()),
        "m0": float(spectrum.m0),
        "peak Hz": float(frequency[int(np.argmax(density))]),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dt", type=float, default=0.2, help="the time step (s); also run at half of it")
    parser.add_argument("--hours", type=float, default=3.0, help="the storm's duration (h)")
    args = parser.parse_args()
    seconds = args.hours * 3600.0
    print(f"`python benches/storm.py --dt {args.dt:g} --hours {args.hours:g}`; {machine()}")
    print()
    record = max(RECORD, args.dt)
    runs = {dt: storm(dt, seconds, record) for dt in (args.dt, args.dt / 2)}
    print("| Δt (s) | wall time (s) | × real time |")
    print("| ---: | ---: | ---: |")
    for dt, (wall, _) in runs.items():
        print(f"| {dt:g} | {wall:.1f} | {(START + seconds) / wall:.0f} |")
    print()
    coarse, fine = runs[args.dt][1], runs[args.dt / 2][1]
    print(f"| series | statistic | Δt = {args.dt:g} s | Δt = {args.dt / 2:g} s | difference |")
    print("| --- | --- | ---: | ---: | ---: |")
    for name in coarse:
        one, two = describe(coarse[name], record), describe(fine[name], record)
        for key in one:
            if key == "min" and "moment" in name:
                continue  # |M| passes near zero: a relative difference there means nothing
            change = (one[key] - two[key]) / abs(two[key]) if two[key] else float("nan")
            print(f"| {name} | {key} | {one[key]:.5g} | {two[key]:.5g} | {change:+.2%} |")


if __name__ == "__main__":
    main()
