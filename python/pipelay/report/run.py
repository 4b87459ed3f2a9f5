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
probable maxima of the top tension over a storm), ``replay`` (`pipelay.plots.replay.replay_html`, with
plotly.js included once in the page's head). Every number in a table is in a cell whose ``id`` names it and
whose ``data-value`` holds it exactly (``repr``), for a reader or a test to find.

Imports of pipelay: the engine (`pipelay._core`), `pipelay.results` (`load`), `pipelay.analysis.extremes`,
`pipelay.analysis.statistics`, `pipelay.analysis.stages`, `pipelay.analysis.sweep` (`STATISTICS`, the units),
`pipelay.plots`, `pipelay.report.html`, `pipelay.scenario` (`scenario_of_results`) and, when a replay is asked
for, `pipelay.plots.replay` (which imports plotly).
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
from pipelay.analysis.extremes import extremes
from pipelay.analysis.stages import top_elements
from pipelay.analysis.statistics import METHODS, MIN_SAMPLES, most_probable_maximum, response_spectrum
from pipelay.analysis.sweep import STATISTICS
from pipelay.report import html
from pipelay.report.html import Cell, Markup, value_cell
from pipelay.results import load
from pipelay.scenario import scenario_of_results

__all__ = ["LAY_SUMMARY_UNITS", "START_FRACTION", "run_report", "steady_window", "toml_text"]

FloatArray = npt.NDArray[np.float64]

START_FRACTION = 0.1
"""The start-up left out of the spectra and most probable maxima: this fraction of the record (or of the first
stage)."""

LAY_SUMMARY_UNITS: dict[str, str] = {
    "top_tension": "N",
    "departure_angle": "rad",
    "liftoff_roller": "1",
    "liftoff_arc_length": "m",
    "inflection_arc_length": "m",
    "layback": "m",
    "touchdown_arc_length": "m",
    "overbend_strain": "1",
    "sagbend_strain": "1",
    "sagbend_moment": "N m",
    "tip_clearance": "m",
}
"""The units of the lay summary's series (``Results.lay_summary()``)."""

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
        Keyword arguments of ``pipelay.checks.dnv_st_f101`` (e.g. ``{"grade": "X65"}``) for the utilisation;
        None: its defaults. Used only for a pipe section with a wall thickness.

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
        _checks(results, model, checks),
        _series(results, model, storm),
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
                row.append(value_cell(record[column], id=f"stage-{k}-{column}"))
        rows.append(row)
    units = {"start": "s", "end": "s", "head_x": "m", "head_z": "m", "head_height_min": "m"}
    units |= {name: "N" for name in ("wire_tension_max", "wire_tension_min", "pipe_force_min")}
    units |= {name: "m" for name in ("touchdown_min", "touchdown_max", "tip_clearance_min")}
    units |= {"roller_reaction_max": "N", "top_tension_max": "N", "top_tension_min": "N"}
    header = [column if column not in units else f"{column} ({units[column]})" for column in columns]
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
        rows = []
        for key, series in summary.items():
            values = np.asarray(series, dtype=np.float64)
            finite = values[np.isfinite(values)]
            low, mean, high = (
                (float(finite.min()), float(finite.mean()), float(finite.max()))
                if finite.size
                else (None,) * 3
            )
            rows.append(
                [
                    Cell(key, header=True),
                    value_cell(low, id=f"lay-{key}-min"),
                    value_cell(mean, id=f"lay-{key}-mean"),
                    value_cell(high, id=f"lay-{key}-max"),
                    LAY_SUMMARY_UNITS.get(key, ""),
                ]
            )
        parts.append(
            html.subsection(
                "Lay summary", html.table(["series", "min", "mean", "max", "unit"], rows, id="lay-summary")
            )
        )
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
        rows.append(
            [
                Cell(key, header=True),
                value_cell(value, id=f"extreme-{key}"),
                STATISTICS[key][0] if key in STATISTICS else "",
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
        said.append(
            f"DNV-ST-F101 local buckling with {json.dumps(dnv, default=str) if dnv else 'its default parameters'}"
        )
    parts.append(
        html.subsection(
            "Extremes",
            html.paragraph("Elements are numbered from 0 at end A; " + "; ".join(said) + "."),
            html.table(["quantity", "value", "unit", "time (s)", "element", "meaning"], rows, id="extremes"),
        )
    )
    return html.section("checks", "Lay summary and code checks", *parts)


# --- time series and spectra -----------------------------------------------------------------------------


def steady_window(results: Results, model: Model | None = None) -> tuple[float, float, str]:
    """The records the spectra and most probable maxima are taken over: (start, end) (s) and a sentence that
    says which. The start-up left out is `START_FRACTION` of the first stage (a staged run) or of the record,
    and at least the waves' build-up (``model.sea.waves.ramp``, from t = 0) when the model has waves.
    """
    time = np.asarray(results.time, dtype=np.float64)
    starts, names = results.stage_starts, results.stage_names
    if starts is not None and names and len(starts) >= 2:
        begin, end = float(starts[0]), float(starts[1])
        said = f"the first stage ({names[0]}) from its {START_FRACTION:.0%} mark"
    else:
        begin, end = float(time[0]), float(time[-1])
        said = f"the record from its {START_FRACTION:.0%} mark"
    start = begin + START_FRACTION * (end - begin)
    sea = model.sea if model is not None else None
    waves = sea.waves if sea is not None else None
    if waves is not None and waves.ramp > start:
        start = float(waves.ramp)
        said += f", moved to the end of the waves' build-up at t = {start:g} s"
    return start, end, f"{said}: t = {start:g} s to {end:g} s"


def _series(results: Results, model: Model | None, storm: float) -> Markup:
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
        ("top_tension", "The force of the pipe at end B", lambda: plots.top_tension(results)),
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
    parts.append(_spectra(results, model, storm))
    return html.section("series", "Time series and spectra", *parts)


def _top_tension(results: Results) -> FloatArray:
    """|F_B| (T,) (N): the force of the pipe on what holds end B."""
    force = np.asarray(results.reaction("B"), dtype=np.float64)[:, :3]
    top: FloatArray = np.linalg.norm(force, axis=1)
    return top


def _hang_off_moment(results: Results) -> FloatArray:
    """The bending moment |(M2, M3)| (T,) (N·m) of the top element of each record (the hang-off)."""
    forces = np.asarray(results.section_forces, dtype=np.float64)
    top = top_elements(np.asarray(results.segment, dtype=np.float64))
    rows = np.arange(len(top))
    moment: FloatArray = np.hypot(forces[rows, top, 4], forces[rows, top, 5])
    return moment


def _spectra(results: Results, model: Model | None, storm: float) -> Markup:
    """The response spectra of the top tension and the hang-off moment, and the top tension's MPMs."""
    time = np.asarray(results.time, dtype=np.float64)
    start, end, said = steady_window(results, model)
    inside = (time >= start - 1e-9 * max(1.0, abs(start))) & (time <= end + 1e-9 * max(1.0, abs(end)))
    window = time[inside]
    heading = "Response spectra and most probable maxima"
    where = Markup(
        f'<p id="window" data-start="{start!r}" data-end="{end!r}" data-records="{window.size}">'
        f"{html.escape(f'Taken over {said} ({window.size} records), the start-up left out.')}</p>"
    )
    series = {
        "top_tension": _top_tension(results)[inside],
        "hang_off_moment": _hang_off_moment(results)[inside],
    }
    top = series["top_tension"]
    if window.size < MIN_SAMPLES or not np.all(np.isfinite(top)) or np.ptp(top) <= 0.0:
        reason = (
            f"{window.size} records, fewer than {MIN_SAMPLES}"
            if window.size < MIN_SAMPLES
            else "the top tension does not vary"
        )
        return html.subsection(heading, where, html.note(f"spectra skipped: {reason}", kind="skipped"))
    steps = np.diff(window)
    dt = float(np.median(steps))
    if np.ptp(steps) > 1e-6 * dt:
        return html.subsection(
            heading, where, html.note("spectra skipped: the records are not evenly spaced", kind="skipped")
        )
    labels = {
        "top_tension": ("top tension |F_B|", "N", 1e3, "kN"),
        "hang_off_moment": ("bending moment of the top element (hang-off)", "N m", 1e3, "kN·m"),
    }
    spectra = {}
    notes: list[str] = []
    for key, values in series.items():
        if not np.all(np.isfinite(values)) or np.ptp(values) <= 1e-9 * max(
            1.0, float(np.max(np.abs(values)))
        ):
            notes.append(html.note(f"no spectrum of the {labels[key][0]}: it does not vary", kind="skipped"))
            continue
        try:
            spectra[key] = response_spectrum(values, dt)
        except InputError as error:
            notes.append(html.note(f"no spectrum of the {labels[key][0]}: {error}", kind="skipped"))
    rows = []
    for key, spectrum in spectra.items():
        rows.append(
            [
                Cell(labels[key][0], header=True),
                value_cell(spectrum.mean, id=f"spectrum-{key}-mean"),
                value_cell(spectrum.std, id=f"spectrum-{key}-std"),
                value_cell(spectrum.tz, id=f"spectrum-{key}-tz"),
                value_cell(spectrum.bandwidth, id=f"spectrum-{key}-bandwidth"),
                value_cell(spectrum.segment, id=f"spectrum-{key}-segment"),
                labels[key][1],
            ]
        )
    parts: list[str] = [where, *notes]
    if spectra:
        parts.append(
            html.figure(_spectrum_figure(spectra, labels), name="spectra", caption="Response spectra")
        )
        parts.append(
            html.table(
                ["series", "mean", "σ", "Tz (s)", "bandwidth ε", "Welch segment (s)", "unit"],
                rows,
                id="spectra",
            )
        )
    parts.append(_maxima(top, dt, storm))
    return html.subsection(heading, *parts)


def _spectrum_figure(spectra: Mapping[str, Any], labels: Mapping[str, tuple[str, str, float, str]]) -> Any:
    """The spectra, one panel each, on an Agg canvas (pyplot is not used)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    chart = Figure(figsize=(9.0, 3.6 * len(spectra)), layout="constrained")
    FigureCanvasAgg(chart)
    axes = chart.subplots(len(spectra), 1, squeeze=False).ravel()
    for axis, (key, spectrum) in zip(axes, spectra.items(), strict=True):
        name, _, scale, unit = labels[key]
        axis.plot(spectrum.frequency, spectrum.density / scale**2, color="k")
        axis.set_xlabel("frequency f (Hz)")
        axis.set_ylabel(f"S(f) ({unit}²/Hz)")
        axis.set_title(
            f"{name}: σ = {spectrum.std / scale:.4g} {unit}, Tz = {spectrum.tz:.3g} s", fontsize=10
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
    rows = []
    for method in METHODS:
        try:
            found = most_probable_maximum(top, dt, storm, method)
        except InputError as error:
            rows.append(
                [
                    Cell(method, header=True),
                    Cell("not computed", id=f"mpm-{method}", data={"value": "nan"}),
                    "N",
                    f"{error}",
                ]
            )
            continue
        fit = ", ".join(f"{key} {html.number(value, 4)}" for key, value in found.parameters.items())
        rows.append([Cell(method, header=True), value_cell(found.value, id=f"mpm-{method}"), "N", fit])
    intro = html.paragraph(
        f"Most probable maxima of the top tension |F_B| over a storm of {storm:g} s ({storm / 3600:.3g} h), from "
        f"{top.size} records of {dt:g} s (largest in the record {html.number(float(top.max()))} N). Each method "
        "assumes a stationary record (see pipelay.analysis.statistics)."
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
