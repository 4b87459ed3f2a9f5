"""Validation table of the statics: measured errors against analytic and published solutions.

Not a test (the tests in ``tests/test_statics_validation.py`` assert these numbers with tolerances); this
script runs the same cases and prints what they measure, for the README. Usage::

    python benches/validation_statics.py
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import pipelay as pl
from irvine import irvine_catenary
from test_statics_validation import (
    BEND_R,
    BEND_REFERENCE,
    PIPE_LENGTH,
    ROLL_L,
    TOP,
    bend45,
    hanging_model,
    observed_order,
    rollup,
    timoshenko_tip,
)


def rows() -> list[tuple[str, str, str]]:
    """(case, reference, measured) rows."""
    out = []
    for turns, name in ((0.5, "half"), (1.0, "full")):
        state, _, radius = rollup(turns, 20)
        theta = 2.0 * math.pi * turns
        exact = np.array([radius * math.sin(theta), radius * (1.0 - math.cos(theta)), 0.0])
        error = np.linalg.norm(state.positions[-1] - exact) / ROLL_L
        out.append((f"roll-up, {name} circle, n = 20", "exact circle", f"tip error {error:.1e} L"))
    elements = [4, 8, 16, 32]
    errors = []
    for n in elements:
        state, _, radius = rollup(0.5, n)
        errors.append(float(np.linalg.norm(state.positions[-1] - np.array([0.0, 2.0 * radius, 0.0]))))
    out.append(("roll-up, n = 4…32", "convergence order", f"{observed_order(elements, errors)[0]:.3f}"))
    errors = []
    for n in elements:
        state, _, exact = timoshenko_tip(2.0, 1.0e4, 1.0e6, n)
        errors.append(abs(state.positions[-1][1] - exact) / exact)
    out.append(("Timoshenko cantilever, n = 32", "PL³/3EI + PL/GA", f"relative error {errors[-1]:.1e}"))
    out.append(
        ("Timoshenko cantilever, n = 4…32", "convergence order", f"{observed_order(elements, errors)[0]:.3f}")
    )
    start = np.array([BEND_R * math.sin(math.pi / 4), BEND_R * (1.0 - math.cos(math.pi / 4)), 0.0])
    for force, reference in sorted(BEND_REFERENCE.items()):
        tip = bend45(force).positions[-1]
        error = np.linalg.norm(tip - np.array(reference)) / np.linalg.norm(np.array(reference) - start)
        out.append(
            (
                f"45° bend, P = {force:.0f}, n = 8",
                f"Simo & Vu-Quoc {tuple(reference)}",
                f"{tuple(round(float(x), 2) for x in tip)}, {100 * error:.2f} % of displacement",
            )
        )
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0)
    weight_section = pl.Section(
        EA=section.EA, GA=section.GA, GJ=1.0, EI=1.0, mass=section.mass, outer_diameter=0.6
    )
    for label, sec in (("EI = 1", weight_section), ("steel EI", section)):
        model = hanging_model(sec, 100, "pinned")
        state = model.static()
        ref = irvine_catenary(PIPE_LENGTH, TOP[0], -TOP[2], model.submerged_weight, sec.EA)
        top = np.linalg.norm(state.reaction("B")[:3])
        out.append(
            (
                f"1200 m line, pinned, {label}, n = 100",
                f"Irvine: tension at B {ref.tension_b / 1e3:.1f} kN",
                f"\\|F_B\\| {top / 1e3:.1f} kN ({100 * (top / ref.tension_b - 1):+.3f} %)",
            )
        )
    return out


def main() -> int:
    """Print the table."""
    print("| case | reference | pipelay |")
    print("| --- | --- | --- |")
    for case, reference, measured in rows():
        print(f"| {case} | {reference} | {measured} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
