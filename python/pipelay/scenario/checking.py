"""Checking a scenario document against the models, and pydantic's errors in the words of `pipelay.scenario`.

`_check` validates a parsed document (raising `pl.InputError` with the message to report first) and `_errors`
lists every message; `explain` turns a `ValidationError` into messages `key.path: what is wrong, got value`,
following each error's loc down the models' type tree to the key and the `Value` at fault.

Imports of pipelay: the package (`pl.InputError`), `pipelay.scenario.values`, `pipelay.scenario.models` and
`pipelay.scenario.schema`.
"""

from __future__ import annotations

import os
import re
import typing
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import ValidationError
from pydantic_core import ErrorDetails

import pipelay as pl
from pipelay.scenario.models import ScenarioFile, Table
from pipelay.scenario.schema import _is_table, _members, _tables_of, _unwrap, _value
from pipelay.scenario.values import _NUMBER, RULE, Choice, Value, _and, join, show, suggest

__all__ = ["explain"]


def _folder(origin: str, folder: str | os.PathLike[str] | None) -> Path:
    """The folder file paths in a scenario are relative to: `folder`, else the origin's if it is a file, else
    the current one."""
    if folder is not None:
        return Path(folder)
    return Path(origin).absolute().parent if Path(origin).is_file() else Path.cwd()


def _errors(data: object, folder: Path) -> list[str]:
    """The messages `key.path: what is wrong` of a document, the one to report first; [] if it is valid."""
    try:
        ScenarioFile.model_validate(data, context={"folder": folder})
    except ValidationError as error:
        return explain(error)
    return []


def _check(data: object, folder: Path) -> ScenarioFile:
    """The checked document; raises InputError `key.path: message` (without the origin)."""
    try:
        return ScenarioFile.model_validate(data, context={"folder": folder})
    except ValidationError as error:
        raise pl.InputError(explain(error)[0]) from None


# Where an error's loc points in the type tree.


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
            place.variants = tuple(_tables_of(node, metadata))  # one model, or a union of kinds
        else:
            node, metadata = _members(node)[part]
        place.node = node
    value = _value(metadata)
    if value is not None:
        place.values = [(place.path, value)]
    return place


# pydantic's errors as messages.

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _shown(key: str) -> str:
    """A key as a message shows it: bare, or quoted as a TOML basic string (an empty key, or one with a dot, a
    colon or a space, would otherwise read as part of the path)."""
    if _BARE_KEY.fullmatch(key):
        return key
    return '"' + key.replace("\\", "\\\\").replace('"', '\\"') + '"'


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
        return f"{join(place.path, _shown(place.unknown))}: {_unknown(place, value)}"
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
