"""The shape of the scenario format, read from the models' type tree: every table's keys (`KEYS`), each model's
table (`TABLES`), the reference of every table and key (`reference_tables`: what each takes, its unit, default
and meaning, as the models state them) and the JSON Schema of scenario files (`json_schema`), documented from
that reference.

Imports of pipelay: `pipelay.scenario.values` and `pipelay.scenario.models`.
"""

from __future__ import annotations

import functools
import inspect
import json
import types
import typing
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Annotated, Any, Literal, Union

from pydantic import BaseModel, Tag
from pydantic.fields import FieldInfo

from pipelay.scenario.models import ScenarioFile, Table
from pipelay.scenario.values import DEFAULT_WORDS, About, Value, join

__all__ = ["KEYS", "TABLES", "KeyRow", "ReferenceTable", "Variant", "json_schema", "reference_tables"]

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


def _walk(
    annotation: Any, metadata: tuple[Any, ...], path: str
) -> Iterator[tuple[str, Any, tuple[Any, ...]]]:
    """Every table from the key at `path` down, depth first in the order of the models' fields: its path, and
    the type and metadata of the key that holds it (a table's path again for each model that has it)."""
    tables = _tables_of(annotation, metadata)
    if tables:
        yield path, annotation, metadata
    for table in tables:
        for name, info in table.model_fields.items():
            yield from _walk(info.annotation, tuple(info.metadata), join(path, name))


KEYS: dict[str, tuple[str, ...]] = {}
"""Every table's keys ("" is the top level; an array of tables lists the keys of one entry; a table whose keys
depend on `kind` lists those of every kind)."""
TABLES: dict[type[Table], str] = {}
"""Each model's table path (the first, for a model used by several tables)."""
for _path, _annotation, _metadata in _walk(ScenarioFile, (), ""):
    for _table in _tables_of(_annotation, _metadata):
        TABLES.setdefault(_table, _path)
        KEYS[_path] = tuple(dict.fromkeys((*KEYS.get(_path, ()), *_table.model_fields)))


# The reference: every table, its variants and keys, as the models state them.


@dataclass(frozen=True)
class KeyRow:
    """One key of a table in the reference.

    Attributes:
        key: the key's name.
        takes: what it takes, in the words of the format's messages (`Value.allowed()`); "" for a key that
            holds a table only.
        unit: its unit ("" for none).
        default: "required", the default in TOML spelling (`7850`, `[0, 1]`, `"B"`), the default in words
            where no single value states it (`π/4·d²`), "none" (the API call has none), or "—" (a table).
        meaning: what it means: the field's `description`; for a key that holds a table, the table's.
        value: the default as a TOML value, None if there is no single one.
        table: the first path of the table the key may hold ("" for none).
        array: whether it holds an array of tables.
    """

    key: str
    takes: str
    unit: str
    default: str
    meaning: str
    value: Any = None
    table: str = ""
    array: bool = False


@dataclass(frozen=True)
class Variant:
    """One model a table can be.

    Attributes:
        model: the model.
        tag: its `kind`, or the tag of its union (None: the table's only model).
        by_kind: whether `kind` chooses it.
        notes: the paragraphs of its docstring, one line each, for a table of several models (its docstring
            is then about this variant); () for a table's only model (its docstring is the table's).
        rows: its keys, in the order of its fields.
    """

    model: type[Table]
    tag: str | None
    by_kind: bool
    notes: tuple[str, ...]
    rows: tuple[KeyRow, ...]


@dataclass(frozen=True)
class ReferenceTable:
    """A TOML table in the reference.

    Attributes:
        paths: its paths (tables of the same models share an entry: `supports.A`, `supports.B`); "" is the top
            level.
        array: whether it is an array of tables (one entry's keys).
        description: what it is, in one line without a final period: the first paragraph of its model's
            docstring, or of the `About` of its union.
        notes: the other paragraphs of that text, one line each.
        variants: its models: one, or one per `kind` (or per way to give the table).
    """

    paths: tuple[str, ...]
    array: bool
    description: str
    notes: tuple[str, ...]
    variants: tuple[Variant, ...]


def _paragraphs(text: str | None) -> tuple[str, ...]:
    """A docstring's paragraphs, each on one line."""
    blocks = inspect.cleandoc(text or "").split("\n\n")
    return tuple(" ".join(block.split()) for block in blocks if block.strip())


def _toml(value: Any) -> str:
    """A default in TOML spelling, as a person writes it: `7850`, `207e9`, `0.3`, `[0, 1]`, `"B"`."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml(item) for item in value) + "]"
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e300:
        value = int(value)
    if isinstance(value, int) and value != 0:
        digits = str(value).rstrip("0")
        zeros = len(str(value)) - len(digits)
        return f"{digits}e{zeros}" if zeros >= 4 else str(value)
    return repr(value)


def _unit(value: Any) -> str:
    """A Value's unit, looking inside vectors, matrices and unions."""
    unit = getattr(value, "unit", None)
    if isinstance(unit, str):
        return unit
    for inner in ("item", "row", "first", "second"):
        found = _unit(getattr(value, inner, None)) if hasattr(value, inner) else ""
        if found:
            return found
    return ""


def _takes(info: FieldInfo) -> tuple[str, str, list[type[Table]], bool]:
    """What a key takes (words), its unit, the tables it may hold and whether it holds an array of them."""
    base, metadata = _unwrap(info.annotation, tuple(info.metadata))
    value = _value(metadata)
    if value is not None:
        return value.allowed(), _unit(value), [], False
    if typing.get_origin(base) is Literal:
        return " or ".join(f'"{option}"' for option in typing.get_args(base)), "", [], False
    array = typing.get_origin(base) is list
    members = [_unwrap(typing.get_args(base)[0] if array else base)]
    if _is_union(members[0][0]):
        members = [_unwrap(arg) for arg in typing.get_args(members[0][0])]
    words = [item.allowed() for _, inner in members if (item := _value(inner)) is not None]
    units = [_unit(item) for _, inner in members if (item := _value(inner)) is not None]
    tables = [member for member, _ in members if _is_table(member)]
    return " or ".join(dict.fromkeys(words)), next((unit for unit in units if unit), ""), tables, array


def _default(info: FieldInfo) -> tuple[str, Any]:
    """A key's default: its words (see `KeyRow.default`) and its TOML value (None if none)."""
    if info.is_required():
        return "required", None
    extra = info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}
    if "default" in extra:
        return _toml(extra["default"]), extra["default"]
    if DEFAULT_WORDS in extra:
        return str(extra[DEFAULT_WORDS]), None
    given = info.get_default(call_default_factory=True)
    if isinstance(given, BaseModel):
        return "—", None
    if given is None or given == []:
        return "none", None
    return _toml(given), given


def _choices(tags: list[str]) -> str:
    """`"a"`, `"b"` or `"c"`: the kinds of a table, the meaning of its `kind`."""
    quoted = [f'`"{tag}"`' for tag in tags]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]


def _entries(annotation: Any, metadata: tuple[Any, ...]) -> tuple[Any, tuple[Any, ...], bool]:
    """The type and metadata of the table a key holds, under Annotated and Optional, and of an array's entries
    (a union of kinds in `[[vessel.thrusters]]`); and whether it is an array of tables."""
    base, metadata = _unwrap(annotation, metadata)
    if typing.get_origin(base) is not list:
        return base, metadata, False
    return (*_unwrap(typing.get_args(base)[0]), True)


@functools.cache
def reference_tables() -> tuple[ReferenceTable, ...]:
    """The reference of the scenario format, from its models: every table (the top level first, then in the
    order of the models' fields, depth first), its variants and, for each variant, every key with what it
    takes, its unit, default and meaning. The Scenario reference page of the documentation and `json_schema`
    are made from it."""
    found: dict[tuple[type[Table], ...], tuple[list[str], Any, tuple[Any, ...]]] = {}
    for path, annotation, metadata in _walk(ScenarioFile, (), ""):
        models = tuple(_tables_of(annotation, metadata))
        paths = found.setdefault(models, ([], annotation, metadata))[0]
        if path not in paths:
            paths.append(path)
    texts: dict[tuple[type[Table], ...], tuple[str, ...]] = {}
    for models, (_, annotation, metadata) in found.items():
        about = next((item for item in _entries(annotation, metadata)[1] if isinstance(item, About)), None)
        texts[models] = _paragraphs(models[0].__doc__ if len(models) == 1 else about.text if about else "")
    first = {model: paths[0] for models, (paths, _, _) in found.items() for model in models}
    described = {
        paths[0]: (texts[models] or ("",))[0].removesuffix(".") for models, (paths, _, _) in found.items()
    }

    tables = []
    for models, (paths, annotation, metadata) in found.items():
        base, _, entries = _entries(annotation, metadata)
        union = _is_union(base)
        tags = {member: tag for tag, (member, _) in _members(base).items()} if union else {}
        variants = []
        for model in models:
            by_kind = "kind" in model.model_fields
            rows = []
            for name, info in model.model_fields.items():
                takes, unit, held, array = _takes(info)
                default, value = _default(info)
                table = first[held[0]] if held else ""
                if info.description:
                    meaning = info.description
                elif name == "kind" and by_kind:
                    meaning = _choices(list(tags.values()))
                else:
                    meaning = described.get(table, "")
                rows.append(KeyRow(info.alias or name, takes, unit, default, meaning, value, table, array))
            notes = _paragraphs(model.__doc__) if len(models) > 1 else ()
            variants.append(Variant(model, tags.get(model), by_kind, notes, tuple(rows)))
        text = texts[models] or ("",)
        tables.append(ReferenceTable(tuple(paths), entries, described[paths[0]], text[1:], tuple(variants)))
    return tuple(tables)


# The JSON Schema, documented from the reference.


def _document(definition: dict[str, Any], table: ReferenceTable, variant: Variant) -> None:
    """Describe a model's schema and its properties from the reference: meaning, unit and default. A key only
    some kinds of its table have says which (`jonswap: peak period, > 0 (s; required)`): an editor may list
    the keys of every kind."""
    if table.description:
        definition["description"] = table.description
    rows = {row.key: row for row in variant.rows}
    everywhere = set.intersection(*({row.key for row in other.rows} for other in table.variants))
    for key, schema in definition.get("properties", {}).items():
        schema.pop("title", None)  # pydantic's "Outer Diameter": the description says more
        schema.pop(DEFAULT_WORDS, None)
        row = rows[key]
        if not row.takes:  # a table: its description; its keys have the defaults
            schema.pop("default", None)
            schema["description"] = row.meaning
            continue
        given = "required" if key in definition.get("required", ()) else f"default {row.default}"
        kind = f"{variant.tag}: " if variant.by_kind and key not in everywhere else ""
        schema["description"] = f"{kind}{row.meaning} ({row.unit + '; ' if row.unit else ''}{given})"
        if given != "required" and row.value is not None:
            schema["default"] = row.value


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
    unit and default of each key from the reference (`reference_tables`), for editors to complete and check
    scenario files (e.g. taplo / Even Better TOML).

    It checks what a schema can: key names, types, bounds, vector and matrix shapes, the keys of each kind.
    The rules across keys (exactly one of [pipe] and [section], a vessel needs a sea, ...) and finiteness are
    left to `load_scenario`.
    """
    schema = ScenarioFile.model_json_schema()
    places = {
        variant.model.__name__: (table, variant) for table in reference_tables() for variant in table.variants
    }
    for name, definition in [("ScenarioFile", schema), *schema.get("$defs", {}).items()]:
        _document(definition, *places[name])
    schema["title"] = "pipelay scenario"
    return {"$schema": _DRAFT, **_without_null(schema)}
