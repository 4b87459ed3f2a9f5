"""Lay-analysis helpers on top of statics: where to put the vessel for a wanted lay configuration.

A lay engineer sets the lay tension by moving the vessel along the lay direction against the pipe's pull:
further out raises the top tension, flattens the departure and the sagbend, and moves the touchdown toward
the vessel. `find_lay_position` finds the vessel position (η's x) at which a lay quantity reaches a target:
a search outward from a start for a sign change of the miss, then the Illinois method inside it, at most
`MAX_SOLVES` static solves in all; positions where statics fails are gaps the search steps around.

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

__all__ = [
    "MAX_SOLVES",
    "RANGES",
    "REACHED",
    "TARGETS",
    "LayPosition",
    "TargetNotReached",
    "check_target",
    "find_lay_position",
    "lay_quantity",
]

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

RANGES: dict[str, tuple[float, float]] = {
    "top_tension": (0.0, math.inf),
    "departure_angle": (0.0, 0.5 * math.pi),
    "layback": (0.0, math.inf),
    "touchdown_arc_length": (0.0, math.inf),
    "sagbend_strain": (0.0, 0.05),
    "overbend_strain": (0.0, 0.05),
    "sagbend_utilisation": (0.0, math.inf),
}
"""The values each target may take, (low, high] in the units of TARGETS: a departure angle in (0, π/2] rad
below the horizontal, a strain in (0, 0.05] (5 %), the others positive."""

MAX_SOLVES = 40
"""The most static solves `find_lay_position` spends by default, the search for a bracket and its narrowing
together (a failed solve counts): from a start 1 m off, doubling steps reach 2^k m in k solves each way and
the Illinois method narrows a bracket of 64 m to 1 cm in about 8."""

REACHED = 1e-3
"""The relative miss within which a position reaches its target; a larger miss at a bracket narrowed to the
tolerance on x is a jump of the quantity across the target (the lift-off moving to another roller, say)."""

_HELD = ("departure_angle", "overbend_strain")
"""Targets that only rollers make: without them the pipe leaves the equipment at its hold point."""

_TURN_PROBES = 3
"""Parabola probes at an extremum of the quantity, to see whether it reaches the target."""

_GIVE_UP = 3
"""Steps in a row away from the target, or failed solves in a row, after which a direction of the search is
given up (a failed solve far from the start can take seconds)."""


@dataclass(frozen=True)
class LayPosition:
    """The outcome of `find_lay_position`.

    Attributes:
        x: the vessel's position along e1 (η's x, m).
        value: the target quantity there (the target's units).
        state: the static state there.
        solves: how many static solves it took (failed ones included).
        reached: whether `value` is within `REACHED` (0.1 %) of the target; False: the quantity jumps across
            the target within the tolerance of x (the lift-off moves to another roller, say), and this is the
            closest state to the target on either side of the jump.
    """

    x: float
    value: float
    state: pl.State
    solves: int
    reached: bool


class TargetNotReached(pl.InputError):
    """No vessel position the search tried reaches the target: beyond what the vessel's positions give, or
    beyond the search's solves (`max_solves`), or where statics fails. The message names the closest position
    found and its value.

    Attributes:
        closest: the tried position whose quantity is closest to the target, with its state
            (``reached`` False); None when the quantity is undefined at every position tried (no touchdown).
    """

    def __init__(self, message: str, closest: LayPosition | None) -> None:
        super().__init__(message)
        self.closest = closest


def _show(target: str, value: float) -> str:
    """`value` of `target` with its unit, and in the unit ``pipelay static`` prints beside it."""
    unit = TARGETS[target].split(",")[0]
    if unit == "N":
        return f"{value:.6g} N ({value / 1e3:.6g} kN)"
    if unit == "rad":
        return f"{value:.6g} rad ({math.degrees(value):.4g}°)"
    if unit == "m":
        return f"{value:.6g} m"
    if target.endswith("strain"):
        return f"{value:.6g} ({100 * value:.4g} %)"
    return f"{value:.6g}"


def check_target(
    target: str, value: float | None = None, rest: pl.State | None = None, *, argument: str | None = None
) -> None:
    """An InputError unless `target` is a key of TARGETS, `value` (its units) is in RANGES, and the model
    whose state at rest is `rest` (``model.rest()``, no solve) can change the target by moving its vessel.

    A departure angle and an overbend strain need rollers: on a J-lay, an S-lay without a stinger or a vessel
    without lay equipment the pipe leaves at the hold point, whose angle the equipment fixes (the J-lay tower's
    lean, plus the vessel's pitch), and it has no overbend. `argument`: the name the messages give (default:
    "target", and "value" for the value's range).
    """
    if target not in TARGETS:
        allowed = ", ".join(TARGETS)
        raise pl.InputError(f"{argument or 'target'}: {target!r} is not a lay quantity; allowed: {allowed}")
    if value is not None:
        low, high = RANGES[target]
        if not (math.isfinite(value) and low < value <= high):
            allowed = (
                "an angle in (0, π/2] rad (0–90°) below the horizontal"
                if target == "departure_angle"
                else "a strain in (0, 0.05] (5 %); 0.15 % is 0.0015"
                if target.endswith("strain")
                else "a positive number"
            )
            hint = (
                f" (in radians; {value:g}° is {math.radians(value):.4g} rad)"
                if target == "departure_angle" and math.isfinite(value) and 0 < value <= 90
                else ""
            )
            raise pl.InputError(
                f"{argument or 'value'}: {target} = {value!r} is out of range{hint}; allowed: {allowed}"
            )
    if rest is None:
        return
    if rest.lay_summary() is None:
        raise pl.InputError(
            f"{argument or 'target'}: the model holds no vessel end, so it has no lay summary to aim {target} at"
        )
    rollers = rest.roller_reactions
    if target in _HELD and (rollers is None or len(rollers) == 0):
        allowed = ", ".join(t for t in TARGETS if t not in _HELD)
        equipment = "a J-lay tower, an S-lay without a stinger, or a vessel without lay equipment"
        why = (
            "departure_angle is fixed by the lay equipment, whatever the vessel's position: it has no rollers "
            f"({equipment}), so the pipe leaves at the hold point, at the angle the equipment holds it (a J-lay "
            "tower's lean, plus the vessel's pitch)"
            if target == "departure_angle"
            else f"overbend_strain has no meaning here: the lay equipment has no rollers ({equipment}), so the "
            "pipe has no overbend"
        )
        raise pl.InputError(f"{argument or 'target'}: {why}; aim at one of {allowed}")


def lay_quantity(state: pl.State, target: str, **check: object) -> float:
    """The lay quantity `target` (a key of TARGETS) of a static state; `check`: arguments of
    ``pl.checks.dnv_st_f101`` for "sagbend_utilisation"."""
    check_target(target)
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


class _Probes:
    """The miss (quantity − target) at the positions a search has tried, each tried once and at most `limit`
    of them: NaN where there is no state (statics failed: its message is in `failures`) or the quantity is
    undefined (no touchdown, say)."""

    def __init__(self, miss: Callable[[float], float], limit: int) -> None:
        self.miss = miss
        self.limit = limit
        self.values: dict[float, float] = {}
        self.failures: dict[float, str] = {}

    @property
    def spent(self) -> bool:
        """Whether `limit` positions have been tried."""
        return len(self.values) >= self.limit

    def __call__(self, x: float) -> float:
        if x not in self.values:
            try:
                self.values[x] = float(self.miss(x))
            except pl.ConvergenceError as error:
                self.values[x] = math.nan
                self.failures[x] = str(error)
        return self.values[x]

    def closest(self) -> float | None:
        """The position tried with the smallest |miss| (None: none has a value)."""
        found = [x for x, v in self.values.items() if math.isfinite(v)]
        return min(found, key=lambda x: abs(self.values[x])) if found else None


@dataclass
class _Front:
    """One direction of the bracket search: its farthest position with a value (x, miss), the position before
    it, the next step (m), whether it has passed an extremum, and how many steps in a row took it away from the
    target and how many solves in a row failed."""

    x: float
    value: float
    size: float
    direction: float
    before: tuple[float, float] | None = None
    turned: bool = False
    away: int = 0
    failed: int = 0


def _search_bracket(probes: _Probes, start: float, step: float) -> tuple[float, float] | None:
    """A bracket (low, high) of a sign change of the miss, searched outward from `start`; None when the probes
    are spent, or both directions are blocked, before one is found.

    Any two positions tried one after the other in one direction whose misses have opposite signs make the
    bracket, `start` and its first step `step` (m) included. Each direction advances from its farthest position
    with a value by a step that doubles after each success; a position with no state halves the step, so the
    next tries come back toward the last good position and, once one succeeds, the doubling steps past the
    gap. A direction is blocked when it would need a step shorter than `step`, and given up after three steps
    in a row away from the target or three failed solves in a row. The direction advanced is the one whose farthest miss is the smallest, so
    the search heads toward the target and turns to the other side when this one stops coming closer. A
    direction that comes closer and then turns away has passed an extremum
    of the quantity: up to three parabola probes look whether the extremum crosses the target.
    """
    here = probes(start)
    if here == 0.0:
        return start, start
    fronts = [_Front(start, here, step, 1.0), _Front(start, here, step, -1.0)]
    while not probes.spent:
        open_fronts = [f for f in fronts if f.size >= step and f.away < _GIVE_UP and f.failed < _GIVE_UP]
        if not open_fronts:
            return None
        front = min(open_fronts, key=lambda f: abs(f.value) if math.isfinite(f.value) else math.inf)
        trial = front.x + front.direction * front.size
        there = probes(trial)
        if not math.isfinite(there):
            front.size *= 0.5
            front.failed += 1
            continue
        front.failed = 0
        if math.isfinite(front.value):
            if front.value * there <= 0.0:
                return min(front.x, trial), max(front.x, trial)
            before = front.before
            if before is not None and not front.turned and abs(before[1]) > abs(front.value) < abs(there):
                front.turned = True
                found = _turn(probes, [before, (front.x, front.value), (trial, there)])
                if found is not None:
                    return found
            front.away = front.away + 1 if abs(there) > abs(front.value) else 0
        front.before = (front.x, front.value) if math.isfinite(front.value) else None
        front.x, front.value, front.size = trial, there, 2.0 * front.size
    return None


def _turn(probes: _Probes, points: list[tuple[float, float]]) -> tuple[float, float] | None:
    """A bracket at the extremum of the miss between three positions (x, miss) of one sign, the middle one the
    closest to zero, from up to `_TURN_PROBES` probes at the vertex of the parabola through three of them;
    None when the extremum does not cross zero (as far as the probes see)."""
    for _ in range(_TURN_PROBES):
        if probes.spent:
            return None
        (a, fa), (b, fb), (c, fc) = sorted(points)
        # The vertex of the parabola through the three points (Brent's minimisation step).
        p = (b - a) ** 2 * (fb - fc) - (b - c) ** 2 * (fb - fa)
        q = (b - a) * (fb - fc) - (b - c) * (fb - fa)
        vertex = b - 0.5 * p / q if q != 0.0 else math.nan
        if not (a < vertex < c) or vertex in probes.values:
            return None
        there = probes(vertex)
        if not math.isfinite(there):
            return None
        if there * fb <= 0.0:
            return min(b, vertex), max(b, vertex)
        # Keep the closest of the four in the middle, with its neighbours.
        ordered = sorted([(a, fa), (b, fb), (c, fc), (vertex, there)])
        best = min(range(1, 3), key=lambda k: abs(ordered[k][1]))
        points = ordered[best - 1 : best + 2]
    return None


def _refine(probes: _Probes, low: float, high: float, tolerance: float) -> tuple[float, float]:
    """The bracket (low, high) of a sign change narrowed to `tolerance` (m) or less, by the Illinois method
    (regula falsi that halves the weight of an end kept twice running) with steps at least tolerance/2 inside
    the ends; positions with no state inside are taken as one gap, whose edges are found by bisecting the
    longer stretch between a bracket's end and the gap. Returns a wider bracket when the probes are spent first or those positions fill it."""
    at_low, at_high = probes(low), probes(high)
    if at_low == 0.0 or at_high == 0.0:
        x = low if at_low == 0.0 else high
        return x, x
    weight_low, weight_high, kept = at_low, at_high, 0
    while high - low > tolerance and not probes.spent:
        gaps = sorted(x for x, v in probes.values.items() if low < x < high and not math.isfinite(v))
        if gaps:
            # A gap is taken as one stretch with no state: its edges are looked for from the bracket's ends.
            stretch = max((low, gaps[0]), (gaps[-1], high), key=lambda s: s[1] - s[0])
            if stretch[1] - stretch[0] <= tolerance:
                break
            trial = 0.5 * (stretch[0] + stretch[1])
        else:
            trial = (low * weight_high - high * weight_low) / (weight_high - weight_low)
            trial = min(max(trial, low + 0.5 * tolerance), high - 0.5 * tolerance)
        there = probes(trial)
        if not math.isfinite(there):
            continue
        if there == 0.0:
            return trial, trial
        if (there > 0.0) == (at_low > 0.0):
            low, at_low, weight_low = trial, there, there
            if kept == 1:
                weight_high *= 0.5
            kept = 1
        else:
            high, at_high, weight_high = trial, there, there
            if kept == -1:
                weight_low *= 0.5
            kept = -1
    return low, high


def find_lay_position(
    build: Callable[[float], pl.Model],
    target: str,
    value: float,
    bracket: tuple[float, float] | None = None,
    *,
    start: float | None = None,
    step: float = 1.0,
    tolerance: float = 0.01,
    max_solves: int = MAX_SOLVES,
    **check: object,
) -> LayPosition:
    """The vessel position x (m along e1) at which the static lay quantity `target` equals `value`.

    Without a bracket, the search starts at `start` and steps outward with steps that double from `step`
    until two neighbouring positions have the quantity on either side of `value` (`start` and `start + step`
    included), both ways if need be; then the Illinois method narrows that bracket to `tolerance`. A position
    where statics fails (a ``pl.ConvergenceError``: no state there) or the quantity is undefined is a gap the
    search steps around; a gap inside the narrowed bracket still gives its end within `REACHED` of `value`. It spends at most `max_solves` static solves in all.

    Args:
        build: the model with the vessel at x (a function of x, m).
        target: a key of TARGETS.
        value: the wanted value, in the target's units (SI, radians; see TARGETS), in RANGES.
        bracket: (x_low, x_high) (m) with the target on either side of `value` at its ends; None: searched
            from `start`.
        start: where the search starts (m); needed without a bracket.
        step: the search's first and shortest step (m).
        tolerance: on x (m).
        max_solves: the most static solves the search spends (default `MAX_SOLVES`, 40).
        check: arguments of ``pl.checks.dnv_st_f101`` for "sagbend_utilisation" (e.g. grade="X65").

    Returns the position, its value and state; ``reached`` is False when the quantity jumps across `value`
    there (the lift-off moves to another roller, say): then it is the closest state to `value`.

    Raises pl.InputError for an unknown target, a value out of RANGES, a target the lay equipment fixes (the
    departure angle or the overbend strain without rollers: a J-lay tower), a bracket that does not straddle
    `value`, or non-finite numbers; `TargetNotReached` (an InputError) when no position tried reaches the
    target within `max_solves` solves, naming the closest found (its ``closest``); pl.ConvergenceError when
    statics fails at a given bracket's end or at every position tried.
    """
    check_target(target)
    if not math.isfinite(value):
        raise pl.InputError(f"value: {value!r} must be a finite number")
    check_target(target, value)
    if not (math.isfinite(tolerance) and tolerance > 0):
        raise pl.InputError(f"tolerance: {tolerance!r} must be a positive number (m)")
    if isinstance(max_solves, bool) or not isinstance(max_solves, int) or max_solves < 2:
        raise pl.InputError(f"max_solves: {max_solves!r} must be a whole number of static solves, at least 2")
    if bracket is None:
        if start is None or not math.isfinite(start):
            raise pl.InputError(f"start: {start!r} must be a finite number (m) when no bracket is given")
        if not (math.isfinite(step) and step > 0):
            raise pl.InputError(f"step: {step!r} must be a positive number (m)")
        first = float(start)
    else:
        low, high = (float(b) for b in bracket)
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise pl.InputError(f"bracket: {bracket!r} must be two finite numbers, low < high (m)")
        first = low
    check_target(target, rest=build(first).rest())
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
        return lay_quantity(solve(x), target, **check) - value

    probes = _Probes(miss, max_solves)

    def position(x: float) -> LayPosition:
        quantity = lay_quantity(states[x], target, **check)
        reached = abs(quantity - value) <= REACHED * abs(value)
        return LayPosition(x=x, value=quantity, state=states[x], solves=len(probes.values), reached=reached)

    def not_reached(why: str) -> Exception:
        closest = probes.closest()
        if closest is None:
            if len(probes.failures) == len(probes.values):
                last = next(reversed(probes.failures.values()))
                return pl.ConvergenceError(
                    f"lay position search: statics failed at every position tried "
                    f"({_tried(probes)}); give another start or a bracket; the last: {last}"
                )
            return TargetNotReached(
                f"target: {target} is undefined at every position tried ({_tried(probes)}; no touchdown "
                "there, say): give another start, a bracket or another target",
                None,
            )
        found = position(closest)
        return TargetNotReached(
            f"target: no vessel position reaches {target} = {_show(target, value)}: {why}; the closest found "
            f"is x = {closest:.3f} m with {_show(target, found.value)} ({_tried(probes)}); give a bracket, "
            "another start or value, or more solves (max_solves)",
            found,
        )

    if bracket is None:
        found = _search_bracket(probes, first, float(step))
        if found is None:
            why = (
                f"none of the {len(probes.values)} static solves allowed (max_solves) found it"
                if probes.spent
                else "each way the quantity moves away from it, or statics fails, beyond the positions tried"
            )
            raise not_reached(why)
        low, high = found
    else:
        at_low, at_high = probes(low), probes(high)
        for x in (low, high):
            if x in probes.failures:
                raise pl.ConvergenceError(f"bracket: {probes.failures[x]}; move the bracket")
            if not math.isfinite(probes.values[x]):
                raise pl.InputError(
                    f"bracket: {target} is undefined at x = {x:g} m (no touchdown there, say): move the bracket"
                )
        if at_low * at_high > 0:
            raise pl.InputError(
                f"bracket: {target} is {_show(target, at_low + value)} at x = {low:g} m and "
                f"{_show(target, at_high + value)} at x = {high:g} m; both on one side of "
                f"{_show(target, value)}: widen or move the bracket"
            )
    low, high = _refine(probes, low, high, tolerance)
    x = min((low, high), key=lambda end: abs(probes.values[end]))
    if high - low > tolerance and abs(probes.values[x]) > REACHED * abs(value):
        raise not_reached(
            f"it lies between x = {low:.3f} and {high:.3f} m, not narrowed to {tolerance:g} m within the "
            f"{probes.limit} static solves allowed (max_solves)"
            if probes.spent
            else f"it lies between x = {low:.3f} and {high:.3f} m, where statics fails (or {target} is "
            "undefined) everywhere the search tried"
        )
    suspect.warn(suspect.suspect_state(states[x]), stacklevel=2)
    return position(x)


def _tried(probes: _Probes) -> str:
    """Where the search looked: how many static solves, over which positions, how many failed."""
    tried = list(probes.values)
    failed = f", statics failed at {len(probes.failures)}" if probes.failures else ""
    return f"{len(tried)} static solves at x = {min(tried):.3f} … {max(tried):.3f} m{failed}"
