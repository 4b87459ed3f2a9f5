"""Lay-analysis helpers on top of statics: where to put the vessel for a wanted lay configuration.

A lay engineer sets the lay tension by moving the vessel along the lay direction against the pipe's pull:
further out raises the top tension, flattens the departure and the sagbend, and moves the touchdown toward
the vessel. `find_lay_position` finds the vessel position (η's x) at which a lay quantity reaches a target,
by Brent's method (``scipy.optimize.brentq``) on static solutions.

Imports of pipelay: the package (the engine's classes and ``pl.checks``, looked up there when used).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

import pipelay as pl
from pipelay.analysis import suspect

__all__ = ["TARGETS", "LayPosition", "find_lay_position", "lay_quantity"]

TARGETS: dict[str, str] = {
    "top_tension": "N, effective tension at the tensioner or tower",
    "departure_angle": "rad, below the horizontal where the pipe leaves the equipment",
    "layback": "m, horizontal distance from the hold point to the touchdown",
    "touchdown_arc_length": "m, touchdown's arc length from end A",
    "sagbend_strain": "largest strain from the inflection point to the touchdown",
    "overbend_strain": "largest strain from the hold point to the inflection point",
    "sagbend_utilisation": "largest DNV-ST-F101 load-controlled utilisation in the sagbend",
}
"""The quantities `find_lay_position` can aim at, with their units."""


@dataclass(frozen=True)
class LayPosition:
    """The outcome of `find_lay_position`.

    Attributes:
        x: the vessel's position along e1 (η's x, m).
        value: the target quantity reached there.
        state: the static state there.
        solves: how many static solves it took.
    """

    x: float
    value: float
    state: pl.State
    solves: int


def _check_target(target: str) -> None:
    """An InputError unless `target` is a key of TARGETS."""
    if target not in TARGETS:
        allowed = ", ".join(TARGETS)
        raise pl.InputError(f"target: {target!r} is not a lay quantity; allowed: {allowed}")


def lay_quantity(state: pl.State, target: str, **check: object) -> float:
    """The lay quantity `target` (a key of TARGETS) of a static state; `check`: arguments of
    ``pl.checks.dnv_st_f101`` for "sagbend_utilisation"."""
    _check_target(target)
    summary = state.lay_summary()
    if summary is None:
        raise pl.InputError("target: the model holds no vessel end, so it has no lay summary")
    if target != "sagbend_utilisation":
        return float(summary[target])
    utilisation = pl.checks.dnv_st_f101(state, **check).load_controlled  # type: ignore[arg-type]
    return float(np.max(utilisation[_sagbend_elements(state, summary)]))


def _sagbend_elements(state: pl.State, summary: dict[str, object]) -> np.ndarray:
    """Indices of the elements of the sagbend: between the touchdown and the inflection point."""
    reference = state.reference_arc_length
    n = len(reference) - 1
    middle = 0.5 * (reference[:-1] + reference[1:])
    inflection = float(summary["inflection_arc_length"])  # type: ignore[arg-type]
    touchdown = float(summary["touchdown_arc_length"])  # type: ignore[arg-type]
    low = touchdown if math.isfinite(touchdown) else 0.0
    chosen = np.flatnonzero((middle >= low) & (middle <= inflection))
    return chosen if len(chosen) else np.arange(n)


def _search_bracket(
    miss: Callable[[float], float], start: float, step: float, tolerance: float
) -> tuple[float, float]:
    """A bracket of a sign change of `miss` from `start`: steps toward smaller |miss| that double while the
    statics converge and halve when it fails."""
    here = miss(start)
    if here == 0.0:
        return start - tolerance, start + tolerance
    ahead = miss(start + step)
    direction = 1.0 if abs(ahead) < abs(here) else -1.0
    x, size = start, step
    for _ in range(60):
        trial = x + direction * size
        try:
            there = miss(trial)
        except pl.ConvergenceError:
            size *= 0.5
            if size < tolerance:
                break
            continue
        if here * there <= 0.0:
            return (min(x, trial), max(x, trial))
        x, here, size = trial, there, 2.0 * size
    raise pl.InputError(
        f"bracket: no vessel position from x = {start:g} m reaches the target (last tried {x:g} m, "
        f"{here:+.6g} from it); give a bracket"
    )


def find_lay_position(
    build: Callable[[float], pl.Model],
    target: str,
    value: float,
    bracket: tuple[float, float] | None = None,
    *,
    start: float | None = None,
    step: float = 1.0,
    tolerance: float = 0.01,
    **check: object,
) -> LayPosition:
    """The vessel position x (m along e1) at which the static lay quantity `target` equals `value`.

    Args:
        build: the model with the vessel at x (a function of x, m).
        target: a key of TARGETS.
        value: the wanted value, in the target's units.
        bracket: (x_low, x_high) (m) with the target on either side of `value` at its ends; None: found from
            `start` by steps that double (from `step`) toward the value, halving back when statics fails.
        start: where the bracket search starts (m); needed without a bracket.
        step: the bracket search's first step (m).
        tolerance: on x (m).
        check: arguments of ``pl.checks.dnv_st_f101`` for "sagbend_utilisation" (e.g. grade="X65").

    Raises pl.InputError for an unknown target, a bracket that does not straddle `value`, or non-finite
    numbers; pl.ConvergenceError (naming x) when a static solve in the search fails.
    """
    from scipy.optimize import brentq

    _check_target(target)
    if not math.isfinite(value):
        raise pl.InputError(f"value: {value!r} must be a finite number")
    if not (math.isfinite(tolerance) and tolerance > 0):
        raise pl.InputError(f"tolerance: {tolerance!r} must be a positive number (m)")
    states: dict[float, pl.State] = {}

    def solve(x: float) -> pl.State:
        if x not in states:
            try:
                # The search passes through suspect positions on its way: only the one found is reported.
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", suspect.PhysicsWarning)
                    states[x] = build(x).static()
            except pl.ConvergenceError as error:
                raise pl.ConvergenceError(
                    f"lay position search: statics failed at x = {x:.3f} m: {error}"
                ) from error
        return states[x]

    def miss(x: float) -> float:
        quantity = lay_quantity(solve(x), target, **check)
        if not math.isfinite(quantity):
            raise pl.InputError(
                f"target: {target} is undefined at x = {x:.3f} m (no touchdown or lift-off there)"
            )
        return quantity - value

    if bracket is None:
        if start is None or not math.isfinite(start):
            raise pl.InputError(f"start: {start!r} must be a finite number (m) when no bracket is given")
        if not (math.isfinite(step) and step > 0):
            raise pl.InputError(f"step: {step!r} must be a positive number (m)")
        bracket = _search_bracket(miss, float(start), float(step), tolerance)
    low, high = (float(b) for b in bracket)
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise pl.InputError(f"bracket: {bracket!r} must be two finite numbers, low < high (m)")
    at_low, at_high = miss(low), miss(high)
    if at_low * at_high > 0:
        raise pl.InputError(
            f"bracket: {target} is {at_low + value:.6g} at x = {low:g} m and {at_high + value:.6g} at "
            f"x = {high:g} m; both on one side of {value:.6g}: widen or move the bracket"
        )
    if at_low == 0.0 or at_high == 0.0:
        x = low if at_low == 0.0 else high
    else:
        x = float(brentq(miss, low, high, xtol=tolerance))
    state = solve(x)
    suspect.warn(suspect.suspect_state(state), stacklevel=2)
    return LayPosition(x=x, value=lay_quantity(state, target, **check), state=state, solves=len(states))
