"""Benchmark: the size of a 3-D replay's HTML file, the time to write it and the time headless Chromium takes to
draw it, for a 3-hour run at 280 elements and 150, 300 and 600 frames.

Not a test, no timing assertions. The run: examples/j_lay_waves.toml (the J-lay tower of a DP vessel in 800 m
of water, a JONSWAP sea of Hs 2.5 m, Tp 9 s) with 280 elements, simulated for 10 800 s, made cheap by a time
step of 0.5 s (18 a peak period, against the example's 0.1 s) and a record every 10 s (1 081 records, all
real: nothing is synthesised); about a minute on 2 cores. The replay's colour is the tension; the files are
self-contained (plotly.js inline, whose own size is printed apart). The load time runs from the navigation
to the file:// page until plotly has drawn the 3-D scene (window.Plotly, the layout and the WebGL canvas,
then two animation frames), in Debian's Chromium with WebGL on SwiftShader (software), the best of 2.

Usage::

    python benches/replay_size.py            # needs chromium on PATH and playwright for the load times
"""

from __future__ import annotations

import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

from pipelay.plots.replay import replay
from pipelay.scenario import apply_overrides, parse_scenario
from plotly.offline import get_plotlyjs

ROOT = Path(__file__).resolve().parent.parent
T_END, DT, RECORD_EVERY, ELEMENTS = 10_800.0, 0.5, 20, 280
FRAMES = (150, 300, 600)
CHROMIUM_ARGS = ["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
DRAWN = """() => {
    const gd = document.querySelector('.js-plotly-plot');
    return !!(window.Plotly && gd && gd._fullLayout && gd._fullLayout.scene && gd._fullLayout.scene._scene
              && gd.querySelector('.gl-container canvas'));
}"""
TWO_FRAMES = "() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r())))"


def header() -> None:
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        commit = subprocess.run(
            ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        commit += " (with uncommitted changes)" if dirty else ""
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    print(f"command: {' '.join([Path(sys.executable).name, *sys.argv])}")
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    print(f"machine: {cores} cores (nproc), {cpu}, {platform.system()} {platform.release()}")
    print(f"git commit: {commit}")


def run() -> tuple[object, object, float]:
    data = tomllib.loads((ROOT / "examples" / "j_lay_waves.toml").read_text())
    scenario = parse_scenario(apply_overrides(data, {"rod.elements": ELEMENTS}))
    model = scenario.model
    start = time.perf_counter()
    state = model.static()
    results = model.simulation(state=state, dt=DT).run(T_END, record_every=RECORD_EVERY, progress=False)
    return results, model, time.perf_counter() - start


def load_times(paths: list[Path]) -> list[float | None]:
    """The best of 2 load times of each page (s), None each without Chromium or playwright."""
    executable = shutil.which("chromium")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        executable = None
    if executable is None:
        print("(no chromium on PATH or no playwright: no load times)")
        return [None] * len(paths)
    times: list[float | None] = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=executable, args=CHROMIUM_ARGS)
        try:
            for path in paths:
                best = float("inf")
                for _ in range(2):
                    page = browser.new_page(viewport={"width": 1280, "height": 800})
                    start = time.perf_counter()
                    page.goto(path.resolve().as_uri(), wait_until="commit", timeout=120_000)
                    page.wait_for_function(DRAWN, timeout=120_000, polling=20)
                    page.evaluate(TWO_FRAMES)
                    best = min(best, time.perf_counter() - start)
                    page.close()
                times.append(best)
        finally:
            browser.close()
    return times


def main() -> None:
    header()
    results, model, seconds = run()
    print(
        f"run: examples/j_lay_waves.toml, {ELEMENTS} elements, {T_END:g} s at dt = {DT:g} s, a record every "
        f"{RECORD_EVERY * DT:g} s: {len(results.time)} records, simulated in {seconds:.1f} s"
    )
    plotly_js = len(get_plotlyjs().encode("utf-8")) / 1e6
    print(f"plotly.js inline: {plotly_js:.2f} MB of each file")
    print()
    with tempfile.TemporaryDirectory() as folder:
        rows = []
        for frames in FRAMES:
            path = Path(folder) / f"replay_{frames}.html"
            start = time.perf_counter()
            replay(results, model, max_frames=frames, path=path)
            rows.append((frames, path, path.stat().st_size / 1e6, time.perf_counter() - start))
        loads = load_times([row[1] for row in rows])
    print("| max_frames | HTML file (MB) | above plotly.js (MB) | write (s) | load in Chromium (s) |")
    print("| ---: | ---: | ---: | ---: | ---: |")
    for (frames, _, size, write), load in zip(rows, loads, strict=True):
        shown = "n/a" if load is None else f"{load:.2f}"
        print(f"| {frames} | {size:.2f} | {size - plotly_js:.2f} | {write:.2f} | {shown} |")


if __name__ == "__main__":
    main()
