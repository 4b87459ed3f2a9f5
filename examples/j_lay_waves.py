"""J-lay in waves (examples/j_lay_waves.toml): what limits the operation in a sea state.

The scenario: a DP vessel keeps station in 800 m of water with the pipe hanging from its J-lay tower, in a
JONSWAP sea (Hs 2.5 m, Tp 9 s) at a relative heading of 30°. The vessel's wave-frequency motion comes from
its RAOs, superposed on the simulated low-frequency motion; the waves also load the pipe near the surface.

After the build-up and the start-up transient (the first 90 s, dropped), the script takes the 20 min record
of the sea surface at the vessel, the hang-off point's heave, the top tension at the tower and the largest
DNV-ST-F101 utilisation in the sagbend (suspended elements in the lower half of the water column; safety
class "low", grade X65), and prints for each its mean, standard deviation, extremes, zero up-crossing period
Tz and the most probable maximum (MPM) in a 3 h storm, by a Gumbel fit to block maxima and by the Gaussian
(Rayleigh) formula (see pipelay.statistics for when to trust which).

Writes to ``--out``: ``j_lay_waves_series.png`` (the time series) and ``j_lay_waves_spectra.png`` (their
response spectra). About two minutes on one core.

Usage::

    python examples/j_lay_waves.py [--out DIR] [--t-end SECONDS]
"""

from __future__ import annotations

import argparse
import time
import tomllib
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pipelay as pl
from pipelay import statistics
from pipelay.scenario import Scenario, parse_scenario

SCENARIO = Path(__file__).resolve().parent / "j_lay_waves.toml"
TRANSIENT = 90.0
"""Build-up and start-up transient dropped before the statistics (s)."""
STORM = 3 * 3600.0
"""Duration of the storm the most probable maxima refer to (s)."""


def run(t_end: float | None) -> tuple[Scenario, pl.Results, float]:
    """Statics, then the simulation to `t_end` (None: the file's); the scenario, results and wall time (s)."""
    data = tomllib.loads(SCENARIO.read_text(encoding="utf-8"))
    if t_end is not None:
        data["solver"]["t_end"] = t_end
        data.pop("output", None)
    scenario = parse_scenario(data, SCENARIO.name)
    start = time.perf_counter()
    state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    simulation = scenario.model.simulation(state=state, dt=scenario.dt)
    assert scenario.t_end is not None
    results = simulation.run(scenario.t_end, progress=False, record_every=scenario.record_every)
    return scenario, results, time.perf_counter() - start


def responses(scenario: Scenario, results: pl.Results) -> dict[str, tuple[np.ndarray, str]]:
    """The series the operation is judged by, after the transient: name → (values, unit)."""
    model = scenario.model
    depth = model.sea.depth
    keep = results.time >= TRANSIENT
    station = results.eta[0, :2]
    hang_off = results.positions[:, -1, :]
    summary = results.lay_summary()
    assert summary is not None and model.sea.waves is not None
    utilisation = statistics.utilisation(results, model=model, checks={"safety_class": "low"})
    middle = 0.5 * (results.positions[:, 1:, 2] + results.positions[:, :-1, 2])
    # e3 points down: the sagbend's suspended elements lie between half the depth and 1 m above the seabed.
    sagbend = (middle > -0.5 * depth) & (middle < -1.0)
    return {
        "surface elevation at the vessel": (model.sea.waves.elevation(results.time, *station)[keep], "m"),
        "hang-off heave": (-(hang_off[:, 2] - hang_off[keep, 2].mean())[keep], "m"),
        "top tension": (summary["top_tension"][keep] / 1e3, "kN"),
        "sagbend utilisation": (np.nanmax(np.where(sagbend, utilisation, np.nan), axis=1)[keep], "1"),
    }


def table(series: dict[str, tuple[np.ndarray, str]], step: float) -> list[dict[str, Any]]:
    """Mean, σ, min, max, Tz and the 3 h MPM (Gumbel, Rayleigh) of each series."""
    rows = []
    for name, (values, unit) in series.items():
        spectrum = statistics.response_spectrum(values, step)
        rows.append(
            {
                "name": name,
                "unit": unit,
                "mean": float(values.mean()),
                "std": spectrum.std,
                "min": float(values.min()),
                "max": float(values.max()),
                "tz": spectrum.tz,
                "gumbel": float(statistics.most_probable_maximum(values, step, STORM, "gumbel")),
                "rayleigh": float(statistics.most_probable_maximum(values, step, STORM, "rayleigh")),
            }
        )
    return rows


def plot(series: dict[str, tuple[np.ndarray, str]], times: np.ndarray, step: float, out: Path) -> None:
    """The time series and their response spectra, one panel each."""
    figure, axes = plt.subplots(len(series), 1, figsize=(9, 2.2 * len(series)), sharex=True)
    for ax, (name, (values, unit)) in zip(axes, series.items(), strict=True):
        ax.plot(times, values, lw=0.6)
        ax.set_ylabel(f"{name}\n({unit})", fontsize=8)
    axes[-1].set_xlabel("time (s)")
    figure.tight_layout()
    figure.savefig(out / "j_lay_waves_series.png", dpi=120)
    figure, axes = plt.subplots(len(series), 1, figsize=(7, 2.2 * len(series)), sharex=True)
    for ax, (name, (values, unit)) in zip(axes, series.items(), strict=True):
        frequency, density = statistics.response_spectrum(values, step)
        ax.plot(frequency, density)
        ax.set_ylabel(f"S ({unit}²/Hz)", fontsize=8)
        ax.set_title(name, fontsize=9)
    axes[-1].set_xlim(0.0, 0.4)
    axes[-1].set_xlabel("frequency (Hz)")
    figure.tight_layout()
    figure.savefig(out / "j_lay_waves_spectra.png", dpi=120)
    plt.close("all")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("output"), help="folder for the figures")
    parser.add_argument("--t-end", type=float, default=None, help="shorter run (s), e.g. for a quick look")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    scenario, results, wall = run(args.t_end)
    step = float(results.time[1] - results.time[0])
    series = responses(scenario, results)
    record = results.time[-1] - TRANSIENT
    print(
        f"{scenario.source.get('title', SCENARIO.name)}: {wall:.0f} s wall; record {record:.0f} s after the transient"
    )
    print(
        f"{'':34}{'unit':>6}{'mean':>11}{'σ':>9}{'min':>10}{'max':>10}{'Tz (s)':>8}{'3 h MPM':>10}{'(Rayl.)':>9}"
    )
    for row in table(series, step):
        print(
            f"{row['name']:34}{row['unit']:>6}{row['mean']:11.4g}{row['std']:9.3g}{row['min']:10.4g}"
            f"{row['max']:10.4g}{row['tz']:8.2f}{row['gumbel']:10.4g}{row['rayleigh']:9.4g}"
        )
    plot(series, results.time[results.time >= TRANSIENT], step, args.out)
    print(f"figures in {args.out}/j_lay_waves_series.png, j_lay_waves_spectra.png")


if __name__ == "__main__":
    main()
