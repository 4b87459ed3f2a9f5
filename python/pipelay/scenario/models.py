"""The scenario format as pydantic models: one model per table (and per kind of a table whose keys depend
on `kind`), its fields the keyword arguments of the API call the table maps onto, up to the whole file
(`ScenarioFile`). Each field's type carries the `Value` (`pipelay.scenario.values`) it is checked with, and a
rule that spans keys raises `rule(message, key)` from a validator.

The models are the format's reference too, stated once: a field's `description` is what the key means, `api`
records the default of a key the API call supplies, a model's docstring says what its table is (its first
paragraph in one line, the rest notes), and the `About` of a union what a table of several models is.
`pipelay.scenario.schema.reference_tables` reads them for the Scenario reference page and the JSON Schema.

This module has the models of the pipe, its supports and loads, the sea, the solver and the outputs, and the
file's; those of the vessel and what works with it are in `pipelay.scenario.models_vessel`, and this module
exposes them too: every model is here.

Imports of pipelay: `pipelay.scenario.values` and `pipelay.scenario.models_vessel`.
"""

from __future__ import annotations

import math
from typing import Annotated, ClassVar, Literal, cast

from pydantic import Discriminator, Field, Tag, model_validator

from pipelay.scenario.models_vessel import (
    ArcStinger,
    AzimuthThruster,
    Cable,
    Controller,
    ControllerTable,
    Environment,
    FixedController,
    Head,
    JLay,
    Lay,
    MainThruster,
    MatrixVessel,
    ModelVessel,
    Observer,
    PayOut,
    ReelLay,
    RollerBox,
    RollerStinger,
    Route,
    RouteController,
    SLay,
    Stinger,
    StingerSection,
    Tension,
    Thruster,
    TunnelThruster,
    Vessel,
    VesselTable,
    Winch,
)
from pipelay.scenario.values import (
    AXES,
    COEFFICIENTS,
    NODE,
    POINT,
    POSITIVE_LENGTH,
    START,
    VELOCITY,
    XYZ,
    About,
    Choice,
    End,
    Flag,
    Integer,
    Matrix,
    Number,
    Table,
    Text,
    Vector,
    _having,
    _table_or,
    api,
    number_or_vector,
    rule,
)

__all__ = [
    "MAX_ELEMENTS",
    "ArcStinger",
    "AzimuthThruster",
    "Bathymetry",
    "Cable",
    "Checks",
    "Clamp",
    "Controller",
    "ControllerTable",
    "Current",
    "Drive",
    "End",
    "Environment",
    "FixedController",
    "FlatBathymetry",
    "Gravity",
    "GridBathymetry",
    "Head",
    "JLay",
    "JonswapWaves",
    "Lay",
    "LinearCurrent",
    "MainThruster",
    "MatrixVessel",
    "ModelVessel",
    "NodesRod",
    "Observer",
    "Output",
    "PayOut",
    "Pin",
    "Pipe",
    "PipeMaterial",
    "PlaneBathymetry",
    "PointLoad",
    "ProfileCurrent",
    "ReelLay",
    "RegularWaves",
    "Rod",
    "RollerBox",
    "RollerStinger",
    "Route",
    "RouteController",
    "SLay",
    "ScenarioFile",
    "Sea",
    "Seabed",
    "Section",
    "Solver",
    "Stage",
    "Stinger",
    "StingerSection",
    "StraightRod",
    "Support",
    "Supports",
    "Table",
    "Tension",
    "Thruster",
    "TunnelThruster",
    "UniformCurrent",
    "Vessel",
    "VesselTable",
    "Waves",
    "Winch",
    "Wind",
]

MAX_ELEMENTS = 1_000_000
"""Largest number of elements a scenario's `[rod]` may ask for."""


class Gravity(Table):
    """Instead of the top-level `gravity` (`pl.Model(rod, sea, gravity)`)."""

    acceleration: Annotated[float, Number("m/s²", ge=0)] = Field(
        description="acceleration of gravity along +e3, ≥ 0"
    )


class Layer(Table):
    """`pl.Coating`: a coating outside the pipe's steel wall, one table per layer from the steel outwards. It
    adds its mass; the coatings' outer surface is the diameter that buoyancy, drag, added mass, the seabed and
    the rollers take."""

    thickness: Annotated[float, POSITIVE_LENGTH] = Field(description="layer thickness, > 0")
    density: Annotated[float, Number("kg/m³", ge=0)] = Field(description="density, ≥ 0")
    youngs_modulus: Annotated[float | None, Number("Pa", ge=0)] = api(
        "Young's modulus the layer adds to the axial and bending stiffness, ≥ 0 (0: none, as usual for concrete)",
        0,
    )


class Lining(Layer):
    """`pl.Coating` as the lining inside the pipe's steel wall: it adds its mass, and the contents fill its
    bore."""


class PipeMaterial(Table):
    """`[pipe.material]`: `pl.Material`, the steel's stress–strain law beyond yield (its Young's modulus the
    pipe's)."""

    kind: Annotated[
        Literal["elastic_perfectly_plastic", "ramberg_osgood", "grade"],
        Choice(("elastic_perfectly_plastic", "ramberg_osgood", "grade")),
    ] = Field(description="the law: elastic–perfectly plastic, Ramberg–Osgood, or a line pipe grade's")
    yield_stress: Annotated[float | None, Number("Pa", gt=0)] = api(
        "the yield stress (Ramberg–Osgood: at 0.5 % total strain); not for a grade", words="none"
    )
    n: Annotated[float | None, Number(gt=1)] = api(
        "Ramberg–Osgood's exponent (a grade's: 15 unless given)", words="none"
    )
    grade: Annotated[str | None, Text()] = api(
        'the line pipe grade, "X52" … "X80" (kind "grade")', words="none"
    )

    @model_validator(mode="after")
    def keys_of_the_kind(self) -> PipeMaterial:
        """Each kind's keys."""
        if self.kind in ("elastic_perfectly_plastic", "ramberg_osgood") and self.yield_stress is None:
            raise rule(f"is needed by kind {self.kind!r}", "yield_stress")
        if self.kind == "ramberg_osgood" and self.n is None:
            raise rule("is needed by kind 'ramberg_osgood'", "n")
        if self.kind == "grade" and self.grade is None:
            raise rule("is needed by kind 'grade'", "grade")
        return self


class StructuralDamping(Table):
    """`Section.with_structural_damping`: Kelvin–Voigt damping of the section's strains, each as a fraction of
    critical damping at one period (MoorDyn's BA/-zeta, OrcaFlex's target damping).

    The resultants gain β·C times the strain rates, β = ζ·period/π: a mode of period T is damped at
    ζ·period/T. Its work is dissipated. Off without the table.
    """

    period: Annotated[float, Number("s", gt=0)] = Field(
        description="the period at which the fractions hold, > 0"
    )
    axial: Annotated[float | None, Number(ge=0)] = api(
        "fraction of critical damping of the axial (and shear) strains at the period, ≥ 0", 0
    )
    bending: Annotated[float | None, Number(ge=0)] = api(
        "fraction of critical damping of the bending curvatures at the period, ≥ 0", 0
    )
    torsion: Annotated[float | None, Number(ge=0)] = api(
        "fraction of critical damping of the torsional curvature at the period, ≥ 0", 0
    )


class Pipe(Table):
    """`pl.Section.pipe`: a pipe from its geometry and material.

    Exactly one of `[pipe]` and `[section]`.
    """

    outer_diameter: Annotated[float, POSITIVE_LENGTH] = Field(description="outer diameter, > 0")
    wall_thickness: Annotated[float, POSITIVE_LENGTH] = Field(
        description="wall thickness, > 0 and ≤ outer_diameter / 2"
    )
    density: Annotated[float | None, Number("kg/m³", gt=0)] = api("density of the wall material, > 0", 7850)
    youngs_modulus: Annotated[float | None, Number("Pa", gt=0)] = api("Young's modulus, > 0", 207e9)
    poisson_ratio: Annotated[float | None, Number(gt=-1, lt=0.5)] = api("Poisson's ratio, in (−1, 0.5)", 0.3)
    contents_density: Annotated[float | None, Number("kg/m³", ge=0)] = api(
        "density of the contents (1025: flooded), ≥ 0", 0
    )
    drag: Annotated[list[float] | None, COEFFICIENTS] = api(
        "Morison drag coefficients [axial, normal], ≥ 0", [0, 1]
    )
    added_mass: Annotated[list[float] | None, COEFFICIENTS] = api(
        "added-mass coefficients [axial, normal], ≥ 0", [0, 1]
    )
    grade: Annotated[str | None, Text()] = api(
        'the steel\'s grade for the design checks, "X52" … "X80" (the checks take X65 without one)'
    )
    coatings: list[Layer] = Field(
        [], description="external coatings, from the steel outwards: `[[pipe.coatings]]` tables"
    )
    lining: Lining | None = api("internal lining: a `[pipe.lining]` table")
    material: PipeMaterial | None = api(
        "the steel's law beyond yield: a `[pipe.material]` table", words="linear elastic"
    )
    structural_damping: StructuralDamping | None = api(
        "Kelvin–Voigt damping of the pipe's strains: a `[pipe.structural_damping]` table", words="none"
    )

    @model_validator(mode="after")
    def thin_wall(self) -> Pipe:
        """The wall is at most half the diameter thick."""
        half = self.outer_diameter / 2.0
        if self.wall_thickness > half:
            got = f"got {self.wall_thickness:g}"
            raise rule(f"must be <= outer_diameter / 2 = {half:g} m, {got}", "wall_thickness")
        return self


class Section(Table):
    """`pl.Section`: the cross-section's properties directly, instead of `[pipe]`."""

    EA: Annotated[float, Number("N", gt=0)] = Field(description="axial stiffness, > 0")
    GA: Annotated[float | list[float], number_or_vector(2, Number("N", gt=0), AXES)] = Field(
        description="shear stiffness, > 0: a number or [axis 2, axis 3]"
    )
    GJ: Annotated[float, Number("N·m²", gt=0)] = Field(description="torsional stiffness, > 0")
    EI: Annotated[float | list[float], number_or_vector(2, Number("N·m²", gt=0), AXES)] = Field(
        description="bending stiffness, > 0: a number or [axis 2, axis 3]"
    )
    mass: Annotated[float, Number("kg/m", gt=0)] = Field(
        description="mass per unit length, contents included, > 0"
    )
    inertia: Annotated[list[float] | None, Vector(3, Number("kg·m", ge=0), "[J1, J2, J3]")] = api(
        "rotational inertia per length [J1, J2, J3], ≥ 0", [0, 0, 0]
    )
    outer_diameter: Annotated[float | None, Number("m", ge=0)] = api(
        "diameter that drag and added mass refer to, ≥ 0", 0
    )
    displaced_area: Annotated[float | None, Number("m²", ge=0)] = api(
        "buoyancy area per length (d: outer_diameter), ≥ 0", words="π/4·d²"
    )
    drag: Annotated[list[float] | None, COEFFICIENTS] = api(
        "Morison drag coefficients [axial, normal], ≥ 0", [0, 0]
    )
    added_mass: Annotated[list[float] | None, COEFFICIENTS] = api(
        "added-mass coefficients [axial, normal], ≥ 0", [0, 0]
    )
    rotational_damping: Annotated[
        float | list[float] | None, number_or_vector(3, Number("N·m·s/m", ge=0), "[t1, t2, t3]")
    ] = api("a number or [t1, t2, t3], ≥ 0", 0)
    structural_damping: StructuralDamping | None = api(
        "Kelvin–Voigt damping of the section's strains: a `[section.structural_damping]` table", words="none"
    )


class LineSegment(Table):
    """`pl.Segment`: one segment of a `[line]`, with exactly one of `[line.segments.pipe]`,
    `[line.segments.section]` and `[line.segments.cable]`."""

    length: Annotated[float, POSITIVE_LENGTH] = Field(description="unstretched length, > 0")
    elements: Annotated[int, Integer(1, MAX_ELEMENTS)] = Field(
        description="number of equal elements, an integer in [1, 1000000]"
    )
    pipe: Pipe | None = api("the segment's pipe: a `[line.segments.pipe]` table")
    section: Section | None = api("the segment's section: a `[line.segments.section]` table")
    cable: Cable | None = api("the segment's cable: a `[line.segments.cable]` table")

    @model_validator(mode="after")
    def one_section(self) -> LineSegment:
        """Exactly one of pipe, section and cable."""
        given = [name for name in ("pipe", "section", "cable") if getattr(self, name) is not None]
        if len(given) != 1:
            got = "none" if not given else " and ".join(given)
            raise rule(f"needs exactly one of pipe, section and cable, got {got}", "pipe")
        return self


class Line(Table):
    """`pl.Rod.segments`: a straight line of consecutive segments (each its own section and element count),
    instead of `[rod]` with `[pipe]` or `[section]`."""

    start: Annotated[list[float], POINT] = Field(description="the line's first node (end A) [x, y, z]")
    direction: Annotated[list[float], POINT] = Field(
        description="the direction from end A to end B [x, y, z], non-zero"
    )
    length: Annotated[float | None, POSITIVE_LENGTH] = api(
        "the line's total unstretched length, if given: the segments' lengths must sum to it (within 1e-9)"
    )
    segments: list[LineSegment] = Field(
        description="the segments from end A: `[[line.segments]]` tables, at least one"
    )

    @model_validator(mode="after")
    def lengths_sum(self) -> Line:
        """The segments, if the line's length is given, sum to it."""
        if not self.segments:
            raise rule("needs at least one [[line.segments]] table", "segments")
        total = sum(segment.length for segment in self.segments)
        if self.length is not None and abs(total - self.length) > 1e-9 * self.length:
            raise rule(f"must equal the segments' total length {total:g} m, got {self.length:g}", "length")
        return self


class StraightRod(Table):
    """`[rod]` with start, end and elements: `pl.Rod.straight`."""

    start: Annotated[list[float], POINT] = Field(description="first node (end A) [x, y, z] of a straight rod")
    end: Annotated[list[float], POINT] = Field(
        description="last node (end B) [x, y, z], distinct from `start`"
    )
    elements: Annotated[int, Integer(1, MAX_ELEMENTS)] = Field(
        description="number of equal elements n, an integer in [1, 1000000]"
    )


class NodesRod(Table):
    """`[rod]` with nodes: `pl.Rod(nodes, section)`."""

    conflicts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("start", "end", "elements"), "conflicts with rod.nodes; give either nodes or start, end and elements"
    )
    nodes: Annotated[list[list[float]], Matrix(None, POINT, at_least=2)] = Field(
        description="the nodes [[x, y, z], ...] from end A to end B, ≥ 2 of them"
    )


Rod = Annotated[
    Annotated[StraightRod, Tag("straight")] | Annotated[NodesRod, Tag("nodes")],
    Discriminator(_having("nodes", "nodes", "straight")),
    About("`pl.Rod.straight(start, end, elements)` or `pl.Rod(nodes)`: the stress-free reference."),
]


_CurrentStart = Annotated[float | None, START, api("time the current starts", 0)]
"""`start`, a key of every kind of current."""


class UniformCurrent(Table):
    """`[sea.current]` of kind "uniform": `pl.Current.uniform`."""

    kind: Literal["uniform"]
    velocity: Annotated[list[float], Vector(3, Number("m/s"), VELOCITY)] = Field(
        description="[vx, vy, vz] in e at every depth"
    )
    start: _CurrentStart = None


class LinearCurrent(Table):
    """`[sea.current]` of kind "linear": `pl.Current.linear`."""

    kind: Literal["linear"]
    surface_velocity: Annotated[list[float], Vector(3, Number("m/s"), VELOCITY)] = Field(
        description="[vx, vy, vz] at the surface, 0 at end A's depth"
    )
    start: _CurrentStart = None


class ProfileCurrent(Table):
    """`[sea.current]` of kind "profile": `pl.Current.profile`."""

    kind: Literal["profile"]
    depths: Annotated[list[float], Vector(None, Number("m"), at_least=1)] = Field(
        description="depths below the surface, increasing"
    )
    velocities: Annotated[list[list[float]], Matrix(None, Vector(3, Number("m/s"), VELOCITY), at_least=1)] = (
        Field(description="one [vx, vy, vz] per depth, interpolated")
    )
    start: _CurrentStart = None

    @model_validator(mode="after")
    def one_velocity_per_depth(self) -> ProfileCurrent:
        """As many velocities as depths."""
        count, got = len(self.depths), len(self.velocities)
        if got != count:
            raise rule(f"must have one row {VELOCITY} (m/s) per depth ({count}), got {got}", "velocities")
        return self


Current = Annotated[
    UniformCurrent | LinearCurrent | ProfileCurrent,
    Discriminator("kind"),
    About("`pl.Current.uniform`, `.linear` or `.profile`, chosen by `kind`."),
]


class FlatBathymetry(Table):
    """`[sea.seabed.bathymetry]` of kind "flat": `pl.Bathymetry.flat`."""

    kind: Literal["flat"]
    z: Annotated[float | None, Number("m")] = api("elevation of the seabed", 0)


class PlaneBathymetry(Table):
    """`[sea.seabed.bathymetry]` of kind "plane": `pl.Bathymetry.plane`."""

    kind: Literal["plane"]
    z: Annotated[float | None, Number("m")] = api("elevation at x = y = 0", 0)
    gradient: Annotated[list[float] | None, Vector(2, Number(), "[dz/dx, dz/dy]")] = api(
        "[dz/dx, dz/dy] (a positive value deepens along that axis)", [0, 0]
    )


class GridBathymetry(Table):
    """`[sea.seabed.bathymetry]` of kind "grid": `pl.Bathymetry.grid`."""

    kind: Literal["grid"]
    x: Annotated[list[float], Vector(None, Number("m"), at_least=2)] = Field(
        description="strictly increasing x of the grid points"
    )
    y: Annotated[list[float], Vector(None, Number("m"), at_least=2)] = Field(
        description="strictly increasing y of the grid points"
    )
    z: Annotated[
        list[list[float]],
        Matrix(None, Vector(None, Number("m")), text="rows of numbers, one row of len(y) per x (m)"),
    ] = Field(description="elevations, rows of len(y) numbers, one row per x")

    @model_validator(mode="after")
    def one_row_per_x(self) -> GridBathymetry:
        """z has a row per x, each with a number per y."""
        shape = Matrix(len(self.x), Vector(len(self.y), Number("m"), "(one per y)"))
        if len(self.z) != len(self.x):
            raise rule(shape.refuse("too_short", self.z), "z")
        for i, row in enumerate(self.z):
            if len(row) != len(self.y):
                raise rule(shape.row.refuse("too_short", row), f"z[{i}]")
        return self


Bathymetry = Annotated[
    FlatBathymetry | PlaneBathymetry | GridBathymetry,
    Discriminator("kind"),
    About(
        """`pl.Bathymetry.flat`, `.plane` or `.grid`, chosen by `kind`; default flat z = 0.

        Elevations z are in frame e (e3 down: larger z is deeper); the seabed must lie below the surface
        z = −depth."""
    ),
]


class Seabed(Table):
    """`pl.Seabed`: contact with the seabed (without it the pipe passes through the bottom)."""

    stiffness: Annotated[float | None, Number("Pa/m", gt=0)] = api(
        "normal force per length = stiffness · d · penetration of the centreline, > 0", 1e5
    )
    damping: Annotated[float | None, Number("Pa·s/m", ge=0)] = api("normal damping (dynamics), ≥ 0", 0)
    friction: Annotated[float | list[float] | None, number_or_vector(2, Number(ge=0), "[axial, lateral]")] = (
        api("Coulomb coefficient, a number or [axial, lateral], ≥ 0", 0)
    )
    mobilisation: Annotated[float | None, Number("m", gt=0)] = api(
        "sliding distance at which friction reaches μN (pipe under its own weight), > 0", 0.01
    )
    bathymetry: Bathymetry | None = None


_WaveDirection = Annotated[
    float | None, Number("rad"), api("direction the waves travel toward, from e1 toward e2", 0)
]
"""`direction`, a key of every kind of waves."""


class RegularWaves(Table):
    """`[sea.waves]` of kind "regular": `pl.Waves.regular`."""

    kind: Literal["regular"]
    height: Annotated[float, POSITIVE_LENGTH] = Field(description="crest-to-trough height, > 0")
    period: Annotated[float, Number("s", gt=0)] = Field(description="period, > 0")
    direction: _WaveDirection = None
    ramp: Annotated[float | None, Number("s", ge=0)] = api(
        "time over which the waves grow smoothly from zero, ≥ 0", words="one period"
    )


class JonswapWaves(Table):
    """`[sea.waves]` of kind "jonswap": `pl.Waves.jonswap`."""

    kind: Literal["jonswap"]
    hs: Annotated[float, POSITIVE_LENGTH] = Field(description="significant wave height, > 0")
    tp: Annotated[float, Number("s", gt=0)] = Field(description="peak period, > 0")
    gamma: Annotated[float | None, Number(ge=1)] = api("peak enhancement factor, ≥ 1", 3.3)
    direction: _WaveDirection = None
    seed: Annotated[int | None, Integer(0)] = api(
        "seed of the random phases (and directions), an integer ≥ 0", 0
    )
    components: Annotated[int | None, Integer(1, 100_000)] = api(
        "number of components, an integer in [1, 100000]", 200
    )
    spreading: Annotated[float | None, Number(gt=0, le=1000)] = api(
        "cos^2s spreading exponent s, > 0 and ≤ 1000; none: long-crested"
    )
    ramp: Annotated[float | None, Number("s", ge=0)] = api(
        "time over which the waves grow smoothly from zero, ≥ 0",
        words="about tp: the period of the largest component",
    )


Waves = Annotated[
    RegularWaves | JonswapWaves,
    Discriminator("kind"),
    About(
        """`pl.Waves.regular` or `.jonswap`, chosen by `kind`: linear (Airy) waves.

        They load the pipe (Morison drag and inertia in the waves' particle kinematics) and, through its RAOs,
        move the vessel at wave frequency. Without `[sea.waves]` the sea is calm."""
    ),
]


class Wind(Table):
    """`pl.Wind`: wind on the vessel's hull (with `vessel.hull_loads`, through its wind coefficients); it does
    not load the pipe."""

    speed: Annotated[float, Number("m/s", ge=0)] = Field(description="1-hour mean speed at 10 m, ≥ 0")
    direction: Annotated[float | None, Number("rad")] = api(
        "direction the wind blows toward, from e1 toward e2 (as the current and the waves)", 0
    )
    spectrum: Annotated[Literal["NPD", "none"] | None, Choice(("NPD", "none"))] = api(
        '`"NPD"`: gusts from the NPD (Frøya) spectrum of ISO 19901-1; `"none"`: a steady wind', "NPD"
    )
    seed: Annotated[int | None, Integer(0)] = api("seed of the gusts' random phases, an integer ≥ 0", 0)


class Sea(Table):
    """`pl.Sea`; without it the pipe hangs in air (no buoyancy, drag or added mass)."""

    depth: Annotated[float, POSITIVE_LENGTH] = Field(
        description="water depth, > 0: the surface is z = −depth"
    )
    density: Annotated[float | None, Number("kg/m³", ge=0)] = api("water density, ≥ 0", 1025)
    current: Current | None = None
    seabed: Seabed | None = None
    waves: Waves | None = None
    wind: Wind | None = None


_DRIVE_KEYS = ("amplitude", "period", "phase", "ramp")


def _still(kind: str) -> dict[str, str]:
    """The conflicts of a support that holds its end still."""
    return dict.fromkeys(_DRIVE_KEYS, f'only kind = "drive" moves its end; a {kind} holds it still')


def _turns(kind: str) -> dict[str, str]:
    """The conflicts of a support that leaves its end's rotation free."""
    return {"rotation": f'only kind = "clamp" holds a rotation; a {kind} leaves it free'}


_HeldAt = Annotated[list[float] | None, POINT, api("where the end is held [x, y, z]", words="reference node")]
"""`position`, a key of the supports that hold their end still."""


class Clamp(Table):
    """`[supports.A]` or `[supports.B]` of kind "clamp": `model.clamp`, position and rotation held."""

    conflicts: ClassVar[dict[str, str]] = _still("clamp")
    kind: Literal["clamp"]
    position: _HeldAt = None
    rotation: Annotated[list[list[float]] | None, Matrix(3, Vector(3, Number()))] = api(
        "R_t^e held, 3 rows of 3 numbers", words="reference frame"
    )


class Pin(Table):
    """`[supports.A]` or `[supports.B]` of kind "pin": `model.pin`, position held, rotation free."""

    conflicts: ClassVar[dict[str, str]] = _turns("pin") | _still("pin")
    kind: Literal["pin"]
    position: _HeldAt = None


class Drive(Table):
    """`[supports.A]` or `[supports.B]` of kind "drive": `model.drive` along a harmonic motion."""

    conflicts: ClassVar[dict[str, str]] = _turns("drive")
    kind: Literal["drive"]
    position: Annotated[list[float] | None, POINT] = api(
        "the centre of the motion [x, y, z]", words="reference node"
    )
    amplitude: Annotated[list[float] | None, POINT] = api(
        "x(t) = position + amplitude · r(t) · sin(2πt/period + phase)", [0, 0, 0]
    )
    period: Annotated[float, Number("s", gt=0)] = Field(description="period of the motion, > 0")
    phase: Annotated[list[float] | None, Vector(3, Number("rad"), XYZ)] = api(
        "phase of each component", [0, 0, 0]
    )
    ramp: Annotated[float | None, Number("s", ge=0)] = api(
        "the amplitude grows smoothly (C²) from 0 over this time, ≥ 0", 0
    )


Support = Annotated[
    Clamp | Pin | Drive,
    Discriminator("kind"),
    About("`model.clamp`, `model.pin` or `model.drive` at that end."),
]


class Supports(Table):
    """The ends held: `[supports.A]` (node 0, the seabed end) and `[supports.B]` (node n, the top end)."""

    unknown: ClassVar[str] = 'unknown end; must be "A" (node 0, seabed end) or "B" (node n, top end)'
    A: Support | None = None
    B: Support | None = None


class PointLoad(Table):
    """`model.point_load`, one table per load of fixed direction in e."""

    node: Annotated[int | str, NODE] = Field(
        description='index in [−(n+1), n] (negative: from the end) or "A"/"B"'
    )
    force: Annotated[list[float] | None, Vector(3, Number("N"), "[fx, fy, fz]")] = api(
        "force [fx, fy, fz] in e", [0, 0, 0]
    )
    moment: Annotated[list[float] | None, Vector(3, Number("N·m"), "[mx, my, mz]")] = api(
        "moment [mx, my, mz] in e", [0, 0, 0]
    )


class Attachment(Table):
    """`model.attach(arc_length, pl.Clump(...))`, one table per body at a point of the line: a clump weight, a
    buoyancy module, an in-line structure. Its weight less buoyancy, mass with added mass and drag act there,
    shared by its element's two nodes."""

    arc_length: Annotated[float, Number("m", ge=0)] = Field(
        description="where it sits: arc length from end A along the reference, on the line"
    )
    mass: Annotated[float, Number("kg", ge=0)] = Field(description="mass in air, ≥ 0")
    volume: Annotated[float | None, Number("m³", ge=0)] = api("displaced volume, ≥ 0", 0)
    drag_area: Annotated[float | None, Number("m²", ge=0)] = api("drag area C_d·A, ≥ 0", 0)
    added_mass: Annotated[float | None, Number(ge=0)] = api(
        "added-mass coefficient on the displaced volume, ≥ 0", 1
    )


_STAGE_RAMP = 10.0
"""The time a stage's speed changes take unless it says (s), or its duration if shorter (`pl.Stage`)."""


class Stage(Table):
    """`pl.Stage`, one table per stage of the lay, in order: `model.simulation(..., stages=pl.Stages([...]))`
    runs through them in one run, from t = 0.

    Each stage lasts `duration` and sets, at its start, what it gives; what it leaves out carries on from the
    stage before (at first: no pay-out, the route's own speed, the tensioner or tower holding the line). A
    change of speed is linear over the stage's `ramp`, from the speed before: the length paid out is the
    integral of those ramped speeds. The first stage with `hold = "winch"` starts with the hand-over to
    `[vessel.winch]`: the tensioner's speed ramps to 0 (the winch's brake then holds) and the winch holds the
    line; `winch_speed` pays its wire out (or hauls it in), `winch_tension` holds a tension. Hauled in to the
    hold point, the pipe's end is taken back by the tensioner (the hand-back), which holds it at rest until a
    stage with `hold = "tensioner"` (which needs the hand-back done by its start) sets its `pay_out`. With
    stages, `solver.t_end` defaults to the end of the last stage (past it, a later `t_end` runs on at the last
    stage's speeds)."""

    name: Annotated[str, Text()] = Field(description="the stage's name, for the results (`res.stage_names`)")
    duration: Annotated[float, Number("s", gt=0)] = Field(
        description="how long the stage lasts, > 0: a whole number of time steps `solver.dt`"
    )
    pay_out: Annotated[float | None, Number("m/s")] = api(
        "the tensioner's pay-out speed of unstretched pipe (< 0 pays in), while it holds the line",
        words="the stage before's (at first 0)",
    )
    route_speed: Annotated[float | None, Number("m/s")] = api(
        "the DP reference's speed along its route (a fixed `reference` moves along its heading ψ)",
        words="the stage before's (at first the route's, or 0 for a fixed `reference`)",
    )
    hold: Annotated[Literal["tensioner", "winch"] | None, Choice(("tensioner", "winch"))] = api(
        'who holds the line: `"tensioner"` (or the tower) or `"winch"` (the first such stage hands over)',
        words="the stage before's (at first the tensioner)",
    )
    winch_speed: Annotated[float | None, Number("m/s")] = api(
        "the winch's pay-out speed once it holds the line (< 0 hauls in; 0: the brake holds), within its "
        "speed_limit",
        words="the stage before's (at first 0)",
    )
    winch_tension: Annotated[float | None, Number("N", gt=0)] = api(
        "the tension the winch holds once it holds the line (constant-tension mode; a later winch_speed "
        "ends it)",
        words="none: the winch runs at winch_speed",
    )
    setpoint: Annotated[list[float] | None, Vector(3, Number("m, m, rad"), "[x, y, ψ]")] = api(
        "a new DP set-point (x, y, ψ): the reference jumps there and waits until a route speed moves it",
        words="none: the reference carries on",
    )
    statics: Annotated[bool | None, Flag()] = api(
        "start the stage from statics of its own configuration (brought to rest in equilibrium, its pay-out or "
        "winch speed ramping up from rest; calm water)",
        words="false",
    )
    ramp: Annotated[float | None, Number("s", ge=0)] = api(
        "time the stage's speed changes take, linear from the speeds before, in [0, duration]",
        words=f"{_STAGE_RAMP:g} s, or the duration if shorter",
    )

    @model_validator(mode="after")
    def ramp_within_the_stage(self) -> Stage:
        """The ramp ends within the stage."""
        if self.ramp is not None and self.ramp > self.duration:
            raise rule(f"must be <= duration = {self.duration:g} s, got {self.ramp:g}", "ramp")
        return self


class Solver(Table):
    """`model.static(steps, start)`, `model.simulation(dt, stages, high_frequency_damping)`,
    `simulation.run(t_end, record_every)`."""

    static_steps: Annotated[int | None, Integer(1)] = api(
        "initial number of (adaptive) static load steps, ≥ 1", 1
    )
    static_start: Annotated[
        Literal["auto", "reference", "catenary"], Choice(("auto", "reference", "catenary"))
    ] = Field("auto", description='Newton\'s start: `"auto"`, `"reference"` or `"catenary"`')
    dt: Annotated[float, Number("s", gt=0)] = Field(0.05, description="time step, > 0")
    t_end: Annotated[float | None, Number("s", gt=0)] = api(
        "end of the time simulation, > 0; none: the end of the `[[stages]]`, or statics only without them"
    )
    record_every: Annotated[int, Integer(1)] = Field(
        1, description="record every k-th time step, an integer ≥ 1"
    )
    high_frequency_damping: Annotated[float, Number(ge=0)] = Field(
        0.0,
        description="ξ ≥ 0: damps the line's strains by ξ C ΔΓ over each step (a mode ω at the ratio ξωΔt/2; "
        "the stiff modes a step cannot resolve decay by (1 − 2ξ)/(1 + 2ξ) a step), its work dissipated; "
        "0: energy conserving",
    )


class Checks(Table):
    """The parameters of the design checks (`pl.checks.dnv_st_f101`, `pl.checks.propagation_buckling`) for every
    utilisation the command line, the figures, the report and sweeps show; a key left out takes the checks'
    default (`pipelay.analysis.checks.DEFAULTS`).
    """

    grade: Annotated[
        Literal["X52", "X56", "X60", "X65", "X70", "X80"] | None,
        Choice(("X52", "X56", "X60", "X65", "X70", "X80")),
    ] = api("line pipe grade (SMYS, SMTS); none: the pipe's `grade`, else X65")
    safety_class: Annotated[Literal["low", "medium", "high"] | None, Choice(("low", "medium", "high"))] = api(
        "DNV safety class (γ_SC, γ_ε); DNV classes installation as low", "medium"
    )
    fabrication: Annotated[
        Literal["seamless", "uoe", "uo_tre", "welded"] | None, Choice(("seamless", "uoe", "uo_tre", "welded"))
    ] = api("fabrication, for α_fab: seamless 1.00, UO/TRB/ERW/HFW 0.93, UOE 0.85", "seamless")
    internal_pressure: Annotated[float | None, Number("Pa", ge=0)] = api(
        "one internal (design or lay) pressure for the whole pipe, ≥ 0",
        words="that of the contents, ρ_c g × depth below the surface",
    )
    condition: Annotated[
        Literal["installation", "operation"] | None, Choice(("installation", "operation"))
    ] = api("installation (t₂ = t) or operation (t₂ = t − corrosion_allowance)", "installation")
    corrosion_allowance: Annotated[float | None, Number("m", ge=0)] = api(
        "corrosion allowance deducted in operation, ≥ 0", 0
    )
    ovality: Annotated[float | None, Number(ge=0.005, le=1)] = api(
        "out-of-roundness (D_max − D_min)/D, from 0.005 to 1", 0.005
    )
    temperature_derating: Annotated[float | None, Number("Pa", ge=0)] = api(
        "de-rating of the yield and tensile strengths, ≥ 0", 0
    )
    strain_limit: Annotated[float | None, Number(gt=0)] = api(
        "allowable strain replacing DNV's strain resistance in the displacement-controlled check, > 0"
    )


class Output(Table):
    """For the figures; kept in `Scenario.output` for the program that runs the scenario."""

    plot_times: Annotated[list[float] | None, Vector(None, Number("s", ge=0), at_least=1)] = api(
        "times of the pipe shapes to plot, each in [0, the run's end]; none: the plotter's choice"
    )


class ScenarioFile(Table):
    """A scenario file: a whole pipelay model, with its solver settings and outputs, in one TOML file.

    Each table is checked on its own first, then the rules across tables: exactly one of `[pipe]` and
    `[section]`, point loads on nodes that exist, something that holds the rod (`[supports]` or a `[vessel]`,
    not both at one end), a `[sea]` for a `[vessel]` and a `[vessel]` for a `[controller]` or
    `[[environment]]`, a `[controller.route]` for a pay-out at the route's speed, a wire and lay equipment
    for a `[vessel.winch]`, `[[stages]]` that fit the model (a winch for `hold = "winch"` and `winch_speed`,
    the winch holding the line for `winch_speed` and not for `pay_out`, a `[controller]` for `route_speed`, no
    `[pay_out]` beside stages that pay out, durations of whole time steps), plot times within the run.
    """

    title: Annotated[str | None, Text()] = api("a name for the scenario (text; kept in `Scenario.source`)")
    description: Annotated[str | None, Text()] = api("free text (kept in `Scenario.source`)")
    gravity: (
        Annotated[
            Annotated[float, Number("m/s²", ge=0), Tag("number")] | Annotated[Gravity, Tag("table")],
            Discriminator(_table_or("number")),
        ]
        | None
    ) = api("acceleration of gravity along +e3, ≥ 0 (or a `[gravity]` table)", 9.81)
    pipe: Pipe | None = None
    section: Section | None = None
    rod: Rod | None = None
    line: Line | None = None
    sea: Sea | None = None
    supports: Supports | None = None
    point_loads: list[PointLoad] = []  # noqa: RUF012 (a Table is a BaseModel: pydantic copies defaults)
    vessel: Vessel | None = None
    controller: Controller | None = None
    pay_out: PayOut | None = None
    environment: list[Environment] = []  # noqa: RUF012 (as point_loads)
    attachments: list[Attachment] = []  # noqa: RUF012 (as point_loads)
    stages: list[Stage] = []  # noqa: RUF012 (as point_loads)
    solver: Solver = Solver()
    checks: Checks = Checks()
    output: Output = Output()

    @model_validator(mode="after")
    def sections_agree(self) -> ScenarioFile:
        """The rules across sections, in the order the sections are read."""
        self._one_cross_section()
        self._nodes_exist()
        self._something_holds_the_rod()
        self._pay_out_speed_has_a_route()
        self._winch_has_a_wire_and_a_lay()
        self._stages_fit_the_model()
        self._plots_within_the_run()
        return self

    def run_end(self) -> float | None:
        """The end of the time simulation (s): `solver.t_end`, else the end of the last stage; None (no
        `t_end`, no stages): statics only."""
        if self.solver.t_end is not None:
            return self.solver.t_end
        if not self.stages:
            return None
        end = 0.0
        for stage in self.stages:  # summed in order, as the engine sums the stages' starts
            end += stage.duration
        return end

    def _top_is_a_cable(self) -> bool:
        """Whether the line's top segment (at end B) is a cable."""
        return self.line is not None and self.line.segments[-1].cable is not None

    def _one_cross_section(self) -> None:
        if self.line is not None:
            for name in ("rod", "pipe", "section"):
                if getattr(self, name) is not None:
                    raise rule(f"conflicts with [line]: a line of segments has no [{name}]", name)
            return
        if self.rod is None:
            raise rule(
                "missing required section; give [rod] with [pipe] or [section], or a [line] of segments",
                "rod",
            )
        if self.pipe is not None and self.section is not None:
            raise rule("conflicts with [pipe]: give exactly one of [pipe] and [section]", "section")
        if self.pipe is None and self.section is None:
            raise rule(
                "missing required section; give [pipe] (pl.Section.pipe) or [section] (pl.Section)", "pipe"
            )

    def _nodes_exist(self) -> None:
        if self.line is not None:
            n = sum(segment.elements for segment in self.line.segments)
        elif isinstance(self.rod, StraightRod):
            n = self.rod.elements
        else:
            n = len(cast(NodesRod, self.rod).nodes) - 1
        for i, load in enumerate(self.point_loads):
            if isinstance(load.node, int) and not -(n + 1) <= load.node <= n:
                range_ = f"[{-(n + 1)}, {n}] (n = {n})"
                raise rule(f"must be a node index in {range_}, got {load.node}", f"point_loads[{i}].node")

    def _something_holds_the_rod(self) -> None:
        if self.vessel is None:
            for section in ("controller", "environment"):
                if getattr(self, section):
                    raise rule("needs a [vessel] to act on", section)
            if self.supports is None or (self.supports.A is None and self.supports.B is None):
                raise rule("missing; hold the rod with [supports.A], [supports.B] or a [vessel]", "supports")
            return
        if self.sea is None:
            raise rule("needs a [sea] to float in", "vessel")
        end = self.vessel.end
        if self.supports is not None and getattr(self.supports, end) is not None:
            held = f'end "{end}" also has [supports.{end}]; an end is held by a support or the vessel'
            raise rule(held, "vessel.end")

    def _pay_out_speed_has_a_route(self) -> None:
        routed = self.pay_out is not None and self.pay_out.speed == "route"
        if routed and not isinstance(self.controller, RouteController):
            reason = '"route" needs a [controller.route] to take the speed from; there is none'
            raise rule(reason, "pay_out.speed")

    def _winch_has_a_wire_and_a_lay(self) -> None:
        vessel = self.vessel
        if vessel is None or vessel.winch is None:
            return
        if vessel.winch.wire is None and not self._top_is_a_cable():
            reason = (
                "missing required section; give the A&R wire: [vessel.winch.wire] with the keys of "
                "pl.Section.cable (the line's top is not a cable to take it from)"
            )
            raise rule(reason, "vessel.winch.wire")
        if vessel.lay is None and not (vessel.end == "B" and self._top_is_a_cable()):
            reason = "needs [vessel.lay]: the winch takes the line over from its tensioner or tower"
            raise rule(reason, "vessel.winch")

    def _stages_fit_the_model(self) -> None:
        winch = None if self.vessel is None else self.vessel.winch
        from_start = winch is not None and self.vessel is not None and self.vessel.end == "B"
        holds = "winch" if from_start and self._top_is_a_cable() else "tensioner"
        dt = self.solver.dt
        for k, stage in enumerate(self.stages):
            key = f"stages[{k}]"
            steps = stage.duration / dt
            if not math.isfinite(steps):
                finite = f"must be a finite number of time steps solver.dt = {dt:g} s, got {stage.duration:g}"
                raise rule(finite, f"{key}.duration")
            if abs(steps - round(steps)) > 1e-6 * max(steps, 1.0):
                whole = f"must be a whole number of time steps solver.dt = {dt:g} s, got {stage.duration:g}"
                raise rule(whole, f"{key}.duration")
            if stage.hold == "winch" and winch is None:
                raise rule("needs a [vessel.winch] to hand the line over to", f"{key}.hold")
            holds = stage.hold or holds
            for name in ("winch_speed", "winch_tension"):
                if getattr(stage, name) is not None and winch is None:
                    raise rule("needs a [vessel.winch] to pay out", f"{key}.{name}")
                if getattr(stage, name) is not None and holds != "winch":
                    first = 'the tensioner holds the line in this stage: hand over first (hold = "winch")'
                    raise rule(first, f"{key}.{name}")
            if stage.winch_speed is not None and stage.winch_tension is not None:
                one = "gives the winch a tension to hold, and winch_speed a speed: give one of them"
                raise rule(one, f"{key}.winch_tension")
            if stage.pay_out is not None and holds == "winch":
                raise rule("the winch holds the line in this stage: set winch_speed", f"{key}.pay_out")
            if stage.route_speed is not None and self.controller is None:
                raise rule("needs a [controller] whose reference it moves", f"{key}.route_speed")
            paying = [
                name
                for name in ("pay_out", "winch_speed", "winch_tension")
                if getattr(stage, name) is not None
            ]
            paying += ["hold"] if stage.hold == "winch" else []
            if paying and self.pay_out is not None:
                twice = "conflicts with [pay_out]: the stages set the pay-out speed; give it one way"
                raise rule(twice, f"{key}.{paying[0]}")

    def _plots_within_the_run(self) -> None:
        t_end = self.run_end()
        if t_end is None:
            limit = "0 s: statics only (no solver.t_end or [[stages]])"
        elif self.solver.t_end is None:
            limit = f"<= the end of the [[stages]] = {t_end:g} s"
        else:
            limit = f"<= solver.t_end = {t_end:g} s"
        for i, time in enumerate(self.output.plot_times or ()):
            if time > (t_end or 0.0):
                raise rule(f"must be {limit}, got {time:g}", f"output.plot_times[{i}]")
