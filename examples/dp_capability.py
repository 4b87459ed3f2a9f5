"""DP capability of the S-lay example (examples/s_lay.toml) at 1000 kN top tension, with and without the pipe.

The scenario: the OSV lays a 24-inch steel pipe in 150 m of water over an 80 m stinger. The vessel is moved
along the lay direction until the static top tension at the tensioner is 1000 kN (`find_lay_position`, a few
static solves); the pipe's force on the vessel there (body frame) is the load the thrusters hold besides the
environment. `dp_capability` then finds, every 15°, the largest wind speed (1-hour mean at 10 m) at which the
thrusters balance the wind, a co-linear 0.75 m/s current, the mean drift of the sea of that wind on the
Beaufort scale (H_s the WMO scale's, T_p = 4.2 √H_s) and the pipe; the same for the vessel alone.

Writes ``dp_capability.png`` to ``--out`` (both envelopes on one polar plot: 0° head-on at the top, 90° from
starboard on the right) and prints the vessel position, the pipe load and the table of both envelopes. About
two seconds.

Usage::

    python examples/dp_capability.py [--out DIR] [--tension NEWTONS] [--current M/S]
"""

from __future__ import annotations

import argparse
import copy
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
from pipelay import plots
from pipelay.analysis import Capability, dp_capability
from pipelay.analysis.lay import LayPosition
from pipelay.scenario import Scenario, parse_scenario

SCENARIO = Path(__file__).resolve().parent / "s_lay.toml"
HEADINGS = np.radians(np.arange(0.0, 360.0, 15.0))


def at(data: dict[str, Any], x: float) -> Scenario:
    """The scenario with the vessel (and its DP reference) moved to x (m) along e1."""
    moved = copy.deepcopy(data)
    shift = x - moved["vessel"]["eta"][0]
    moved["vessel"]["eta"][0] = x
    moved["controller"]["reference"][0] += shift
    return parse_scenario(moved, str(SCENARIO))


def envelopes(tension: float, current: float) -> tuple[Capability, Capability, LayPosition]:
    """The capability with the pipe at top tension `tension` (N) and of the vessel alone, and where the vessel
    is for that tension."""
    data = tomllib.loads(SCENARIO.read_text(encoding="utf-8"))
    found = pl.find_lay_position(
        lambda x: at(data, x).model, "top_tension", tension, start=data["vessel"]["eta"][0]
    )
    pipe = dp_capability(
        at(data, found.x), HEADINGS, current=current, label=f"with the pipe, {tension / 1e3:g} kN top tension"
    )
    alone = dp_capability(pl.Vessel.osv(), HEADINGS, current=current, label="vessel alone")
    return pipe, alone, found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("output"), help="directory for the figure")
    parser.add_argument("--tension", type=float, default=1e6, help="top tension (N), default 1e6")
    parser.add_argument("--current", type=float, default=0.75, help="co-linear current (m/s), default 0.75")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    pipe, alone, found = envelopes(args.tension, args.current)
    load = pipe.pipe_load + 0.0  # no −0.0 shown
    print(f"S-lay: vessel at x = {found.x:.2f} m for a top tension of {found.value / 1e3:.1f} kN")
    print(
        f"pipe load on the vessel (body frame): X {load[0] / 1e3:.1f} kN, Y {load[1] / 1e3:.1f} kN, "
        f"Z {load[2] / 1e3:.1f} kN, N {load[5] / 1e3:.1f} kN m (the thrusters hold X, Y, N)"
    )
    print(f"largest wind speed held (m/s), environment from the heading; current {args.current:g} m/s")
    print(f"{'heading':>8} {'alone':>7} {'pipe':>7} {'change':>7}")
    for heading, bare, loaded in zip(pipe.heading_deg, alone.wind_speed, pipe.wind_speed, strict=True):
        capped = " (held to 60 m/s, the search's limit)" if loaded >= pipe.max_wind else ""
        print(f"{heading:7.0f}° {bare:7.2f} {loaded:7.2f} {loaded - bare:+7.2f}{capped}")
    path = args.out / "dp_capability.png"
    plots.capability(
        [alone, pipe],
        path=path,
        title=(
            f"DP capability of the OSV, S-lay at {found.value / 1e3:.0f} kN top tension\n"
            f"environment from (relative to the bow), current {args.current:g} m/s, Beaufort sea\n"
            f"pipe load X = {load[0] / 1e3:.0f} kN (body frame)"
        ),
    )
    print(f"figure: {path}")


if __name__ == "__main__":
    main()
