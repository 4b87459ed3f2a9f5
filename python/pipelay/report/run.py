"""The HTML report of one run (`run_report`): a single self-contained page with the run's inputs, its time span,
stages and energy balance, its lay summary and code checks, its figures, response spectra and most probable
maxima, and its 3-D replay.

```python
from pipelay.report import run_report

run_report("run.nc", "run.html")                   # a results file of `pipelay run`: its scenario is in it
run_report(results, "run.html", scenario=scenario)  # or a Results with its scenario (or its model)
```

Sections (their ``id`` in the page): ``inputs`` (the scenario's title, source and TOML data, the model's key
numbers), ``run`` (time span, records, stages, passivity margin and energy balance), ``checks`` (the lay
summary's minimum, mean and maximum; the extremes of `pipelay.analysis.extremes.extremes`, with their times
and elements, and the DNV-ST-F101 utilisation for a pipe with a wall thickness), ``series`` (the figures of
`pipelay.plots`, the response spectra of the top tension and of the hang-off bending moment and the most
probable maxima of the top tension over a storm, on the stationary part of the run: `steady_window`),
``replay`` (`pipelay.plots.replay.replay_html`, with plotly.js included once in the page's head).

The tables show each quantity by its label, in the unit people read (kN, kN·m, degrees, percent; rollers
numbered from 1: `pipelay.report.units`). Every number in a table is in a cell whose ``id`` names it, whose
``data-value`` holds its SI value exactly (``repr``; a roller's Python index, from 0) and whose ``data-unit``
names that SI unit, for a reader or a test to find.

Imports of pipelay: the engine (`pipelay._core`), `pipelay.results` (`load`), `pipelay.analysis.checks`,
`pipelay.analysis.extremes`, `pipelay.analysis.statistics`, `pipelay.analysis.sweep` (`STATISTICS`, the units),
`pipelay.plots`, `pipelay.report.html`, `pipelay.report.units`, `pipelay.scenario` (`scenario_of_results`) and,
when a replay is asked for, `pipelay.plots.replay` (which imports plotly).
"""

from __future__ import annotations

import json
import math
import os
import re
import warnings
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from pipelay._core import InputError, Model, Results
from pipelay.analysis.checks import dnv_st_f101, propagation_buckling
from pipelay.analysis.extremes import extremes, record_state, top_elements
from pipelay.analysis.statistics import (
    METHODS,
    MIN_SAMPLES,
    SETTLING_STEPS,
    most_probable_maximum,
    response_spectrum,
    stationarity,
    stationary_part,
    top_tension,
)
from pipelay.analysis.supports import support_count
from pipelay.analysis.sweep import STATISTICS
from pipelay.report import html
from pipelay.report.html import Cell, Markup, value_cell
from pipelay.report.units import quantity, roller_cell
from pipelay.results import load
from pipelay.scenario import scenario_of_results

__all__ = ["run_report", "steady_window", "toml_text"]

FloatArray = npt.NDArray[np.float64]

NOT_RECORDED = "not recorded"


def run_report(
    results: Results | str | os.PathLike[str],
    path: str | os.PathLike[str] = "report.html",
    *,
    model: Model | None = None,
    scenario: Any = None,
    title: str | None = None,
    storm: float = 10800.0,
    replay: bool = True,
    checks: Mapping[str, Any] | None = None,
) -> Path:
    """Writes the HTML report of a run to `path` (atomically) and returns the path.

    Parameters
    ----------
    results : pipelay.Results or path
        The run, or its results file (read with `pipelay.load`).
    path : path
        The report's file (HTML, created with its folder if missing).
    model : pipelay.Model or None
        The model of the run (its section, sea and vessel: strain, the DNV-ST-F101 checks, the key numbers);
        None: ``scenario.model``, or the model of the scenario stored in the results file
        (`pipelay.scenario.scenario_of_results`) when neither is given.
    scenario : pipelay.scenario.Scenario or None
        The inputs: its title, origin and TOML data (``scenario.source``) are shown; None: the scenario stored
        in the results file, if any.
    title : str or None
        The page's title; None: the scenario's ``title``, else "pipelay run report".
    storm : float
        Duration (s) of the most probable maxima of the top tension, default 3 h.
    replay : bool
        Include the 3-D replay (`pipelay.plots.replay.replay_html`, with plotly.js: about 5 MB).
    checks : mapping or None
        Keyword arguments of ``pipelay.checks.dnv_st_f101`` and ``propagation_buckling`` (e.g.
        ``{"safety_class": "low"}``) for the utilisations; None: the scenario's ``[checks]`` (``Scenario.checks``),
        else the checks' defaults. Used only for a pipe section with a wall thickness.

    Returns
    -------
    pathlib.Path
        `path`.

    Raises
    ------
    pipelay.InputError
        If `results` is a path that is not a results file (as `pipelay.load`), or `storm` is not a positive
        number.
    """
    file = None
    if not isinstance(results, Results):
        file = Path(results)
        results = load(file)
    if isinstance(storm, bool) or not (
        isinstance(storm, (int, float)) and math.isfinite(storm) and storm > 0
    ):
        raise InputError(f"storm: the duration of the most probable maxima, a number of s > 0, got {storm!r}")
    stored = ""
    if scenario is None and model is None and file is not None:
        scenario, stored = _stored_scenario(file)
    if model is None and scenario is not None:
        model = scenario.model
    source = getattr(scenario, "source", None) or {}
    heading = title or str(source.get("title") or "pipelay run report")

    head = ""
    body = [
        _inputs(results, model, scenario, file, stored),
        _the_run(results, model),
        _checks(results, model, checks if checks is not None else getattr(scenario, "checks", None)),
        _series(results, model, scenario, storm),
    ]
    if replay:
        part, head = _replay(results, model, heading)
        body.append(part)
    return html.write(path, html.page(heading, body, head=head))


# --- inputs ----------------------------------------------------------------------------------------------


def _stored_scenario(file: Path) -> tuple[Any, str]:
    """The scenario stored in the results file (None without one) and a note on why there is none."""
    try:
        found = scenario_of_results(file)
    except InputError as error:
        return None, str(error)
    return found, "" if found is not None else "the results file holds no scenario"


def _inputs(results: Results, model: Model | None, scenario: Any, file: Path | None, stored: str) -> Markup:
    source = getattr(scenario, "source", None)
    facts: list[tuple[str, Any]] = []
    if scenario is None:
        facts.append(("scenario", NOT_RECORDED + (f" ({stored})" if stored else "")))
    else:
        facts.append(("scenario title", str((source or {}).get("title") or NOT_RECORDED)))
        facts.append(("scenario source", str(getattr(scenario, "origin", None) or NOT_RECORDED)))
        folder = getattr(scenario, "folder", None)
        if folder:
            facts.append(("relative paths from", str(folder)))
    facts.append(("results file", str(file) if file is not None else "(given in memory)"))
    parts: list[str] = [html.definitions(facts, id="provenance")]
    if source:
        parts.append(
            html.details("scenario data (TOML)", html.preformatted(toml_text(source), id="scenario-data"))
        )
    facts = _model_facts(results, model, scenario)
    parts.append(html.subsection("Model", html.definitions(facts, id="model")))
    return html.section("inputs", "Inputs", *parts)


def _model_facts(results: Results, model: Model | None, scenario: Any) -> list[tuple[str, Any]]:
    """The model's key numbers, from the model, else what the results say."""
    facts: list[tuple[str, Any]] = []
    if model is not None:
        rod, sea = model.rod, model.sea
        section = rod.section
        facts.append(("elements", rod.elements))
        facts.append(("segments", len(rod.sections)))
        facts.append(("length (m)", rod.length))
        facts.append(("water depth (m)", sea.depth if sea is not None else "no sea"))
        facts.append(("outer diameter (m)", section.outer_diameter))
        facts.append(
            (
                "wall thickness (m)",
                section.wall_thickness if section.wall_thickness is not None else "none (not a Section.pipe)",
            )
        )
        facts.append(("submerged weight (N/m)", model.submerged_weight))
        facts.append(("mass (kg/m)", section.mass))
        facts.append(("EA (N)", section.EA))
        facts.append(("EI (N m²)", section.EI[0]))
        facts.append(("vessel", "yes" if model.vessel is not None else "no"))
        waves = sea.waves if sea is not None else None
        facts.append(("seabed", "yes" if sea is not None and sea.seabed is not None else "no"))
        facts.append(("current", "yes" if sea is not None and sea.current is not None else "no"))
        facts.append(("waves Hs (m)", waves.hs if waves is not None else "calm"))
        if waves is not None:
            period = _wave_period(scenario)
            facts.append(("waves Tp (s)", period if period is not None else NOT_RECORDED))
        return facts
    # No model: what the results file records.
    walls = [wall for wall in results.pipe_walls if wall is not None]
    facts.append(("elements", int(np.asarray(results.section_forces).shape[1])))
    water = results.water
    facts.append(("water depth (m)", water[0] if water is not None else NOT_RECORDED))
    facts.append(("outer diameter (m)", walls[0][0] if walls else NOT_RECORDED))
    facts.append(("wall thickness (m)", walls[0][1] if walls else NOT_RECORDED))
    facts.append(("submerged weight (N/m)", NOT_RECORDED))
    facts.append(("vessel", "yes" if results.eta is not None else "no"))
    facts.append(("seabed", "yes" if results.touchdown is not None else "no"))
    facts.append(("waves Hs (m)", NOT_RECORDED))
    return facts


def _wave_period(scenario: Any) -> Any:
    """The peak (JONSWAP) or wave period (regular) of the scenario's `[sea.waves]`, or None."""
    source = getattr(scenario, "source", None) or {}
    waves = source.get("sea", {}).get("waves", {}) if isinstance(source.get("sea"), Mapping) else {}
    if not isinstance(waves, Mapping):
        return None
    return waves.get("tp", waves.get("period"))


# --- the run ---------------------------------------------------------------------------------------------


def _the_run(results: Results, model: Model | None) -> Markup:
    time = np.asarray(results.time, dtype=np.float64)
    steps = np.diff(time)
    facts: list[tuple[str, Any]] = [
        ("start (s)", float(time[0])),
        ("end (s)", float(time[-1])),
        ("duration (s)", float(time[-1] - time[0])),
        ("records", len(time)),
        ("record interval (s)", float(np.median(steps)) if steps.size else "—"),
        ("nodes (most)", results.nodes),
    ]
    parts: list[str] = [html.definitions(facts, id="span")]
    names = results.stage_names
    if names:
        parts.append(html.subsection("Stages", _stages(results, model)))
    parts.append(html.subsection("Energy balance", _energy(results)))
    return html.section("run", "The run", *parts)


def _stages(results: Results, model: Model | None) -> Markup:
    try:
        frame = results.stage_summary(model)
    except InputError as error:
        return html.note(f"stage summary not available: {error}")
    columns = [
        column
        for column in frame.columns
        if column == "name" or np.isfinite(np.asarray(frame[column], dtype=np.float64)).any()
    ]
    rows = []
    for k, record in enumerate(frame.to_dict("records")):
        row: list[Any] = []
        for column in columns:
            if column == "name":
                row.append(Cell(str(record[column]), header=True))
            else:
                row.append(quantity(column).cell(record[column], id=f"stage-{k}-{column}"))
        rows.append(row)
    header = ["stage" if column == "name" else quantity(column).heading for column in columns]
    return html.table(header, rows, id="stages")


def _energy(results: Results) -> Markup:
    parts = results.energy
    total = np.asarray(parts["total"], dtype=np.float64)
    work = np.asarray(results.supplied_work, dtype=np.float64)
    dissipated = np.asarray(results.dissipated, dtype=np.float64)
    balance = total - total[0] - (work - dissipated)
    margin = results.passivity_margin()
    rows = [
        ["passivity margin max_t E(t) − E(0) − W(t)", value_cell(margin, id="passivity-margin"), "J"],
        ["largest |E − E(0) − (W − D)| (balance residual)", value_cell(float(np.max(np.abs(balance)))), "J"],
        ["energy change E(end) − E(0)", value_cell(float(total[-1] - total[0])), "J"],
        ["supplied work W(end)", value_cell(float(work[-1])), "J"],
        ["dissipated D(end)", value_cell(float(dissipated[-1])), "J"],
    ]
    explanation = html.paragraph(
        "The energy–momentum integrator books every step's change of energy E against the work W supplied to "
        "the system and the energy D it dissipated: a passive run has a margin ≤ 0 up to round-off."
    )
    return Markup(explanation + html.table(["quantity", "value", "unit"], rows, id="energy"))


# --- lay summary and checks ------------------------------------------------------------------------------


def _checks(results: Results, model: Model | None, checks: Mapping[str, Any] | None) -> Markup:
    parts: list[str] = []
    summary = results.lay_summary()
    if summary is None:
        parts.append(html.subsection("Lay summary", html.note("no lay summary: the model has no vessel")))
    else:
        supports = None if model is None else model.rest().roller_supports
        parts.append(html.subsection("Lay summary", _lay_summary(results, summary, supports)))
        vectors = results.roller_reaction_vectors
        if supports and vectors is not None and support_count(supports)[1] == "box":
            parts.append(html.subsection("Roller boxes", _roller_boxes(results, vectors, supports)))
    section = model.rod.section if model is not None else None
    dnv = dict(checks or {}) if section is not None and section.wall_thickness is not None else None
    try:
        found = extremes(results, model=model, checks=dnv)
    except InputError as error:
        parts.append(html.subsection("Extremes", html.note(f"extremes not computed: {error}")))
        return html.section("checks", "Lay summary and code checks", *parts)
    rows = []
    for key, value in found.items():
        if key.endswith(("_time", "_element")):
            continue
        element = found.get(f"{key}_element")
        shown = quantity(key, STATISTICS[key][0] if key in STATISTICS else "")
        rows.append(
            [
                Cell(shown.label, header=True),
                shown.cell(value, id=f"extreme-{key}"),
                shown.shown or "—",
                value_cell(found.get(f"{key}_time"), id=f"extreme-{key}-time"),
                Cell(html.number(element), id=f"extreme-{key}-element", numeric=True),
                STATISTICS[key][1] if key in STATISTICS else "",
            ]
        )
    said = []
    if model is None:
        said.append("no model: no strain and no DNV-ST-F101 utilisation")
    elif dnv is None:
        said.append("the section has no wall thickness: no DNV-ST-F101 utilisation")
    else:
        said.append("the DNV-ST-F101 utilisation on the basis of the code checks below")
    parts.append(
        html.subsection(
            "Extremes",
            html.paragraph("Elements are numbered from 0 at end A; " + "; ".join(said) + "."),
            html.table(["quantity", "value", "unit", "time (s)", "element", "meaning"], rows, id="extremes"),
        )
    )
    if model is not None and dnv is not None:
        parts.append(_code_checks(results, model, dnv))
    return html.section("checks", "Lay summary and code checks", *parts)


STINGER_ONLY = ("liftoff_roller", "overbend_strain", "tip_clearance")
"""The lay summary's quantities that only a stinger has: a lay without rollers (a J-lay tower) leaves them out."""


def _lay_summary(results: Results, summary: Mapping[str, Any], supports: list[int] | None = None) -> Markup:
    """The lay summary's minimum, mean and maximum over the run, each quantity in the unit people read; the
    lift-off roller (or box, on a stinger of roller boxes: `supports`, each roller's box, from the model)
    numbered from 1 (no mean: it names a roller); without rollers, only what a lay without a stinger has
    (`STINGER_ONLY` left out)."""
    rollers = results.roller_reactions
    count = None if rollers is None else int(np.asarray(rollers).shape[1])
    noun = "roller"
    if supports and count is not None:
        count, noun = support_count(supports)
    rows = []
    for key, series in summary.items():
        if rollers is None and key in STINGER_ONLY:
            continue
        values = np.asarray(series, dtype=np.float64)
        finite = values[np.isfinite(values)]
        low, mean, high = (
            (float(finite.min()), float(finite.mean()), float(finite.max())) if finite.size else (None,) * 3
        )
        shown = quantity(key)
        if key == "liftoff_roller":
            cells = [
                roller_cell(low, count, id=f"lay-{key}-min", noun=noun),
                Cell("—", id=f"lay-{key}-mean"),
                roller_cell(high, count, id=f"lay-{key}-max", noun=noun),
                "numbered from 1 in the stinger's order",
            ]
        else:
            cells = [
                shown.cell(low, id=f"lay-{key}-min"),
                shown.cell(mean, id=f"lay-{key}-mean"),
                shown.cell(high, id=f"lay-{key}-max"),
                shown.shown or "—",
            ]
        rows.append([Cell(shown.label, header=True), *cells])
    return html.table(["quantity", "min", "mean", "max", "unit"], rows, id="lay-summary")


def _roller_boxes(results: Results, vectors: Any, supports: list[int]) -> Markup:
    """Each roller box's largest vertical load on the pipe (up) and largest lateral load (either way) over the
    run, in kN, with the times they occur, and the most boxes the pipe was leaving at once."""
    vectors = np.asarray(vectors, dtype=np.float64)
    box_of = np.asarray(supports)
    time = np.asarray(results.time)
    rows = []
    for box in range(int(box_of.max()) + 1):
        load = vectors[:, box_of == box, :].sum(axis=1)
        vertical, lateral = -load[:, 2], load[:, 1]
        up, side = int(np.argmax(vertical)), int(np.argmax(np.abs(lateral)))
        rows.append(
            [
                Cell(f"box {box + 1}", header=True),
                value_cell(vertical[up] / 1e3, id=f"box-{box}-vertical", digits=4),
                value_cell(time[up], digits=4),
                value_cell(lateral[side] / 1e3, id=f"box-{box}-lateral", digits=4),
                value_cell(time[side], digits=4),
            ]
        )
    lay = results.lay_summary() or {}
    left = np.asarray(lay.get("boxes_left", [0.0]), dtype=np.float64)
    most = int(np.nanmax(left)) if left.size else 0
    said = (
        "The pipe stayed in its boxes." if most == 0 else f"The pipe was leaving up to {most} boxes at once."
    )
    return Markup(
        html.paragraph(
            "The boxes' loads on the pipe in the vessel's body frame: vertical up, lateral to starboard (+) or "
            f"port (−), numbered from 1 from the tensioner. {said}"
        )
        + html.table(
            ["box", "largest vertical (kN)", "at t (s)", "largest lateral (kN)", "at t (s)"],
            rows,
            id="roller-boxes",
        )
    )


def _code_checks(results: Results, model: Model, checks: Mapping[str, Any]) -> Markup:
    """The DNV-ST-F101 checks of the run's first record (the static state it starts from), on the basis they
    are taken on, with the governing elements and the propagation buckling advice."""
    state = record_state(results, 0, model=model)
    check = dnv_st_f101(state, **checks)
    propagation = propagation_buckling(state, **checks)
    nodes = np.asarray(model.rod.nodes, dtype=np.float64)
    arcs = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(nodes, axis=0), axis=1))])
    rows = []
    for key, label, values in (
        ("load_controlled", "load-controlled (local buckling)", check.load_controlled),
        (
            "displacement_controlled",
            "displacement-controlled (local buckling)",
            check.displacement_controlled,
        ),
        ("propagation", "propagation buckling", propagation.utilisation),
    ):
        worst = int(np.argmax(values))
        middle = 0.5 * (arcs[worst] + arcs[worst + 1]) if worst + 1 < len(arcs) else math.nan
        rows.append(
            [
                Cell(label, header=True),
                value_cell(float(values[worst]), id=f"check-{key}"),
                Cell(html.number(worst), id=f"check-{key}-element", numeric=True),
                value_cell(middle, id=f"check-{key}-arc"),
            ]
        )
    parts = [
        html.paragraph(
            f"At t = {state.time:g} s (the first record: the static state the run starts from), on the basis "
            f"{check.basis}. Elements are numbered from 0 at end A; the arc length is along the reference."
        ),
        html.table(["check", "utilisation", "element", "arc length from A (m)"], rows, id="code-checks"),
    ]
    advice = propagation.arrestors or "no buckle arrestors needed: the propagation check holds along the pipe"
    parts.append(html.paragraph(f"Propagation buckling: {advice}."))
    parts.extend(html.note(note) for note in (*check.notes, *propagation.notes))
    return html.subsection("Code checks", *parts)


# --- time series and spectra -----------------------------------------------------------------------------


def steady_window(
    results: Results, model: Model | None = None, scenario: Any = None
) -> tuple[float, float, str]:
    """The stationary part of a run, over which the report takes its spectra and most probable maxima: the
    start and end (s) and a sentence that says how they were found.

    The end is the last record, or the end of the first stage of a run through stages. The start is found in
    two steps:

    1. the latest of the known starts of what loads the run: its first record (the first stage's start), the
       end of the waves' build-up (``model.sea.waves.ramp``, from t = 0), the current's start
       (``model.sea.current.start``) and, in the scenario, the controller's (``controller.start``), its
       tension loop's (``controller.tension.start``), its route's (``controller.route.start_time``) and each
       environmental force's (``environment[k].start``);
    2. the start-up transient, measured: the first of the starts tried every 1/20 of the records left, over
       their first half, from which the top tension (`pipelay.analysis.statistics.top_tension`) is a
       stationary record (`pipelay.analysis.statistics.stationary_part`: at least 30 of its mean zero
       up-crossing periods Tz, a trend of at most 0.25 σ, its halves' standard deviations within a factor 2).

    Parameters
    ----------
    results : pipelay.Results
        The run.
    model : pipelay.Model or None
        Its model (the sea's waves and current); None: only the records and the scenario say.
    scenario : pipelay.scenario.Scenario or None
        Its scenario (``scenario.source``: the controller's and environmental forces' starts); None: none.

    Returns
    -------
    tuple of float, float, str
        The window's first and last record's times (s), and how the window was found.

    Raises
    ------
    pipelay.InputError
        Naming `results`, when the records after the known starts are not evenly spaced or too few, or no
        start leaves a stationary top tension (with the stationarity test's reason: too short, a trend, a
        changing spread).
    """
    time = np.asarray(results.time, dtype=np.float64)
    known = [("the first record", float(time[0]))]
    end, until = float(time[-1]), "the last record"
    starts, names = results.stage_starts, results.stage_names
    if starts is not None and names and len(starts) >= 2:
        known.append((f"the first stage's start ({names[0]})", float(starts[0])))
        end, until = float(starts[1]), f"the end of the first stage ({names[0]})"
    known.extend(_known_starts(model, scenario))
    after, begin = max(known, key=lambda item: item[1])
    inside = _between(time, begin, end)
    window = time[inside]
    if window.size < MIN_SAMPLES:
        raise InputError(
            f"results: {window.size} records from t = {begin:g} s ({after}) to t = {end:g} s ({until}); "
            f"allowed: at least {MIN_SAMPLES}"
        )
    steps = np.diff(window)
    dt = float(np.median(steps))
    if np.ptp(steps) > 1e-6 * dt:
        raise InputError(
            f"results: records from t = {begin:g} s to {end:g} s at uneven intervals ({steps.min():g} to "
            f"{steps.max():g} s); allowed: a constant record interval"
        )
    try:
        first, found = stationary_part(top_tension(results)[inside], dt)
    except InputError as error:
        raise InputError(
            f"results: the top tension from t = {begin:g} s ({after}) to t = {end:g} s ({until}) is not a "
            f"stationary record: {str(error).removeprefix('series: ')}"
        ) from None
    start = float(window[first])
    settled = (
        "stationary from there"
        if first == 0
        else f"then the start-up transient, settled by t = {start:g} s (the first of the starts tried every "
        f"1/{SETTLING_STEPS} of the records that leaves a stationary top tension)"
    )
    ratio = max(found.halves) / min(found.halves)
    said = (
        f"t = {start:g} s to {end:g} s ({until}): after {after} at t = {begin:g} s, {settled}; "
        f"{found.periods:.0f} periods Tz = {found.tz:.3g} s of the top tension, its trend {found.trend:+.2f} σ, "
        f"its halves' standard deviations a factor {ratio:.2f} apart"
    )
    return start, end, said


def _known_starts(model: Model | None, scenario: Any) -> list[tuple[str, float]]:
    """What starts loading the run and when (s): the waves' build-up's end and the current's start (the
    model's sea), the controller's, its tension loop's and route's and the environmental forces' starts (the
    scenario's data)."""
    found: list[tuple[str, float]] = []
    sea = model.sea if model is not None else None
    if sea is not None and sea.waves is not None:
        found.append(("the waves' build-up (sea.waves.ramp)", float(sea.waves.ramp)))
    if sea is not None and sea.current is not None:
        found.append(("the current's start (sea.current.start)", float(sea.current.start)))
    source = getattr(scenario, "source", None) or {}
    controller = source.get("controller")
    controller = controller if isinstance(controller, Mapping) else {}
    tables = {
        "controller.start": (controller, "start"),
        "controller.tension.start": (controller.get("tension"), "start"),
        "controller.route.start_time": (controller.get("route"), "start_time"),
    }
    forces = source.get("environment")
    for k, force in enumerate(forces if isinstance(forces, list) else []):
        tables[f"environment[{k}].start"] = (force, "start")
    for name, (table, key) in tables.items():
        value = table.get(key) if isinstance(table, Mapping) else None
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            found.append((f"its start ({name})", float(value)))
    return found


def _between(time: FloatArray, start: float, end: float) -> npt.NDArray[np.bool_]:
    """Which records lie from `start` to `end` (s), with a relative margin of 1e-9 for round-off."""
    inside: npt.NDArray[np.bool_] = (time >= start - 1e-9 * max(1.0, abs(start))) & (
        time <= end + 1e-9 * max(1.0, abs(end))
    )
    return inside


def _series(results: Results, model: Model | None, scenario: Any, storm: float) -> Markup:
    from pipelay import plots

    depth = model.sea.depth if model is not None and model.sea is not None else None
    if depth is None and results.water is not None:
        depth = results.water[0]
    drawn: list[tuple[str, str, Callable[[], Any]]] = [
        (
            "shape",
            "The pipe's shape: first, middle and last records",
            lambda: plots.shape(results, depth=depth),
        ),
        ("top_tension", "The top tension and the reaction at end B", lambda: plots.top_tension(results)),
    ]
    if results.eta is not None:
        drawn.append(("vessel_motion", "The vessel's pose η(t)", lambda: plots.vessel_motion(results)))
    if results.touchdown is not None:
        drawn.append(("touchdown", "The touchdown point over time", lambda: plots.touchdown_path(results)))
    if results.lay_summary() is not None and results.roller_reactions is not None:
        drawn.append(("lay_summary", "The lay summary over time", lambda: plots.lay_summary(results)))
    drawn.append(
        (
            "tension_and_bending",
            "Tension and bending moment along the pipe",
            lambda: plots.tension_and_bending(results),
        )
    )
    drawn.append(("energy", "The energy balance", lambda: plots.energy(results)))
    if results.stage is not None:
        drawn.append(("stage_tensions", "Tensions over the stages", lambda: plots.stage_tensions(results)))
        drawn.append(
            (
                "stage_configurations",
                "The line at the end of each stage",
                lambda: plots.stage_configurations(results, depth=depth),
            )
        )
    parts: list[str] = []
    for name, caption, draw in drawn:
        try:
            chart = draw()
        except Exception as error:  # noqa: BLE001 - one figure that cannot be drawn does not stop the report
            warnings.warn(f"run_report: figure {name} not drawn: {error}", RuntimeWarning, stacklevel=3)
            parts.append(
                html.note(f"figure {name} not drawn: {type(error).__name__}: {error}", kind="skipped")
            )
            continue
        parts.append(html.figure(chart, name=name, caption=caption))
    parts.append(_spectra(results, model, scenario, storm))
    return html.section("series", "Time series and spectra", *parts)


def _hang_off_moment(results: Results) -> FloatArray:
    """The bending moment |(M2, M3)| (T,) (N·m) of the top element of each record (the hang-off)."""
    forces = np.asarray(results.section_forces, dtype=np.float64)
    top = top_elements(np.asarray(results.segment, dtype=np.float64))
    rows = np.arange(len(top))
    moment: FloatArray = np.hypot(forces[rows, top, 4], forces[rows, top, 5])
    return moment


def _spectra(results: Results, model: Model | None, scenario: Any, storm: float) -> Markup:
    """The response spectra of the top tension and the hang-off moment, and the top tension's MPMs, over the
    stationary part of the run (`steady_window`); refused, with the reason, without one."""
    heading = "Response spectra and most probable maxima"
    try:
        start, end, said = steady_window(results, model, scenario)
    except InputError as error:
        text = f"spectra and most probable maxima refused: {error}"
        return html.subsection(heading, html.note(text, kind="refused"))
    time = np.asarray(results.time, dtype=np.float64)
    inside = _between(time, start, end)
    window = time[inside]
    dt = float(np.median(np.diff(window)))
    where = Markup(
        f'<p id="window" data-start="{start!r}" data-end="{end!r}" data-records="{window.size}">'
        f"{html.escape(f'Taken over the stationary part of the run, {said} ({window.size} records).')}</p>"
    )
    series = {
        "top_tension": top_tension(results)[inside],
        "hang_off_moment": _hang_off_moment(results)[inside],
    }
    spectra = {}
    notes: list[str] = []
    for key, values in series.items():
        try:
            stationarity(values, dt)
            spectra[key] = response_spectrum(values, dt)
        except InputError as error:
            notes.append(html.note(f"no spectrum of the {quantity(key).label}: {error}", kind="refused"))
    rows = []
    for key, spectrum in spectra.items():
        shown = quantity(key)
        rows.append(
            [
                Cell(shown.label, header=True),
                shown.cell(spectrum.mean, id=f"spectrum-{key}-mean"),
                shown.cell(spectrum.std, id=f"spectrum-{key}-std"),
                value_cell(spectrum.tz, id=f"spectrum-{key}-tz"),
                value_cell(spectrum.bandwidth, id=f"spectrum-{key}-bandwidth"),
                value_cell(spectrum.segment, id=f"spectrum-{key}-segment"),
                shown.shown,
            ]
        )
    parts: list[str] = [where, *notes]
    if spectra:
        parts.append(html.figure(_spectrum_figure(spectra), name="spectra", caption="Response spectra"))
        parts.append(
            html.table(
                ["series", "mean", "σ", "Tz (s)", "bandwidth ε", "Welch segment (s)", "unit"],
                rows,
                id="spectra",
            )
        )
    parts.append(_maxima(series["top_tension"], dt, storm))
    return html.subsection(heading, *parts)


def _spectrum_figure(spectra: Mapping[str, Any]) -> Any:
    """The spectra, one panel each, in the units people read, on an Agg canvas (pyplot is not used)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    chart = Figure(figsize=(9.0, 3.6 * len(spectra)), layout="constrained")
    FigureCanvasAgg(chart)
    axes = chart.subplots(len(spectra), 1, squeeze=False).ravel()
    for axis, (key, spectrum) in zip(axes, spectra.items(), strict=True):
        shown = quantity(key)
        axis.plot(spectrum.frequency, spectrum.density * shown.scale**2, color="k")
        axis.set_xlabel("frequency f (Hz)")
        axis.set_ylabel(f"S(f) ({shown.shown}²/Hz)")
        axis.set_title(
            f"{shown.label}: σ = {spectrum.std * shown.scale:.4g} {shown.shown}, Tz = {spectrum.tz:.3g} s",
            fontsize=10,
        )
        axis.grid(alpha=0.3)
        # Up to where the spectrum has all but 0.1 % of its variance, with room to spare.
        cumulative = np.cumsum(spectrum.density)
        reach = spectrum.frequency[
            min(np.searchsorted(cumulative, 0.999 * cumulative[-1]), cumulative.size - 1)
        ]
        axis.set_xlim(0.0, min(float(spectrum.frequency[-1]), 1.5 * float(reach)))
    return chart


def _maxima(top: FloatArray, dt: float, storm: float) -> Markup:
    """The table of the top tension's most probable maxima over `storm` by the three methods."""
    shown = quantity("top_tension")
    rows = []
    for method in METHODS:
        try:
            found = most_probable_maximum(top, dt, storm, method)
        except InputError as error:
            rows.append(
                [
                    Cell(method, header=True),
                    Cell("not computed", id=f"mpm-{method}", data={"value": "nan", "unit": shown.unit}),
                    shown.shown,
                    f"{error}",
                ]
            )
            continue
        fit = ", ".join(f"{key} {html.number(value, 4)}" for key, value in found.parameters.items())
        rows.append(
            [Cell(method, header=True), shown.cell(found.value, id=f"mpm-{method}"), shown.shown, fit]
        )
    intro = html.paragraph(
        f"Most probable maxima of the top tension over a storm of {storm:g} s ({storm / 3600:.3g} h), from the "
        f"{top.size} records of {dt:g} s above (largest in the record {html.number(float(top.max()) * shown.scale)} "
        f"{shown.shown}). Each method assumes the record is a sample of the storm's stationary process (see "
        "pipelay.analysis.statistics); the fits' parameters are in SI units (N, s)."
    )
    return Markup(
        intro + html.table(["method", "most probable maximum", "unit", "fit"], rows, id="mpm", caption="MPM")
    )


# --- replay ----------------------------------------------------------------------------------------------


def _replay(results: Results, model: Model | None, title: str) -> tuple[Markup, str]:
    """The replay's section and what the page's head needs for it (plotly.js), or a note and nothing."""
    from pipelay.plots.replay import replay_html  # imports plotly: only when a replay is asked for

    try:
        division = replay_html(results, model, full_html=False, title=title)
    except Exception as error:  # noqa: BLE001 - the report is written without its replay
        warnings.warn(f"run_report: replay not drawn: {error}", RuntimeWarning, stacklevel=3)
        text = f"replay not available: {type(error).__name__}: {error}"
        return html.section("replay", "Replay", html.note(text, kind="skipped")), ""
    return html.section(
        "replay", "Replay", Markup(f'<div class="replay">{division}</div>')
    ), html.plotly_script()


# --- the scenario's data as TOML-like text ---------------------------------------------------------------


def toml_text(data: Mapping[str, Any]) -> str:
    """`data` (a scenario's TOML data) as TOML text: its keys, then its tables (``[a.b]``) and arrays of
    tables (``[[a]]``); values inline (tables in arrays as inline tables)."""
    lines: list[str] = []
    _table(lines, data, ())
    return "\n".join(lines).strip() + "\n"


def _is_tables(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(entry, Mapping) for entry in value)


def _table(lines: list[str], data: Mapping[str, Any], prefix: tuple[str, ...]) -> None:
    plain = {k: v for k, v in data.items() if not isinstance(v, Mapping) and not _is_tables(v)}
    tables = {k: v for k, v in data.items() if isinstance(v, Mapping)}
    arrays = {k: v for k, v in data.items() if _is_tables(v)}
    if prefix and (plain or not (tables or arrays)):
        lines.append(f"\n[{'.'.join(map(_key, prefix))}]")
    lines.extend(f"{_key(key)} = {_inline(value)}" for key, value in plain.items())
    for key, value in tables.items():
        _table(lines, value, (*prefix, key))
    for key, entries in arrays.items():
        for entry in entries:
            lines.append(f"\n[[{'.'.join(map(_key, (*prefix, key)))}]]")
            lines.extend(f"{_key(k)} = {_inline(v)}" for k, v in entry.items())


def _key(key: Any) -> str:
    text = str(key)
    return text if re.fullmatch(r"[A-Za-z0-9_-]+", text) else json.dumps(text, ensure_ascii=False)


def _inline(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        real = float(value)
        if math.isnan(real):
            return "nan"
        if math.isinf(real):
            return "inf" if real > 0 else "-inf"
        return repr(real)
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_inline(v)}" for k, v in value.items()) + " }"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_inline(v) for v in value) + "]"
    return json.dumps(str(value), ensure_ascii=False)
