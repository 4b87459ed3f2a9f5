"""The frame of pipelay's HTML reports: one self-contained page (no file or network access when it is opened),
its sections, tables whose cells carry ids and data attributes, figures embedded as base64 PNG, numbers
printed one way, text escaped with `html.escape`, and the page written atomically.

* `page(title, body, head=...)`: the whole document (``<!DOCTYPE html>``, ``<meta charset="utf-8">``, a
  ``<title>``, the style sheet);
* `section`, `subsection`, `details`, `paragraph`, `preformatted`, `definitions`, `table` (of `Cell` or plain
  values; `value_cell` prints a number and keeps it exactly in ``data-value``), `figure` (a matplotlib figure as
  an ``<img>`` of a ``data:image/png;base64`` URL), `gallery` (figures side by side), `link`, `note`;
* `plotly_script()`: plotly.js for the page's head, once, for the plotly ``<div>`` s in the page;
* `number(value)`: how a report prints a number (``"—"`` for NaN or None);
* `Markup`: text that is already HTML (everything else is escaped);
* `write(path, text)`: the page written to a temporary file in the same folder, then renamed into place.

Imports of pipelay: `pipelay.results.atomic` (the atomic write); of the rest, plotly (`plotly_script`).
"""

from __future__ import annotations

import base64
import html
import math
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from io import BytesIO
from pathlib import Path
from typing import Any

from pipelay.results.atomic import _atomic_write

__all__ = [
    "DPI",
    "Cell",
    "Markup",
    "definitions",
    "details",
    "escape",
    "figure",
    "gallery",
    "link",
    "note",
    "number",
    "page",
    "paragraph",
    "plotly_script",
    "preformatted",
    "section",
    "subsection",
    "table",
    "value_cell",
    "write",
]

DPI = 100
"""Resolution of the figures embedded in a report (dots per inch)."""

STYLE = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 1.5em auto;
       max-width: 1200px; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; border-bottom: 2px solid #446; padding-bottom: 0.2em; }
h2 { font-size: 1.3em; margin-top: 1.8em; border-bottom: 1px solid #bbb; }
h3 { font-size: 1.05em; }
table { border-collapse: collapse; margin: 0.6em 0 1em; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: left; vertical-align: top; }
td.number { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
th { background: #eef; }
caption { caption-side: top; text-align: left; font-weight: 600; padding: 0.2em 0; }
figure.plot { margin: 1em 0; }
figure.plot img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.85em; color: #555; }
pre { background: #f6f6f6; padding: 0.8em; overflow-x: auto; font-size: 0.85em; }
details summary { cursor: pointer; font-weight: 600; }
dl.facts { display: grid; grid-template-columns: max-content auto; gap: 0.15em 1.2em; }
dl.facts dt { font-weight: 600; }
dl.facts dd { margin: 0; }
p.note { color: #664; background: #ffd; padding: 0.4em 0.8em; border-left: 3px solid #cc9; }
tr.failed td { color: #900; }
div.scroll { overflow-x: auto; max-width: 100%; }
div.gallery { display: flex; flex-wrap: wrap; gap: 0 1.5em; }
div.gallery figure.plot { max-width: 560px; }
"""


class Markup(str):
    """Text that is already HTML: `table`, `section` and the others insert it as it is (any other text is
    escaped)."""

    __slots__ = ()


def escape(text: Any) -> Markup:
    """`text` (anything, as ``str(text)``) with ``& < > " '`` escaped for HTML text and attribute values;
    `Markup` as it is."""
    if isinstance(text, Markup):
        return text
    return Markup(html.escape(str(text), quote=True))


def number(value: Any, digits: int = 6) -> str:
    """How a report prints a number: an int as it is, a float to `digits` significant digits (``%g``), ``"—"``
    for None or NaN, anything else as ``str``."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    try:
        real = float(value)
    except (TypeError, ValueError):
        return str(value)
    if math.isnan(real):
        return "—"
    if float(real).is_integer() and abs(real) < 1e15 and not isinstance(value, float):
        return str(int(real))  # a numpy integer
    return f"{real:.{digits}g}"


@dataclass(frozen=True)
class Cell:
    """A table cell: its text (escaped unless `Markup`) and attributes.

    Attributes
    ----------
    text : str
        What the cell shows.
    id : str or None
        The cell's ``id`` (unique in the page).
    data : mapping of str to str
        ``data-<key>`` attributes, e.g. ``{"value": repr(x)}``: the exact number behind the printed one.
    numeric : bool
        Right-aligned, tabular digits.
    header : bool
        A ``<th>`` (a row's label) instead of a ``<td>``.
    """

    text: str
    id: str | None = None
    data: Mapping[str, str] = field(default_factory=dict)
    numeric: bool = False
    header: bool = False


def value_cell(value: Any, *, id: str | None = None, digits: int = 6) -> Cell:
    """A numeric cell printing `value` with `number`, its exact value (``repr(float(value))``) in
    ``data-value`` (``"nan"`` for None)."""
    exact = "nan" if value is None else repr(float(value))
    return Cell(number(value, digits), id=id, data={"value": exact}, numeric=True)


def _attributes(attributes: Mapping[str, Any]) -> str:
    """` key="value"` for each attribute that is not None."""
    return "".join(f' {key}="{escape(value)}"' for key, value in attributes.items() if value is not None)


def _cell(value: Any, tag: str) -> str:
    if not isinstance(value, Cell):
        value = Cell(value if isinstance(value, str) else number(value), numeric=not isinstance(value, str))
    tag = "th" if value.header else tag
    attributes: dict[str, Any] = {"id": value.id, "class": "number" if value.numeric else None}
    attributes |= {f"data-{key}": text for key, text in value.data.items()}
    return f"<{tag}{_attributes(attributes)}>{escape(value.text)}</{tag}>"


def table(
    header: Sequence[Any],
    rows: Iterable[Sequence[Any]],
    *,
    id: str | None = None,
    caption: str | None = None,
    row_classes: Sequence[str | None] | None = None,
) -> Markup:
    """A ``<table>``: a header row of `header` and a row per entry of `rows`; a cell is a `Cell`, a string
    (escaped unless `Markup`) or a number (printed with `number`).

    Parameters
    ----------
    header : sequence
        The column headings.
    rows : iterable of sequences
        The rows' cells.
    id : str or None
        The table's ``id``.
    caption : str or None
        A caption above the table.
    row_classes : sequence of str or None
        A ``class`` for each row (None: none).
    """
    lines = [f'<div class="scroll"><table{_attributes({"id": id})}>']
    if caption:
        lines.append(f"<caption>{escape(caption)}</caption>")
    lines.append(
        "<thead><tr>" + "".join(_cell(Cell(str(h), header=True), "th") for h in header) + "</tr></thead>"
    )
    lines.append("<tbody>")
    for k, row in enumerate(rows):
        kind = row_classes[k] if row_classes is not None else None
        lines.append(f"<tr{_attributes({'class': kind})}>" + "".join(_cell(c, "td") for c in row) + "</tr>")
    lines.append("</tbody></table></div>")
    return Markup("\n".join(lines))


def figure(chart: Any, *, name: str, caption: str | None = None, dpi: int = DPI) -> Markup:
    """A matplotlib figure as a ``<figure class="plot" data-name=name>`` holding an ``<img>`` of its PNG
    (at `dpi`) in a base64 ``data:`` URL, with an optional caption."""
    buffer = BytesIO()
    chart.savefig(buffer, format="png", dpi=dpi)
    encoded = base64.b64encode(buffer.getvalue()).decode("ascii")
    label = caption or name
    text = f"<figcaption>{escape(caption)}</figcaption>" if caption else ""
    return Markup(
        f'<figure class="plot" data-name="{escape(name)}">'
        f'<img src="data:image/png;base64,{encoded}" alt="{escape(label)}">{text}</figure>'
    )


def gallery(parts: Sequence[str]) -> Markup:
    """`parts` (figures) side by side as the page's width allows, in a ``<div class="gallery">``."""
    return Markup('<div class="gallery">\n' + "\n".join(escape(part) for part in parts) + "\n</div>")


def section(id: str, heading: str, *parts: str) -> Markup:
    """A ``<section id=id>`` with an ``<h2>`` `heading` and `parts` (escaped unless `Markup`) in order."""
    body = "\n".join(escape(part) for part in parts)
    return Markup(f'<section id="{escape(id)}">\n<h2>{escape(heading)}</h2>\n{body}\n</section>')


def subsection(heading: str, *parts: str) -> Markup:
    """An ``<h3>`` `heading` followed by `parts`."""
    return Markup("\n".join([f"<h3>{escape(heading)}</h3>", *(escape(part) for part in parts)]))


def paragraph(text: str) -> Markup:
    """A ``<p>`` of `text` (escaped unless `Markup`)."""
    return Markup(f"<p>{escape(text)}</p>")


def note(text: str, *, kind: str = "note") -> Markup:
    """A highlighted ``<p class="note">`` of `text`, with ``data-kind`` `kind` (e.g. ``"skipped"``)."""
    return Markup(f'<p class="note" data-kind="{escape(kind)}">{escape(text)}</p>')


def details(summary: str, body: str, *, open: bool = False) -> Markup:
    """A collapsible ``<details>`` block: `summary` shown, `body` (escaped unless `Markup`) on a click."""
    return Markup(
        f"<details{' open' if open else ''}><summary>{escape(summary)}</summary>\n{escape(body)}\n</details>"
    )


def preformatted(text: str, *, id: str | None = None) -> Markup:
    """A ``<pre>`` block of `text` (escaped)."""
    return Markup(f"<pre{_attributes({'id': id})}>{escape(text)}</pre>")


def definitions(items: Iterable[tuple[str, Any]], *, id: str | None = None) -> Markup:
    """A ``<dl class="facts">`` of (term, description) pairs; a description is escaped unless `Markup`, a
    number printed with `number`."""
    lines = [f'<dl class="facts"{_attributes({"id": id})}>']
    for term, description in items:
        text = description if isinstance(description, str) else number(description)
        lines.append(f"<dt>{escape(term)}</dt><dd>{escape(text)}</dd>")
    lines.append("</dl>")
    return Markup("\n".join(lines))


def link(href: str, text: str) -> Markup:
    """An ``<a href=href>`` of `text` (both escaped)."""
    return Markup(f'<a href="{escape(href)}">{escape(text)}</a>')


def plotly_script() -> Markup:
    """plotly.js (``plotly.offline.get_plotlyjs``, about 5 MB) in a ``<script>``, for a page's head: the
    plots of ``plotly`` ``<div>`` s made without it (``include_plotlyjs=False``) then draw offline."""
    from plotly.offline import get_plotlyjs

    return Markup(
        "<script>window.PlotlyConfig = {MathJaxConfig: 'local'};</script>\n"
        f"<script>{get_plotlyjs()}</script>"
    )


def page(title: str, body: Sequence[str], *, head: str = "") -> str:
    """The whole HTML document: ``<!DOCTYPE html>``, ``<html lang="en">``, a ``<head>`` with
    ``<meta charset="utf-8">``, the ``<title>`` `title`, the style sheet and `head` (Markup, e.g. a
    ``<script>``), and a ``<body>`` with an ``<h1>`` `title` followed by `body`'s parts."""
    parts = "\n".join(escape(part) for part in body)
    return (
        "<!DOCTYPE html>\n"
        '<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>{escape(title)}</title>\n<style>{STYLE}</style>\n{head}\n</head>\n"
        f"<body>\n<h1>{escape(title)}</h1>\n{parts}\n</body>\n</html>\n"
    )


def write(path: str | os.PathLike[str], text: str) -> Path:
    """Writes `text` (UTF-8) to `path` atomically (a temporary file in the same folder, then renamed; the
    folder is created if missing), readable by all as a file written with the process's umask; returns the
    path."""
    target = Path(path)

    def put(temporary: Path) -> None:
        temporary.write_text(text, encoding="utf-8")
        mask = os.umask(0)
        os.umask(mask)
        temporary.chmod(0o666 & ~mask)

    _atomic_write(target, put)
    return target
