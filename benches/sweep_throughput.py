"""Benchmark: a sweep's throughput on this machine's cores against the same runs as independent processes.

Not a test. The J-lay of ``examples/j_lay_waves.toml`` (1290 s simulated), two cases that differ in the sea's
seed: once as two ``pipelay run`` processes started together, once as ``pipelay sweep ... --over
sea.waves.seed=1,2 --workers 2`` (a local Dask cluster of two single-threaded worker processes, started and
stopped by the sweep). Prints the wall time of each (the best of `--repeat`) and their ratio (the issue's goal:
the sweep within 10 % of the independent runs).

Usage::

    python benches/sweep_throughput.py [--repeat 2] [--t-end 1290]
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from machine import machine

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
PIPELAY = [sys.executable, "-m", "pipelay"]


def scenario(folder: Path, t_end: float) -> Path:
    """The J-lay example with `t_end` (s), written into `folder`."""
    text = (EXAMPLES / "j_lay_waves.toml").read_text()
    text = text.replace("t_end = 1290.0", f"t_end = {t_end}")
    text = "\n".join(line for line in text.splitlines() if not line.startswith("plot_times"))
    path = folder / "j_lay.toml"
    path.write_text(text)
    return path


def independent(path: Path, folder: Path) -> float:
    """Wall time (s) of the two seeds as two `pipelay run` processes started together."""
    runs = []
    began = time.perf_counter()
    for seed in (1, 2):
        text = path.read_text().replace("seed = 1", f"seed = {seed}")
        case = folder / f"seed{seed}.toml"
        case.write_text(text)
        command = [*PIPELAY, "run", str(case), "-o", str(folder / f"seed{seed}.nc"), "--no-progress"]
        runs.append(subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    for run in runs:
        if run.wait() != 0:
            raise RuntimeError("pipelay run failed")
    return time.perf_counter() - began


def swept(path: Path, folder: Path) -> float:
    """Wall time (s) of the two seeds as one `pipelay sweep` on two local workers."""
    output = folder / "sweep"
    shutil.rmtree(output, ignore_errors=True)
    command = [
        *PIPELAY, "sweep", str(path), "--over", "sea.waves.seed=1,2", "-o", str(output), "--workers", "2",
        "--no-progress",
    ]  # fmt: skip
    began = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - began


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--t-end", type=float, default=1290.0)
    args = parser.parse_args()
    print(f"`python benches/sweep_throughput.py --repeat {args.repeat} --t-end {args.t_end:g}`; {machine()}")
    print()
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        path = scenario(folder, args.t_end)
        alone = min(independent(path, folder) for _ in range(args.repeat))
        together = min(swept(path, folder) for _ in range(args.repeat))
    print("| two cases as | wall time (s) |")
    print("| --- | ---: |")
    print(f"| two `pipelay run` processes | {alone:.1f} |")
    print(f"| `pipelay sweep --workers 2` | {together:.1f} |")
    print(f"| ratio | {together / alone:.3f} |")


if __name__ == "__main__":
    main()
