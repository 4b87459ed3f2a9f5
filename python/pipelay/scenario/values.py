"""The building blocks of the scenario format: what one key takes (a `Value`), what every table is (a
`Table`), and the words the format's messages use.

Each value's type in the models (`pipelay.scenario.models`) carries a `Value` (`Number`, `Integer`,
`Vector`, ...): the core schema pydantic checks the value with (strict: no conversions; numbers finite;
integers accepted for numbers, not the reverse) and the words a message uses for it. Here too are the values
the tables share (`POINT`, `END`, ...), `Table`, the base of every model (unknown keys are errors), and the
helpers every message of the format is worded with (`show`, `join`, `suggest`, and `rule`, the error a
validator raises for a rule that spans keys).

What a key means is its field's `description`; a key the file may leave out for the API call's default
applies is declared with `api` (the model holds None, the field records that default), and a table that
several models make up (a union chosen by `kind` or by its keys) is described by the `About` in its union's
`Annotated`. The scenario reference and the JSON Schema are made from these (`pipelay.scenario.schema`).

Imports nothing of pipelay.
"""

from __future__ import annotations

import difflib
import reprlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator
from pydantic_core import PydanticCustomError, core_schema

__all__ = [
    "AXES",
    "COEFFICIENTS",
    "DEFAULT_WORDS",
    "END",
    "ETA",
    "INT64",
    "NODE",
    "PAIR",
    "POINT",
    "POSITIVE_LENGTH",
    "RULE",
    "START",
    "VELOCITY",
    "XYZ",
    "About",
    "Choice",
    "Either",
    "End",
    "Flag",
    "Integer",
    "Matrix",
    "Number",
    "Table",
    "Text",
    "Value",
    "Vector",
    "api",
    "gains",
    "join",
    "number_or_vector",
    "rule",
    "show",
    "suggest",
]

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
class Flag(Value):
    """true or false."""

    def allowed(self) -> str:
        """What is allowed."""
        return "true or false"

    def schema(self) -> core_schema.CoreSchema:
        """A strict bool."""
        return core_schema.bool_schema(strict=True)


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


# Documenting keys and tables: what a key means and the default the API gives it; what a table is.

DEFAULT_WORDS = "x-default-words"
"""The field metadata (`json_schema_extra`) key of a default that no single value states (`api(words=...)`);
`pipelay.scenario.json_schema` leaves it out of the schema."""


def api(meaning: str, default: object = None, *, words: str = "") -> Any:
    """A key the file may leave out, the default of the API call it maps onto applying: the field's default is
    None (the key is then not passed) and its metadata records the API's default, `default` (a TOML value,
    `json_schema_extra={"default": ...}`; None: the call has none either) or, where no single value states it,
    `words` (e.g. "π/4·d²"). `meaning` is the field's description."""
    extra: dict[str, Any] = {}
    if default is not None:
        extra["default"] = default
    if words:
        extra[DEFAULT_WORDS] = words
    return Field(None, description=meaning, json_schema_extra=extra or None)


@dataclass(frozen=True)
class About:
    """What a table is that several models make up (the union of its kinds, or of the ways to give it), as
    metadata of the union's `Annotated`: `text`'s first paragraph is the table's one-line description, the
    rest notes for the reference. A table of one model is described by that model's docstring."""

    text: str


# Tables: the base of every model.


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
