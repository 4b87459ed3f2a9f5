"""MkDocs hook: the scenario reference, generated at build time from the scenario format's pydantic models.

A page that holds the line ``<!-- scenario-reference -->`` gets it replaced by one section per TOML table
(``[pipe]``, ``[sea.current]``, ...): its keys, what each takes (with units), its default and its meaning. Every
table is found by walking the models from the root model of ``pipelay.scenario``: the format is described once,
in the Python package, and the site cannot drift from it.

Where each fact comes from:

- keys, nesting, kinds, required keys and explicit defaults: the models' fields;
- what a key takes and its unit: the field's ``Value`` metadata (``allowed()``, ``unit``), the words the
  format's own error messages use;
- the meaning: the field's ``description`` (``Field(description=...)``);
- a default that the field leaves to the API (``None`` in the model, the API call's default applies) and a
  meaning the field does not carry yet: the reference tables of the ``pipelay.scenario`` docstring, which
  ``pipelay.scenario.json_schema`` reads as well. That fallback goes unused once every field has a
  description (and ``json_schema_extra={"default": ...}`` for the API's defaults).

Run ``python docs/hooks/scenario_reference.py`` to print the generated Markdown, and the fields that have no
``description`` of their own, on standard error.
"""

from __future__ import annotations

import importlib
import re
import sys
import types
import typing
from dataclasses import dataclass, field
from typing import Annotated, Any, Literal, Union

from pydantic import BaseModel, Tag
from pydantic_core import PydanticUndefined

PLACEHOLDER = "<!-- scenario-reference -->"

SEE_ALSO: dict[str, tuple[str, str]] = {
    "pipe": ("statics.md#the-pipe-and-its-cross-section", "Statics: the pipe"),
    "section": ("statics.md#the-pipe-and-its-cross-section", "Statics: the pipe"),
    "rod": ("statics.md#the-rod-and-its-reference", "Statics: the rod"),
    "sea": ("statics.md#loads-sea-and-current", "Statics: loads, sea and current"),
    "sea.current": ("statics.md#loads-sea-and-current", "Statics: loads, sea and current"),
    "sea.seabed": ("seabed.md", "Seabed"),
    "sea.seabed.bathymetry": ("seabed.md#bathymetry", "Seabed: bathymetry"),
    "sea.waves": ("waves.md", "Waves"),
    "supports.A": ("statics.md#supports", "Statics: supports"),
    "point_loads": ("statics.md#loads-sea-and-current", "Statics: loads"),
    "vessel": ("vessel-and-dp.md", "Vessel and DP"),
    "vessel.lay": ("lay-equipment.md", "Lay equipment and checks"),
    "vessel.lay.stinger": ("lay-equipment.md#rollers-and-the-stinger", "Lay equipment: rollers"),
    "controller": ("vessel-and-dp.md#dp-control", "Vessel and DP: control"),
    "controller.route": ("vessel-and-dp.md#following-a-lay-route", "Vessel and DP: lay route"),
    "controller.tension": ("vessel-and-dp.md#holding-the-lay-tension", "Vessel and DP: lay tension"),
    "pay_out": ("pay-out.md#in-a-scenario-file", "Pay-out"),
    "environment": ("vessel-and-dp.md#environmental-forces", "Vessel and DP: environmental forces"),
    "solver": ("scenario-files.md#solver-settings", "Scenario files: solver settings"),
}
"""The capability page that explains a table (its path as the walk finds it first)."""


# The root model.


def root_model() -> type[BaseModel]:
    """The scenario format's root pydantic model: ``pipelay.scenario.Scenario`` if that is one, else the
    ``ScenarioFile`` of the package's models module."""
    scenario = importlib.import_module("pipelay.scenario")
    candidate = getattr(scenario, "Scenario", None)
    if _is_model(candidate):
        return candidate
    for name in ("pipelay.scenario.models", "pipelay.scenario_models"):
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError:
            continue
        for attribute in ("Scenario", "ScenarioFile"):
            candidate = getattr(module, attribute, None)
            if _is_model(candidate):
                return candidate
    raise RuntimeError("no pydantic root model of the scenario format in pipelay.scenario")


def _is_model(candidate: object) -> bool:
    return isinstance(candidate, type) and issubclass(candidate, BaseModel)


# The walk: every table, its variants (kinds) and its keys.


@dataclass
class Variant:
    """One model a table can be: its tag (the `kind`, or the union's Tag) and the model."""

    tag: str | None
    model: type[BaseModel]
    by_kind: bool = False


@dataclass
class TableInfo:
    """A TOML table: its paths (tables that take the same models share a section), whether it is an array of
    tables, and its variants."""

    paths: list[str]
    array: bool
    variants: list[Variant]
    anchor: str = ""


def _unwrap(annotation: Any) -> tuple[Any, list[Any]]:
    """The type under Annotated and Optional, with the Annotated metadata collected."""
    metadata: list[Any] = []
    while True:
        origin = typing.get_origin(annotation)
        if origin is Annotated:
            annotation, *more = typing.get_args(annotation)
            metadata.extend(more)
        elif _is_union(annotation) and type(None) in typing.get_args(annotation):
            rest = [arg for arg in typing.get_args(annotation) if arg is not type(None)]
            if len(rest) > 1:
                return Union[tuple(rest)], metadata  # noqa: UP007 (a union built at run time)
            annotation = rest[0]
        else:
            return annotation, metadata


def _is_union(annotation: Any) -> bool:
    return typing.get_origin(annotation) in (Union, types.UnionType)


def _members(annotation: Any) -> list[tuple[Any, list[Any]]]:
    """The members of a union (each unwrapped), or the one type."""
    annotation, metadata = _unwrap(annotation)
    if _is_union(annotation):
        return [_unwrap(arg) for arg in typing.get_args(annotation)]
    return [(annotation, metadata)]


def _kind(model: type[BaseModel]) -> str | None:
    """The `kind` a model of a kind takes, or None."""
    info = model.model_fields.get("kind")
    if info is None:
        return None
    base, _ = _unwrap(info.annotation)
    if typing.get_origin(base) is Literal:
        return str(typing.get_args(base)[0])
    return None


def _tables_of(annotation: Any) -> tuple[bool, list[Variant]]:
    """Whether a key holds an array of tables, and the tables it may hold (none for a value)."""
    base, _ = _unwrap(annotation)
    array = typing.get_origin(base) is list
    if array:
        base = typing.get_args(base)[0]
    variants = []
    for member, metadata in _members(base):
        if _is_model(member):
            kind = _kind(member)
            tag = next((item.tag for item in metadata if isinstance(item, Tag)), None)
            variants.append(Variant(kind if kind is not None else tag, member, kind is not None))
    return array, variants


def walk(root: type[BaseModel]) -> list[TableInfo]:
    """Every table under `root`, in the order of the models' fields; tables of the same models merged."""
    found: list[TableInfo] = [TableInfo([""], False, [Variant(None, root)])]
    by_models: dict[tuple[type[BaseModel], ...], TableInfo] = {}

    def visit(path: str, variants: list[Variant]) -> None:
        for variant in variants:
            for name, info in variant.model.model_fields.items():
                array, inner = _tables_of(info.annotation)
                if not inner:
                    continue
                child = f"{path}.{name}" if path else name
                models = tuple(item.model for item in inner)
                if models in by_models:
                    if child not in by_models[models].paths:
                        by_models[models].paths.append(child)
                    continue
                table = TableInfo([child], array, inner)
                by_models[models] = table
                found.append(table)
                visit(child, inner)

    visit("", found[0].variants)
    return found


# What a key takes, its unit and default.


def _value(metadata: list[Any]) -> Any:
    """The format's Value in a field's metadata (anything with `allowed()`), or None."""
    return next((item for item in metadata if callable(getattr(item, "allowed", None))), None)


def _unit(value: Any) -> str:
    """A Value's unit, looking inside vectors, matrices and unions."""
    if value is None:
        return ""
    unit = getattr(value, "unit", None)
    if isinstance(unit, str):
        return unit
    for inner in ("item", "row", "first", "second"):
        found = _unit(getattr(value, inner, None))
        if found:
            return found
    return ""


def _toml(value: Any) -> str:
    """A default in TOML spelling."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return repr(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml(item) for item in value) + "]"
    return str(value)


def _extra(info: Any) -> dict[str, Any]:
    extra = info.json_schema_extra
    return extra if isinstance(extra, dict) else {}


def _takes(annotation: Any, metadata: list[Any], link: dict[type[BaseModel], str]) -> tuple[str, str]:
    """What a key takes (words) and its unit."""
    value = _value(metadata)
    if value is not None:
        return value.allowed(), _unit(value)
    base, inner_metadata = _unwrap(annotation)
    value = _value(inner_metadata)
    if value is not None:
        return value.allowed(), _unit(value)
    if typing.get_origin(base) is Literal:
        return " or ".join(f'"{option}"' for option in typing.get_args(base)), ""
    array = typing.get_origin(base) is list
    if array:
        base = typing.get_args(base)[0]
    words, units = [], []
    for member, member_metadata in _members(base):
        if _is_model(member):
            target = link.get(member, "")
            words.append(f"an array of tables {target}" if array else f"a table {target}")
        else:
            value = _value(member_metadata)
            words.append(value.allowed() if value is not None else getattr(member, "__name__", str(member)))
            units.append(_unit(value))
    unique = list(dict.fromkeys(words))
    return " or ".join(unique), next((unit for unit in units if unit), "")


# The transitional fallback: the reference tables of the pipelay.scenario docstring.


def docstring_reference() -> dict[str, tuple[str, dict[str, list[str]]]]:
    """Each table path's heading text and rows [unit, default, meaning] by key, from the reference tables in the
    docstrings of `pipelay.scenario` (and of the module `json_schema` is defined in); {} where there are none."""
    scenario = importlib.import_module("pipelay.scenario")
    docs = [scenario.__doc__ or ""]
    schema = getattr(scenario, "json_schema", None)
    if schema is not None and schema.__module__ in sys.modules:
        docs.append(sys.modules[schema.__module__].__doc__ or "")
    tables: dict[str, tuple[str, dict[str, list[str]]]] = {}
    for doc in docs:
        for block in re.split(r"^#{2,4} ", doc, flags=re.MULTILINE)[1:]:
            heading, _, body = block.partition("\n")
            names, _, about = heading.partition(" — ")
            rows = {}
            for line in body.splitlines():
                if line.startswith("| `"):
                    key, *cells = (cell.strip() for cell in line.strip().strip("|").split("|"))
                    rows[key.strip("`")] = cells
            paths = re.findall(r"`\[\[?([\w.]+)\]\]?`", names) or ([""] if "Top level" in heading else [])
            for path in paths:
                tables.setdefault(path, (about, {}))[1].update(rows)
    return tables


# Rendering.


def _anchor(path: str) -> str:
    return "top-level" if not path else path.replace(".", "-").replace("_", "-").lower()


def _heading(table: TableInfo) -> str:
    if table.paths == [""]:
        return "Top level"
    brackets = "[[{}]]" if table.array else "[{}]"
    return ", ".join(f"`{brackets.format(path)}`" for path in table.paths)


def _doc(model: type[BaseModel]) -> str:
    """A model's docstring, its first paragraph on one line."""
    text = (model.__doc__ or "").strip().split("\n\n")[0]
    return " ".join(text.split())


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _strip_tag(meaning: str, tag: str | None) -> str:
    """The fallback meaning without a leading `kind: ` that the variant's own section makes redundant."""
    if tag and meaning.startswith(f"{tag}: "):
        return meaning[len(tag) + 2 :]
    return meaning


@dataclass
class Report:
    """Fields without a description of their own (path.key), and those the fallback did not cover either."""

    undescribed: list[str] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)


def render(root: type[BaseModel] | None = None, report: Report | None = None) -> str:
    """The Markdown of the reference: one section per table, one row per key."""
    root = root or root_model()
    report = report if report is not None else Report()
    tables = walk(root)
    fallback = docstring_reference()
    link = {}
    documented: dict[str, str] = {}
    for table in tables:
        table.anchor = _anchor(table.paths[0])
        for variant in table.variants:
            link.setdefault(variant.model, f"[{_heading(table)}](#{table.anchor})")
        for path in table.paths:
            documented[path] = _doc(table.variants[0].model)
    out: list[str] = []
    for table in tables:
        path = table.paths[0]
        out.append(f"## {_heading(table)} {{#{table.anchor}}}\n")
        if table.array:
            out.append("An array of tables: each entry is one table with these keys.\n")
        if path in SEE_ALSO:
            page, title = SEE_ALSO[path]
            out.append(f"What it means and how it is used: [{title}]({page}).\n")
        several = len(table.variants) > 1
        if several:
            tags = ", ".join(
                f'`kind = "{item.tag}"`' if item.by_kind else f"*{item.tag}*" for item in table.variants
            )
            out.append(f"One of: {tags}.\n")
        for variant in table.variants:
            if several:
                label = f'`kind = "{variant.tag}"`' if variant.by_kind else str(variant.tag)
                out.append(f"### {_heading(table)}: {label}\n")
            if variant.model is not root and _doc(variant.model):
                out.append(_doc(variant.model) + "\n")
            out.append("| key | takes | unit | default | meaning |")
            out.append("| --- | --- | --- | --- | --- |")
            rows = fallback.get(path, ("", {}))[1]
            for name, info in variant.model.model_fields.items():
                key = info.alias or name
                takes, unit = _takes(info.annotation, list(info.metadata), link)
                extra = _extra(info)
                unit = str(extra.get("unit", unit))
                row = rows.get(key)
                meaning = info.description or ""
                where = f"{path}.{key}" if path else key
                if not meaning:
                    report.undescribed.append(where)
                    if key == "kind" and variant.by_kind:
                        meaning = "selects this kind's keys"
                    elif row is not None:
                        meaning = _strip_tag(row[2], variant.tag)
                    elif where in fallback and fallback[where][0]:
                        meaning = fallback[where][0]
                    elif where in documented:
                        meaning = documented[where]
                    else:
                        report.missing.append(where)
                if info.is_required():
                    default = "required"
                elif "default" in extra:
                    default = _toml(extra["default"])
                else:
                    given = info.get_default(call_default_factory=True)
                    if given is PydanticUndefined or isinstance(given, BaseModel):
                        default = "—"
                    elif given is None or given == []:
                        default = row[1] if row is not None else "none"
                        if default == "see below":  # the fallback's prose lives on the page linked above
                            default, meaning = "—", f"{meaning} (see the page linked above)"
                    else:
                        default = _toml(given)
                out.append(
                    f"| `{key}` | {_cell(takes)} | {_cell(unit) or '—'} | {_cell(default)} | {_cell(meaning)} |"
                )
            out.append("")
    return "\n".join(out)


def on_page_markdown(markdown: str, page: Any, config: Any, files: Any) -> str:
    """MkDocs event: the placeholder replaced by the generated reference."""
    if PLACEHOLDER not in markdown:
        return markdown
    return markdown.replace(PLACEHOLDER, render())


if __name__ == "__main__":
    found = Report()
    print(render(report=found))
    print(f"fields without a description: {len(found.undescribed)}", file=sys.stderr)
    print(f"  of which not in the docstring's reference either: {found.missing}", file=sys.stderr)
