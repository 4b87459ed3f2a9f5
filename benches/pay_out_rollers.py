"""Benchmark: how steady a steady S-lay stays when pipe slides over the stinger's rollers with pay-out, against
the roller contact's stiffness and the time step.

Not a test. The S-lay of ``tests/test_pay_out.py``: a 0.6 m × 30 mm steel pipe (empty), 700 m in 140 elements,
pinned at A on a frictionless seabed in 150 m of water, held by an OSV's tensioner over a 200 m-radius, 100 m
stinger of 15 rollers; the DP follows a route at 0.3 m/s and the tensioner pays out at 0.3 m/s, both ramped
over 60 s; 300 s. A contact that bumped as pipe slides over it (the pipe's chord polygon did, once per element)
would ring where the time step does not resolve its stiffness (ω = √(k/(m ℓ)), ωΔt ≫ 1). Prints a Markdown
table of the top tension's standard deviation over 200–300 s.

Usage::

    python benches/pay_out_rollers.py
"""

from __future__ import annotations

import math
import time

import pipelay as pl
from machine import machine

SPEED, RAMP = 0.3, 60.0


def smooth(t: float) -> float:
    """Smoothstep of t/RAMP clipped to [0, 1]."""
    s = min(max(t / RAMP, 0.0), 1.0)
    return s * s * (3.0 - 2.0 * s)


def distance(t: float) -> float:
    """∫ SPEED·smooth dt (m)."""
    s = min(max(t / RAMP, 0.0), 1.0)
    return SPEED * (RAMP * (s**3 - s**4 / 2) + max(t - RAMP, 0.0))


def s_lay(stiffness: float, elements: int) -> pl.Model:
    section = pl.Section.pipe(0.6, 0.03, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0))
    model = pl.Model(
        pl.Rod.straight((0, 0, 0), (700, 0, 0), elements, section),
        sea=pl.Sea(150.0, seabed=pl.Seabed(stiffness=1e5)),
    )
    model.pin("A")
    stinger = pl.Stinger(200.0, 100.0, 15, origin=(-40, 0, -6))
    lay = pl.SLay(tensioner=(10, 0, -6.3), stinger=stinger, roller_stiffness=stiffness)
    pid = pl.PID(
        kp=[2e5, 2e5, 0, 0, 0, 1e7],
        kd=[4e6, 4e6, 0, 0, 0, 1e8],
        reference=lambda t: [660.0 + distance(t), 0, 0, 0, 0, 0],
        reference_rate=lambda t: [SPEED * smooth(t), 0, 0, 0, 0, 0],
    )
    model.attach_vessel("B", pl.Vessel.osv(), eta=[660.0, 0, -150, 0, 0, 0], controller=pid, lay=lay)
    model.pay_out("B", speed=lambda t: SPEED * smooth(t))
    return model


def main() -> None:
    print(f"`python benches/pay_out_rollers.py`; {machine()}")
    print(
        "| roller stiffness k | elements | Δt | ωΔt | static top tension | std over 200–300 s | iterations (max) | wall |"
    )
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for stiffness, dt, elements in [
        (1e6, 0.5, 140),
        (3e6, 0.5, 140),
        (1e7, 0.5, 140),
        (1e7, 0.1, 140),
        (1e6, 0.5, 280),
    ]:
        model = s_lay(stiffness, elements)
        state = model.static()
        static = state.lay_summary()["top_tension"]
        section = state.section
        element_mass = (section.mass + 1025.0 * math.pi / 4 * section.outer_diameter**2) * 700.0 / elements
        omega = math.sqrt(stiffness / element_mass)
        start = time.perf_counter()
        results = model.simulation(state, dt=dt).run(300.0, progress=False)
        wall = time.perf_counter() - start
        tension = results.lay_summary()["top_tension"][results.time > 200.0]
        print(
            f"| {stiffness:.0e} N/m | {elements} | {dt} s | {omega * dt:.0f} | {static:.0f} N | "
            f"{100 * tension.std() / static:.2f} % | {results.iterations.max():.0f} | {wall:.1f} s |"
        )


if __name__ == "__main__":
    main()
