"""Realistic S-lay and J-lay cases as scenario documents, designed the way a lay engineer would and drawn at random
from a seed: the cases of the robustness campaign (``benches/robustness.py``) and of its fixed subset in
``tests/test_robustness.py``, with the physical-state check both apply to a converged static state.

A case is a scenario document (the dict a TOML scenario file parses into, read by
``pipelay.scenario.parse_scenario``) and its **design**: the numbers the generator's own design equations give
(catenary parameter, horizontal and top tension, departure angle, layback, strains), written down before anything
is solved. `draw(seed, index)` gives case `index` of the campaign of seed `seed` on its own; `design(Choices(...))`
builds a case from chosen parameters.

**Sensible.** A case is sensible when its design satisfies every rule of `RULES` below; the generator draws until
it does (the draws it threw away are counted by rule). The rules are a lay engineer's design rules evaluated on the
pipe's properties and on closed-form catenary and stinger geometry, never on a solver's outcome:

* the pipe: an API 5L size (6–32", standard wall) with D/t in [15, 45], whose collapse resistance (DNV-ST-F101
  Sec.5 [5.4.4], ovality 0.5 %) is at least γ_m·γ_SC = 1.15·1.04 times the water pressure at the seabed, and whose
  specific gravity (empty or flooded, coatings included) is at least 1.1, so that the laid pipe stays down (an
  empty pipe too light gets a concrete coat in S-lay depths, else the draw is thrown away);
* the catenary of submerged weight w and horizontal tension H = a·w from the seabed to the lift-off point (S-lay)
  or the tower exit (J-lay), of height h and arc length s: sagbend strain (D/2)/a ≤ 0.20 %; top tension
  w·(a + height of the hold point above the seabed) ≤ 6000 kN; and the catenary a valid design: the pipe's bending
  length sqrt(EI/H) at most h/2 (a stiff pipe in shallow water at a low tension is not a catenary), the current's
  drag on the span, ½ρ·C_d·D_h·v²·s at the surface speed, at most H (the tension, not the current, shapes the
  line);
* S-lay: a stinger of radius R (50–400 m) chosen for an overbend bending strain D/2R of 55–85 % of DNV's 0.85·SMYS/E,
  and D/2R + T_top/EA ≤ 0.85·SMYS/E; the pipe leaves it at 72–92 % of its length (some tip clearance), at a
  departure angle ≤ 60°; the stinger 30–150 m long, its tip at least max(5 m, 10 % of the depth) above the seabed;
* J-lay: the catenary's natural top angle 2–20° from the vertical, the tower within 1.5° of it;
* DP (thrusters, allocation, observer, wind and current on the hull): only where the design's horizontal pull is
  at most 40 % of what the OSV's thrusters give in surge;
* the sea: currents 0–1.2 m/s toward any heading (uniform, linearly sheared or a 1/7 power law), JONSWAP waves of
  Hs 0.5–3 m (a lay's operating range) or none.

**Where the vessel sits.** The laid pipe runs along e1 from end A (pinned at the origin, on the seabed) to the
touchdown at x_td; the catenary spans x_c = a·acosh(1 + h/a) horizontally from there to the lift-off point (S-lay)
or the tower exit (J-lay), h that point's height above the seabed; the vessel's x follows from the equipment's
body-frame geometry. The pipe's unstretched length is the path's length less its elastic stretch under the design
tension, so that the static state's horizontal tension is near the design's H.

The model's limits the design takes as they are: the pipe carries its submerged weight also above the surface
(Limitations), and the vessel's centre of origin sits at the surface (η's z = −depth).
"""

from __future__ import annotations

import dataclasses
import math
from collections import Counter
from dataclasses import dataclass
from typing import Any

import numpy as np
import pipelay as pl

G = 9.81
"""Gravity (m/s²), the model's default."""
RHO_WATER = 1025.0
"""Sea water density (kg/m³), the model's default."""
STEEL_E = 207e9
"""Young's modulus of the steel (Pa), Section.pipe's default."""

NOMINAL_OD: dict[int, float] = {
    6: 0.1683, 8: 0.2191, 10: 0.2731, 12: 0.3239, 14: 0.3556, 16: 0.4064, 18: 0.4572, 20: 0.5080,
    22: 0.5588, 24: 0.6096, 26: 0.6604, 28: 0.7112, 30: 0.7620, 32: 0.8128,
}  # fmt: skip
"""API 5L outer diameters (m) by nominal size (inch)."""

API_WALLS: tuple[float, ...] = (
    0.0048, 0.0052, 0.0056, 0.0064, 0.0071, 0.0079, 0.0087, 0.0095, 0.0103, 0.0111, 0.0119, 0.0127, 0.0143,
    0.0159, 0.0175, 0.0191, 0.0206, 0.0222, 0.0238, 0.0254, 0.0270, 0.0286, 0.0302, 0.0318, 0.0333, 0.0349,
    0.0365, 0.0381,
)  # fmt: skip
"""API 5L standard wall thicknesses (m)."""

GRADES = (("X52", 0.10), ("X60", 0.15), ("X65", 0.50), ("X70", 0.25))
"""Line pipe grades and how often the generator picks each."""
SMYS = {"X52": 360e6, "X60": 415e6, "X65": 450e6, "X70": 485e6}
"""Specified minimum yield strength (Pa) of each grade (as pipelay.analysis.checks tabulates them)."""

TENSIONER_X = 10.0
"""The S-lay tensioner's body-frame x (m), as in the examples; its z puts the pipe on the stinger's first roller."""
STINGER_ORIGIN = (-40.0, -6.0)
"""The stinger's origin (top line), body frame x and z (m): 40 m aft of CO, 6 m above the waterline."""
TOWER_EXIT = (0.0, -10.0)
"""The J-lay tower exit, body frame x and z (m): at CO, 10 m above the waterline."""
ROLLER_RADIUS = 0.25
"""Roller radius (m), pl.Stinger's default."""

# The design rules ("sensible"), each with its limit: D/t range, collapse safety factor γ_m·γ_SC, least specific
# gravity, largest sagbend strain, largest top tension (N), overbend strain as a share of SMYS/E, stinger radius and
# length (m), steepest departure (rad), J-lay natural top angle (rad from the vertical), largest DP pull as a share of
# the OSV's surge thrust, largest bending length as a share of the catenary's height, largest current drag on the
# span as a share of H.
DT_RANGE = (15.0, 45.0)
COLLAPSE_FACTOR = 1.15 * 1.04
SPECIFIC_GRAVITY_MIN = 1.1
SAGBEND_STRAIN_MAX = 0.0020
TOP_TENSION_MAX = 6.0e6
OVERBEND_FACTOR = 0.85
STINGER_RADIUS = (50.0, 400.0)
STINGER_LENGTH = (30.0, 150.0)
DEPARTURE_MAX = math.radians(60.0)
JLAY_TOP_ANGLE = (math.radians(2.0), math.radians(20.0))
DP_PULL_SHARE = 0.4
BENDING_SHARE = 0.5
DRAG_SHARE = 1.0

RULES: dict[str, str] = {
    "d/t": "D/t in [15, 45]",
    "collapse": "collapse pressure ≥ 1.15·1.04 × the water pressure at the seabed (DNV-ST-F101, ovality 0.5 %)",
    "floats": "specific gravity ≥ 1.1 (coatings and contents included)",
    "sagbend": "catenary sagbend strain (D/2)/a ≤ 0.20 %",
    "tension": "top tension ≤ 6000 kN",
    "stiffness": "the pipe's bending length sqrt(EI/H) ≤ half the catenary's height (the catenary design holds)",
    "drag": "the current's drag on the suspended span, ½ρC_d D_h v²·s, ≤ H (the tension holds the catenary)",
    "overbend": "D/2R + T_top/EA ≤ 0.85·SMYS/E on the stinger",
    "stinger": "stinger 30–150 m long, radius 50–400 m, departure ≤ 60°, its tip clear of the seabed",
    "tower": "J-lay natural top angle 2–20° from the vertical",
    "dp": "DP only for a horizontal pull ≤ 40 % of the OSV's surge thrust",
}
"""The rules a sensible case satisfies (what each rejection counts against)."""


class Unsensible(Exception):
    """A draw that breaks a design rule (its key in RULES)."""

    def __init__(self, rule: str, detail: str) -> None:
        super().__init__(f"{rule}: {detail}")
        self.rule = rule


@dataclass(frozen=True)
class Choices:
    """What a case is made of: the lay, pipe, sea and mesh choices the design works from (SI units; angles in
    degrees where the name says so). The defaults are a typical case; `draw_choices` draws them all."""

    kind: str = "s-lay"
    depth: float = 120.0
    nps: int = 16
    wall: float = 0.0159
    grade: str = "X65"
    coating: str = "3lpe"  # "bare", "3lpe" (3 mm polyethylene) or "concrete" (3LPE and a concrete coat)
    concrete: float = 0.05  # m, the concrete coat's thickness
    concrete_density: float = 3040.0  # kg/m³
    flooded: bool = False
    sagbend_strain: float = 0.0010  # J-lay: the design's (D/2)/a, which sets the tower's angle
    departure_deg: float | None = None  # S-lay: the departure angle aimed at (None: the depth's typical one)
    bend_share: float = 0.7  # D/2R as a share of the overbend limit 0.85·SMYS/E (S-lay)
    liftoff: float = 0.85  # where on the stinger the pipe leaves it, a share of the stinger's length
    roller_spacing: float = 6.5  # m
    tower_offset_deg: float = 0.0  # the J-lay tower's angle less the catenary's natural top angle
    laid_share: float = 0.3  # the laid pipe's length as a share of the catenary's span (plus 30 m)
    element: float = 8.0  # m, the element length away from the stinger
    fine_element: float = 2.5  # m, on and near the stinger (S-lay)
    elements: int | None = None  # a number of elements to aim at (the element length follows), or None
    current: float = 0.0  # m/s at the surface
    current_heading_deg: float = 0.0  # toward, from e1 (the lay direction) toward e2
    current_profile: str = "uniform"  # "uniform", "linear" (to 0 at the seabed) or "power" (1/7 power law)
    hs: float = 0.0  # m, 0: no waves
    tp: float = 8.0  # s
    wave_heading_deg: float = 0.0
    wave_seed: int = 1
    dp: bool = False
    wind: float = 0.0  # m/s (DP cases: on the hull)
    wind_heading_deg: float = 0.0
    seabed_stiffness: float = 1e5  # Pa/m
    seabed_friction: float = 0.5


@dataclass(frozen=True)
class LayCase:
    """A generated case: its scenario document and its design numbers.

    Attributes:
        index: the case's index in its campaign (-1 for a case built from chosen parameters).
        seed: the campaign's seed.
        choices: what it was made of.
        scenario: the scenario document (the dict of a TOML scenario file).
        design: the design's numbers (SI units, rad): "a" (m), "h" (the catenary's height, m), "H" and
            "top_tension" (N), "departure" (rad), "sagbend_strain", "overbend_strain", "layback" (m),
            "x_touchdown" (m), "x_vessel" (m), "length" (unstretched, m), "stretch" (m), "hold_z" (the hold
            point's body-frame z, m), "elements", "w" (submerged weight, N/m), "w_dry" (N/m), "D_h" (m),
            "specific_gravity", "EA" (N), "EI" (N·m²), and for an S-lay "stinger_radius", "stinger_length" (m),
            "rollers", "liftoff_arc" (m); for a J-lay "top_angle" (natural, rad from the vertical) and
            "tower_angle" (rad).
    """

    index: int
    seed: int
    choices: Choices
    scenario: dict[str, Any]
    design: dict[str, float]

    @property
    def kind(self) -> str:
        """The lay: "s-lay" or "j-lay"."""
        return self.choices.kind

    @property
    def label(self) -> str:
        """A one-line description: lay, pipe, depth, current, waves, DP."""
        c = self.choices
        coat = {"bare": "bare", "3lpe": "3LPE", "concrete": f"{1e3 * c.concrete:.0f} mm concrete"}[c.coating]
        sea = f"current {c.current:.2f} m/s toward {c.current_heading_deg:.0f}° ({c.current_profile})"
        if c.current == 0.0:
            sea = "no current"
        if c.hs > 0.0:
            sea += f", Hs {c.hs:.1f} m Tp {c.tp:.1f} s toward {c.wave_heading_deg:.0f}°"
        return (
            f'{c.kind} {c.depth:.0f} m, {c.nps}" × {1e3 * c.wall:.1f} mm {c.grade} {coat}'
            f"{' flooded' if c.flooded else ''}, {sea}{', DP' if c.dp else ''}, {self.design['elements']:.0f} el."
        )


# The pipe.


def collapse_pressure(od: float, wall: float, smys: float, fabrication: float = 0.85) -> float:
    """DNV-ST-F101 Sec.5 [5.4.4] collapse pressure p_c (Pa) of a pipe of outer diameter `od` and wall `wall` (m),
    yield strength `smys` (Pa), fabrication factor `fabrication`, ovality 0.5 %: the root of
    (p_c − p_el)(p_c² − p_p²) = p_c·p_el·p_p·f0·D/t below min(p_el, p_p)."""
    ratio = od / wall
    elastic = 2.0 * STEEL_E / (1.0 - 0.3**2) / ratio**3
    plastic = 2.0 * smys * fabrication / ratio
    f0 = 0.005

    def excess(p: float) -> float:
        return (p - elastic) * (p * p - plastic * plastic) - p * elastic * plastic * f0 * ratio

    low, high = 0.0, min(elastic, plastic)
    for _ in range(100):
        middle = 0.5 * (low + high)
        if excess(middle) > 0.0:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


def pipe_table(c: Choices) -> dict[str, Any]:
    """The `[pipe]` table of the choices."""
    table: dict[str, Any] = {
        "outer_diameter": NOMINAL_OD[c.nps],
        "wall_thickness": c.wall,
        "grade": c.grade,
        "contents_density": RHO_WATER if c.flooded else 0.0,
        "drag": [0.0, 1.2 if c.coating == "concrete" else 1.0],
        "added_mass": [0.0, 1.0],
    }
    if c.coating in ("3lpe", "concrete"):
        table["coatings"] = [{"thickness": 0.003, "density": 940.0}]
    if c.coating == "concrete":
        table["coatings"].append({"thickness": round(c.concrete, 4), "density": c.concrete_density})
    return table


def section_of(pipe: dict[str, Any]) -> pl.Section:
    """The pl.Section of a `[pipe]` table."""
    coatings = [pl.Coating(layer["thickness"], layer["density"]) for layer in pipe.get("coatings", [])]
    return pl.Section.pipe(
        pipe["outer_diameter"],
        pipe["wall_thickness"],
        grade=pipe["grade"],
        contents_density=pipe["contents_density"],
        coatings=coatings,
        drag=tuple(pipe["drag"]),
        added_mass=tuple(pipe["added_mass"]),
    )


def _check_pipe(c: Choices) -> None:
    """The pipe's rules: D/t and collapse (a float raises Unsensible("floats") in `design`)."""
    od = NOMINAL_OD[c.nps]
    ratio = od / c.wall
    if not DT_RANGE[0] <= ratio <= DT_RANGE[1]:
        raise Unsensible("d/t", f"D/t = {ratio:.1f}")
    fabrication = 1.0 if c.nps <= 16 else 0.85  # seamless up to 16", UOE above
    resistance = collapse_pressure(od, c.wall, SMYS[c.grade], fabrication)
    pressure = RHO_WATER * G * c.depth
    if resistance < COLLAPSE_FACTOR * pressure:
        raise Unsensible("collapse", f"p_c = {resistance / 1e6:.1f} MPa at {pressure / 1e6:.1f} MPa")


# The catenary.


def catenary_span(a: float, h: float) -> tuple[float, float]:
    """Horizontal span and arc length (m) of a catenary of parameter `a` (m) rising `h` (m) from its lowest
    point, where it is horizontal."""
    return a * math.acosh(1.0 + h / a), math.sqrt(h * h + 2.0 * a * h)


def catenary_tension_integral(a: float, h: float, w: float) -> float:
    """∫ T ds (N·m) along that catenary, T = w(a + y): w·a²(u/2 + sinh(2u)/4), u = span/a."""
    u = math.acosh(1.0 + h / a)
    return w * a * a * (0.5 * u + 0.25 * math.sinh(2.0 * u))


def parameter_for_angle(h: float, angle: float) -> float:
    """The catenary parameter a (m) whose slope is `angle` (rad below the horizontal) at height `h` (m):
    cos(angle) = a/(a + h)."""
    return h * math.cos(angle) / (1.0 - math.cos(angle))


# Stinger geometry (body frame: x forward, z down), for a stinger of radius R from STINGER_ORIGIN at slope 0.


def stinger_centreline(radius: float, angle: float, diameter: float) -> tuple[float, float]:
    """Body-frame x and z (m) of the centreline of a pipe of diameter `diameter` resting on the stinger where
    its top line slopes `angle` (rad)."""
    x0, z0 = STINGER_ORIGIN
    outer = radius + 0.5 * diameter
    return x0 - outer * math.sin(angle), z0 + radius - outer * math.cos(angle)


def design(c: Choices, index: int = -1, seed: int = 0) -> LayCase:
    """The case of choices `c`: its design and scenario; raises Unsensible if it breaks a rule."""
    _check_pipe(c)
    pipe = pipe_table(c)
    section = section_of(pipe)
    w = float(section.submerged_weight)
    od, dh = NOMINAL_OD[c.nps], float(section.hydrodynamic_diameter)
    gravity_g = float(section.mass) / (RHO_WATER * math.pi / 4.0 * dh * dh)
    if gravity_g < SPECIFIC_GRAVITY_MIN:
        raise Unsensible("floats", f"specific gravity {gravity_g:.2f}")
    w_dry = float(section.mass) * G
    ea, ei = float(section.EA), float(np.max(section.EI))
    strain_limit = OVERBEND_FACTOR * SMYS[c.grade] / STEEL_E
    d: dict[str, float] = {
        "w": w,
        "w_dry": w_dry,
        "D_h": dh,
        "EA": ea,
        "EI": ei,
        "specific_gravity": gravity_g,
    }
    if c.kind == "s-lay":
        onboard, path = _s_lay(c, od, dh, w, strain_limit, d)
    else:
        onboard, path = _j_lay(c, od, w, d)
    a, h = d["a"], d["h"]
    span, arc = catenary_span(a, h)
    laid = 30.0 + c.laid_share * span
    stretch = (a * w * laid + catenary_tension_integral(a, h, w) + d["top_tension"] * path) / ea
    length = laid + arc + path - stretch
    x_vessel = laid + span - onboard
    d.update(
        H=a * w,
        sagbend_strain=0.5 * od / a,
        layback=span + (TENSIONER_X if c.kind == "s-lay" else TOWER_EXIT[0]) - onboard,
        x_touchdown=laid,
        x_vessel=x_vessel,
        length=length,
        stretch=stretch,
    )
    if d["sagbend_strain"] > SAGBEND_STRAIN_MAX:
        raise Unsensible("sagbend", f"{100 * d['sagbend_strain']:.3f} %")
    if d["top_tension"] > TOP_TENSION_MAX:
        raise Unsensible("tension", f"{d['top_tension'] / 1e3:.0f} kN")
    bending_length = math.sqrt(ei / (a * w))
    if bending_length > BENDING_SHARE * h:
        raise Unsensible("stiffness", f"sqrt(EI/H) = {bending_length:.0f} m for a height of {h:.0f} m")
    drag = 0.5 * RHO_WATER * pipe["drag"][1] * dh * c.current**2 * arc
    if drag > DRAG_SHARE * a * w:
        raise Unsensible("drag", f"{drag / 1e3:.0f} kN on the span against H = {a * w / 1e3:.0f} kN")
    if c.kind == "s-lay":
        d["overbend_strain"] = 0.5 * od / d["stinger_radius"] + d["top_tension"] / ea
        if d["overbend_strain"] > strain_limit:
            raise Unsensible("overbend", f"{100 * d['overbend_strain']:.3f} % > {100 * strain_limit:.3f} %")
    if c.dp and a * w > DP_PULL_SHARE * osv_surge_thrust():
        raise Unsensible("dp", f"pull {a * w / 1e3:.0f} kN")
    fine_zone = 0.0
    if c.kind == "s-lay":  # onboard and the whole stinger
        fine_zone = (
            TENSIONER_X - STINGER_ORIGIN[0] + d["stinger_length"] * (1.0 + 0.5 * dh / d["stinger_radius"])
        )
    nodes = _mesh(c, length, fine_zone)
    d["elements"] = float(len(nodes) - 1)
    case = LayCase(index=index, seed=seed, choices=c, scenario=_scenario(c, pipe, nodes, d), design=d)
    name = f"robustness case {index} of seed {seed}" if index >= 0 else "robustness case"
    case.scenario["title"] = f"{name}: {case.label}"
    return case


def typical_departure(depth: float) -> float:
    """The departure angle (rad) an S-lay of depth `depth` (m) is typically designed for: 15° at 30 m to 55° at
    1000 m, linear in log(depth)."""
    share = min(max(math.log(depth / 30.0) / math.log(1000.0 / 30.0), 0.0), 1.0)
    return math.radians(15.0 + 40.0 * share)


def _s_lay(
    c: Choices, od: float, dh: float, w: float, strain_limit: float, d: dict[str, float]
) -> tuple[float, float]:
    """The S-lay's stinger and catenary into `d`; returns the lift-off point's body-frame x (m) and the pipe's
    path length (m) from the lift-off to the tensioner.

    The stinger's radius follows from the overbend; the departure angle is the choices' (or the depth's typical
    one), kept within what the rules allow: no steeper than 60°, than a 150 m stinger reaches or than a sagbend
    strain of 90 % of the limit, and no flatter than a top tension of 90 % of the limit. The catenary parameter
    follows from the angle and the lift-off's height; the stinger's length puts the lift-off at `c.liftoff` of
    it."""
    radius = 0.5 * od / (c.bend_share * strain_limit)
    radius = 10.0 * math.ceil(radius / 10.0)
    if not STINGER_RADIUS[0] <= radius <= STINGER_RADIUS[1]:
        raise Unsensible("stinger", f"radius {radius:.0f} m")
    hold_z = STINGER_ORIGIN[1] - 0.5 * dh

    def catenary(angle: float) -> tuple[float, float]:
        """The catenary parameter and the lift-off's height above the seabed (m) for a departure `angle`."""
        h = c.depth - stinger_centreline(radius, angle, dh)[1]
        if h <= 0.0:
            return math.inf, h
        return parameter_for_angle(h, angle), h

    def bisect(too_low: Any) -> float:
        """The angle in [1°, 60°] where `too_low(angle)` turns false (angles above it are not too low)."""
        low, high = math.radians(1.0), DEPARTURE_MAX
        for _ in range(60):
            middle = 0.5 * (low + high)
            if too_low(middle):
                low = middle
            else:
                high = middle
        return high

    # The sagbend strain grows and the top tension falls with the angle.
    steepest = min(
        DEPARTURE_MAX,
        c.liftoff * STINGER_LENGTH[1] / radius,
        bisect(lambda angle: 0.5 * od / catenary(angle)[0] < 0.9 * SAGBEND_STRAIN_MAX),
    )
    flattest = bisect(lambda angle: w * (catenary(angle)[0] + c.depth - hold_z) > 0.9 * TOP_TENSION_MAX)
    if flattest > steepest:
        raise Unsensible("tension", f"no departure between {math.degrees(flattest):.1f}° and the steepest")
    wanted = typical_departure(c.depth) if c.departure_deg is None else math.radians(c.departure_deg)
    angle = min(max(wanted, flattest), steepest)
    a, h = catenary(angle)
    if h <= 0.0:
        raise Unsensible("stinger", f"the lift-off at {math.degrees(angle):.0f}° lies below the seabed")
    length = max(5.0 * math.ceil(radius * angle / c.liftoff / 5.0), STINGER_LENGTH[0])
    tip = STINGER_ORIGIN[1] + radius * (1.0 - math.cos(length / radius))
    if c.depth - tip < max(5.0, 0.1 * c.depth):
        raise Unsensible("stinger", f"tip {tip:.1f} m deep in {c.depth:.0f} m")
    rollers = max(4, round(length / c.roller_spacing) + 1)
    x_liftoff = stinger_centreline(radius, angle, dh)[0]
    onboard_arc = (radius + 0.5 * dh) * angle + (TENSIONER_X - STINGER_ORIGIN[0])
    d.update(
        a=a,
        h=h,
        departure=angle,
        stinger_radius=radius,
        stinger_length=length,
        rollers=float(rollers),
        liftoff_arc=radius * angle,
        top_tension=w * (a + c.depth - hold_z),
        hold_z=hold_z,
    )
    return x_liftoff, onboard_arc


def vessel_position(case: LayCase, a: float) -> float:
    """The vessel's x (m) at which the design's equations put a catenary of parameter `a` (m) with the case's pipe:
    the same unstretched length, the laid pipe taking up what the catenary and the stinger leave (S-lay: the
    lift-off moves along the stinger with the departure angle a gives), stretched by the tension. The design's own
    position for the design's a; a target's position for another a."""
    c, d = case.choices, case.design
    w, dh = d["w"], d["D_h"]
    if c.kind == "s-lay":
        radius, angle = d["stinger_radius"], d["departure"]
        for _ in range(100):  # the departure whose lift-off height gives cos(angle) = a/(a + h)
            h = c.depth - stinger_centreline(radius, angle, dh)[1]
            angle = math.acos(a / (a + h))
        onboard = stinger_centreline(radius, angle, dh)[0]
        path = (radius + 0.5 * dh) * angle + (TENSIONER_X - STINGER_ORIGIN[0])
    else:
        h, onboard, path = d["h"], TOWER_EXIT[0], 0.0
    span, arc = catenary_span(a, h)
    top = w * (a + c.depth - d["hold_z"])
    stretch = (a * w * d["x_touchdown"] + catenary_tension_integral(a, h, w) + top * path) / d["EA"]
    laid = d["length"] + stretch - arc - path
    return laid + span - onboard


def _j_lay(c: Choices, od: float, w: float, d: dict[str, float]) -> tuple[float, float]:
    """The J-lay's catenary and tower into `d`; returns the tower exit's body-frame x (m) and 0 (no path beyond
    the catenary)."""
    h = c.depth - TOWER_EXIT[1]
    a = 0.5 * od / c.sagbend_strain
    top = math.asin(a / (a + h))  # the catenary's natural top angle from the vertical
    if not JLAY_TOP_ANGLE[0] <= top <= JLAY_TOP_ANGLE[1]:
        raise Unsensible("tower", f"natural top angle {math.degrees(top):.1f}°")
    tower = max(0.0, top + math.radians(c.tower_offset_deg))
    d.update(a=a, h=h, top_angle=top, tower_angle=tower, top_tension=w * (a + h), hold_z=TOWER_EXIT[1])
    return TOWER_EXIT[0], 0.0


def _mesh(c: Choices, length: float, fine_zone: float) -> list[float]:
    """The nodes' x (m) along the reference from end A: `c.element` long elements, and for an S-lay
    `c.fine_element` ones over the last `fine_zone` + 20 m (onboard, stinger and lift-off), graded by at most 1.25
    between neighbours; with `c.elements`, the coarse length that gives that many (if it stays within 3–15 m)."""

    def nodes(coarse: float) -> list[float]:
        fine = c.fine_element if c.kind == "s-lay" else coarse
        start_fine = length - fine_zone - 20.0 if c.kind == "s-lay" else length
        xs, x, size = [length], length, fine
        while x > 1e-9:
            size = fine if x > start_fine else min(coarse, 1.25 * size)
            if x - size < 0.5 * size:  # the last element takes what is left
                size = x
            x = max(x - size, 0.0)
            xs.append(x)
        return [round(v, 4) for v in reversed(xs)]

    coarse = c.element
    if c.elements is not None:
        low, high = 3.0, 15.0
        if len(nodes(low)) - 1 >= c.elements >= len(nodes(high)) - 1:
            for _ in range(60):
                middle = 0.5 * (low + high)
                if len(nodes(middle)) - 1 > c.elements:
                    low = middle
                else:
                    high = middle
            coarse = high
    return nodes(coarse)


def _direction(degrees: float) -> tuple[float, float]:
    """cos and sin of an angle in degrees, rounded (a current's heading)."""
    angle = math.radians(degrees)
    return round(math.cos(angle), 6), round(math.sin(angle), 6)


def _current(c: Choices) -> dict[str, Any] | None:
    """The `[sea.current]` table, or None for no current."""
    if c.current <= 0.0:
        return None
    cos, sin = _direction(c.current_heading_deg)
    surface = [round(c.current * cos, 4), round(c.current * sin, 4), 0.0]
    if c.current_profile == "uniform":
        return {"kind": "uniform", "velocity": surface}
    if c.current_profile == "linear":
        return {"kind": "linear", "surface_velocity": surface}
    shares = (0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)
    depths = [round(s * c.depth, 3) for s in shares]
    velocities = [[round(v * (1.0 - s) ** (1.0 / 7.0), 4) for v in surface] for s in shares]
    return {"kind": "profile", "depths": depths, "velocities": velocities}


def _scenario(c: Choices, pipe: dict[str, Any], xs: list[float], d: dict[str, float]) -> dict[str, Any]:
    """The scenario document of a designed case."""
    sea: dict[str, Any] = {
        "depth": c.depth,
        "seabed": {
            "stiffness": c.seabed_stiffness,
            "friction": [c.seabed_friction, c.seabed_friction],
            "mobilisation": 0.02,
        },
    }
    current = _current(c)
    if current is not None:
        sea["current"] = current
    if c.hs > 0.0:
        sea["waves"] = {
            "kind": "jonswap",
            "hs": c.hs,
            "tp": c.tp,
            "direction": round(math.radians(c.wave_heading_deg), 6),
            "seed": c.wave_seed,
            "components": 60,
        }
    if c.dp and c.wind > 0.0:
        sea["wind"] = {"speed": c.wind, "direction": round(math.radians(c.wind_heading_deg), 6), "seed": 2}
    x_vessel = round(d["x_vessel"], 3)
    vessel: dict[str, Any] = {"end": "B", "model": "osv", "eta": [x_vessel, 0.0, -c.depth, 0.0, 0.0, 0.0]}
    if c.kind == "s-lay":
        vessel["lay"] = {
            "kind": "s-lay",
            "tensioner": [TENSIONER_X, 0.0, round(d["hold_z"], 4)],
            "stinger": {
                "radius": d["stinger_radius"],
                "length": d["stinger_length"],
                "rollers": int(d["rollers"]),
                "origin": [STINGER_ORIGIN[0], 0.0, STINGER_ORIGIN[1]],
            },
        }
    else:
        vessel["lay"] = {
            "kind": "j-lay",
            "position": [TOWER_EXIT[0], 0.0, TOWER_EXIT[1]],
            "angle": round(d["tower_angle"], 6),
        }
    document: dict[str, Any] = {
        "title": "",
        "pipe": pipe,
        "rod": {"nodes": [[x, 0.0, 0.0] for x in xs]},
        "sea": sea,
        "supports": {"A": {"kind": "pin"}},
        "vessel": vessel,
    }
    if c.dp:
        vessel["hull_loads"] = True
        document["controller"] = dp_controller(x_vessel + d["H"] / DP_GAINS[0][0], c.depth)
    document["solver"] = {"dt": 0.1, "t_end": 30.0}
    return document


DP_GAINS = (
    [55768.9, 69768.9, 0.0, 0.0, 0.0, 1.3941e8],
    [1.11538e6, 1.39538e6, 0.0, 0.0, 0.0, 1.3941e9],
    [557.689, 697.689, 0.0, 0.0, 0.0, 2.78819e6],
)
"""kp, kd, ki of examples/j_lay_dp.toml: pole placement on the OSV's diag(M)."""


def dp_controller(x_reference: float, depth: float) -> dict[str, Any]:
    """The `[controller]` of a DP case: examples/j_lay_dp.toml's PID on the passive observer's estimate through
    the QP allocation, acting from t = 0, its reference `x_reference` (m) ahead of where the pipe's pull holds
    the vessel statically."""
    kp, kd, ki = DP_GAINS
    return {
        "kp": kp,
        "kd": kd,
        "ki": ki,
        "reference": [round(x_reference, 3), 0.0, -depth, 0.0, 0.0, 0.0],
        "allocation": "qp",
        "observer": {"noise": [0.5, 0.5, 0.005], "seed": 3},
    }


_SURGE_THRUST: list[float] = []


def osv_surge_thrust() -> float:
    """What the OSV's thrusters give in surge (N): the allocation of a large surge command."""
    if not _SURGE_THRUST:
        allocation = pl.Vessel.osv().allocate(np.array([1e8, 0.0, 0.0, 0.0, 0.0, 0.0]))
        _SURGE_THRUST.append(float(allocation.tau[0]))
    return _SURGE_THRUST[0]


# Drawing.


def _pick(rng: np.random.Generator, options: tuple[tuple[Any, float], ...]) -> Any:
    """One of `options` ((value, weight), ...) at random."""
    weights = np.array([weight for _, weight in options])
    return options[int(rng.choice(len(options), p=weights / weights.sum()))][0]


def draw_choices(rng: np.random.Generator, kind: str) -> Choices:
    """Choices at random for a lay of `kind`: S-lay in 30–1000 m or J-lay in 300–3000 m (log-uniform), any size
    and wall, grades, coatings and contents as a project would, currents, waves and DP as the sea and the spread
    come."""
    low, high = (30.0, 1000.0) if kind == "s-lay" else (300.0, 3000.0)
    depth = float(np.round(np.exp(rng.uniform(math.log(low), math.log(high))), 1))
    nps = int(rng.choice(list(NOMINAL_OD)))
    od = NOMINAL_OD[nps]
    walls = [t for t in API_WALLS if DT_RANGE[0] <= od / t <= DT_RANGE[1]]
    wall = float(walls[int(rng.integers(len(walls)))])
    shallow = kind == "s-lay" and depth <= 300.0
    if shallow:
        coating = _pick(rng, (("bare", 0.2), ("3lpe", 0.3), ("concrete", 0.5)))
    elif kind == "s-lay":
        coating = _pick(rng, (("bare", 0.35), ("3lpe", 0.55), ("concrete", 0.1)))
    else:  # deep-water lines carry no weight coat
        coating = _pick(rng, (("bare", 0.4), ("3lpe", 0.6)))
    concrete = float(np.round(rng.uniform(0.04, 0.12), 3))
    concrete_density = float(rng.choice([2400.0, 3040.0]))
    current = 0.0 if rng.random() < 0.15 else float(np.round(rng.uniform(0.1, 1.2), 2))
    waves = rng.random() < 0.5
    hs = float(np.round(rng.uniform(0.5, 3.0), 2)) if waves else 0.0
    tp = float(np.round(rng.uniform(max(5.0, 4.0 * math.sqrt(max(hs, 0.5))), 13.0), 2))
    wave_heading = float(np.round(rng.uniform(0.0, 360.0), 1))
    elements = 500 if rng.random() < 0.3 else None
    spacing = float(np.round(rng.uniform(5.0, 8.0), 2))
    choices = Choices(
        kind=kind,
        depth=depth,
        nps=nps,
        wall=wall,
        grade=_pick(rng, GRADES),
        coating=coating,
        concrete=concrete,
        concrete_density=concrete_density,
        flooded=bool(rng.random() < 0.1),
        sagbend_strain=float(np.round(rng.uniform(0.0004, 0.0020), 6)),
        departure_deg=float(np.round(math.degrees(typical_departure(depth)) + rng.uniform(-8.0, 8.0), 2)),
        bend_share=float(np.round(rng.uniform(0.55, 0.85), 3)),
        liftoff=float(np.round(rng.uniform(0.72, 0.92), 3)),
        roller_spacing=spacing,
        tower_offset_deg=float(np.round(rng.uniform(-1.5, 1.5), 2)),
        laid_share=float(np.round(rng.uniform(0.1, 0.4), 3)),
        element=float(np.round(rng.uniform(5.0, 10.0), 2)),
        fine_element=float(np.round(spacing / rng.uniform(2.0, 3.0), 2)),
        elements=elements,
        current=current,
        current_heading_deg=float(np.round(rng.uniform(0.0, 360.0), 1)),
        current_profile=_pick(rng, (("uniform", 0.4), ("linear", 0.3), ("power", 0.3))),
        hs=hs,
        tp=tp,
        wave_heading_deg=wave_heading,
        wave_seed=int(rng.integers(1000)),
        dp=bool(rng.random() < 0.3),
        wind=float(np.round(rng.uniform(0.0, 15.0), 1)),
        wind_heading_deg=float(np.round((wave_heading + rng.uniform(-30.0, 30.0)) % 360.0, 1)),
        seabed_stiffness=float(rng.choice([1e5, 2e5, 3e5])),
        seabed_friction=float(np.round(rng.uniform(0.3, 0.8), 2)),
    )
    return choices


def _coated(choices: Choices) -> Choices:
    """An S-lay pipe too light to stay down gets the concrete coat that makes its specific gravity 1.3 (in
    5 mm steps, 40–150 mm), as a shallow-water project would give it; other cases are left as they are."""
    if choices.kind != "s-lay" or choices.depth > 300.0:
        return choices
    for millimetres in range(40, 155, 5):
        trial = dataclasses.replace(choices, coating="concrete", concrete=millimetres / 1e3)
        section = section_of(pipe_table(trial))
        dh = float(section.hydrodynamic_diameter)
        if float(section.mass) / (RHO_WATER * math.pi / 4.0 * dh * dh) >= 1.3:
            return trial
    return choices


def draw(seed: int, index: int, rejections: Counter[str] | None = None) -> LayCase:
    """Case `index` of the campaign of seed `seed`: an S-lay (60 %) or a J-lay, drawn from its own random stream
    ((seed, index)) until a draw is sensible, counting the others in `rejections` by rule."""
    rng = np.random.default_rng([seed, index])
    kind = "s-lay" if rng.random() < 0.6 else "j-lay"
    for _ in range(10_000):
        choices = draw_choices(rng, kind)
        try:
            return design(choices, index, seed)
        except Unsensible as refused:
            if refused.rule == "floats":
                try:
                    return design(_coated(choices), index, seed)
                except Unsensible as again:
                    refused = again
            if rejections is not None:
                rejections[refused.rule] += 1
    raise RuntimeError(f"no sensible case in 10000 draws (seed {seed}, case {index})")


# The physical-state check of a converged static state.

NONPHYSICAL: dict[str, str] = {
    "non-finite": "a position, rotation, tension or the vessel's pose is not finite",
    "through the rollers": "the pipe's centreline below a roller's top line by more than the contact's overlap "
    "(max(0.1 m, D_h/4)): the pipe passes through or under the stinger",
    "roller overload": "a roller carries more than 8 × (T_top/R + w)·spacing, a rope-over-pulley estimate of its "
    "share (the last roller: plus T_top times the angle by which the departure exceeds the stinger's tip slope)",
    "through the seabed": "a node deeper in the seabed than max(D_h, 10 × the penetration under the submerged weight)",
    "compression": "the pipe pushed at the hold point (top tension < 0)",
    "against the current": "the suspended span's largest sideways offset from its chord (touchdown to lift-off) "
    "against the current's cross component (≥ 0.1 m/s), by more than D_h",
    "strain": "a strain beyond 5 × the yield strain SMYS/E",
}
"""What makes a converged state non-physical (`physical_problems`), by kind."""


def body_rotation(eta: np.ndarray) -> np.ndarray:
    """R_b^e of the vessel's zyx Euler angles η[3:6]: Rz(ψ) Ry(θ) Rx(φ)."""
    phi, theta, psi = (float(v) for v in eta[3:6])
    cx, sx, cy, sy, cz, sz = (math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta), math.cos(psi),
                              math.sin(psi))  # fmt: skip
    rz = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    return rz @ ry @ rx


def roller_gaps(state: pl.State, case: LayCase) -> np.ndarray:
    """For each roller of an S-lay's stinger, the gap (m) between the pipe's surface and the roller: the distance
    from the roller's axis to the pipe's centreline (the chords between nodes), in the plane normal to the axis,
    along the roller's outward normal, less the roller's radius and half the hydrodynamic diameter. Negative: an
    overlap; far below zero: the pipe is under the roller."""
    tops = np.asarray(state.roller_positions)
    eta = np.asarray(state.eta)
    rotation = body_rotation(eta)
    axis = rotation @ np.array([0.0, 1.0, 0.0])
    radius, length = case.design["stinger_radius"], case.design["stinger_length"]
    count = len(tops)
    slopes = length * np.arange(count) / max(count - 1, 1) / radius
    normals = (rotation @ np.stack([-np.sin(slopes), np.zeros(count), -np.cos(slopes)])).T
    centres = tops - ROLLER_RADIUS * normals
    positions = np.asarray(state.positions)
    flat = positions - np.outer(positions @ axis, axis)  # in the plane normal to the axis
    gaps = np.empty(count)
    for k in range(count):
        centre = centres[k] - (centres[k] @ axis) * axis
        start, chord = flat[:-1], flat[1:] - flat[:-1]
        along = np.clip(np.einsum("ij,ij->i", centre - start, chord) / np.maximum(
            np.einsum("ij,ij->i", chord, chord), 1e-300), 0.0, 1.0)  # fmt: skip
        closest = start + along[:, None] * chord
        nearest = int(np.argmin(np.linalg.norm(closest - centre, axis=1)))
        gaps[k] = (closest[nearest] - centre) @ normals[k] - ROLLER_RADIUS - 0.5 * case.design["D_h"]
    return gaps


def current_cross(case: LayCase) -> float:
    """The current's component across the lay direction at the surface (m/s, along e2)."""
    c = case.choices
    return c.current * math.sin(math.radians(c.current_heading_deg))


def physical_problems(state: pl.State, case: LayCase) -> list[tuple[str, str]]:
    """What is non-physical in a converged static state of `case`: (kind, message) pairs, kinds of NONPHYSICAL
    (empty: nothing)."""
    d = case.design
    dh = d["D_h"]
    positions = np.asarray(state.positions)
    eta = np.asarray(state.eta)
    arrays = (positions, np.asarray(state.rotations), np.asarray(state.tension), eta)
    if not all(np.all(np.isfinite(array)) for array in arrays):
        return [("non-finite", "the state holds non-finite numbers")]
    problems: list[tuple[str, str]] = []
    summary = state.lay_summary() or {}
    top = float(summary.get("top_tension", math.nan))
    if top < 0.0:
        problems.append(("compression", f"top tension {top / 1e3:.1f} kN"))
    if case.kind == "s-lay":
        gaps = roller_gaps(state, case)
        tolerance = max(0.1, 0.25 * dh)
        if np.min(gaps) < -tolerance:
            k = int(np.argmin(gaps))
            problems.append(
                (
                    "through the rollers",
                    f"the pipe's surface {-gaps[k]:.2f} m below roller {k + 1}'s top (of {len(gaps)}, from 1)",
                )
            )
        reactions = np.asarray(state.roller_reactions)
        spacing = d["stinger_length"] / max(len(reactions) - 1, 1)
        tension = max(top, 0.0)
        share = np.full(len(reactions), (tension / d["stinger_radius"] + d["w"]) * spacing)
        # The last roller also turns the pipe through what its departure exceeds the stinger's tip slope by.
        kink = float(summary.get("departure_angle", 0.0)) - d["stinger_length"] / d["stinger_radius"]
        share[-1] += tension * max(kink, 0.0) if math.isfinite(kink) else 0.0
        if reactions.size and np.any(reactions > 8.0 * share):
            k = int(np.argmax(reactions / share))
            problems.append(
                (
                    "roller overload",
                    f"roller {k + 1} (of {len(reactions)}) carries {reactions[k] / 1e3:.0f} kN, > 8 × {share[k] / 1e3:.0f} kN",
                )
            )
    penetration = d["w"] / (case.choices.seabed_stiffness * dh)
    deepest = float(np.max(positions[:, 2]))
    if deepest > max(dh, 10.0 * penetration):
        problems.append(("through the seabed", f"a node {deepest:.2f} m below the seabed"))
    cross = current_cross(case)
    if abs(cross) >= 0.1:
        # The suspended span, from the touchdown to the lift-off, bowed from its chord: the vessel's heel and yaw
        # move the span's top sideways either way, the current bows the span downstream of its chord.
        arcs = np.asarray(state.reference_arc_length)
        liftoff = float(summary.get("liftoff_arc_length", arcs[-1]))
        span = np.flatnonzero((positions[:, 2] < -dh) & (arcs <= liftoff))
        offsets = np.empty(0)
        if span.size > 2:
            ends = [int(span[0]), int(span[-1])]
            offsets = positions[span, 1] - np.interp(arcs[span], arcs[ends], positions[ends, 1])
        if offsets.size:
            largest = float(offsets[int(np.argmax(np.abs(offsets)))])
            if largest * cross < 0.0 and abs(largest) > dh:
                problems.append(
                    (
                        "against the current",
                        f"largest offset {largest:+.2f} m, the current's cross {cross:+.2f} m/s",
                    )
                )
    strain = float(np.max(np.abs(np.asarray(state.strain))))
    yield_strain = SMYS[case.choices.grade] / STEEL_E
    if strain > 5.0 * yield_strain:
        problems.append(("strain", f"strain {100 * strain:.2f} % > 5 × yield {100 * yield_strain:.3f} %"))
    return problems
