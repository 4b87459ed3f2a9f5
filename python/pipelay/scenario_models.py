"""The scenario format as pydantic models, and pydantic's errors in the words of `pipelay.scenario`.

One model per table (and per kind of a table whose keys depend on `kind`), its fields the keyword arguments of
the API call the table maps onto; `pipelay.scenario`'s docstring is the human reference of every key. Each
value's type carries a `Value` (`Number`, `Integer`, `Vector`, ...): the core schema pydantic checks the value
with (strict: no conversions; numbers finite; integers accepted for numbers, not the reverse) and the words a
message uses for it. `explain` turns a `ValidationError` into `key.path: what is wrong, got value`; a rule that
spans keys raises `rule(message, key)` from a validator.
"""

from __future__ import annotations

import difflib
import reprlib
import types
import typing
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Union

from pydantic import (
    BaseModel,
    ConfigDict,
    Discriminator,
    Tag,
    ValidationError,
    ValidationInfo,
    field_validator,
    model_validator,
)
from pydantic_core import ErrorDetails, PydanticCustomError, core_schema

__all__ = [
    "KEYS",
    "MAX_ELEMENTS",
    "TABLES",
    "ScenarioFile",
    "Table",
    "Value",
    "explain",
    "join",
    "rule",
    "show",
    "suggest",
]

MAX_ELEMENTS = 1_000_000
"""Largest number of elements a scenario's `[rod]` may ask for."""
INT64 = 2**63 - 1
"""The largest count the engine takes."""
RULE = "scenario_rule"
"""pydantic error type of `rule`: a message about a key (ctx: key, message)."""

_SHOW = reprlib.Repr()
_SHOW.maxlist = _SHOW.maxdict = 8
_SHOW.maxstring = _SHOW.maxother = 60


def show(value: object) -> str:
    """A short rendering of a value for messages, in TOML spelling where it differs from Python's."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return "a table"
    return _SHOW.repr(value)


def rule(message: str, key: str = "") -> PydanticCustomError:
    """The error `key: message`, `key` relative to the table whose validator raises it ("": the key checked)."""
    return PydanticCustomError(RULE, "{key}: {message}", {"key": key, "message": message})


def join(path: str, key: str) -> str:
    """The key path of `key` inside the table at `path` ("" for the top level; `[i]` for an entry)."""
    if not path or not key:
        return path or key
    return f"{path}{key}" if key.startswith("[") else f"{path}.{key}"


def _paren(unit: str) -> str:
    """` (unit)`, or nothing for a dimensionless quantity."""
    return f" ({unit})" if unit else ""


def _either(options: tuple[str, ...]) -> str:
    """`"a", "b" or "c"`."""
    quoted = [f'"{option}"' for option in options]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]


def _and(names: list[str]) -> str:
    """`a, b and c`."""
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def suggest(name: str, allowed: tuple[str, ...]) -> str:
    """`; did you mean 'x'?` for the closest allowed name (case-insensitive), else the allowed names."""
    lowered = {option.lower(): option for option in allowed}
    close = difflib.get_close_matches(name.lower(), list(lowered), n=1, cutoff=0.6)
    if close:
        return f"; did you mean '{lowered[close[0]]}'?"
    return f"; allowed: {', '.join(allowed)}"


# Values: what one key takes. Each is Annotated metadata giving pydantic its core schema.

_RANGE = ("greater_than", "greater_than_equal", "less_than", "less_than_equal")
_NUMBER = ("finite_number", *_RANGE)  # errors about a number's value: the innermost Value explains them
_LENGTH = ("too_short", "too_long")


class Value:
    """What one key takes: the core schema it is checked with, and the words messages use for it."""

    def allowed(self) -> str:
        """What is allowed, with units, e.g. `a number > 0 (m)`."""
        raise NotImplementedError

    def schema(self) -> core_schema.CoreSchema:
        """The core schema pydantic checks a value with."""
        raise NotImplementedError

    def __get_pydantic_core_schema__(self, source: Any, handler: Any) -> core_schema.CoreSchema:
        """pydantic's hook: this Value's schema, whatever the annotated Python type."""
        return self.schema()

    def locate(self, loc: tuple[Any, ...]) -> list[tuple[str, Value]]:
        """The Values an error's `loc` inside this one passes, each with its key path suffix (`[1]`)."""
        return [("", self)]

    def refuse(self, kind: str, value: object) -> str:
        """The message for pydantic's error `kind` about `value`."""
        if kind in _LENGTH and isinstance(value, list):
            return f"must be {self.allowed()}, got {len(value)}: {show(value)}"
        return f"must be {self.allowed()}, got {show(value)}"


@dataclass(frozen=True)
class Number(Value):
    """A finite number in `unit`, within the bounds given."""

    unit: str = ""
    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None

    def limits(self) -> str:
        """The bounds as text, e.g. `> -1 and < 0.5`."""
        bounds = ((">", self.gt), (">=", self.ge), ("<", self.lt), ("<=", self.le))
        return " and ".join(f"{op} {limit:g}" for op, limit in bounds if limit is not None)

    def allowed(self) -> str:
        """What is allowed."""
        limits = self.limits()
        return f"a number{' ' + limits if limits else ''}{_paren(self.unit)}"

    def schema(self) -> core_schema.CoreSchema:
        """A strict, finite float within the bounds."""
        return core_schema.float_schema(
            gt=self.gt, ge=self.ge, lt=self.lt, le=self.le, allow_inf_nan=False, strict=True
        )

    def refuse(self, kind: str, value: object) -> str:
        """Not finite (an integer beyond the largest float too), out of bounds, or not a number."""
        huge = kind == "float_type" and isinstance(value, int) and not isinstance(value, bool)
        if kind == "finite_number" or huge:
            return f"must be a finite number{_paren(self.unit)}, got {show(value)}"
        if kind in _RANGE:
            unit = _paren(self.unit) if "," in self.unit else f" {self.unit}".rstrip()
            return f"must be {self.limits()}{unit}, got {show(value)}"
        return f"must be a number{_paren(self.unit)}, got {show(value)}"


@dataclass(frozen=True)
class Integer(Value):
    """An integer in [low, high] (None: no limit but 64 bits)."""

    low: int | None = None
    high: int | None = None

    def allowed(self) -> str:
        """What is allowed."""
        if self.low is None:
            return "an integer"
        return (
            f"an integer >= {self.low}" if self.high is None else f"an integer in [{self.low}, {self.high}]"
        )

    def schema(self) -> core_schema.CoreSchema:
        """A strict int within the bounds and 64 bits."""
        high = INT64 if self.high is None else self.high
        return core_schema.int_schema(ge=self.low, le=high, strict=True)

    def refuse(self, kind: str, value: object) -> str:
        """Out of bounds (or of 64 bits), or not an integer."""
        if kind in _RANGE and self.high is None and isinstance(value, int) and value > INT64:
            return f"must be {self.allowed()} and <= {INT64} (64 bits), got {show(value)}"
        return super().refuse(kind, value)


@dataclass(frozen=True)
class Text(Value):
    """Any text."""

    def allowed(self) -> str:
        """What is allowed."""
        return "text (a quoted string)"

    def schema(self) -> core_schema.CoreSchema:
        """A strict str."""
        return core_schema.str_schema(strict=True)


@dataclass(frozen=True)
class Choice(Value):
    """One of a few words."""

    options: tuple[str, ...]

    def allowed(self) -> str:
        """What is allowed."""
        return _either(self.options)

    def schema(self) -> core_schema.CoreSchema:
        """One of the words."""
        return core_schema.literal_schema(list(self.options))

    def refuse(self, kind: str, value: object) -> str:
        """Not one of the words: the closest one suggested."""
        close = (
            difflib.get_close_matches(value, self.options, n=1, cutoff=0.6) if isinstance(value, str) else []
        )
        hint = f'; did you mean "{close[0]}"?' if close else ""
        return f"must be {self.allowed()}, got {show(value)}{hint}"


def _indexed(container: Value, item: Value, loc: tuple[Any, ...]) -> list[tuple[str, Value]]:
    """`Value.locate` of a list of `item`s: the list, then what `item` passes at index `loc[0]` (`[i]...`)."""
    if not loc:
        return [("", container)]
    return [("", container), *((f"[{loc[0]}]{suffix}", value) for suffix, value in item.locate(loc[1:]))]


def _sized(items: core_schema.CoreSchema, least: int, most: int | None) -> core_schema.CoreSchema:
    """A strict list of `items`, from `least` to `most` of them: its length checked before its items (a
    tuple, from Python, taken as a list)."""

    def length(value: object) -> object:
        value = list(value) if isinstance(value, tuple) else value
        if isinstance(value, list) and not least <= len(value) <= (len(value) if most is None else most):
            raise PydanticCustomError("too_short" if len(value) < least else "too_long", "wrong length")
        return value

    sized = core_schema.list_schema(items, min_length=least, max_length=most, strict=True)
    return core_schema.no_info_before_validator_function(length, sized)


def _some(at_least: int) -> str:
    """`a list of at least n` (or `a non-empty list of` for n = 1), for lists of any length."""
    return "a non-empty list of" if at_least == 1 else f"a list of at least {at_least}"


@dataclass(frozen=True)
class Vector(Value):
    """`count` numbers (`labels` names them) of `item`; count None: at least `at_least` of them."""

    count: int | None
    item: Number
    labels: str = ""
    at_least: int = 0

    def allowed(self) -> str:
        """What is allowed."""
        limits = self.item.limits()
        bounds = f" {limits}" if limits else ""
        if self.count is None:
            return f"{_some(self.at_least)} numbers{bounds}{_paren(self.item.unit)}"
        labels = f" {self.labels}" if self.labels else ""
        return f"{self.count} numbers{labels}{bounds}{_paren(self.item.unit)}"

    def schema(self) -> core_schema.CoreSchema:
        """A strict list of numbers."""
        return _sized(self.item.schema(), self.at_least if self.count is None else self.count, self.count)

    def locate(self, loc: tuple[Any, ...]) -> list[tuple[str, Value]]:
        """This vector, then the number at `loc[0]`."""
        return _indexed(self, self.item, loc)


@dataclass(frozen=True)
class Matrix(Value):
    """Rows, each a `row`: exactly `rows` of them, or (rows None) at least `at_least`; `text` says so instead."""

    rows: int | None
    row: Vector
    at_least: int = 0
    text: str = ""

    def allowed(self) -> str:
        """What is allowed."""
        if self.text:
            return self.text
        row = f"{self.row.count} numbers {self.row.labels}".rstrip()
        unit = _paren(self.row.item.unit)
        if self.rows is None:
            return f"{_some(self.at_least)} rows of {row}{unit}"
        return f"a {self.rows}×{self.row.count} matrix, {self.rows} rows of {row}{unit}"

    def schema(self) -> core_schema.CoreSchema:
        """A strict list of rows."""
        return _sized(self.row.schema(), self.at_least if self.rows is None else self.rows, self.rows)

    def locate(self, loc: tuple[Any, ...]) -> list[tuple[str, Value]]:
        """This matrix, then the row at `loc[0]` and its number."""
        return _indexed(self, self.row, loc)


@dataclass(frozen=True)
class Either(Value):
    """`first` or `second`, `pick(value)` choosing `second`; `text` says what is allowed."""

    first: Value
    second: Value
    pick: Callable[[object], bool]
    text: str

    def allowed(self) -> str:
        """What is allowed."""
        return self.text

    def schema(self) -> core_schema.CoreSchema:
        """A union tagged by `pick`."""
        return core_schema.tagged_union_schema(
            {"first": self.first.schema(), "second": self.second.schema()},
            discriminator=lambda value: "second" if self.pick(value) else "first",
        )

    def locate(self, loc: tuple[Any, ...]) -> list[tuple[str, Value]]:
        """This union, then the member `loc[0]` names."""
        if not loc:
            return [("", self)]
        return [("", self), *(self.first if loc[0] == "first" else self.second).locate(loc[1:])]


def _is_list(value: object) -> bool:
    return isinstance(value, list | tuple)


def _is_text(value: object) -> bool:
    return isinstance(value, str)


def _is_matrix(value: object) -> bool:
    return isinstance(value, list | tuple) and bool(value) and _is_list(value[0])


def number_or_vector(count: int, item: Number, labels: str) -> Either:
    """One number, or `count` numbers (`labels`), each an `item`."""
    vector = Vector(count, item, labels)
    return Either(item, vector, _is_list, f"a number or {vector.allowed()}")


def gains(unit: str) -> Either:
    """Controller gains: 6 numbers (a diagonal matrix) or a 6×6 matrix."""
    diagonal = Vector(6, Number(unit))
    return Either(
        diagonal, Matrix(6, diagonal), _is_matrix, f"6 numbers (the diagonal) or a 6×6 matrix{_paren(unit)}"
    )


End = Literal["A", "B"]
XYZ = "[x, y, z]"
VELOCITY = "[vx, vy, vz]"
ETA = "[x, y, z, φ, θ, ψ]"
PAIR = "[axial, normal]"
AXES = "[axis 2, axis 3]"
END = Choice(("A", "B"))
POINT = Vector(3, Number("m"), XYZ)
START = Number("s")
POSITIVE_LENGTH = Number("m", gt=0)
COEFFICIENTS = Vector(2, Number(ge=0), PAIR)
NODE = Either(
    Integer(), END, _is_text, 'a node index (an integer; negative counts from the end) or "A" / "B"'
)


# Tables.


class Table(BaseModel):
    """A TOML table: unknown keys are errors; `conflicts` maps keys this table refuses to the reason why;
    `unknown` replaces the message for an unknown key."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False)
    conflicts: ClassVar[dict[str, str]] = {}
    unknown: ClassVar[str] = ""

    @model_validator(mode="before")
    @classmethod
    def refuse_conflicts(cls, data: Any) -> Any:
        """The first key of `conflicts` given is an error."""
        if isinstance(data, dict):
            for key, reason in cls.conflicts.items():
                if key in data:
                    raise rule(reason, key)
        return data

    def given(self, *exclude: str) -> dict[str, Any]:
        """The keys the file gives, but `kind` and `exclude`: the keyword arguments of the API call."""
        skip = {"kind", *exclude}
        return {key: getattr(self, key) for key in self.model_fields_set if key not in skip}


def _having(key: str, present: str, absent: str) -> Callable[[object], str]:
    """A discriminator: the tag `present` for a table with `key`, else `absent`."""
    return lambda value: present if isinstance(value, dict) and key in value else absent


def _table_or(tag: str) -> Callable[[object], str]:
    """A discriminator: "table" for a table, else `tag`."""
    return lambda value: "table" if isinstance(value, dict) else tag


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
    point_loads: list[PointLoad] = []
    vessel: Vessel | None = None
    controller: Controller | None = None
    pay_out: PayOut | None = None
    environment: list[Environment] = []
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


# The type tree: KEYS and TABLES from it, and where an error's loc points in it.


def _unwrap(annotation: Any, metadata: tuple[Any, ...] = ()) -> tuple[Any, tuple[Any, ...]]:
    """The type under Annotated and Optional, with the Annotated metadata collected."""
    while True:
        origin = typing.get_origin(annotation)
        if origin is Annotated:
            annotation, *more = typing.get_args(annotation)
            metadata = (*metadata, *more)
        elif origin in (Union, types.UnionType) and type(None) in typing.get_args(annotation):
            rest = [arg for arg in typing.get_args(annotation) if arg is not type(None)]
            if len(rest) > 1:
                return Union[tuple(rest)], metadata  # noqa: UP007 (a union built at run time)
            annotation = rest[0]
        else:
            return annotation, metadata


def _is_table(annotation: Any) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, Table)


def _is_union(annotation: Any) -> bool:
    return typing.get_origin(annotation) in (Union, types.UnionType)


def _value(metadata: tuple[Any, ...]) -> Value | None:
    return next((item for item in metadata if isinstance(item, Value)), None)


def _members(annotation: Any) -> dict[str, tuple[Any, tuple[Any, ...]]]:
    """A tagged union's members by tag: the `Tag`, or the `kind` a member's Literal field takes."""
    members = {}
    for arg in typing.get_args(annotation):
        member, metadata = _unwrap(arg)
        tag = next((item.tag for item in metadata if isinstance(item, Tag)), None)
        if tag is None:
            tag = typing.get_args(member.model_fields["kind"].annotation)[0]
        members[tag] = (member, metadata)
    return members


def _tables_of(annotation: Any, metadata: tuple[Any, ...] = ()) -> list[type[Table]]:
    """The models a key's type may hold: a table, the tables of a union, those of an array of tables."""
    annotation, metadata = _unwrap(annotation, metadata)
    if _value(metadata) is not None:
        return []
    if _is_table(annotation):
        return [annotation]
    if typing.get_origin(annotation) is list:
        return _tables_of(typing.get_args(annotation)[0])
    if _is_union(annotation):
        members = _members(annotation).values()
        return [table for member, inner in members for table in _tables_of(member, inner)]
    return []


def _walk_tables(
    annotation: Any,
    metadata: tuple[Any, ...],
    path: str,
    keys: dict[str, tuple[str, ...]],
    tables: dict[type[Table], str],
) -> None:
    """Fill `keys` (each table's keys, kinds merged) and `tables` (each model's table) from `path` down."""
    for table in _tables_of(annotation, metadata):
        tables.setdefault(table, path)
        keys[path] = tuple(dict.fromkeys((*keys.get(path, ()), *table.model_fields)))
        for name, info in table.model_fields.items():
            _walk_tables(info.annotation, tuple(info.metadata), join(path, name), keys, tables)


KEYS: dict[str, tuple[str, ...]] = {}
"""Every table's keys ("" is the top level; an array of tables lists the keys of one entry; a table whose keys
depend on `kind` lists those of every kind)."""
TABLES: dict[type[Table], str] = {}
"""Each model's table path (the first, for a model used by several tables)."""
_walk_tables(ScenarioFile, (), "", KEYS, TABLES)


@dataclass
class _Place:
    """Where an error's loc points: the key path, the Values passed (with their paths), the innermost table
    and the models it may be, the type at the end, the key the table does not have."""

    path: str = ""
    values: list[tuple[str, Value]] = field(default_factory=list)
    table: type[Table] = ScenarioFile
    variants: tuple[type[Table], ...] = (ScenarioFile,)
    node: Any = ScenarioFile
    array: str = ""
    unknown: str | None = None


def _locate(loc: tuple[Any, ...]) -> _Place:
    """Follow `loc` (keys, array indices, union tags) down the type tree of ScenarioFile."""
    place = _Place()
    node, metadata = ScenarioFile, ()
    for i, part in enumerate(loc):
        value = _value(metadata)
        if value is not None:
            place.values = [(place.path + suffix, inner) for suffix, inner in value.locate(loc[i:])]
            place.path = place.values[-1][0]
            return place
        place.array = ""
        if _is_table(node):
            place.table = node
            if part not in node.model_fields:
                place.unknown = str(part)
                return place
            place.path = join(place.path, str(part))
            info = node.model_fields[part]
            node, metadata = _unwrap(info.annotation, tuple(info.metadata))
            place.variants = tuple(_tables_of(node, metadata))
        elif typing.get_origin(node) is list:
            place.array = place.path
            place.path = f"{place.path}[{part}]"
            node, metadata = _unwrap(typing.get_args(node)[0])
            place.variants = (node,)
        else:
            node, metadata = _members(node)[part]
        place.node = node
    value = _value(metadata)
    if value is not None:
        place.values = [(place.path, value)]
    return place


# pydantic's errors as messages.

_EMPTY_KEY = '""'
_RANK = {"extra_forbidden": 0, "missing": 1, "union_tag_not_found": 1}
"""Which error a message is about: an unknown key first, then a missing one (a misspelt key is both)."""


def explain(error: ValidationError) -> list[str]:
    """The messages `key.path: what is wrong` of pydantic's errors, the first the one the format's reader
    reports (an unknown key before a missing one, before a bad value; an array's shape before its items)."""
    errors = error.errors(include_url=False)
    locs = {item["loc"] for item in errors}
    outermost = [item for item in errors if not any(item["loc"][:n] in locs for n in range(len(item["loc"])))]
    return [_message(item) for item in sorted(outermost, key=lambda item: _RANK.get(item["type"], 2))]


def _message(error: ErrorDetails) -> str:
    """One error's message."""
    kind, value, context = error["type"], error["input"], error.get("ctx") or {}
    place = _locate(error["loc"])
    if kind == RULE:
        return f"{join(place.path, context['key'])}: {context['message']}"
    if place.unknown is not None:
        return f"{join(place.path, place.unknown or _EMPTY_KEY)}: {_unknown(place, value)}"
    if place.values:
        return f"{place.path}: {_refuse(place, kind, value)}"
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        return f"{join(place.path, 'kind')}: {_refuse_kind(place, kind, value)}"
    return f"{place.path or 'scenario'}: {_table_message(place, kind, value, error['msg'])}"


def _refuse(place: _Place, kind: str, value: object) -> str:
    """A value's message: the Value at the error's path says what it allows; a number's value the innermost."""
    path, innermost = place.values[-1]
    if kind == "missing":
        return f"missing required key; must be {place.values[0][1].allowed()}"
    if kind in _NUMBER:
        return innermost.refuse(kind, value)
    outer = next(inner for where, inner in place.values if where == path)
    return outer.refuse(kind, value)


def _kind_of(table: type[Table]) -> str | None:
    """The `kind` a table of a kind takes, or None."""
    info = table.model_fields.get("kind")
    return None if info is None else typing.get_args(info.annotation)[0]


def _unknown(place: _Place, value: object) -> str:
    """The message for a key `place.table` does not have: another kind's key, or an unknown one."""
    table, key = place.table, place.unknown or ""
    if table.unknown:
        return table.unknown
    kind = _kind_of(table)
    if kind is not None and any(key in variant.model_fields for variant in place.variants):
        takes = ", ".join(name for name in table.model_fields if name != "kind")
        return f'not a key of kind = "{kind}", which takes {takes}'
    names = tuple(
        dict.fromkeys(name for variant in place.variants or (table,) for name in variant.model_fields)
    )
    tables = isinstance(value, list) and bool(value) and all(isinstance(item, dict) for item in value)
    what = "section" if isinstance(value, dict) or tables else "key"
    return f"unknown {what}{suggest(key, names)}"


def _refuse_kind(place: _Place, kind: str, value: object) -> str:
    """The message for a table of kinds without a `kind`, or with one no kind is."""
    kinds = Choice(tuple(_members(place.node)))
    if kind == "union_tag_not_found" or not isinstance(value, dict):
        return f"missing required key; must be {kinds.allowed()}"
    return kinds.refuse(kind, value["kind"])


def _table_message(place: _Place, kind: str, value: object, fallback: str) -> str:
    """A table's message: missing, not a table, not an array of tables, no or a wrong `kind`."""
    path = place.path
    if kind == "missing":
        required = [
            _and([name for name, info in table.model_fields.items() if info.is_required()])
            for table in _tables_of(place.node)
        ]
        return f"missing required section; give {', or '.join(required)}"
    if not path:
        return f"must be a table of sections (a dict), got {show(value)}"
    if kind == "list_type":
        return f"must be an array of tables [[{path}]], got {show(value)}"
    if kind in ("model_type", "model_attributes_type"):
        if place.array:
            return f"must be a table (an entry of [[{place.array}]]), got {show(value)}"
        return f"must be a table [{path}], got {show(value)}"
    return f"{fallback}, got {show(value)}"
