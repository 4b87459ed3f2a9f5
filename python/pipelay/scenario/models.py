"""The scenario format as pydantic models: one model per table (and per kind of a table whose keys depend
on `kind`), its fields the keyword arguments of the API call the table maps onto, up to the whole file
(`ScenarioFile`). `pipelay.scenario`'s docstring is the human reference of every key; each field's type
carries the `Value` (`pipelay.scenario.values`) it is checked with, and a rule that spans keys raises
`rule(message, key)` from a validator.

This module has the models of the pipe, its supports and loads, the sea, the solver and the outputs, and the
file's; those of the vessel and what works with it are in `pipelay.scenario.models_vessel`, and this module
exposes them too: every model is here.

Imports of pipelay: `pipelay.scenario.values` and `pipelay.scenario.models_vessel`.
"""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Discriminator, Tag, model_validator

from pipelay.scenario.models_vessel import (
    ArcStinger,
    Controller,
    ControllerTable,
    Environment,
    FixedController,
    JLay,
    Lay,
    MatrixVessel,
    ModelVessel,
    PayOut,
    RollerStinger,
    Route,
    RouteController,
    SLay,
    Stinger,
    Tension,
    Vessel,
    VesselTable,
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
    Choice,
    End,
    Integer,
    Matrix,
    Number,
    Table,
    Text,
    Vector,
    _having,
    _table_or,
    number_or_vector,
    rule,
)

__all__ = [
    "MAX_ELEMENTS",
    "ArcStinger",
    "Bathymetry",
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
    "JLay",
    "JonswapWaves",
    "Lay",
    "LinearCurrent",
    "MatrixVessel",
    "ModelVessel",
    "NodesRod",
    "Output",
    "PayOut",
    "Pin",
    "Pipe",
    "PlaneBathymetry",
    "PointLoad",
    "ProfileCurrent",
    "RegularWaves",
    "Rod",
    "RollerStinger",
    "Route",
    "RouteController",
    "SLay",
    "ScenarioFile",
    "Sea",
    "Seabed",
    "Section",
    "Solver",
    "Stinger",
    "StraightRod",
    "Support",
    "Supports",
    "Table",
    "Tension",
    "UniformCurrent",
    "Vessel",
    "VesselTable",
    "Waves",
]

MAX_ELEMENTS = 1_000_000
"""Largest number of elements a scenario's `[rod]` may ask for."""


class Gravity(Table):
    """`[gravity]`: the acceleration of gravity (`pl.Model(rod, sea, gravity)`)."""

    acceleration: Annotated[float, Number("m/s²", ge=0)]


class Pipe(Table):
    """`[pipe]`: `pl.Section.pipe`."""

    outer_diameter: Annotated[float, POSITIVE_LENGTH]
    wall_thickness: Annotated[float, POSITIVE_LENGTH]
    density: Annotated[float | None, Number("kg/m³", gt=0)] = None
    youngs_modulus: Annotated[float | None, Number("Pa", gt=0)] = None
    poisson_ratio: Annotated[float | None, Number(gt=-1, lt=0.5)] = None
    contents_density: Annotated[float | None, Number("kg/m³", ge=0)] = None
    drag: Annotated[list[float] | None, COEFFICIENTS] = None
    added_mass: Annotated[list[float] | None, COEFFICIENTS] = None

    @model_validator(mode="after")
    def thin_wall(self) -> Pipe:
        """The wall is at most half the diameter thick."""
        half = self.outer_diameter / 2.0
        if self.wall_thickness > half:
            got = f"got {self.wall_thickness:g}"
            raise rule(f"must be <= outer_diameter / 2 = {half:g} m, {got}", "wall_thickness")
        return self


class Section(Table):
    """`[section]`: `pl.Section`."""

    EA: Annotated[float, Number("N", gt=0)]
    GA: Annotated[float | list[float], number_or_vector(2, Number("N", gt=0), AXES)]
    GJ: Annotated[float, Number("N·m²", gt=0)]
    EI: Annotated[float | list[float], number_or_vector(2, Number("N·m²", gt=0), AXES)]
    mass: Annotated[float, Number("kg/m", gt=0)]
    inertia: Annotated[list[float] | None, Vector(3, Number("kg·m", ge=0), "[J1, J2, J3]")] = None
    outer_diameter: Annotated[float | None, Number("m", ge=0)] = None
    displaced_area: Annotated[float | None, Number("m²", ge=0)] = None
    drag: Annotated[list[float] | None, COEFFICIENTS] = None
    added_mass: Annotated[list[float] | None, COEFFICIENTS] = None
    rotational_damping: Annotated[
        float | list[float] | None, number_or_vector(3, Number("N·m·s/m", ge=0), "[t1, t2, t3]")
    ] = None


class StraightRod(Table):
    """`[rod]` with start, end and elements: `pl.Rod.straight`."""

    start: Annotated[list[float], POINT]
    end: Annotated[list[float], POINT]
    elements: Annotated[int, Integer(1, MAX_ELEMENTS)]


class NodesRod(Table):
    """`[rod]` with nodes: `pl.Rod(nodes, section)`."""

    conflicts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("start", "end", "elements"), "conflicts with rod.nodes; give either nodes or start, end and elements"
    )
    nodes: Annotated[list[list[float]], Matrix(None, POINT, at_least=2)]


Rod = Annotated[
    Annotated[StraightRod, Tag("straight")] | Annotated[NodesRod, Tag("nodes")],
    Discriminator(_having("nodes", "nodes", "straight")),
]


class UniformCurrent(Table):
    """`[sea.current]` of kind "uniform": `pl.Current.uniform`."""

    kind: Literal["uniform"]
    velocity: Annotated[list[float], Vector(3, Number("m/s"), VELOCITY)]
    start: Annotated[float | None, START] = None


class LinearCurrent(Table):
    """`[sea.current]` of kind "linear": `pl.Current.linear`."""

    kind: Literal["linear"]
    surface_velocity: Annotated[list[float], Vector(3, Number("m/s"), VELOCITY)]
    start: Annotated[float | None, START] = None


class ProfileCurrent(Table):
    """`[sea.current]` of kind "profile": `pl.Current.profile`."""

    kind: Literal["profile"]
    depths: Annotated[list[float], Vector(None, Number("m"), at_least=1)]
    velocities: Annotated[list[list[float]], Matrix(None, Vector(3, Number("m/s"), VELOCITY), at_least=1)]
    start: Annotated[float | None, START] = None

    @model_validator(mode="after")
    def one_velocity_per_depth(self) -> ProfileCurrent:
        """As many velocities as depths."""
        count, got = len(self.depths), len(self.velocities)
        if got != count:
            raise rule(f"must have one row {VELOCITY} (m/s) per depth ({count}), got {got}", "velocities")
        return self


Current = Annotated[UniformCurrent | LinearCurrent | ProfileCurrent, Discriminator("kind")]


class FlatBathymetry(Table):
    """`[sea.seabed.bathymetry]` of kind "flat": `pl.Bathymetry.flat`."""

    kind: Literal["flat"]
    z: Annotated[float | None, Number("m")] = None


class PlaneBathymetry(Table):
    """`[sea.seabed.bathymetry]` of kind "plane": `pl.Bathymetry.plane`."""

    kind: Literal["plane"]
    z: Annotated[float | None, Number("m")] = None
    gradient: Annotated[list[float] | None, Vector(2, Number(), "[dz/dx, dz/dy]")] = None


class GridBathymetry(Table):
    """`[sea.seabed.bathymetry]` of kind "grid": `pl.Bathymetry.grid`."""

    kind: Literal["grid"]
    x: Annotated[list[float], Vector(None, Number("m"), at_least=2)]
    y: Annotated[list[float], Vector(None, Number("m"), at_least=2)]
    z: Annotated[
        list[list[float]],
        Matrix(None, Vector(None, Number("m")), text="rows of numbers, one row of len(y) per x (m)"),
    ]

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


Bathymetry = Annotated[FlatBathymetry | PlaneBathymetry | GridBathymetry, Discriminator("kind")]


class Seabed(Table):
    """`[sea.seabed]`: `pl.Seabed`."""

    stiffness: Annotated[float | None, Number("Pa/m", gt=0)] = None
    damping: Annotated[float | None, Number("Pa·s/m", ge=0)] = None
    friction: Annotated[float | list[float] | None, number_or_vector(2, Number(ge=0), "[axial, lateral]")] = (
        None
    )
    mobilisation: Annotated[float | None, Number("m", gt=0)] = None
    bathymetry: Bathymetry | None = None


class RegularWaves(Table):
    """`[sea.waves]` of kind "regular": `pl.Waves.regular`."""

    kind: Literal["regular"]
    height: Annotated[float, POSITIVE_LENGTH]
    period: Annotated[float, Number("s", gt=0)]
    direction: Annotated[float | None, Number("rad")] = None
    ramp: Annotated[float | None, Number("s", ge=0)] = None


class JonswapWaves(Table):
    """`[sea.waves]` of kind "jonswap": `pl.Waves.jonswap`."""

    kind: Literal["jonswap"]
    hs: Annotated[float, POSITIVE_LENGTH]
    tp: Annotated[float, Number("s", gt=0)]
    gamma: Annotated[float | None, Number(ge=1)] = None
    direction: Annotated[float | None, Number("rad")] = None
    seed: Annotated[int | None, Integer(0)] = None
    components: Annotated[int | None, Integer(1, 100_000)] = None
    spreading: Annotated[float | None, Number(gt=0, le=1000)] = None
    ramp: Annotated[float | None, Number("s", ge=0)] = None


Waves = Annotated[RegularWaves | JonswapWaves, Discriminator("kind")]


class Sea(Table):
    """`[sea]`: `pl.Sea`."""

    depth: Annotated[float, POSITIVE_LENGTH]
    density: Annotated[float | None, Number("kg/m³", ge=0)] = None
    current: Current | None = None
    seabed: Seabed | None = None
    waves: Waves | None = None


_DRIVE_KEYS = ("amplitude", "period", "phase", "ramp")


def _still(kind: str) -> dict[str, str]:
    """The conflicts of a support that holds its end still."""
    return dict.fromkeys(_DRIVE_KEYS, f'only kind = "drive" moves its end; a {kind} holds it still')


def _turns(kind: str) -> dict[str, str]:
    """The conflicts of a support that leaves its end's rotation free."""
    return {"rotation": f'only kind = "clamp" holds a rotation; a {kind} leaves it free'}


class Clamp(Table):
    """`[supports.A]` or `[supports.B]` of kind "clamp": `model.clamp`."""

    conflicts: ClassVar[dict[str, str]] = _still("clamp")
    kind: Literal["clamp"]
    position: Annotated[list[float] | None, POINT] = None
    rotation: Annotated[list[list[float]] | None, Matrix(3, Vector(3, Number()))] = None


class Pin(Table):
    """`[supports.A]` or `[supports.B]` of kind "pin": `model.pin`."""

    conflicts: ClassVar[dict[str, str]] = _turns("pin") | _still("pin")
    kind: Literal["pin"]
    position: Annotated[list[float] | None, POINT] = None


class Drive(Table):
    """`[supports.A]` or `[supports.B]` of kind "drive": `model.drive` along a harmonic motion."""

    conflicts: ClassVar[dict[str, str]] = _turns("drive")
    kind: Literal["drive"]
    position: Annotated[list[float] | None, POINT] = None
    amplitude: Annotated[list[float] | None, POINT] = None
    period: Annotated[float, Number("s", gt=0)]
    phase: Annotated[list[float] | None, Vector(3, Number("rad"), XYZ)] = None
    ramp: Annotated[float | None, Number("s", ge=0)] = None


Support = Annotated[Clamp | Pin | Drive, Discriminator("kind")]


class Supports(Table):
    """`[supports]`: the ends held."""

    unknown: ClassVar[str] = 'unknown end; must be "A" (node 0, seabed end) or "B" (node n, top end)'
    A: Support | None = None
    B: Support | None = None


class PointLoad(Table):
    """An entry of `[[point_loads]]`: `model.point_load`."""

    node: Annotated[int | str, NODE]
    force: Annotated[list[float] | None, Vector(3, Number("N"), "[fx, fy, fz]")] = None
    moment: Annotated[list[float] | None, Vector(3, Number("N·m"), "[mx, my, mz]")] = None


class Solver(Table):
    """`[solver]`: the static and time solvers' settings, defaults filled in."""

    static_steps: Annotated[int | None, Integer(1)] = None
    static_start: Annotated[
        Literal["auto", "reference", "catenary"], Choice(("auto", "reference", "catenary"))
    ] = "auto"
    dt: Annotated[float, Number("s", gt=0)] = 0.05
    t_end: Annotated[float | None, Number("s", gt=0)] = None
    record_every: Annotated[int, Integer(1)] = 1


class Output(Table):
    """`[output]`: for the program that runs the scenario."""

    plot_times: Annotated[list[float] | None, Vector(None, Number("s", ge=0), at_least=1)] = None


class ScenarioFile(Table):
    """A whole scenario file. Rules across sections are checked once every section is valid."""

    title: Annotated[str | None, Text()] = None
    description: Annotated[str | None, Text()] = None
    gravity: (
        Annotated[
            Annotated[float, Number("m/s²", ge=0), Tag("number")] | Annotated[Gravity, Tag("table")],
            Discriminator(_table_or("number")),
        ]
        | None
    ) = None
    pipe: Pipe | None = None
    section: Section | None = None
    rod: Rod
    sea: Sea | None = None
    supports: Supports | None = None
    point_loads: list[PointLoad] = []  # noqa: RUF012 (a Table is a BaseModel: pydantic copies defaults)
    vessel: Vessel | None = None
    controller: Controller | None = None
    pay_out: PayOut | None = None
    environment: list[Environment] = []  # noqa: RUF012 (as point_loads)
    solver: Solver = Solver()
    output: Output = Output()

    @model_validator(mode="after")
    def sections_agree(self) -> ScenarioFile:
        """The rules across sections, in the order the sections are read."""
        self._one_cross_section()
        self._nodes_exist()
        self._something_holds_the_rod()
        self._pay_out_speed_has_a_route()
        self._plots_within_the_run()
        return self

    def _one_cross_section(self) -> None:
        if self.pipe is not None and self.section is not None:
            raise rule("conflicts with [pipe]: give exactly one of [pipe] and [section]", "section")
        if self.pipe is None and self.section is None:
            raise rule(
                "missing required section; give [pipe] (pl.Section.pipe) or [section] (pl.Section)", "pipe"
            )

    def _nodes_exist(self) -> None:
        n = self.rod.elements if isinstance(self.rod, StraightRod) else len(self.rod.nodes) - 1
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

    def _plots_within_the_run(self) -> None:
        t_end = self.solver.t_end
        limit = "0 s: statics only (no solver.t_end)" if t_end is None else f"<= solver.t_end = {t_end:g} s"
        for i, time in enumerate(self.output.plot_times or ()):
            if time > (t_end or 0.0):
                raise rule(f"must be {limit}, got {time:g}", f"output.plot_times[{i}]")
