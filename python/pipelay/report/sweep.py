"""The HTML report of a sweep (`sweep_report`): one self-contained page for the output folder of `pipelay.sweep`
(its ``summary.nc`` and ``cases/``), with the replays of the worst cases written beside their results.

```python
from pipelay.report import sweep_report

sweep_report("lay-sweep")                   # → lay-sweep/report.html, and lay-sweep/cases/<name>.html replays
```

Sections (their ``id`` in the page): ``sweep`` (the scenario's source, the swept keys and their values, the
counts of cases, finished and failed), ``failures`` (each failed case with its message), ``operability`` (a map
of every statistic that has values, `pipelay.plots.operability`, over the first two swept keys; a line of it
against the key for a sweep over one key), ``worst`` (for each of ``utilisation_max``, ``top_tension_max`` and
``strain_max`` the summary has, the cases ranked from the largest, with a link to the replay of each of the
`replays` worst), ``cases`` (the summary: every case's values and statistics). A replay is
``cases/<name>.html``, `pipelay.plots.replay.replay_html` of the case's results (a page of its own), linked
relatively, so the folder can be moved whole.

Statistics are shown by their labels, in the units people read (kN, kN·m, percent: `pipelay.report.units`);
each cell keeps the statistic's SI value exactly in ``data-value`` and names its SI unit in ``data-unit``, and
its ``id`` names the statistic (``case-<k>-<name>``, ``worst-<by>-<rank>-<name>``).

Imports of pipelay: the engine (`pipelay._core`, its InputError), `pipelay.results` (`load`),
`pipelay.analysis.sweep` (`STATISTICS`), `pipelay.plots` (`operability`), `pipelay.report.html`,
`pipelay.report.units`,
`pipelay.scenario` (`scenario_of_results`) and, when replays are written, `pipelay.plots.replay`.
"""

from __future__ import annotations

import json
import os
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import quote

import numpy as np

from pipelay._core import InputError
from pipelay.analysis.sweep import STATISTICS
from pipelay.report import html
from pipelay.report.html import Cell, Markup
from pipelay.report.units import Quantity, quantity
from pipelay.results import load
from pipelay.scenario import scenario_of_results

__all__ = ["WORST", "sweep_report"]

WORST = ("utilisation_max", "top_tension_max", "strain_max")
"""The statistics the worst cases are ranked by (largest first), those of them the summary has."""

SHOWN = 10
"""Most rows of a worst-case table (at least `replays`)."""


@dataclass(frozen=True)
class _Case:
    """One case of the summary: its index in the grid, its values (as text), name, failure and statistics."""

    index: tuple[int, ...]
    values: tuple[str, ...]
    name: str
    failed: bool
    error: str
    statistics: dict[str, float]


def sweep_report(
    folder: str | os.PathLike[str], path: str | os.PathLike[str] | None = None, *, replays: int = 3
) -> Path:
    """Writes the HTML report of a sweep's output folder to `path` (atomically) and the replays of its
    `replays` worst cases (by each statistic of `WORST`) as ``folder/cases/<name>.html``; returns the path.

    Parameters
    ----------
    folder : path
        The output folder of `pipelay.sweep` (``summary.nc``, ``cases/``).
    path : path or None
        The report's file; None: ``folder/report.html``.
    replays : int
        The number of worst cases, by each statistic of `WORST`, whose replay is written and linked (≥ 0;
        the same case counts once). Each replay is a page with plotly.js (about 5 MB).

    Returns
    -------
    pathlib.Path
        The report's path.

    Raises
    ------
    pipelay.InputError
        If `folder` has no ``summary.nc`` (naming `folder`), or `replays` is not a whole number ≥ 0.
    """
    import xarray as xr

    directory = Path(folder)
    file = directory / "summary.nc"
    if not file.is_file():
        raise InputError(
            f"folder: no summary.nc in {str(directory)!r}; give the output folder of pl.sweep (summary.nc, cases/)"
        )
    if isinstance(replays, bool) or not isinstance(replays, (int, np.integer)) or replays < 0:
        raise InputError(
            f"replays: the number of worst cases to replay, a whole number >= 0, got {replays!r}"
        )
    target = Path(path) if path is not None else directory / "report.html"
    with xr.open_dataset(file, engine="h5netcdf") as opened:
        summary = opened.load()
    keys = _swept_keys(summary)
    cases = _cases(summary, keys)
    statistics = [
        name for name in STATISTICS if name in summary.data_vars and np.isfinite(summary[name].values).any()
    ]
    ranked = {name: _ranked(cases, name) for name in WORST if name in statistics}
    chosen = list(dict.fromkeys(case.name for order in ranked.values() for case in order[:replays]))
    links, said = _write_replays(directory, target.parent, chosen)

    title = f"pipelay sweep report: {summary.attrs.get('source', directory.name)}"
    body = [
        _overview(summary, keys, cases, directory),
        _failures(cases, keys),
        _operability(summary, keys, statistics),
        _worst(ranked, keys, links, replays, said),
        _all_cases(summary, cases, keys, statistics, links),
    ]
    return html.write(target, html.page(title, body))


def _swept_keys(summary: Any) -> list[str]:
    """The swept keys, in order: the summary's ``swept_keys`` attribute, else the dimensions of ``failed``."""
    text = summary.attrs.get("swept_keys")
    if text:
        try:
            keys = json.loads(text)
        except (TypeError, ValueError):
            keys = None
        if isinstance(keys, list) and all(key in summary.dims for key in keys):
            return [str(key) for key in keys]
    reference = summary["failed"] if "failed" in summary else next(iter(summary.data_vars.values()))
    return [str(dim) for dim in reference.dims]


def _label(value: Any) -> str:
    """A coordinate value as text."""
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, (float, np.floating)):
        return html.number(float(value), 10)
    return str(value)


def _cases(summary: Any, keys: Sequence[str]) -> list[_Case]:
    """Every case of the summary's grid, in the order of its dimensions."""
    shape = tuple(summary.sizes[key] for key in keys)

    def grid(name: str, fill: Any) -> np.ndarray:
        if name not in summary:
            return np.full(shape, fill, dtype=object)
        return np.asarray(summary[name].transpose(*keys).values)

    names, failed, errors = grid("case", ""), grid("failed", 0), grid("error", "")
    columns = {name: grid(name, np.nan) for name in STATISTICS if name in summary.data_vars}
    cases = []
    for index in np.ndindex(*shape):
        values = tuple(_label(summary[key].values[i]) for key, i in zip(keys, index, strict=True))
        cases.append(
            _Case(
                index=index,
                values=values,
                name=_label(names[index]),
                failed=bool(int(failed[index])),
                error=_label(errors[index]) if errors[index] is not None else "",
                statistics={name: float(column[index]) for name, column in columns.items()},
            )
        )
    return cases


def _ranked(cases: Sequence[_Case], name: str) -> list[_Case]:
    """The cases with a finite `name`, largest first (ties in the grid's order)."""
    finite = [case for case in cases if np.isfinite(case.statistics.get(name, np.nan))]
    return sorted(finite, key=lambda case: -case.statistics[name])


def _write_replays(directory: Path, home: Path, names: Sequence[str]) -> tuple[dict[str, str], str]:
    """Writes ``cases/<name>.html``, the replay of each case of `names`; returns {name: link relative to the
    report's folder `home`} of those written, and a sentence on any not written."""
    if not names:
        return {}, ""
    from pipelay.plots.replay import replay_html  # imports plotly: only when replays are written

    links: dict[str, str] = {}
    missing = []
    for name in names:
        results_file = directory / "cases" / f"{name}.nc"
        if not results_file.is_file():
            missing.append(f"{name} (no results file)")
            continue
        try:
            text = replay_html(load(results_file), _stored_model(results_file), full_html=True, title=name)
        except Exception as error:  # noqa: BLE001 - the report is written without this replay
            warnings.warn(
                f"sweep_report: replay of {name} not written: {error}", RuntimeWarning, stacklevel=3
            )
            missing.append(f"{name} ({type(error).__name__}: {error})")
            continue
        replay = html.write(directory / "cases" / f"{name}.html", text)
        relative = os.path.relpath(replay.absolute(), home.absolute())
        links[name] = quote(Path(relative).as_posix(), safe="/=+-_.")
    return links, ("replays not written: " + "; ".join(missing)) if missing else ""


def _stored_model(file: Path) -> Any:
    """The model of the scenario stored in a case's results file, or None."""
    try:
        scenario = scenario_of_results(file)
    except InputError:
        return None
    return None if scenario is None else scenario.model


# --- sections --------------------------------------------------------------------------------------------


def _overview(summary: Any, keys: Sequence[str], cases: Sequence[_Case], directory: Path) -> Markup:
    finished = sum(
        not case.failed and any(np.isfinite(v) for v in case.statistics.values()) for case in cases
    )
    failed = sum(case.failed for case in cases)
    facts: list[tuple[str, Any]] = [
        ("scenario", str(summary.attrs.get("source", "not recorded"))),
        ("folder", str(directory)),
        ("summary written", str(summary.attrs.get("created", "not recorded"))),
    ]
    if "utilisation_max" in summary and summary["utilisation_max"].attrs.get("checks"):
        facts.append(("utilisation's basis", str(summary["utilisation_max"].attrs["checks"])))
    counts = [
        ["cases", Cell(str(len(cases)), id="count-cases", numeric=True)],
        ["finished", Cell(str(finished), id="count-finished", numeric=True)],
        ["failed", Cell(str(failed), id="count-failed", numeric=True)],
        ["not run", Cell(str(len(cases) - finished - failed), id="count-not-run", numeric=True)],
    ]
    rows = []
    for key in keys:
        unit = summary[key].attrs.get("units", "")
        values = ", ".join(_label(value) for value in summary[key].values)
        rows.append([Cell(key, header=True), unit or "—", values])
    return html.section(
        "sweep",
        "The sweep",
        html.definitions(facts, id="sweep-facts"),
        html.table(["swept key", "unit", "values"], rows, id="keys"),
        html.table(["", "count"], counts, id="counts"),
    )


def _failures(cases: Sequence[_Case], keys: Sequence[str]) -> Markup:
    failed = [case for case in cases if case.failed]
    if not failed:
        return html.section("failures", "Failures", html.paragraph("No case failed."))
    rows = [
        [*case.values, Cell(case.name, id=f"failure-{k}"), Cell(case.error, id=f"failure-{k}-error")]
        for k, case in enumerate(failed)
    ]
    return html.section(
        "failures",
        "Failures",
        html.paragraph(f"{len(failed)} of {len(cases)} cases failed; their messages:"),
        html.table([*keys, "case", "error"], rows, id="failure-list"),
    )


def _operability(summary: Any, keys: Sequence[str], statistics: Sequence[str]) -> Markup:
    from pipelay import plots

    if not statistics:
        return html.section(
            "operability", "Operability", html.note("no statistic has a value: no case finished")
        )
    parts: list[str] = []
    for name in statistics:
        draw: Callable[[], Any]
        if len(keys) >= 2:
            caption = f"{_statistic(summary, name).label} ({name}) over {keys[0]} and {keys[1]}"

            def draw(name: str = name) -> Any:
                return plots.operability(summary, name, x=keys[0], y=keys[1])
        else:
            caption = f"{_statistic(summary, name).label} ({name}) against {keys[0]}"

            def draw(name: str = name) -> Any:
                return _line(summary, name, keys[0])

        try:
            chart = draw()
        except Exception as error:  # noqa: BLE001 - one map that cannot be drawn does not stop the report
            warnings.warn(f"sweep_report: map of {name} not drawn: {error}", RuntimeWarning, stacklevel=3)
            parts.append(
                html.note(f"map of {name} not drawn: {type(error).__name__}: {error}", kind="skipped")
            )
            continue
        parts.append(html.figure(chart, name=f"operability-{name}", caption=caption))
    intro = (
        "One map per statistic with values; failed cases are hatched."
        if len(keys) >= 2
        else "One line per statistic with values; failed cases are marked × on the axis."
    )
    if len(keys) > 2:
        intro += f" One panel per value of {', '.join(keys[2:])}."
    return html.section("operability", "Operability", html.paragraph(intro), html.gallery(parts))


def _line(summary: Any, name: str, key: str) -> Any:
    """A statistic of a one-key sweep against its key, failed cases marked; on an Agg canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    chart = Figure(figsize=(8.0, 4.0), layout="constrained")
    FigureCanvasAgg(chart)
    axis = chart.subplots()
    coordinate = summary[key].values
    numeric = coordinate.dtype.kind in "iuf"
    x = coordinate.astype(np.float64) if numeric else np.arange(len(coordinate), dtype=np.float64)
    order = np.argsort(x)
    shown = _statistic(summary, name)
    values = np.asarray(summary[name].values, dtype=np.float64) * shown.scale
    axis.plot(x[order], values[order], "o-", color="k")
    if "failed" in summary:
        failed = np.asarray(summary["failed"].values).astype(bool)
        if failed.any():
            axis.plot(
                x[failed],
                np.zeros(int(failed.sum())),
                "x",
                color="tab:red",
                markersize=10,
                transform=axis.get_xaxis_transform(),
                clip_on=False,
                label="failed",
            )
            axis.legend(fontsize=8)
    if not numeric:
        axis.set_xticks(x, [str(value) for value in coordinate], fontsize=8)
    unit = summary[key].attrs.get("units", "")
    axis.set_xlabel(f"{key} ({unit})" if unit else key)
    axis.set_ylabel(shown.heading)
    axis.set_title(f"{shown.label} ({name})", fontsize=10)
    axis.grid(alpha=0.3)
    return chart


def _statistic(summary: Any, name: str) -> Quantity:
    """How the statistic `name` of the summary is shown (its SI unit from the summary's ``units``)."""
    return quantity(name, str(summary[name].attrs.get("units", STATISTICS[name][0])))


def _replay_cell(name: str, links: dict[str, str], id: str) -> Cell:
    """A cell linking the replay of case `name`, or a dash without one."""
    return Cell(html.link(links[name], "replay") if name in links else "—", id=id)


def _worst(
    ranked: dict[str, list[_Case]], keys: Sequence[str], links: dict[str, str], replays: int, said: str
) -> Markup:
    if not ranked:
        text = "none of " + ", ".join(WORST) + " has a value: no worst cases"
        return html.section("worst", "Worst cases", html.note(text))
    parts: list[str] = [
        html.paragraph(
            f"The cases ranked from the largest value of each statistic; the {replays} worst of each have a replay "
            "(a 3-D animation of the run, its own page)."
        )
    ]
    if said:
        parts.append(html.note(said, kind="skipped"))
    criteria = list(ranked)
    for name, order in ranked.items():
        rows = []
        for rank, case in enumerate(order[: max(SHOWN, replays)]):
            row: list[Any] = [Cell(str(rank + 1), numeric=True), *case.values]
            for other in criteria:
                shown = quantity(other, STATISTICS[other][0])
                row.append(shown.cell(case.statistics[other], id=f"worst-{name}-{rank}-{other}"))
            row.append(Cell(case.name, id=f"worst-{name}-{rank}", data={"case": case.name}))
            row.append(_replay_cell(case.name, links, f"worst-{name}-{rank}-replay"))
            rows.append(row)
        header = ["rank", *keys, *(quantity(c, STATISTICS[c][0]).heading for c in criteria), "case", "replay"]
        label = quantity(name, STATISTICS[name][0]).label
        parts.append(html.subsection(f"By {label}", html.table(header, rows, id=f"worst-{name}")))
    return html.section("worst", "Worst cases", *parts)


def _all_cases(
    summary: Any,
    cases: Sequence[_Case],
    keys: Sequence[str],
    statistics: Sequence[str],
    links: dict[str, str],
) -> Markup:
    rows = []
    kinds: list[str | None] = []
    for k, case in enumerate(cases):
        row: list[Any] = [*case.values]
        row.extend(
            _statistic(summary, name).cell(case.statistics[name], id=f"case-{k}-{name}")
            for name in statistics
        )
        row.append("failed" if case.failed else "")
        row.append(Cell(case.name, id=f"case-{k}", data={"case": case.name}))
        row.append(_replay_cell(case.name, links, f"case-{k}-replay"))
        rows.append(row)
        kinds.append("failed" if case.failed else None)
    header = [*keys, *(_statistic(summary, name).heading for name in statistics)]
    header += ["status", "case", "replay"]
    table = html.table(header, rows, id="summary", row_classes=kinds)
    meanings = html.definitions(
        [(f"{_statistic(summary, name).label} ({name})", STATISTICS[name][1]) for name in statistics],
        id="statistics",
    )
    return html.section("cases", "All cases", table, html.details("what the statistics are", meanings))
