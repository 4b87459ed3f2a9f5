"""The scenario format's models of the vessel and what works with it: `[vessel]` (given by a built-in model or
by its matrices, with its thrusters `[[vessel.thrusters]]` and hull tables) with its lay equipment
(`[vessel.lay]`, `[vessel.lay.stinger]`) and A&R winch (`[vessel.winch]`, its wire and head), `[controller]`
with its route, tension loop and observer, `[pay_out]` and `[[environment]]`. The winch's wire is a `Cable`,
the model a cable segment of a `[line]` takes too. `pipelay.scenario.models` exposes them with the others.

Imports of pipelay: `pipelay.scenario.values`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Discriminator, Field, Tag, ValidationInfo, field_validator, model_validator

from pipelay.scenario.values import (
    COEFFICIENTS,
    END,
    ETA,
    POINT,
    POSITIVE_LENGTH,
    START,
    XYZ,
    About,
    Choice,
    Either,
    End,
    Flag,
    Integer,
    Matrix,
    Number,
    Table,
    Text,
    Vector,
    _having,
    _is_text,
    api,
    gains,
    rule,
)

__all__ = [
    "ArcStinger",
    "AzimuthThruster",
    "Cable",
    "Controller",
    "ControllerTable",
    "Environment",
    "FixedController",
    "Head",
    "JLay",
    "Lay",
    "MainThruster",
    "MatrixVessel",
    "ModelVessel",
    "Observer",
    "PayOut",
    "ReelLay",
    "RollerBox",
    "RollerStinger",
    "Route",
    "RouteController",
    "SLay",
    "Stinger",
    "StingerSection",
    "Tension",
    "Thruster",
    "TunnelThruster",
    "Vessel",
    "VesselTable",
    "Winch",
]


_RollerRadius = Annotated[float | None, POSITIVE_LENGTH, api("radius of every roller", 0.25)]
"""`roller_radius`, a key of either way to give a stinger."""


class RollerBox(Table):
    """`[vessel.lay.stinger.box]` or an entry of `[[vessel.lay.stinger.boxes]]`: `pl.RollerBox`, rollers of
    finite length set across the pipe at a place of the stinger."""

    arc_length: Annotated[float | None, Number("m", ge=0)] = api(
        "where the box stands along the stinger from its start (boxes only; default: the place of the "
        "roller it replaces)",
        words="the roller's place",
    )
    kind: Annotated[Literal["v", "u"] | None, Choice(("v", "u"))] = api(
        "v: two rollers in a V (optional bottom and side rollers); u: a bottom roller between two vertical "
        "side rollers",
        "v",
    )
    half_angle: Annotated[float | None, Number("rad", gt=0)] = api(
        "each V roller's rise from the lateral, below π/2", words="π/6"
    )
    roller_length: Annotated[float | None, Number("m", gt=0)] = api("every roller's length", 1.2)
    bottom: Annotated[bool | None, Flag()] = api("a bottom roller between the V's rollers", False)
    sides: Annotated[bool | None, Flag()] = api("vertical side rollers at the V's upper ends", False)
    friction: Annotated[float | None, Number(ge=0)] = api(
        "Coulomb friction μ of the rollers: along them if they turn, every way if locked", 0
    )
    rolling_resistance: Annotated[float | None, Number(ge=0)] = api(
        "rolling resistance of free-turning rollers along the pipe (force per normal force)", 0
    )
    locked: Annotated[bool | None, Flag()] = api("rollers braked or locked: they do not turn", False)


class StingerSection(Table):
    """An entry of `[[vessel.lay.stinger.sections]]`: `pl.StingerSection`, a hinged section of an articulated
    stinger, the next stretch of the arc after the one before (the first after the fixed part)."""

    length: Annotated[float, POSITIVE_LENGTH] = Field(description="the length of the arc the section carries")
    mass: Annotated[float, Number("kg", ge=0)] = Field(description="the section's mass")
    buoyancy: Annotated[float, Number("N", ge=0)] = Field(
        description="its buoyancy, upward, constant: its displaced water with its ballast set"
    )
    hinge_stiffness: Annotated[float | None, Number("N·m/rad", ge=0)] = api(
        "the hinge's spring about the angle 0 where the section lies on the arc (0: a free hinge)", 0
    )
    hinge_limits: Annotated[list[float] | None, Vector(2, Number("rad"), "[min, max]")] = api(
        "the hinge's angle limits [min, max], min ≤ 0 ≤ max (positive: the aft end down)", [-0.5, 0.5]
    )
    drag_area: Annotated[float | None, Number("m²", ge=0)] = api("the section's drag area C_d A", 0)
    added_mass: Annotated[float | None, Number("kg", ge=0)] = api(
        "the water the section carries along as it moves (its inertia, not its weight)", 0
    )


class ArcStinger(Table):
    """`[vessel.lay.stinger]` as an arc: `pl.Stinger`, its supports lone rollers across it or roller boxes
    (`box`: the same box at every roller's place; `boxes`: one box per place, or each at its arc length)."""

    conflicts: ClassVar[dict[str, str]] = {"axes": "belongs to positions (rollers given point by point)"}
    radius: Annotated[float, POSITIVE_LENGTH] = Field(description="radius of the arc, the rollers' top line")
    length: Annotated[float, POSITIVE_LENGTH] = Field(description="the arc's length (≤ π · radius)")
    rollers: Annotated[int, Integer(1, 1000)] = Field(
        description="number of rollers spread evenly over the arc, 1 to 1000"
    )
    origin: Annotated[list[float] | None, POINT] = api(
        "where the arc starts [x, y, z]; it runs aft and bends down", [0, 0, 0]
    )
    angle: Annotated[float | None, Number("rad")] = api(
        "the arc's slope below the horizontal at the origin", 0
    )
    roller_radius: _RollerRadius = None
    box: RollerBox | None = api("the roller box standing at every roller's place", words="lone rollers")
    boxes: list[RollerBox] | None = api("the roller boxes, one per place or each at its arc_length")
    sections: list[StingerSection] | None = api(
        "the arc's last stretches as hinged sections (an articulated stinger); the part before them is fixed "
        "on the vessel",
        words="one rigid stinger",
    )

    @model_validator(mode="after")
    def box_or_boxes(self) -> ArcStinger:
        """Not both `box` and `boxes`; `box` has no arc length; the sections fit on the arc."""
        if self.box is not None and self.boxes is not None:
            raise rule("conflicts with boxes: give one box for every place, or the list", "box")
        if self.box is not None and self.box.arc_length is not None:
            raise rule("has no arc_length: the box stands at every roller's place", "box.arc_length")
        if self.sections is not None:
            total = sum(s.length for s in self.sections)
            if total > self.length * (1 + 1e-12):
                raise rule(
                    f"must fit on the arc: their lengths add up to {total} m, the arc is {self.length} m",
                    "sections",
                )
        return self


class RollerStinger(Table):
    """`[vessel.lay.stinger]` given roller by roller: `pl.Stinger.from_rollers`."""

    conflicts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("radius", "length", "rollers", "origin", "angle"),
        "conflicts with positions: give an arc or the rollers' points",
    )
    positions: Annotated[list[list[float]], Matrix(None, POINT, at_least=1)] = Field(
        description="the rollers' top points, one row [x, y, z] per roller"
    )
    axes: Annotated[list[list[float]] | None, Matrix(None, Vector(3, Number(), XYZ), at_least=1)] = api(
        "the rollers' axis directions, one row per roller", words="b2 (athwartships)"
    )
    roller_radius: _RollerRadius = None

    @model_validator(mode="after")
    def one_axis_per_roller(self) -> RollerStinger:
        """As many axes as rollers."""
        if self.axes is not None and len(self.axes) != len(self.positions):
            count = len(self.positions)
            raise rule(f"must have one row per roller ({count}), got {len(self.axes)}", "axes")
        return self


Stinger = Annotated[
    Annotated[ArcStinger, Tag("arc")] | Annotated[RollerStinger, Tag("rollers")],
    Discriminator(_having("positions", "rollers", "arc")),
    About(
        """`pl.Stinger`: the rollers of an s-lay.

        Either an arc (`radius`, `length`, `rollers`, …) or the rollers' top points (`positions`, `axes`)."""
    ),
]


class SLay(Table):
    """`[vessel.lay]` of kind "s-lay": `pl.SLay`, the pipe held by a tensioner, over a stinger."""

    kind: Literal["s-lay"]
    tensioner: Annotated[list[float], POINT] = Field(
        description="the tensioner [x, y, z]; the firing line is horizontal, +b1"
    )
    roller_stiffness: Annotated[float | None, Number("N/m", gt=0)] = api(
        "contact stiffness of every roller", 1e7
    )
    friction: Annotated[float | None, Number(ge=0)] = api(
        "rolling resistance along the pipe (force per normal force) of the stinger's lone rollers", 0
    )
    stinger: Stinger | None = None


class JLay(Table):
    """`[vessel.lay]` of kind "j-lay": `pl.JLay`, the pipe held at the exit of a tower."""

    kind: Literal["j-lay"]
    position: Annotated[list[float], POINT] = Field(description="the tower exit [x, y, z]")
    angle: Annotated[float | None, Number("rad")] = api(
        "the tower's lean from vertical toward the bow, in [0, π/2]", 0
    )
    guide: Annotated[float | None, Number("m", gt=0)] = api(
        "bend radius of a bellmouth at the exit, over which a line leaving at an angle bends, > 0",
        words="none: no guide",
    )
    guide_opening: Annotated[float | None, Number("m", gt=0)] = api(
        "the bellmouth's narrowest opening across, > 0", 1
    )


class ReelLay(Table):
    """`[vessel.lay]` of kind "reel-lay": `pl.ReelLay`, the pipe reeled (reel, aligner, straightener) and held
    at the exit of a ramp; its wall enters the water in the state the reeling left it in."""

    kind: Literal["reel-lay"]
    position: Annotated[list[float], POINT] = Field(description="the ramp's exit [x, y, z]")
    ramp_angle: Annotated[float | None, Number("rad")] = api(
        "the ramp's lean from vertical toward the bow, in [0, π/2]", 0
    )
    reel_radius: Annotated[float, Number("m", gt=0)] = Field(
        description="the radius of the pipe's centreline on the reel"
    )
    aligner_radius: Annotated[float, Number("m", gt=0)] = Field(
        description="the radius of the pipe's centreline over the aligner"
    )
    straightener: Annotated[
        float | str | None,
        Either(Number("1/m"), Choice(("design",)), _is_text, 'a number (1/m) or "design"'),
    ] = api(
        "the straightener's curvature of the pipe (negative: against the reel's), or `\"design\"`: the setting "
        "that leaves the pipe straight (`pl.design_straightener`)",
        0,
    )


Lay = Annotated[
    SLay | JLay | ReelLay,
    Discriminator("kind"),
    About(
        """`pl.SLay`, `pl.JLay` or `pl.ReelLay`: the pipe held by lay equipment instead of at CO.

        Positions in the vessel's body frame (forward, starboard, down; m from CO). Leave `vessel.angle` out."""
    ),
]


class Cable(Table):
    """`pl.Section.cable`: the section of a cable segment or of the A&R wire (wire rope, chain): tension
    only, no bending or torsion."""

    diameter: Annotated[float, POSITIVE_LENGTH] = Field(description="nominal diameter, > 0")
    mass: Annotated[float, Number("kg/m", gt=0)] = Field(description="mass per unit length in air, > 0")
    EA: Annotated[float, Number("N", gt=0)] = Field(description="axial stiffness, > 0")
    drag: Annotated[list[float] | None, COEFFICIENTS] = api(
        "Morison drag coefficients [axial, normal] on the diameter, ≥ 0", [0, 1.2]
    )
    added_mass: Annotated[list[float] | None, COEFFICIENTS] = api(
        "added-mass coefficients [axial, normal], ≥ 0", [0, 1]
    )
    damping: Annotated[float | None, Number("N·s", ge=0)] = api(
        "axial internal damping B of the taut cable (MoorDyn's BA), force B·dε/dt, ≥ 0: it damps the stiff "
        "axial modes a time step cannot resolve",
        0,
    )


class Head(Table):
    """`pl.Clump`: the laydown (A&R) head fitted to the pipe's end at the hand-over to the winch. Its weight
    less buoyancy, mass with added mass and drag act at the joint of the pipe and the wire; with `length` and
    `diameter` (`pl.Winch(head_length=, head_diameter=)`) it is a body, an element of the line from the pipe's
    end to the wire whose surface tapers from `diameter` to the wire's (the rollers and the seabed see it)."""

    mass: Annotated[float, Number("kg", ge=0)] = Field(description="mass in air, ≥ 0")
    volume: Annotated[float | None, Number("m³", ge=0)] = api("displaced volume, ≥ 0", 0)
    drag_area: Annotated[float | None, Number("m²", ge=0)] = api("drag area C_d·A, ≥ 0", 0)
    added_mass: Annotated[float | None, Number(ge=0)] = api(
        "added-mass coefficient on the displaced volume, ≥ 0", 1
    )
    length: Annotated[float | None, POSITIVE_LENGTH] = api(
        "the head body's length, > 0 (with `diameter`)", words="none: a point body"
    )
    diameter: Annotated[float | None, POSITIVE_LENGTH] = api(
        "the head body's diameter at the pipe's end, > 0 (with `length`)", words="none: a point body"
    )


class Winch(Table):
    """`pl.Winch`: the abandonment and recovery (A&R) winch the line is handed over to, `attach_vessel(...,
    winch=)`; needs `[vessel.lay]` (or a `[line]` whose top segment is a cable, held by the winch from the
    start).

    The first `[[stages]]` entry with `hold = "winch"` starts with the hand-over: the wire, from `position` to
    the tensioner or tower exit, stretched to the pipe's axial force there, joins the pipe's end (with the
    head), and the vessel holds the line by the winch; the stages' `winch_speed` then pays the wire out, or
    their `winch_tension` holds a tension (constant-tension mode), within the drive's limits.
    `position` must lie on the firing line, ahead of the hold point along the pipe: in an S-lay forward of the
    tensioner along +b1, in a J-lay up the tower, the tower exit + d·[sin a, 0, −cos a] with d > 0 and a the
    tower's `angle`."""

    position: Annotated[list[float], POINT] = Field(
        description="where the wire enters the firing line [x, y, z] (body frame), ahead of the tensioner or "
        "tower exit along the pipe"
    )
    tension_limit: Annotated[float | None, Number("N", gt=0)] = api("the wire's rating, > 0; none: no limit")
    element_length: Annotated[float | None, POSITIVE_LENGTH] = api(
        "length of the wire elements pay-out adds, > 0", words="the line's top element's"
    )
    wire: Cable | None = api(
        "the wire's section: a `[vessel.winch.wire]` table", words="the line's top segment, if it is a cable"
    )
    head: Head | None = api(
        "the head fitted to the pipe's end at the hand-over: a `[vessel.winch.head]` table"
    )
    speed_limit: Annotated[float | None, Number("m/s", gt=0)] = api(
        "the drive's largest speed either way, > 0", words="1 m/s"
    )
    acceleration_limit: Annotated[float | None, Number("m/s²", gt=0)] = api(
        "the drive's largest change of speed, > 0", words="0.5 m/s²"
    )
    tension_band: Annotated[float | None, Number("N", gt=0)] = api(
        "constant-tension mode stands within the set tension ± band and runs at full speed 2·band away; "
        "the rating renders from tension_limit − band",
        words="50 kN",
    )


def _table_file(path: str, info: ValidationInfo, what: str) -> str:
    """A table's path, resolved from the scenario's folder (the context's `folder`); it must be a file."""
    resolved = Path((info.context or {}).get("folder", ".")) / path
    if not resolved.is_file():
        raise rule(f"must be {what} (CSV) relative to the scenario's folder; no file {resolved}")
    return str(resolved)


_ThrusterAt = Annotated[
    list[float],
    Vector(2, Number("m"), "[l_x, l_y]"),
    Field(
        description="where it acts [l_x, l_y], body frame from CO (forward, starboard), on the hull: "
        "|l_x| ≤ vessel.length / 2"
    ),
]
"""`position`, a key of every kind of thruster."""
_MaxThrust = Annotated[float, Number("N", gt=0), Field(description="largest forward thrust, > 0")]
"""`max_thrust`, a key of every kind of thruster."""
_ThrustRate = Annotated[
    float | None, Number("N/s", gt=0), api("bound on the thrust's rate of change, > 0; none: no limit")
]
"""`thrust_rate`, a key of every kind of thruster."""
_TimeConstant = Annotated[
    float | None,
    Number("s", ge=0),
    api("time constant T of the thrust's first-order lag, ḟ = (f_c − f)/T, ≥ 0 (0: at once)", 1),
]
"""`time_constant`, a key of every kind of thruster."""
_ReverseThrust = Annotated[
    float | None, Number("N", ge=0), api("largest reverse thrust, ≥ 0", words="max_thrust")
]
"""`reverse_thrust`, a key of the thrusters that push both ways."""
_TURNS = {"azimuth_rate": 'only kind = "azimuth" turns; a tunnel thruster or main propeller does not'}


class TunnelThruster(Table):
    """`[[vessel.thrusters]]` of kind "tunnel": `pl.Thruster("tunnel", ...)`, pushing athwartships (positive:
    to starboard)."""

    conflicts: ClassVar[dict[str, str]] = _TURNS
    kind: Literal["tunnel"]
    position: _ThrusterAt
    max_thrust: _MaxThrust
    reverse_thrust: _ReverseThrust = None
    thrust_rate: _ThrustRate = None
    time_constant: _TimeConstant = None


class AzimuthThruster(Table):
    """`[[vessel.thrusters]]` of kind "azimuth": `pl.Thruster("azimuth", ...)`, pushing along an azimuth it
    turns (no reverse thrust: it turns instead)."""

    conflicts: ClassVar[dict[str, str]] = {
        "reverse_thrust": "an azimuth thruster turns to push the other way; it has no reverse thrust"
    }
    kind: Literal["azimuth"]
    position: _ThrusterAt
    max_thrust: _MaxThrust
    thrust_rate: _ThrustRate = None
    azimuth_rate: Annotated[float | None, Number("rad/s", gt=0)] = api(
        "bound on the azimuth's rate of turn, > 0; none: no limit"
    )
    time_constant: _TimeConstant = None


class MainThruster(Table):
    """`[[vessel.thrusters]]` of kind "main": `pl.Thruster("main", ...)`, a main propeller pushing ahead
    (positive) or astern."""

    conflicts: ClassVar[dict[str, str]] = _TURNS
    kind: Literal["main"]
    position: _ThrusterAt
    max_thrust: _MaxThrust
    reverse_thrust: _ReverseThrust = None
    thrust_rate: _ThrustRate = None
    time_constant: _TimeConstant = None


Thruster = Annotated[
    TunnelThruster | AzimuthThruster | MainThruster,
    Discriminator("kind"),
    About(
        """`pl.Thruster`, one table per thruster of a vessel given by its matrices, chosen by `kind`.

        `controller.allocation = "qp"` shares the controller's command among them; a vessel with thrusters
        needs its `length` (they must lie on the hull). `model = "osv"` has its own six."""
    ),
]


class VesselTable(Table):
    """`[vessel]`: the keys of `model.attach_vessel` and the RAOs, whichever way the vessel is given."""

    end: Annotated[End, END] = Field(description='the end held, "A" or "B"; not in `[supports]`')
    eta: Annotated[list[float], Vector(6, Number("m, rad"), ETA)] = Field(
        description="starting pose η = [x, y, z, φ, θ, ψ] in e (zyx); z at the sea surface, −depth, within 10 m"
    )
    angle: Annotated[list[float] | None, Vector(3, Number("rad"), "[φ, θ, ψ]")] = api(
        "clamp angle β of the pipe on the vessel (zyx)", [0, 0, 0]
    )
    raos: Annotated[str | None, Text()] = api(
        "first-order motion RAOs: path of a CSV table", words='the built-in OSV\'s (model = "osv"), else none'
    )
    hull_loads: Annotated[bool | None, Flag()] = api(
        "the sea's wind, current and waves push on the hull through the vessel's wind, current and drift "
        "tables (mean and slowly varying loads); false: the hull feels only `[[environment]]`",
        False,
    )
    lay: Lay | None = None
    winch: Winch | None = None

    @field_validator("raos")
    @classmethod
    def raos_file(cls, path: str, info: ValidationInfo) -> str:
        """The RAO table's path, resolved from the scenario's folder; it must be a file."""
        return _table_file(path, info, "an RAO table")

    @model_validator(mode="after")
    def lay_sets_the_angle(self) -> VesselTable:
        """Lay equipment holds the pipe at its own angle."""
        if self.lay is not None and self.angle is not None:
            raise rule("conflicts with [vessel.lay]: the tensioner or tower sets the pipe's angle", "angle")
        return self


_MATRICES = ("M", "D", "G", "M_RB", "quadratic_damping")
_HULL_TABLES = ("wind_coefficients", "current_coefficients", "drift_coefficients")


class ModelVessel(VesselTable):
    """`[vessel]` with `model`: `pl.Vessel.osv`."""

    conflicts: ClassVar[dict[str, str]] = (
        dict.fromkeys(_MATRICES, "conflicts with vessel.model; give either model or the matrices M, D, G")
        | dict.fromkeys(
            ("thrusters", "length"),
            'conflicts with model = "osv": the OSV has its own thrusters and length (six thrusters, 83 m); '
            "give the matrices M, D, G for a vessel of your own",
        )
        | dict.fromkeys(
            _HULL_TABLES,
            'conflicts with model = "osv": the OSV has its own wind, current and drift tables; give the '
            "matrices M, D, G for a vessel of your own",
        )
    )
    model: Annotated[str, Choice(("osv",))] = Field(
        description='`"osv"`: the built-in offshore supply vessel'
    )


def _six_by_six(unit: str) -> Matrix:
    """A 6×6 matrix in `unit`."""
    return Matrix(6, Vector(6, Number(unit)))


class MatrixVessel(VesselTable):
    """`[vessel]` with the matrices: `pl.Vessel(M, D, G, ...)`."""

    M: Annotated[list[list[float]], _six_by_six("kg, kg·m, kg·m²")] = Field(
        description="M = M_RB + M_A, symmetric, positive definite"
    )
    D: Annotated[list[list[float]], _six_by_six("kg/s, kg·m/s, kg·m²/s")] = Field(
        description="linear damping, positive semi-definite"
    )
    G: Annotated[list[list[float]], _six_by_six("N/m, N, N·m/rad")] = Field(
        description="restoring: heave, roll and pitch only"
    )
    M_RB: Annotated[list[list[float]] | None, _six_by_six("kg, kg·m, kg·m²")] = api(
        "rigid-body mass; M − M_RB is added mass", words="M"
    )
    quadratic_damping: Annotated[list[list[float]] | None, _six_by_six("kg/m, kg, kg·m²")] = api(
        "D_q, positive semi-definite"
    )
    length: Annotated[float | None, POSITIVE_LENGTH] = api(
        "overall length, > 0; needed with thrusters (they must lie within ±length/2 of CO)"
    )
    thrusters: list[Thruster] = Field(
        [], description="the thrusters, for `controller.allocation`: `[[vessel.thrusters]]` tables"
    )
    wind_coefficients: Annotated[str | None, Text()] = api(
        "wind coefficients of the hull, for `hull_loads` in a `[sea.wind]`: path of a CSV table "
        "(`pl.HullCoefficients.read`)"
    )
    current_coefficients: Annotated[str | None, Text()] = api(
        "current coefficients of the hull, for `hull_loads` in a `[sea.current]`: path of a CSV table "
        "(`pl.HullCoefficients.read`)"
    )
    drift_coefficients: Annotated[str | None, Text()] = api(
        "mean wave-drift coefficients, for `hull_loads` in `[sea.waves]`: path of a CSV table "
        "(`pl.DriftCoefficients.read`)"
    )

    @field_validator("wind_coefficients", "current_coefficients")
    @classmethod
    def hull_file(cls, path: str, info: ValidationInfo) -> str:
        """A hull coefficient table's path, resolved from the scenario's folder; it must be a file."""
        return _table_file(path, info, "a table of hull coefficients")

    @field_validator("drift_coefficients")
    @classmethod
    def drift_file(cls, path: str, info: ValidationInfo) -> str:
        """The drift coefficient table's path, resolved from the scenario's folder; it must be a file."""
        return _table_file(path, info, "a table of wave-drift coefficients")

    @model_validator(mode="before")
    @classmethod
    def some_vessel(cls, data: Any) -> Any:
        """Without `model`, the matrices say what the vessel is."""
        if isinstance(data, dict) and not any(key in data for key in _MATRICES):
            raise rule('missing; give model = "osv" or the matrices M, D and G (6×6)', "model")
        return data


Vessel = Annotated[
    Annotated[ModelVessel, Tag("model")] | Annotated[MatrixVessel, Tag("matrices")],
    Discriminator(_having("model", "model", "matrices")),
    About(
        """`pl.Vessel.osv(raos)` or `pl.Vessel(M, D, G, ..., raos)`, then `model.attach_vessel`.

        Needs `[sea]`. Give `model` or the matrices (6×6, about CO, rows and columns surge … yaw).

        `raos` is the path (text) of a table of first-order displacement RAOs in pipelay's CSV format
        (`pl.Raos.read`: columns period_s, heading_deg and <dof>_amp, <dof>_phase for surge … yaw), relative to
        the scenario file's folder. Without it, `model = "osv"` moves with the built-in OSV's table, and a
        vessel given by its matrices has no wave-frequency motion.

        `model = "osv"` has its own thrusters, length and wind, current and drift tables. A vessel given by
        its matrices takes them as keys: `length`, `[[vessel.thrusters]]` and the paths (relative to the
        scenario file's folder, as `raos`) of `wind_coefficients`, `current_coefficients`
        (`pl.HullCoefficients.read`: columns angle_deg, surge … yaw) and `drift_coefficients`
        (`pl.DriftCoefficients.read`: period_s, heading_deg, surge … yaw). With `hull_loads = true`, each of
        the sea's wind, current and waves needs its table."""
    ),
]


class Route(Table):
    """`pl.Route`: a moving reference along a lay route, instead of `reference`: a straight line from `start`
    along `heading`, or `pl.Route.legs` through `waypoints` with arcs of `radius` at their corners."""

    start: Annotated[list[float] | None, Vector(2, Number("m"), "[x, y]")] = api(
        "where a straight route starts, [x, y] (or give waypoints)"
    )
    heading: Annotated[float | None, Number("rad")] = api("the route's direction and the vessel's heading", 0)
    waypoints: Annotated[
        list[list[float]] | None, Matrix(None, Vector(2, Number("m"), "[x, y]"), at_least=2)
    ] = api("the route's waypoints, one row [x, y] each, instead of start and heading")
    radius: Annotated[float | None, Number("m", gt=0)] = api(
        "radius of the arcs that cut the waypoints' corners, > 0"
    )
    speed: Annotated[float | None, Number("m/s")] = api("lay speed along the route", 0)
    start_time: Annotated[float | None, START] = api("when the reference starts moving", 0)

    @model_validator(mode="after")
    def straight_or_legs(self) -> Route:
        """A straight route (start, heading) or one through waypoints (radius), not both."""
        if (self.start is None) == (self.waypoints is None):
            raise rule("give start (a straight route) or waypoints (legs), one of them", "start")
        if self.waypoints is not None and self.heading is not None:
            raise rule("belongs to a straight route: the legs' heading follows the waypoints", "heading")
        if self.start is not None and self.radius is not None:
            raise rule("belongs to waypoints: a straight route has no corners", "radius")
        return self


class Tension(Table):
    """`pl.TensionControl`: the lay-tension loop, `PID(tension=...)`.

    Moves the DP set-point along the reference's heading (the route's, or ψ of a fixed `reference`) at
    −gain · (T_f − target) m/s, T_f the top tension low-passed with the `filter` time constant.
    """

    target: Annotated[float, Number("N")] = Field(description="top tension to hold")
    gain: Annotated[float, Number("m/(s·N)", gt=0)] = Field(
        description="set-point speed per newton of tension error, > 0"
    )
    start: Annotated[float | None, START] = api("time the loop starts", 0)
    rate_limit: Annotated[float | None, Number("m/s", gt=0)] = api("bound on the set-point's speed, > 0")
    filter: Annotated[float | None, Number("s", gt=0)] = api(
        "time constant of the tension's low-pass filter, > 0", 20
    )


class Observer(Table):
    """`pl.Observer.passive`: Fossen's nonlinear passive observer, `PID(observer=...)`; the controller acts on
    its estimate of the low-frequency pose from measurements of x, y and ψ with Gaussian noise, instead of the
    true pose."""

    noise: Annotated[list[float] | None, Vector(3, Number("m, m, rad", ge=0), "[σx, σy, σψ]")] = api(
        "standard deviations of the measurements' noise [σx, σy, σψ], ≥ 0", [0, 0, 0]
    )
    seed: Annotated[int | None, Integer(0)] = api("seed of the noise, an integer ≥ 0", 0)
    wave_period: Annotated[float | None, Number("s", gt=0, le=60)] = api(
        "period the wave filter notches, in (0, 60]",
        words="the sea's peak period when the run starts, else 10 s",
    )


class ControllerTable(Table):
    """`[controller]`: the keys of `pl.PID` whichever way the reference is given."""

    kp: Annotated[list[float] | list[list[float]], gains("N/m, N·m/rad")] = Field(
        description="proportional gains"
    )
    kd: Annotated[list[float] | list[list[float]], gains("N·s/m, N·m·s/rad")] = Field(
        description="derivative gains"
    )
    ki: Annotated[list[float] | list[list[float]] | None, gains("N/(m·s), N·m/(rad·s)")] = api(
        "integral gains; none: PD control"
    )
    start: Annotated[float | None, START] = api("time the controller takes over from holding thrust", 0)
    bumpless: Annotated[bool | None, Flag()] = api(
        "bumpless transfer: a controller starting after t = 0 takes the static holding thrust over in its "
        "integral (where `ki` reaches), so the thrust is continuous at `start`; false: ∫(η − η_ref) dt starts "
        "at 0",
        True,
    )
    integral_limit: Annotated[list[float] | None, Vector(6, Number("m·s, rad·s", gt=0), ETA)] = api(
        "bound on ∫(η − η_ref) dt, 6 numbers > 0"
    )
    thrust_limit: Annotated[
        list[float] | None, Vector(3, Number("N, N, N·m", gt=0), "[surge, sway, yaw]")
    ] = api("bound on thrust [surge, sway, yaw], > 0")
    allocation: Annotated[Literal["qp"] | None, Choice(("qp",))] = api(
        '`"qp"`: the command goes to the vessel\'s thrusters through a quadratic program (thrust allocation)',
        words="none: the command acts on the vessel directly",
    )
    passivity: Annotated[Literal["observe", "certify"] | None, Choice(("observe", "certify"))] = api(
        '`"certify"`: the time-domain passivity observer and controller keep the controller\'s work on the vessel '
        'within its storage at the start, every step; `"observe"`: the observer books it, nothing more (about a '
        "fixed `reference`; Thrusters › Energy and passivity)",
        words="none: the loop is not observed",
    )
    tension: Tension | None = None
    observer: Observer | None = None


class FixedController(ControllerTable):
    """`[controller]` with a fixed `reference`."""

    reference: Annotated[list[float], Vector(6, Number("m, rad"), ETA)] = Field(
        description="η_ref = [x, y, z, φ, θ, ψ]; or give `[controller.route]`"
    )


class RouteController(ControllerTable):
    """`[controller]` following `[controller.route]`."""

    conflicts: ClassVar[dict[str, str]] = {"reference": "conflicts with [controller.route]: give one of them"}
    route: Route


Controller = Annotated[
    Annotated[FixedController, Tag("reference")] | Annotated[RouteController, Tag("route")],
    Discriminator(_having("route", "route", "reference")),
    About(
        """`pl.PID` on the vessel's η; needs `[vessel]`.

        Gains are 6 numbers (a diagonal matrix) or a 6×6 matrix."""
    ),
]


class PayOut(Table):
    """`model.pay_out(end, speed)`: pipe paid out (or in) through the tensioner or tower.

    The end must be the one `[vessel]` holds or a driven `[supports]` end. The speed rises smoothly from 0 at
    `start_time` to `speed` over `ramp` seconds, v(t) = speed · (3s² − 2s³), s = (t − start_time)/ramp clipped
    to [0, 1] (a sudden start sends an axial shock v·√(EA·m) through the pipe): the length paid out by t ≥
    start_time + ramp is speed · (t − start_time − ramp/2). A route starts at full speed: a pay-out that starts
    with it falls speed · ramp/2 behind the vessel, which lifts laid pipe off the seabed; starting it ramp/2
    earlier (`start_time` = the route's − ramp/2) keeps the length paid out equal to the route's advance.
    """

    end: Annotated[End | None, END] = api('the end the pipe is paid out at, "A" or "B"', "B")
    speed: Annotated[
        float | str, Either(Number("m/s"), Choice(("route",)), _is_text, 'a number (m/s) or "route"')
    ] = Field(
        description='of unstretched pipe (< 0 pays in), or `"route"`: the speed of `[controller.route]`'
    )
    start_time: Annotated[float | None, START] = api(
        'when the pay-out starts; with speed = "route", the route\'s `start_time`', 0
    )
    ramp: Annotated[float | None, Number("s", ge=0)] = api(
        "time over which the speed rises to its value, ≥ 0 (0: at once)", 60
    )


class Environment(Table):
    """`pl.Force`, one table per force on the vessel; needs `[vessel]`."""

    value: Annotated[list[float], Vector(6, Number("N, N·m"), "[X, Y, Z, K, M, N]")] = Field(
        description="force and moment [X, Y, Z, K, M, N], body frame"
    )
    start: Annotated[float | None, START] = api("time the force starts", 0)
