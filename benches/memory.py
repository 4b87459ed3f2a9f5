"""Peak memory against run length: a run kept in memory against the same run streamed to a netCDF file.

A 200 m pipe of 500 elements hanging in 300 m of water from a drive swaying 0.5 m, Δt = 0.1 s, every step recorded,
run for 1×, 2×, 4× and 8× 30 s, each run in a fresh process. In memory the records (~22 numbers a node) pile up,
88 kB each; streamed (``run(..., output=path)``, default segments of at most 32 MB of records) the peak stops
growing once a segment is full. Peak RSS is the process's VmHWM (Linux); "before" is the RSS after the statics,
before the run. Prints a Markdown table.

Usage::

    python benches/memory.py [--elements N] [--seconds T]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

RUN = """
import time
import numpy as np
import pipelay as pl

def rss(key):
    return next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith(key)) / 1024

section = pl.Section.pipe(0.3, 0.02, contents_density=0.0, drag=(0.1, 1.0), added_mass=(0.0, 1.0))
model = pl.Model(pl.Rod.straight((0, 0, 200), (0, 0, 0), {elements}, section), sea=pl.Sea(300.0))
model.drive("B", position=lambda t: np.array([0.5 * np.sin(0.3 * t), 0.0, 0.0]))
simulation = model.simulation(model.static(), dt=0.1)
output = {output!r}
if output is not None:
    import h5netcdf  # imported before the baseline, as the in-memory run's figures do not include it
before = rss("VmRSS")
start = time.perf_counter()
results = simulation.run({t_end}, progress=False, output=output)
wall = time.perf_counter() - start
print(before, rss("VmHWM"), wall)
"""


def measure(elements: int, t_end: float, output: Path | None) -> tuple[float, float, float]:
    """(RSS before the run, peak RSS, wall time of the run) of one run in a fresh process (MB, MB, s)."""
    code = RUN.format(elements=elements, t_end=t_end, output=None if output is None else str(output))
    done = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    before, peak, wall = (float(value) for value in done.stdout.split())
    return before, peak, wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements", type=int, default=500)
    parser.add_argument("--seconds", type=float, default=30.0, help="simulated time of the 1x run (s)")
    args = parser.parse_args()
    if not Path("/proc/self/status").exists():
        raise SystemExit("needs /proc/self/status (Linux) for the peak RSS")
    print(f"{args.elements} elements, Δt = 0.1 s, every step recorded; peak RSS (VmHWM) of a fresh process\n")
    print(
        "| simulated time | records | in memory: before → peak (growth) | streamed: before → peak (growth) "
        "| file | wall in memory / streamed |"
    )
    print("| --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as folder:
        for factor in (1, 2, 4, 8):
            t_end = factor * args.seconds
            path = Path(folder) / f"run{factor}.nc"
            m_before, m_peak, m_wall = measure(args.elements, t_end, None)
            s_before, s_peak, s_wall = measure(args.elements, t_end, path)
            records = round(t_end / 0.1) + 1
            print(
                f"| {t_end:g} s ({factor}×) | {records} | {m_before:.0f} → {m_peak:.0f} MB (+{m_peak - m_before:.0f}) "
                f"| {s_before:.0f} → {s_peak:.0f} MB (+{s_peak - s_before:.0f}) "
                f"| {path.stat().st_size / 2**20:.0f} MB | {m_wall:.1f} s / {s_wall:.1f} s |",
                flush=True,
            )


if __name__ == "__main__":
    main()
