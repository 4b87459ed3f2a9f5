"""Stinger design: the radius and the roller heights of an S-lay stinger for a target overbend strain and a
target tip clearance, at a given top tension.

```python
import pipelay as pl

section = pl.Section.pipe(0.6, 0.03)
design = pl.design_stinger(section, 150.0, 1.0e6, overbend_strain=0.0018, tip_clearance=0.3)
design.radius, design.length, design.roller_tops      # m; the rollers' top points (k, 3), body frame
lay = pl.SLay(tensioner=design.tensioner, stinger=design.stinger)   # the stinger, ready to use
design.table()                                        # the [vessel.lay.stinger] table of a scenario file
```

The pipe runs from the tensioner on a horizontal firing line over rollers whose tops lie on a circular arc of
radius R (body frame: forward, starboard, down; the arc starts at `origin`, level, and bends down aft). Over
the arc the pipe's outer fibre strains by about (D/2)/(R + D/2) + T/EA; where it leaves the stinger it
straightens into the catenary. Three searches nest, each on a quantity that moves one way with its unknown:

1. the vessel's position x along e1 for the top tension (`pipelay.analysis.lay.find_lay_position`);
2. the stinger's length L (the arc length of its last roller) for the tip clearance — the gap between the pipe
   and the last roller grows as the stinger runs on past the lift-off point (about ΔL²/2R) — found by the
   Illinois method inside a bracket stepped out from the first length with the pipe resting on the tip;
3. the radius R for the overbend strain, by the secant method from the thin-arc estimate
   R = (D/2)/(ε − T/EA) − D/2: the solved strain over discrete rollers is a few percent above the estimate.

The rollers, `rollers` of them spread evenly over the arc (about `roller_spacing` apart), have their tops on
the arc by construction: `roller_heights` are the heights the roller supports are set to.

Units: SI (m, N, rad; strains as fractions). Imports of pipelay: the package (the engine's classes),
`pipelay.analysis.checks` (`_number`, the wording of input errors) and `pipelay.analysis.lay`
(`find_lay_position`).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

import pipelay as pl
from pipelay.analysis.checks import _number
from pipelay.analysis.lay import MAX_SOLVES, TargetNotReached, find_lay_position

__all__ = ["StingerDesign", "design_stinger"]

FloatArray = NDArray[np.float64]

START_OFFSET = 20.0
"""The vessel's first position: the tensioner this far (m) short of the pipe's end B along e1, its reference."""

MAX_ROUNDS = 12
"""The most radii (outer search) and stinger lengths per radius (inner search) tried."""


@dataclass(frozen=True)
class StingerDesign:
    """A stinger designed by `design_stinger`, with the lay it was designed for solved on it.

    Attributes:
        radius: R of the rollers' top line (m).
        length: the arc length of the last roller from the first (m).
        rollers: how many rollers, spread evenly over the arc.
        origin: the first roller's top point (body frame, m).
        tensioner: the tensioner's position (body frame, m).
        stinger: the `pl.Stinger`, for `pl.SLay(tensioner, stinger=...)`.
        roller_tops: the rollers' top points (k, 3), body frame (m): on the arc of `radius` (with boxes, the
            boxes' stations).
        roller_heights: the rollers' tops' height above the origin's level, −z (k,) (m; negative below it).
        vessel_x: the vessel's position along e1 (η's x, m) at which the top tension is met.
        pipe_length: the length of the pipe the lay was solved with (m), from its pinned end A at the origin
            along e1, in elements of `element_length`.
        top_tension: the solved top tension (N).
        overbend_strain: the solved overbend strain (the largest over the stinger).
        tip_clearance: the solved gap between the pipe and the last roller (m).
        state: the static state of the design.
        solves: the static solves the design took.
        box: the `pl.RollerBox` at every roller's place, or None (lone rollers).
    """

    radius: float
    length: float
    rollers: int
    origin: tuple[float, float, float]
    tensioner: tuple[float, float, float]
    stinger: Any
    roller_tops: FloatArray
    roller_heights: FloatArray
    vessel_x: float
    pipe_length: float
    top_tension: float
    overbend_strain: float
    tip_clearance: float
    state: Any
    solves: int
    box: Any = None

    def table(self) -> dict[str, Any]:
        """The stinger as a scenario file's ``[vessel.lay.stinger]`` table (radius, length, rollers, origin, and
        the box at every place)."""
        return {
            "radius": self.radius,
            "length": self.length,
            "rollers": self.rollers,
            "origin": list(self.origin),
            **({} if self.box is None else {"box": _box_table(self.box)}),
        }


@dataclass
class _Solved:
    """One stinger solved at the top tension."""

    radius: float
    length: float
    rollers: int
    x: float
    state: Any
    clearance: float
    strain: float


def _point(name: str, value: Sequence[float]) -> tuple[float, float, float]:
    """`value` as a finite 3-vector, else an InputError naming `name`."""
    array = np.asarray(value, dtype=np.float64)
    if array.shape != (3,) or not np.all(np.isfinite(array)):
        raise pl.InputError(f"{name}: a point (x, y, z) in the vessel's body frame (m), got {value!r}")
    return (float(array[0]), float(array[1]), float(array[2]))


def design_stinger(
    section: Any,
    depth: float,
    top_tension: float,
    *,
    overbend_strain: float = 0.0018,
    tip_clearance: float = 0.3,
    vessel: Any = None,
    tensioner: Sequence[float] = (10.0, 0.0, -6.3),
    origin: Sequence[float] = (-40.0, 0.0, -6.0),
    roller_spacing: float = 7.0,
    seabed: Any = None,
    element_length: float = 2.5,
    strain_tolerance: float = 0.01,
    clearance_tolerance: float = 0.005,
    box: Any = None,
) -> StingerDesign:
    """The stinger (radius, length, roller tops) on which a pipe laid in `depth` at `top_tension` strains by
    `overbend_strain` over the stinger and clears its last roller by `tip_clearance`.

    Args:
        section: the pipe (`pl.Section.pipe`, with its EA and outer diameter).
        depth: water depth (m).
        top_tension: the effective tension at the tensioner (N).
        overbend_strain: the target largest strain over the stinger (a fraction, above T/EA).
        tip_clearance: the target gap between the pipe and the last roller (m, > 0).
        vessel: the lay vessel (`pl.Vessel`); None: `pl.Vessel.osv()`.
        tensioner: the tensioner on the firing line (body frame, m).
        origin: the first roller's top point, where the arc starts level (body frame, m).
        roller_spacing: about how far apart the rollers are along the arc (m).
        seabed: the seabed (`pl.Seabed`); None: soft clay (k = 1e5 Pa/m, μ = 0.5, 2 cm mobilisation).
        element_length: the pipe's element length (m).
        strain_tolerance: on the solved overbend strain, relative to the target.
        clearance_tolerance: on the solved tip clearance (m).
        box: a `pl.RollerBox` standing at every roller's place (its station on the arc), or None: lone rollers.

    Returns:
        The design (`StingerDesign`), its lay solved on it.

    Raises:
        pipelay.InputError: a bad argument, or a target no stinger meets (an overbend strain at or below the
            axial strain T/EA; a clearance that needs more than a quarter circle of stinger).
    """
    depth = _number("depth", depth, positive=True)
    tension = _number("top_tension", top_tension, positive=True)
    target = _number("overbend_strain", overbend_strain, positive=True)
    clearance = _number("tip_clearance", tip_clearance, positive=True)
    spacing = _number("roller_spacing", roller_spacing, positive=True)
    element = _number("element_length", element_length, positive=True)
    strain_tolerance = _number("strain_tolerance", strain_tolerance, positive=True)
    clearance_tolerance = _number("clearance_tolerance", clearance_tolerance, positive=True)
    tensioner_point = _point("tensioner", tensioner)
    origin_point = _point("origin", origin)
    diameter = float(section.outer_diameter)
    axial = tension / float(section.EA)
    if target <= axial:
        raise pl.InputError(
            f"overbend_strain: above the axial strain T/EA = {axial:.4g} of the top tension, got {target!r}"
        )
    vessel = vessel if vessel is not None else pl.Vessel.osv()
    seabed = seabed if seabed is not None else pl.Seabed(stiffness=1e5, friction=0.5, mobilisation=0.02)

    # The pipe: 100 m laid from end A, then the catenary of the top tension's horizontal part H (w the
    # submerged weight), which rises the depth over an arc length s = √(h² + 2hH/w), the longest stinger
    # (a quarter circle) and the deck to the tensioner; the vessel first with the tensioner just short of
    # the pipe's end B (its reference), from where the search for the top tension moves it.
    weight = float(section.submerged_weight)
    horizontal = max(tension - weight * depth, 0.1 * tension)
    suspended = math.sqrt(depth**2 + 2.0 * depth * horizontal / weight)
    thin_radius = 0.5 * diameter / (target - axial) - 0.5 * diameter
    deck = tensioner_point[0] - origin_point[0]
    laid = 100.0
    pipe_length = laid + suspended + 0.5 * math.pi * thin_radius + deck
    elements = math.ceil(pipe_length / element)
    pipe_length = elements * element
    start_x = pipe_length - deck - START_OFFSET

    solves = 0
    last_x = [start_x]

    def solve(radius: float, length: float, rollers: int) -> _Solved:
        nonlocal solves
        stinger = _stinger(radius, length, rollers, origin_point, box)

        def build(x: float) -> Any:
            rod = pl.Rod.straight((0.0, 0.0, 0.0), (pipe_length, 0.0, 0.0), elements, section)
            model = pl.Model(rod, sea=pl.Sea(depth, seabed=seabed))
            model.pin("A")
            lay = pl.SLay(tensioner=tensioner_point, stinger=stinger)
            model.attach_vessel("B", vessel, eta=[x, 0.0, -depth, 0.0, 0.0, 0.0], lay=lay)
            return model

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pl.PhysicsWarning)  # trial stingers may overbend the pipe
            found = find_lay_position(build, "top_tension", tension, start=last_x[0], max_solves=MAX_SOLVES)
        solves += found.solves
        last_x[0] = found.x
        summary = found.state.lay_summary()
        return _Solved(
            radius,
            length,
            rollers,
            found.x,
            found.state,
            float(summary["tip_clearance"]),
            float(summary["overbend_strain"]),
        )

    def rollers_over(length: float) -> int:
        """The rollers spread over a stinger of `length`, about `roller_spacing` apart (3 at least)."""
        return max(3, round(length / spacing) + 1)

    def _attempt(radius: float, length: float) -> _Solved | None:
        """The stinger of `radius` and `length` solved, or None where statics fail on it."""
        try:
            return solve(radius, length, rollers_over(length))
        except (pl.ConvergenceError, TargetNotReached):
            return None

    def for_clearance(radius: float) -> _Solved:
        """The stinger of `radius` whose last roller clears the pipe by `clearance`: lengths stepped up from
        0.3 R until the clearance passes the target (a length whose statics fail counts as too short: the pipe
        bends over the tip), then down from the first long enough if none below the target was solved."""
        longest = 0.5 * math.pi * radius
        step = max(2.0 * spacing, 0.1 * radius)
        low: _Solved | None = None
        high: _Solved | None = None
        length = 0.3 * radius
        while high is None:
            if length > longest:
                raise pl.InputError(
                    f"tip_clearance: a stinger of radius {radius:.1f} m would need more than a quarter circle "
                    f"({longest:.1f} m) to clear the pipe by {clearance!r} m"
                )
            trial = _attempt(radius, length)
            if trial is not None and trial.clearance >= clearance:
                high = trial
            else:
                low = trial or low
                length += step
        while low is None:
            length -= 0.5 * step
            trial = _attempt(radius, length) if length > 0.05 * radius else None
            if trial is None:
                raise pl.InputError(
                    f"tip_clearance: {clearance!r} m not bracketed at radius {radius:.1f} m: statics fail "
                    f"on the stinger {length:.1f} m long below {high.length:.1f} m"
                )
            if trial.clearance < clearance:
                low = trial
            else:
                high = trial
        # Illinois on the clearance's miss, the roller count kept: the rollers spread over the length found.
        rollers = rollers_over(high.length)
        low, high = solve(radius, low.length, rollers), solve(radius, high.length, rollers)
        best = min((low, high), key=lambda s: abs(s.clearance - clearance))
        low_length, low_miss = low.length, low.clearance - clearance
        high_length, high_miss = high.length, high.clearance - clearance
        side = 0
        for _ in range(MAX_ROUNDS):
            if abs(best.clearance - clearance) <= clearance_tolerance:
                return best
            if low_miss >= 0.0 or high_miss <= 0.0:
                break  # the roller count kept moved the bracket: no root between
            length = (low_length * high_miss - high_length * low_miss) / (high_miss - low_miss)
            trial = solve(radius, length, rollers)
            best = min((best, trial), key=lambda s: abs(s.clearance - clearance))
            miss = trial.clearance - clearance
            if miss < 0.0:
                low_length, low_miss = length, miss
                high_miss *= 0.5 if side == -1 else 1.0
                side = -1
            else:
                high_length, high_miss = length, miss
                low_miss *= 0.5 if side == 1 else 1.0
                side = 1
        if abs(best.clearance - clearance) > clearance_tolerance:
            raise pl.InputError(
                f"tip_clearance: {clearance!r} m not met within {clearance_tolerance} m at radius {radius:.1f} m "
                f"(closest {best.clearance:.4f} m)"
            )
        return best

    radius = thin_radius
    previous: _Solved | None = None
    design = for_clearance(radius)
    for _ in range(MAX_ROUNDS):
        if abs(design.strain - target) <= strain_tolerance * target:
            break
        if previous is None:
            # The strain goes as 1/R: scale the radius by the ratio of the strains' bending parts.
            step = radius * (design.strain - axial) / (target - axial)
        else:
            slope = (design.strain - previous.strain) / (design.radius - previous.radius)
            step = design.radius + (target - design.strain) / slope
        previous, radius = design, step
        design = for_clearance(radius)
    else:
        raise pl.InputError(
            f"overbend_strain: {target!r} not met within {strain_tolerance:.0%} (closest {design.strain:.5g} at "
            f"radius {design.radius:.1f} m)"
        )
    return _design(design, origin_point, tensioner_point, pipe_length, solves, box)


def _box_table(box: Any) -> dict[str, Any]:
    """A roller box as a scenario file's ``[vessel.lay.stinger.box]`` table."""
    keys = (
        "kind",
        "half_angle",
        "roller_length",
        "bottom",
        "sides",
        "friction",
        "rolling_resistance",
        "locked",
    )
    return {key: getattr(box, key) for key in keys}


def _stinger(radius: float, length: float, rollers: int, origin: tuple[float, float, float], box: Any) -> Any:
    """The stinger of `rollers` lone rollers, or of `box`es at their places, over the arc."""
    boxes = None if box is None else [box] * rollers
    return pl.Stinger(radius=radius, length=length, rollers=rollers, origin=origin, boxes=boxes)


def _design(
    solved: _Solved,
    origin: tuple[float, float, float],
    tensioner: tuple[float, float, float],
    pipe_length: float,
    solves: int,
    box: Any = None,
) -> StingerDesign:
    """The `StingerDesign` of a solved stinger."""
    state = solved.state
    rollers = solved.rollers
    stinger = _stinger(solved.radius, solved.length, rollers, origin, box)
    tops = np.asarray(stinger.stations, dtype=np.float64)
    return StingerDesign(
        radius=solved.radius,
        length=solved.length,
        rollers=rollers,
        origin=origin,
        tensioner=tensioner,
        stinger=stinger,
        roller_tops=tops,
        roller_heights=origin[2] - tops[:, 2],
        vessel_x=solved.x,
        pipe_length=pipe_length,
        top_tension=float(state.lay_summary()["top_tension"]),
        overbend_strain=solved.strain,
        tip_clearance=solved.clearance,
        state=state,
        solves=solves,
        box=box,
    )
