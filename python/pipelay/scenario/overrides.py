"""Overrides of a scenario's keys, for parameter sweeps: dotted keys (`"sea.waves.hs"`,
`"point_loads[0].force"`) checked against the format with the values to try (`validate_overrides`), and set in
a parsed document (`apply_overrides`).

Imports of pipelay: the package (`pl.InputError`), `pipelay.scenario.values`, `pipelay.scenario.schema` and
`pipelay.scenario.checking`.
"""

from __future__ import annotations

import copy
import itertools
import os
import re
from pathlib import Path
from typing import Any

import pipelay as pl
from pipelay.scenario.checking import _check, _errors, _folder
from pipelay.scenario.schema import KEYS
from pipelay.scenario.values import join, show, suggest

__all__ = ["apply_overrides", "validate_overrides"]

_NAME = re.compile(r"([A-Za-z_]\w*)((?:\[\d+\])*)")


def _dotted(key: str) -> list[str | int]:
    """`sea.waves.hs` as ["sea", "waves", "hs"], `point_loads[0].force` as ["point_loads", 0, "force"]."""
    parts: list[str | int] = []
    for name in key.split("."):
        found = _NAME.fullmatch(name)
        if found is None:
            raise pl.InputError(f"{key}: not a dotted key (key names joined by '.', entries as name[i])")
        parts.append(found.group(1))
        parts.extend(int(index) for index in re.findall(r"\d+", found.group(2)))
    return parts


def _check_key(key: str) -> None:
    """A dotted key names a key of the format."""
    table = ""
    for name in (part for part in _dotted(key) if isinstance(part, str)):
        if table not in KEYS:
            raise pl.InputError(f"{key}: {table} is a value, not a table")
        if name not in KEYS[table]:
            raise pl.InputError(
                f"{key}: {join(table, name)} is not a key of the format{suggest(name, KEYS[table])}"
            )
        table = join(table, name)


def _child(node: object, part: str | int, key: str) -> Any:
    """The table or entry `part` of `node` on the way to `key` (a missing table is created)."""
    if isinstance(part, str) and isinstance(node, dict):
        return node.setdefault(part, {})
    if isinstance(part, int) and isinstance(node, list) and -len(node) <= part < len(node):
        return node[part]
    raise pl.InputError(f"{key}: no table or entry {part!r} on the way in the scenario, got {show(node)}")


def apply_overrides(data: dict[str, Any], case: dict[str, Any]) -> dict[str, Any]:
    """A deep copy of the parsed document `data` with each dotted key of `case` (`"sea.waves.hs"`,
    `"point_loads[0].force"`) set to its value, creating missing tables; `data` is left as it is.

    Raises pl.InputError naming the key if its way goes through a value or a missing entry of an array.
    """
    result = copy.deepcopy(data)
    for key, value in case.items():
        *way, last = _dotted(key)
        node: Any = result
        for part in way:
            node = _child(node, part, key)
        if isinstance(last, int):
            _child(node, last, key)  # the entry must exist
        elif not isinstance(node, dict):
            raise pl.InputError(f"{key}: no table to set {last!r} in, got {show(node)}")
        node[last] = copy.deepcopy(value)
    return result


def _check_case(data: dict[str, Any], case: dict[str, Any], folder: Path) -> None:
    """`data` with the case's keys set is a valid document: an error about one of its keys first, an error
    elsewhere said to come from the case's values."""
    messages = _errors(apply_overrides(data, case), folder)
    prefixes = tuple(f"{key}{end}" for key in case for end in (":", ".", "["))
    about = [message for message in messages if message.startswith(prefixes)]
    if about:
        raise pl.InputError(about[0])
    if messages:
        values = ", ".join(f"{key} = {show(value)}" for key, value in case.items())
        raise pl.InputError(f"{values}: {messages[0]}")


def validate_overrides(
    data: dict[str, Any],
    overrides: dict[str, list[Any]],
    origin: str = "<sweep>",
    folder: str | os.PathLike[str] | None = None,
) -> None:
    """Check a parameter sweep before any case runs: each dotted key of `overrides` (`"sea.waves.hs"`,
    `"controller.kp"`, `"point_loads[0].force"`) names a key of the format, and every case (one value of each
    key), put in the parsed document `data` (itself valid), makes a valid document: keys that depend on each
    other (`solver.t_end` and `output.plot_times`) are judged together.

    Only the keys are checked, nothing is built (the engine's own checks, e.g. a matrix's symmetry, come when
    a case runs). `folder` is as for `parse_scenario`. Raises pl.InputError naming the dotted key, the bad
    value and what is allowed, ending with `(in origin)`.
    """
    where = _folder(origin, folder)
    try:
        for key, values in overrides.items():
            _check_key(key)
            if not isinstance(values, list) or not values:
                raise pl.InputError(f"{key}: must be a non-empty list of values, got {show(values)}")
        _check(data, where)
        for values in itertools.product(*overrides.values()):
            _check_case(data, dict(zip(overrides, values, strict=True)), where)
    except pl.InputError as error:
        raise pl.InputError(f"{error} (in {origin})") from None
