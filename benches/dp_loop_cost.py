"""Benchmark: what a DP loop as engineers design it costs per time step.

Not a test. The 1200 m flooded steel pipe of ``benches/dynamic_step_cost.py`` (pinned at the seabed, 800 m of
water) in 10 and 100 elements, its top held by the OSV under PD control about a set-point 20 m off its static
pose, runs 100 s of Δt = 0.1 s: with the implicit PID (τ at the step's midpoint); with thrust allocation
(Clarabel, within the six thrusters' rates and lag); with allocation and the passive observer on noisy
measurements; and with wind and current on the hull besides; then in a JONSWAP sea (Hs 2.5 m, 100 components)
with the implicit PID and no hull loads, and with the whole loop and the hull's drift. Prints a Markdown table:
elements, loop, steps, wall time per step (ms) and the overhead over the first row of its kind (µs per step).

Usage::

    python benches/dp_loop_cost.py
"""

from __future__ import annotations

import math
import time

import pipelay as pl

LOOPS = {
    "implicit PID": ({}, False, False),
    "allocation": ({"allocation": "qp"}, False, False),
    "allocation + observer": ({"allocation": "qp", "observer": True}, False, False),
    "… + wind and current on the hull": ({"allocation": "qp", "observer": True}, True, False),
    "waves, implicit PID": ({}, False, True),
    "waves, whole loop + hull drift": ({"allocation": "qp", "observer": True}, True, True),
}


def build(elements: int, loop: str) -> pl.Model:
    """The pipe with `elements` elements held by the OSV under the DP loop `loop`."""
    options, hull, waves = LOOPS[loop]
    options = dict(options)
    if options.pop("observer", False):
        options["observer"] = pl.Observer.passive(noise=(0.3, 0.3, 0.003), seed=1)
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0, drag=(0.0, 1.2), added_mass=(0.0, 1.0))
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (1200.0, 0.0, 0.0), elements, section)
    sea = pl.Sea(
        800.0,
        current=pl.Current.uniform([0.0, -0.5, 0.0]),
        waves=pl.Waves.jonswap(2.5, 9.0, direction=math.pi / 2, components=100, seed=2) if waves else None,
        wind=pl.Wind(15.0, direction=math.pi / 2, seed=3) if hull else None,
    )
    model = pl.Model(rod, sea)
    model.pin("A")
    pid = pl.PID(
        kp=[0.4e6, 0.4e6, 0, 0, 0, 1e8],
        kd=[0.5e7, 0.4e7, 0, 0, 0, 1e9],
        reference=[870.0, 0, 0, 0, 0, 0],
        start=1.0,
        **options,
    )
    model.attach_vessel(
        "B", pl.Vessel.osv(), eta=[850.0, 0.0, -800.0, 0, 0, 0], controller=pid, hull_loads=hull
    )
    return model


def main() -> None:
    dt = 0.1
    print("| elements | loop | steps | ms/step | overhead µs/step |")
    print("| ---: | --- | ---: | ---: | ---: |")
    for elements in (10, 100):
        base: dict[bool, float] = {}
        for loop, (_, _, waves) in LOOPS.items():
            model = build(elements, loop)
            simulation = model.simulation(model.static(), dt=dt)
            start = time.perf_counter()
            results = simulation.run(100.0, progress=False, record_every=100)
            elapsed = time.perf_counter() - start
            steps = round(results.time[-1] / dt)
            per_step = elapsed / steps
            first = waves not in base
            base.setdefault(waves, per_step)
            overhead = "" if first else f"{(per_step - base[waves]) * 1e6:.0f}"
            print(f"| {elements} | {loop} | {steps} | {per_step * 1e3:.3f} | {overhead} |")


if __name__ == "__main__":
    main()
