"""Steady J-lay (examples/steady_lay.toml) with and without the lay-tension loop.

The scenario: a DP vessel follows a straight route at 0.4 m/s in 800 m of water while its J-lay tower pays
the pipe out at the route's speed; a sheared cross current switches on half-way. The file's
`[controller.tension]` table is the lay-tension loop; this script runs the scenario as written and once more
with that table removed, both from their static states.

Writes to ``--out``: ``steady_lay_tension.png`` (top tension of both runs, with the loop's target),
``steady_lay_touchdown.png`` and ``steady_lay_accuracy.png`` (the touchdown's track and the laid pipe's
deviation from the route, with the loop). Prints, for each run: the pipe length paid out, the mean and
standard deviation of the top tension over the second half, the touchdown's advance along the route against
the vessel's, the largest lateral deviation of the laid pipe from the route, and the wall time. Both runs go
at once (the engine releases the GIL while it steps): about 80 s on two cores.

Usage::

    python examples/steady_lay.py [--out DIR] [--t-end SECONDS]
"""

from __future__ import annotations

import argparse
import copy
import time
import tomllib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
from pipelay import plots
from pipelay.scenario import parse_scenario

SCENARIO = Path(__file__).resolve().parent / "steady_lay.toml"


def load(tension_loop: bool, t_end: float | None = None) -> dict[str, Any]:
    """The scenario's TOML as a dict, with or without `[controller.tension]`, optionally shortened."""
    data = tomllib.loads(SCENARIO.read_text(encoding="utf-8"))
    if not tension_loop:
        data["controller"].pop("tension", None)
    if t_end is not None:
        data["solver"]["t_end"] = t_end
        times = data.get("output", {}).get("plot_times")
        if times is not None:
            data["output"]["plot_times"] = [t for t in times if t <= t_end]
    return data


def run(data: dict[str, Any], name: str) -> tuple[pl.Results, float]:
    """Statics, then the simulation to solver.t_end; the results and the wall time (s)."""
    scenario = parse_scenario(copy.deepcopy(data), name)
    start = time.perf_counter()
    state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    simulation = scenario.model.simulation(state=state, dt=scenario.dt)
    assert scenario.t_end is not None
    results = simulation.run(scenario.t_end, progress=False, record_every=scenario.record_every)
    return results, time.perf_counter() - start


def route_of(data: dict[str, Any]) -> pl.Route:
    """The scenario's `[controller.route]` as a pl.Route."""
    return pl.Route(**data["controller"]["route"])


def table(results: pl.Results, route: pl.Route) -> dict[str, float]:
    """The run's figures of merit (SI units)."""
    time_ = results.time
    summary = results.lay_summary()
    assert summary is not None
    tension = summary["top_tension"]
    late = time_ >= 0.5 * time_[-1]
    pose, _ = route.at(0.0)
    direction = np.array([np.cos(pose[5]), np.sin(pose[5])])
    touchdown = results.touchdown
    assert touchdown is not None and results.eta is not None
    vessel_along = results.eta[:, :2] @ direction
    touchdown_along = touchdown[:, :2] @ direction
    half = int(np.argmax(late))
    _, across = plots.lay_deviation(results, route)
    return {
        "paid_out": float(results.length[-1] - results.length[0]),
        "tension_mean": float(np.nanmean(tension[late])),
        "tension_std": float(np.nanstd(tension[late])),
        "vessel_advance": float(vessel_along[-1] - vessel_along[0]),
        "touchdown_advance": float(touchdown_along[-1] - touchdown_along[0]),
        "late_ratio": float(
            (touchdown_along[-1] - touchdown_along[half]) / (vessel_along[-1] - vessel_along[half])
        ),
        "deviation": float(np.max(np.abs(across))) if len(across) else float("nan"),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("output"), help="directory for the figures")
    parser.add_argument("--t-end", type=float, default=None, help="end time (s); default: the scenario's")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    variants = {"with tension loop": load(True, args.t_end), "without": load(False, args.t_end)}
    # The engine releases the GIL while it steps, so the two runs share the machine's cores.
    with ThreadPoolExecutor(max_workers=len(variants)) as pool:
        futures = {name: pool.submit(run, data, name) for name, data in variants.items()}
        runs = {name: future.result() for name, future in futures.items()}

    data = variants["with tension loop"]
    route = route_of(data)
    target = data["controller"]["tension"]["target"]
    results = {name: r for name, (r, _) in runs.items()}
    figures = [
        plots.tension_comparison(results, target=target, path=args.out / "steady_lay_tension.png"),
        plots.touchdown_track(
            results["with tension loop"], route=route, path=args.out / "steady_lay_touchdown.png"
        ),
        plots.lay_accuracy(
            results["with tension loop"],
            route=route,
            times=[0.5 * results["with tension loop"].time[-1], results["with tension loop"].time[-1]],
            path=args.out / "steady_lay_accuracy.png",
        ),
    ]
    del figures

    t_end = data["solver"]["t_end"]
    print(f"steady J-lay, {t_end:g} s, target top tension {target / 1e3:g} kN")
    header = (
        f"{'run':<18} {'paid out':>9} {'T mean':>8} {'T std':>7} {'vessel':>8} {'touchdown':>9} "
        f"{'ratio 2nd':>9} {'max dev':>8} {'wall':>6}"
    )
    print(header)
    print(f"{'':<18} {'m':>9} {'kN':>8} {'kN':>7} {'m':>8} {'m':>9} {'':>9} {'m':>8} {'s':>6}")
    for name, (r, wall) in runs.items():
        row = table(r, route)
        print(
            f"{name:<18} {row['paid_out']:9.2f} {row['tension_mean'] / 1e3:8.1f} "
            f"{row['tension_std'] / 1e3:7.1f} {row['vessel_advance']:8.2f} {row['touchdown_advance']:9.2f} "
            f"{row['late_ratio']:9.4f} {row['deviation']:8.2f} {wall:6.1f}"
        )
    print("T mean, T std: top tension over the second half; vessel, touchdown: advance along the route;")
    print(
        "ratio 2nd: touchdown advance / vessel advance in the second half; max dev: laid pipe off the route"
    )
    print(
        f"figures: {args.out / 'steady_lay_tension.png'}, steady_lay_touchdown.png, steady_lay_accuracy.png"
    )


if __name__ == "__main__":
    main()
