"""The JSON Schema of scenario files (``pipelay.scenario.json_schema``): it accepts every example, refuses bad
files at the key at fault, and documents every key with its meaning, unit and default from the reference."""

from __future__ import annotations

import copy
import json
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import pytest
from jsonschema.exceptions import best_match
from pipelay.scenario import KEYS, json_schema

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCHEMA = json_schema()
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)


def test_schema_is_draft_2020_12() -> None:
    """The schema declares draft 2020-12 and is valid under its meta-schema; it is plain JSON."""
    assert SCHEMA["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    assert json.loads(json.dumps(SCHEMA)) == SCHEMA


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda path: path.name)
def test_schema_accepts_every_example(path: Path) -> None:
    """Every example scenario is valid under the schema."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    errors = [f"{list(error.absolute_path)}: {error.message}" for error in VALIDATOR.iter_errors(data)]
    assert not errors, errors


BASE = tomllib.loads((EXAMPLES / "j_lay_waves.toml").read_text(encoding="utf-8"))


def edited(table: tuple[str, ...], key: str, value: Any) -> dict[str, Any]:
    """The J-lay example with `key` of the table at `table` set to `value`."""
    data = copy.deepcopy(BASE)
    node = data
    for name in table:
        node = node[name]
    node[key] = value
    return data


@pytest.mark.parametrize(
    ("data", "path", "validator", "says"),
    [
        (edited(("pipe",), "outer_diamter", 0.6), ["pipe"], "additionalProperties", "outer_diamter"),
        (edited((), "seas", {"depth": 1.0}), [], "additionalProperties", "seas"),
        (edited(("pipe",), "outer_diameter", "abc"), ["pipe", "outer_diameter"], "type", "number"),
        (edited(("solver",), "record_every", 1.5), ["solver", "record_every"], "type", "integer"),
        (edited(("sea",), "depth", -800.0), ["sea", "depth"], "exclusiveMinimum", "-800"),
        (edited(("sea", "waves"), "hs", -1.0), ["sea", "waves", "hs"], "exclusiveMinimum", "-1"),
        (edited(("rod",), "elements", 0), ["rod", "elements"], "minimum", "0"),
        (edited(("pipe",), "drag", [0.0, 1.0, 2.0]), ["pipe", "drag"], "maxItems", "too long"),
        (edited(("solver",), "static_start", "fast"), ["solver", "static_start"], "enum", "'fast'"),
    ],
    ids=["unknown key", "unknown section", "text", "float", "depth", "hs", "elements", "drag", "word"],
)
def test_schema_refuses_bad_files_at_the_key(
    data: dict[str, Any], path: list[str], validator: str, says: str
) -> None:
    """An unknown key, a value of the wrong type or out of range: the schema's best error names the path."""
    error = best_match(VALIDATOR.iter_errors(data))
    assert error is not None
    assert (list(error.absolute_path), error.validator) == (path, validator), error.message
    assert says in error.message


def tables(schema: dict[str, Any]) -> Iterator[tuple[str, dict[str, Any]]]:
    """Every table's schema (the top level and each definition) with its name."""
    yield "", schema
    yield from schema["$defs"].items()


def test_every_key_is_in_the_schema_with_a_description() -> None:
    """Each key of every table is a property of one of the schema's tables, and every property has a
    description; descriptions carry the unit, defaults are TOML values of the reference."""
    properties = {key for _, table in tables(SCHEMA) for key in table.get("properties", {})}
    assert {key for keys in KEYS.values() for key in keys} <= properties
    for name, table in tables(SCHEMA):
        for key, schema in table.get("properties", {}).items():
            assert schema.get("description"), (name, key)
    pipe = SCHEMA["$defs"]["Pipe"]["properties"]
    assert pipe["density"]["default"] == 7850 and "(kg/m³; default 7850)" in pipe["density"]["description"]
    assert "(m; required)" in pipe["outer_diameter"]["description"]
    waves = SCHEMA["$defs"]["JonswapWaves"]["properties"]
    assert waves["gamma"]["default"] == 3.3 and waves["components"]["maximum"] == 100_000
    assert "default" not in waves["spreading"] and "default" not in waves["ramp"]
    assert SCHEMA["$defs"]["PayOut"]["properties"]["end"]["default"] == "B"
    assert "waves" in SCHEMA["$defs"]["Sea"]["properties"]["waves"]["description"].lower()


def test_schema_has_no_null() -> None:
    """TOML has no null: absent keys are not written as `null` branches or defaults."""
    text = json.dumps(SCHEMA)
    assert '"null"' not in text and "null" not in text
