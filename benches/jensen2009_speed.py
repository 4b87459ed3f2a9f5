"""Benchmark: wall time of the paper's 200 s scenario (examples/jensen2009.py, PD controller) at n = 10 and
n = 100 elements, for several time steps, with the accuracy each step size gives.

Not a test. Times statics plus the 200 s simulation (best of 7: the machine is shared). Accuracy: the largest
difference in η(t) (x, y, ψ) over the run against the same run at Δt = 0.025 s. Prints a Markdown table.

Usage::

    python benches/jensen2009_speed.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import jensen2009 as paper


def timed(elements: int, dt: float, repeats: int = 7) -> tuple[float, np.ndarray, np.ndarray]:
    """Best wall time (s), times and η history of the PD run."""
    best = float("inf")
    results = None
    for _ in range(repeats):
        began = time.perf_counter()
        _, results, _ = paper.run("PD", paper.controllers()["PD"], elements, dt)
        best = min(best, time.perf_counter() - began)
    assert results is not None
    return best, results.time, results.eta


def main() -> int:
    """Print the table."""
    print("| n | Δt (s) | steps | wall time (s) | max |Δx|, |Δy| (m) vs Δt = 0.025 s | max |Δψ| (rad) |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    for elements in (10, 100):
        _, ref_time, ref_eta = timed(elements, 0.025, repeats=1)
        for dt in (0.25, 0.1):
            seconds, t, eta = timed(elements, dt)
            reference = np.column_stack([np.interp(t, ref_time, ref_eta[:, k]) for k in range(6)])
            position = np.max(np.abs(eta[:, :2] - reference[:, :2]))
            heading = np.max(np.abs(eta[:, 5] - reference[:, 5]))
            steps = len(t) - 1
            print(
                f"| {elements} | {dt} | {steps} | {seconds:.3f} | {position:.2e} | {heading:.2e} |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
