"""The scenario format's models of the vessel and what works with it: `[vessel]` (given by a built-in model or
by its matrices) with its lay equipment (`[vessel.lay]`, `[vessel.lay.stinger]`), `[controller]` with its
route and tension loop, `[pay_out]` and `[[environment]]`. `pipelay.scenario.models` exposes them with the
others.

Imports of pipelay: `pipelay.scenario.values`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Discriminator, Tag, ValidationInfo, field_validator, model_validator

from pipelay.scenario.values import (
    END,
    ETA,
    POINT,
    POSITIVE_LENGTH,
    START,
    XYZ,
    Choice,
    Either,
    End,
    Integer,
    Matrix,
    Number,
    Table,
    Text,
    Vector,
    _having,
    _is_text,
    gains,
    rule,
)

__all__ = [
    "ArcStinger",
    "Controller",
    "ControllerTable",
    "Environment",
    "FixedController",
    "JLay",
    "Lay",
    "MatrixVessel",
    "ModelVessel",
    "PayOut",
    "RollerStinger",
    "Route",
    "RouteController",
    "SLay",
    "Stinger",
    "Tension",
    "Vessel",
    "VesselTable",
]


class ArcStinger(Table):
    """`[vessel.lay.stinger]` as an arc: `pl.Stinger`."""

    conflicts: ClassVar[dict[str, str]] = {"axes": "belongs to positions (rollers given point by point)"}
    radius: Annotated[float, POSITIVE_LENGTH]
    length: Annotated[float, POSITIVE_LENGTH]
    rollers: Annotated[int, Integer(1, 1000)]
    origin: Annotated[list[float] | None, POINT] = None
    angle: Annotated[float | None, Number("rad")] = None
    roller_radius: Annotated[float | None, POSITIVE_LENGTH] = None


class RollerStinger(Table):
    """`[vessel.lay.stinger]` given roller by roller: `pl.Stinger.from_rollers`."""

    conflicts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("radius", "length", "rollers", "origin", "angle"),
        "conflicts with positions: give an arc or the rollers' points",
    )
    positions: Annotated[list[list[float]], Matrix(None, POINT, at_least=1)]
    axes: Annotated[list[list[float]] | None, Matrix(None, Vector(3, Number(), XYZ), at_least=1)] = None
    roller_radius: Annotated[float | None, POSITIVE_LENGTH] = None

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
]


class SLay(Table):
    """`[vessel.lay]` of kind "s-lay": `pl.SLay`."""

    kind: Literal["s-lay"]
    tensioner: Annotated[list[float], POINT]
    roller_stiffness: Annotated[float | None, Number("N/m", gt=0)] = None
    friction: Annotated[float | None, Number(ge=0)] = None
    stinger: Stinger | None = None


class JLay(Table):
    """`[vessel.lay]` of kind "j-lay": `pl.JLay`."""

    kind: Literal["j-lay"]
    position: Annotated[list[float], POINT]
    angle: Annotated[float | None, Number("rad")] = None


Lay = Annotated[SLay | JLay, Discriminator("kind")]


class VesselTable(Table):
    """`[vessel]`: the keys of `model.attach_vessel` and the RAOs, whichever way the vessel is given."""

    end: Annotated[End, END]
    eta: Annotated[list[float], Vector(6, Number("m, rad"), ETA)]
    angle: Annotated[list[float] | None, Vector(3, Number("rad"), "[φ, θ, ψ]")] = None
    raos: Annotated[str | None, Text()] = None
    lay: Lay | None = None

    @field_validator("raos")
    @classmethod
    def raos_file(cls, path: str, info: ValidationInfo) -> str:
        """The RAO table's path, resolved from the scenario's folder (the `folder` of the context); it must be
        a file."""
        resolved = Path((info.context or {}).get("folder", ".")) / path
        if not resolved.is_file():
            raise rule(f"must be an RAO table (CSV) relative to the scenario's folder; no file {resolved}")
        return str(resolved)

    @model_validator(mode="after")
    def lay_sets_the_angle(self) -> VesselTable:
        """Lay equipment holds the pipe at its own angle."""
        if self.lay is not None and self.angle is not None:
            raise rule("conflicts with [vessel.lay]: the tensioner or tower sets the pipe's angle", "angle")
        return self


_MATRICES = ("M", "D", "G", "M_RB", "quadratic_damping")


class ModelVessel(VesselTable):
    """`[vessel]` with `model`: `pl.Vessel.osv`."""

    conflicts: ClassVar[dict[str, str]] = dict.fromkeys(
        _MATRICES, "conflicts with vessel.model; give either model or the matrices M, D, G"
    )
    model: Annotated[str, Choice(("osv",))]


def _six_by_six(unit: str) -> Matrix:
    """A 6×6 matrix in `unit`."""
    return Matrix(6, Vector(6, Number(unit)))


class MatrixVessel(VesselTable):
    """`[vessel]` with the matrices: `pl.Vessel(M, D, G, ...)`."""

    M: Annotated[list[list[float]], _six_by_six("kg, kg·m, kg·m²")]
    D: Annotated[list[list[float]], _six_by_six("kg/s, kg·m/s, kg·m²/s")]
    G: Annotated[list[list[float]], _six_by_six("N/m, N, N·m/rad")]
    M_RB: Annotated[list[list[float]] | None, _six_by_six("kg, kg·m, kg·m²")] = None
    quadratic_damping: Annotated[list[list[float]] | None, _six_by_six("kg/m, kg, kg·m²")] = None

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
]


class Route(Table):
    """`[controller.route]`: `pl.Route`."""

    start: Annotated[list[float], Vector(2, Number("m"), "[x, y]")]
    heading: Annotated[float | None, Number("rad")] = None
    speed: Annotated[float | None, Number("m/s")] = None
    start_time: Annotated[float | None, START] = None


class Tension(Table):
    """`[controller.tension]`: `pl.TensionControl`."""

    target: Annotated[float, Number("N")]
    gain: Annotated[float, Number("m/(s·N)", gt=0)]
    start: Annotated[float | None, START] = None
    rate_limit: Annotated[float | None, Number("m/s", gt=0)] = None
    filter: Annotated[float | None, Number("s", gt=0)] = None


class ControllerTable(Table):
    """`[controller]`: the keys of `pl.PID` whichever way the reference is given."""

    kp: Annotated[list[float] | list[list[float]], gains("N/m, N·m/rad")]
    kd: Annotated[list[float] | list[list[float]], gains("N·s/m, N·m·s/rad")]
    ki: Annotated[list[float] | list[list[float]] | None, gains("N/(m·s), N·m/(rad·s)")] = None
    start: Annotated[float | None, START] = None
    integral_limit: Annotated[list[float] | None, Vector(6, Number("m·s, rad·s", gt=0), ETA)] = None
    thrust_limit: Annotated[
        list[float] | None, Vector(3, Number("N, N, N·m", gt=0), "[surge, sway, yaw]")
    ] = None
    tension: Tension | None = None


class FixedController(ControllerTable):
    """`[controller]` with a fixed `reference`."""

    reference: Annotated[list[float], Vector(6, Number("m, rad"), ETA)]


class RouteController(ControllerTable):
    """`[controller]` following `[controller.route]`."""

    conflicts: ClassVar[dict[str, str]] = {"reference": "conflicts with [controller.route]: give one of them"}
    route: Route


Controller = Annotated[
    Annotated[FixedController, Tag("reference")] | Annotated[RouteController, Tag("route")],
    Discriminator(_having("route", "route", "reference")),
]


class PayOut(Table):
    """`[pay_out]`: `model.pay_out(end, speed)` with a smoothly started speed."""

    end: Annotated[End | None, END] = None
    speed: Annotated[
        float | str, Either(Number("m/s"), Choice(("route",)), _is_text, 'a number (m/s) or "route"')
    ]
    start_time: Annotated[float | None, START] = None
    ramp: Annotated[float | None, Number("s", ge=0)] = None


class Environment(Table):
    """An entry of `[[environment]]`: `pl.Force`."""

    value: Annotated[list[float], Vector(6, Number("N, N·m"), "[X, Y, Z, K, M, N]")]
    start: Annotated[float | None, START] = None
