"""MkDocs hook: the scenario reference, rendered at build time from the scenario format's pydantic models.

A page that holds the line ``<!-- scenario-reference -->`` gets it replaced by one section per TOML table
(``[pipe]``, ``[sea.current]``, ...): what the table is, then its keys, what each takes (with units), its
default and its meaning, one table of keys per kind where the keys depend on ``kind``.

What the page says comes from ``pipelay.scenario.schema.reference_tables()``, which reads the models: the
keys, kinds and defaults from their fields, what a key takes and its unit from the field's ``Value``, its
meaning from its ``description``, a default the API call supplies from ``api(...)``, what a table is from its
model's docstring (or the ``About`` of its union). The JSON Schema of ``pipelay schema`` is made from the same
reference. This hook only writes Markdown, and links each table to the page that explains it (``SEE_ALSO``).

Run ``python docs/hooks/scenario_reference.py`` to print the generated Markdown, and on standard error the
tables and keys that have no description.
"""

from __future__ import annotations

import sys
from typing import Any

from pipelay.scenario.schema import KeyRow, ReferenceTable, reference_tables

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
    "sea.wind": ("dp.md#wind-current-and-wave-drift-on-the-hull", "DP: wind, current and wave drift"),
    "supports.A": ("statics.md#supports", "Statics: supports"),
    "point_loads": ("statics.md#loads-sea-and-current", "Statics: loads"),
    "vessel": ("vessel-and-dp.md", "Vessel and DP"),
    "vessel.thrusters": ("dp.md#thrusters", "DP: thrusters"),
    "vessel.lay": ("lay-equipment.md", "Lay equipment and checks"),
    "vessel.lay.stinger": ("lay-equipment.md#rollers-and-the-stinger", "Lay equipment: rollers"),
    "controller": ("vessel-and-dp.md#dp-control", "Vessel and DP: control"),
    "controller.route": ("vessel-and-dp.md#following-a-lay-route", "Vessel and DP: lay route"),
    "controller.tension": ("vessel-and-dp.md#holding-the-lay-tension", "Vessel and DP: lay tension"),
    "controller.observer": ("dp.md#the-observer", "DP: the observer"),
    "pay_out": ("pay-out.md#in-a-scenario-file", "Pay-out"),
    "environment": ("vessel-and-dp.md#environmental-forces", "Vessel and DP: environmental forces"),
    "solver": ("scenario-files.md#solver-settings", "Scenario files: solver settings"),
}
"""The capability page that explains a table (by its first path)."""


def _anchor(path: str) -> str:
    return "top-level" if not path else path.replace(".", "-").replace("_", "-").lower()


def _heading(table: ReferenceTable) -> str:
    if table.paths == ("",):
        return "Top level"
    brackets = "[[{}]]" if table.array else "[{}]"
    return ", ".join(f"`{brackets.format(path)}`" for path in table.paths)


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _takes(row: KeyRow, links: dict[str, str]) -> str:
    """What a key takes: its values' words, or (and) a link to the table it holds."""
    words = [row.takes] if row.takes else []
    if row.table:
        words.append(f"{'an array of tables' if row.array else 'a table'} {links[row.table]}")
    return " or ".join(words)


def render(tables: tuple[ReferenceTable, ...] | None = None) -> str:
    """The Markdown of the reference: one section per table, one row per key."""
    tables = reference_tables() if tables is None else tables
    links = {table.paths[0]: f"[{_heading(table)}](#{_anchor(table.paths[0])})" for table in tables}
    out: list[str] = []
    for table in tables:
        path = table.paths[0]
        out.append(f"## {_heading(table)} {{#{_anchor(path)}}}\n")
        if table.array:
            out.append("An array of tables: each entry is one table with these keys.\n")
        if path in SEE_ALSO:
            page, title = SEE_ALSO[path]
            out.append(f"What it means and how it is used: [{title}]({page}).\n")
        if table.description:
            out.append(f"{table.description}.\n")
        out.extend(f"{note}\n" for note in table.notes)
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
            out.extend(f"{note}\n" for note in variant.notes)
            out.append("| key | takes | unit | default | meaning |")
            out.append("| --- | --- | --- | --- | --- |")
            for row in variant.rows:
                cells = (_takes(row, links), row.unit or "—", row.default, row.meaning)
                out.append(f"| `{row.key}` | " + " | ".join(_cell(cell) for cell in cells) + " |")
            out.append("")
    return "\n".join(out)


def on_page_markdown(markdown: str, page: Any, config: Any, files: Any) -> str:
    """MkDocs event: the placeholder replaced by the generated reference."""
    if PLACEHOLDER not in markdown:
        return markdown
    return markdown.replace(PLACEHOLDER, render())


if __name__ == "__main__":
    found = reference_tables()
    print(render(found))
    undescribed = [_heading(table) for table in found if not table.description]
    meaningless = [
        f"{table.paths[0]}.{row.key}".lstrip(".")
        for table in found
        for variant in table.variants
        for row in variant.rows
        if not row.meaning
    ]
    print(f"tables without a description: {undescribed}", file=sys.stderr)
    print(f"keys without a meaning: {sorted(set(meaningless))}", file=sys.stderr)
