"""The shape of the scenario format: every table's keys (`KEYS`) and each model's table (`TABLES`), read from
the models' type tree, and the JSON Schema of scenario files (`json_schema`), documented from the reference
in `pipelay.scenario`'s docstring.

Imports of pipelay: `pipelay.scenario.values` and `pipelay.scenario.models`; `pipelay.scenario` itself (its
docstring, the reference) only when a schema is made.
"""

from __future__ import annotations

import re
import tomllib
import types
import typing
from typing import Annotated, Any, Union

from pydantic import Tag

from pipelay.scenario.models import ScenarioFile, Table
from pipelay.scenario.values import Value, join

__all__ = ["KEYS", "TABLES", "json_schema"]

_DRAFT = "https://json-schema.org/draft/2020-12/schema"


# The type tree: KEYS and TABLES from it.


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


# The JSON Schema, documented from the reference.


def _reference_doc() -> str:
    """The format's reference: the docstring of the package `pipelay.scenario` (this module's parent, imported
    before it)."""
    from pipelay import scenario

    return scenario.__doc__ or ""


def _reference(doc: str) -> dict[str, tuple[str, dict[str, list[str]]]]:
    """The reference tables of `doc`: for each table path, its heading's description and its rows by key
    ([unit, default, meaning])."""
    tables = {}
    for block in re.split(r"^### ", doc, flags=re.MULTILINE)[1:]:
        heading, _, body = block.partition("\n")
        names, _, about = heading.partition(" — ")
        rows = {}
        for line in body.splitlines():
            if line.startswith("| `"):
                key, *cells = (cell.strip() for cell in line.strip("|").split("|"))
                rows[key.strip("`")] = cells
        for path in re.findall(r"`\[\[?([\w.]+)\]\]?`", names) or [""]:
            tables[path] = (about, rows)
    return tables


def _toml(text: str) -> object:
    """The TOML value `text` spells (a default of the reference), or None."""
    try:
        return tomllib.loads(f"value = {text}")["value"]
    except tomllib.TOMLDecodeError:
        return None


def _heading(reference: dict[str, Any], path: str) -> str:
    """The description of the table at `path`: its heading's, or that of its first table (`[supports.A]`)."""
    inside = (about for table, (about, _) in reference.items() if table.startswith(f"{path}."))
    return reference[path][0] if path in reference else next(inside, "")


def _document(definition: dict[str, Any], path: str, reference: dict[str, Any]) -> None:
    """Describe a table's schema and its properties from the reference: meaning, unit and default."""
    about, rows = reference.get(path, ("", {}))
    if about:
        definition["description"] = about
    for key, schema in definition.get("properties", {}).items():
        schema.pop("title", None)  # pydantic's "Outer Diameter": the description says more
        if key not in rows:  # a table: its heading's description; its keys have the defaults
            schema.pop("default", None)
            schema["description"] = _heading(reference, join(path, key))
            continue
        unit, default, meaning = rows[key]
        given = "required" if key in definition.get("required", ()) else f"default {default}"
        schema["description"] = f"{meaning} ({'' if unit == '—' else unit + '; '}{given})"
        value = _toml(default)
        if given != "required" and value is not None:
            schema["default"] = value


def _without_null(schema: Any) -> Any:
    """The schema without pydantic's `null` (an absent key, which TOML cannot write): no `{"type": "null"}`
    branches, no `"default": null`."""
    if isinstance(schema, list):
        return [_without_null(item) for item in schema]
    if not isinstance(schema, dict):
        return schema
    result = {key: _without_null(value) for key, value in schema.items() if (key, value) != ("default", None)}
    branches = [branch for branch in result.pop("anyOf", []) if branch != {"type": "null"}]
    if len(branches) == 1:
        result.update(branches[0])
    elif branches:
        result["anyOf"] = branches
    return result


def json_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of scenario files, from the format's pydantic models, with the meaning,
    unit and default of each key from the reference in `pipelay.scenario`'s docstring, for editors to complete
    and check scenario files (e.g. taplo / Even Better TOML).

    It checks what a schema can: key names, types, bounds, vector and matrix shapes, the keys of each kind.
    The rules across keys (exactly one of [pipe] and [section], a vessel needs a sea, ...) and finiteness are
    left to `load_scenario`.
    """
    schema = ScenarioFile.model_json_schema()
    doc = _reference_doc()
    reference = _reference(doc)
    paths = {table.__name__: path for table, path in TABLES.items()}
    for name, definition in [("ScenarioFile", schema), *schema.get("$defs", {}).items()]:
        _document(definition, paths[name], reference)
    schema["title"] = "pipelay scenario"
    schema["description"] = doc.split("\n", 1)[0]
    return {"$schema": _DRAFT, **_without_null(schema)}
