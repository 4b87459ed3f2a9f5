"""The HTML reports of a run and of a sweep (pipelay.report): the numbers they print are those of the analysis
functions (extremes, most probable maxima, the lay summary, the passivity margin, a sweep's ranking), the
figures and replays they promise are there, the scenario's TOML data reads back as the scenario, the page is
valid HTML, and it opens in a real browser without an error, its replay drawn.

The pages are parsed with `html.parser`; every number of a table is in a cell whose id names it and whose
``data-value`` holds it exactly.
"""

from __future__ import annotations

import base64
import functools
import math
import tomllib
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from browser import open_page, screenshot, wait_for_plotly
from dp_in_waves import scenario_text
from pipelay.analysis.extremes import extremes
from pipelay.analysis.statistics import METHODS, most_probable_maximum, stationarity
from pipelay.analysis.sweep import STATISTICS
from pipelay.report import run_report, sweep_report
from pipelay.report.html import number
from pipelay.report.run import steady_window
from pipelay.scenario import apply_overrides, mark_results, parse_scenario

# The tests' DP vessel in waves (tests/dp_in_waves.py: a DP vessel holding a 12-element pipe on the seabed, in a
# JONSWAP sea), run for 300 s instead of 60: 676 records after the start-up, enough for all three most probable
# maximum methods (10 Tz for Rayleigh, 30 peaks for Weibull). A fraction of a second.
SCENARIO = scenario_text("report test: DP vessel in waves, pipe on the seabed", t_end=300.0)

TITLE = "report test: DP vessel in waves, pipe on the seabed"
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


class Page(HTMLParser):
    """A parsed page: its tags' balance and counts, its <title>, <h1> and <meta charset>, the text and
    attributes of each element with an id, the figures, images, links and scripts."""

    def __init__(self, text: str) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[str] = []
        self.mismatches: list[str] = []
        self.counts: dict[str, int] = {}
        self.attributes: dict[str, dict[str, str]] = {}
        self.texts: dict[str, str] = {}
        self.open: list[tuple[str, int]] = []  # (id, depth)
        self.figures: list[str] = []
        self.images: list[str] = []
        self.links: list[str] = []
        self.scripts: list[str] = []
        self.title = self.heading = self.charset = ""
        self.feed(text)
        self.close()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {key: value or "" for key, value in attrs}
        self.counts[tag] = self.counts.get(tag, 0) + 1
        if tag == "meta" and "charset" in values:
            self.charset = values["charset"]
        if tag == "figure" and "data-name" in values:
            self.figures.append(values["data-name"])
        if tag == "img":
            self.images.append(values.get("src", ""))
        if tag == "a":
            self.links.append(values.get("href", ""))
        if tag == "script":
            self.scripts.append("")
        if "id" in values:
            assert values["id"] not in self.attributes, f"id {values['id']} twice"
            self.attributes[values["id"]] = values
        if tag in VOID:
            return
        self.stack.append(tag)
        if "id" in values:
            self.texts[values["id"]] = ""
            self.open.append((values["id"], len(self.stack)))

    def handle_endtag(self, tag: str) -> None:
        if tag in VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.mismatches.append(f"</{tag}> closes <{self.stack[-1] if self.stack else None}>")
            return
        if self.open and self.open[-1][1] == len(self.stack):
            self.open.pop()
        self.stack.pop()

    def handle_data(self, data: str) -> None:
        for name, _ in self.open:
            self.texts[name] += data
        inside = self.stack[-1] if self.stack else None
        if inside == "script":
            self.scripts[-1] += data
        elif inside == "title":
            self.title += data
        elif inside == "h1":
            self.heading += data

    def text(self, id: str) -> str:
        """The text of the element `id`, stripped."""
        return self.texts[id].strip()

    def value(self, id: str, attribute: str = "data-value") -> float:
        """The number in the attribute of the element `id` (by default its exact value)."""
        return float(self.attributes[id][attribute])


def parse(path: Path, title: str) -> Page:
    """The page at `path`, checked: UTF-8, one html, head, body, title and h1 (both `title`), tags balanced."""
    page = Page(path.read_text(encoding="utf-8"))
    assert page.charset == "utf-8"
    assert not page.mismatches and not page.stack, (page.mismatches, page.stack)
    for tag in ("html", "head", "body", "title", "h1"):
        assert page.counts.get(tag) == 1, tag
    assert page.title == title and page.heading == title
    return page


# --- a run -----------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def scenario() -> Any:
    return parse_scenario(tomllib.loads(SCENARIO))


@pytest.fixture(scope="module")
def results(scenario: Any) -> pl.Results:
    model = scenario.model
    simulation = model.simulation(state=model.static(), dt=scenario.dt)
    return simulation.run(scenario.t_end, record_every=scenario.record_every, progress=False)


@pytest.fixture(scope="module")
def report(results: pl.Results, scenario: Any, tmp_path_factory: pytest.TempPathFactory) -> Path:
    return run_report(results, tmp_path_factory.mktemp("run") / "run.html", scenario=scenario)


def test_run_report_prints_the_numbers_of_the_analysis(
    report: Path, results: pl.Results, scenario: Any
) -> None:
    """The extremes, lay summary, passivity margin and MPMs in the page are those of the functions: printed by
    their labels in the units people read (kN, kN·m, degrees, percent), their SI values exact in data-value
    with their SI unit in data-unit; the figures are those that apply; the scenario's data reads back; the
    page is valid."""
    page = parse(report, TITLE)
    model = scenario.model

    found = extremes(results, model=model, checks={})  # the section has a wall thickness: DNV checks
    assert "utilisation_max" in found
    for key, scale, unit, label in [
        ("top_tension_max", 1e-3, "N", "largest top tension"),
        ("top_tension_min", 1e-3, "N", "smallest top tension"),
        ("reaction_B_max", 1e-3, "N", "largest reaction at B |F_B|"),
        ("moment_max", 1e-3, "N m", "largest bending moment"),
        ("strain_max", 100.0, "1", "largest strain"),
        ("utilisation_max", 1.0, "1", "largest DNV-ST-F101 utilisation"),
    ]:
        assert page.text(f"extreme-{key}") == number(found[key] * scale)
        assert page.value(f"extreme-{key}") == found[key]
        assert page.attributes[f"extreme-{key}"]["data-unit"] == unit
        assert page.value(f"extreme-{key}-time") == found[f"{key}_time"]
        assert label in page.text("extremes")
    assert "top_tension_max" not in page.text("extremes") and "lay_top_tension" not in page.text("extremes")
    assert page.text("extreme-strain_max-element") == str(found["strain_max_element"])
    assert page.text("extreme-top_tension_max-element") == "—"  # a value at the top: no element

    # The top tension is the lay summary's (the tension the vessel holds), not the reaction |F_B|.
    lay = results.lay_summary()
    assert lay is not None
    reaction = np.linalg.norm(results.reaction("B")[:, :3], axis=1)
    assert found["top_tension_max"] == float(np.nanmax(lay["top_tension"]))
    assert found["reaction_B_max"] == float(reaction.max())
    assert found["reaction_B_max"] > 1.02 * found["top_tension_max"]  # |F_B| also carries the shear
    assert page.value("lay-top_tension-max") == float(np.nanmax(lay["top_tension"]))
    assert page.text("lay-top_tension-max") == number(float(np.nanmax(lay["top_tension"])) / 1e3)
    assert page.value("lay-layback-mean") == float(np.nanmean(lay["layback"]))
    departure = float(np.nanmax(lay["departure_angle"]))
    assert page.text("lay-departure_angle-max") == number(math.degrees(departure))
    assert page.value("lay-departure_angle-max") == departure
    assert page.attributes["lay-departure_angle-max"]["data-unit"] == "rad"
    assert page.text("lay-sagbend_strain-max") == number(100.0 * float(np.nanmax(lay["sagbend_strain"])))
    lay_rows = page.text("lay-summary")
    assert all(label in lay_rows for label in ("top tension", "departure angle", "sagbend strain", "kN", "°"))
    assert "top_tension" not in lay_rows and "departure_angle" not in lay_rows
    # a J-lay tower, no stinger: no overbend, lift-off roller or tip clearance rows
    assert results.roller_reactions is None
    assert (
        "overbend" not in lay_rows and "lift-off roller" not in lay_rows and "tip clearance" not in lay_rows
    )
    assert "lay-overbend_strain-max" not in page.attributes
    assert page.value("passivity-margin") == results.passivity_margin()

    # The stationary part: the top tension passes the stationarity test from the end of the waves' 10 s
    # build-up (the scenario's latest start), so the window starts at its first record there.
    time = results.time
    inside = time >= 10.0 - 1e-6
    top = lay["top_tension"][inside]
    assert page.value("window", "data-start") == pytest.approx(10.0, rel=1e-9)
    assert int(page.attributes["window"]["data-records"]) == inside.sum() == len(time) - 25
    measured = stationarity(top, 0.4)
    print(f"window from t = 10 s: {measured}")
    assert "waves' build-up (sea.waves.ramp)" in page.text("window")
    assert page.value("spectrum-top_tension-std") == pytest.approx(float(np.std(top)), rel=0.05)
    for method in METHODS:
        expected = most_probable_maximum(top, 0.4, 10800.0, method).value
        assert page.value(f"mpm-{method}") == pytest.approx(expected, rel=1e-12), method
        assert page.text(f"mpm-{method}") == number(expected / 1e3)
        assert page.attributes[f"mpm-{method}"]["data-unit"] == "N"
    assert page.value("mpm-rayleigh") > top.max()  # 3 h against 290 s

    names = ["shape", "top_tension", "vessel_motion", "touchdown", "tension_and_bending", "energy", "spectra"]
    assert page.figures == names
    assert len(page.images) == len(names)
    for source in page.images:
        prefix = "data:image/png;base64,"
        assert source.startswith(prefix)
        assert base64.b64decode(source[len(prefix) :])[:8] == b"\x89PNG\r\n\x1a\n"

    assert tomllib.loads(page.text("scenario-data")) == scenario.source
    assert "report test: DP vessel in waves" in page.text("provenance")
    model_facts = page.text("model")
    assert "elements12" in model_facts.replace("\n", "") and "waves Tp (s)8" in model_facts.replace("\n", "")


def test_the_replay_is_embedded_with_plotly_once(report: Path) -> None:
    text = report.read_text(encoding="utf-8")
    page = parse(report, TITLE)
    assert 'id="replay"' in text and "replay not available" not in text
    assert text.count("plotly.js v") == 1  # the library's banner: included once, in the head
    head, _, body = text.partition("</head>")
    assert "plotly.js v" in head and "Plotly.newPlot" in body
    assert "plotly-graph-div" in text[text.index('id="replay"') :]
    assert not page.mismatches


def test_a_results_file_brings_its_scenario_and_bad_files_are_refused(
    results: pl.Results, scenario: Any, tmp_path: Path
) -> None:
    """A results file marked with its scenario reports its title and model; replay=False leaves the replay
    (and plotly.js) out; a file that is not a results file raises pl.load's InputError."""
    file = tmp_path / "run.nc"
    results.to_netcdf(file)
    mark_results(file, scenario)
    written = run_report(file, tmp_path / "sub" / "run.html", replay=False)
    assert written == tmp_path / "sub" / "run.html"
    page = parse(written, TITLE)
    assert "replay" not in page.attributes and not any("plotly" in script for script in page.scripts)
    assert str(file) in page.text("provenance")
    assert "extreme-utilisation_max" in page.attributes  # the stored model's section: DNV checks
    assert not list((tmp_path / "sub").glob(".*"))  # no temporary left behind

    bare = tmp_path / "bare.nc"
    results.to_netcdf(bare)  # no scenario: no model, no strain, "not recorded"
    page = parse(run_report(bare, tmp_path / "bare.html", replay=False, title="bare"), "bare")
    assert "not recorded" in page.text("provenance") and "extreme-strain_max" not in page.attributes

    text_file = tmp_path / "notes.nc"
    text_file.write_text("not a results file")
    with pytest.raises(pl.InputError) as raised:
        run_report(text_file, tmp_path / "never.html")
    with pytest.raises(pl.InputError) as direct:
        pl.load(text_file)
    assert str(raised.value) == str(direct.value)
    assert not (tmp_path / "never.html").exists()


# --- the stationary part, stages ---------------------------------------------------------------------------

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _example(name: str, t_end: float) -> tuple[Any, pl.Results]:
    """examples/<name>.toml run to `t_end` (s) from its statics, as `pipelay run` runs it (kept in memory)."""
    data = tomllib.loads((EXAMPLES / f"{name}.toml").read_text(encoding="utf-8"))
    data["solver"]["t_end"] = t_end
    data.pop("output", None)
    scenario = parse_scenario(data, f"{name}.toml")
    model = scenario.model
    simulation = model.simulation(
        state=model.static(scenario.static_steps, scenario.static_start), dt=scenario.dt
    )
    return scenario, simulation.run(t_end, record_every=scenario.record_every, progress=False)


def test_a_calm_start_up_gets_no_spectra_or_maxima(tmp_path: Path) -> None:
    """examples/s_lay.toml, 60 s in calm water (its current from t = 10 s, its controller from 5 s): the top
    tension settles (it falls by tens of kN), so the page refuses the spectra and most probable maxima, says
    why, and shows no storm maximum; the lay summary's lift-off roller is numbered from 1."""
    scenario, results = _example("s_lay", 60.0)
    page = parse(
        run_report(results, tmp_path / "s_lay.html", scenario=scenario, replay=False),
        scenario.source["title"],
    )
    text = page.text("series")
    print(text[text.index("Response spectra") :])
    assert "spectra and most probable maxima refused: results: the top tension from t = 10 s" in text
    assert "(the current's start (sea.current.start))" in text and "has a trend" in text
    assert "window" not in page.attributes and "mpm-gumbel" not in page.attributes and "storm" not in text
    lay = results.lay_summary()
    assert lay is not None and results.roller_reactions is not None
    last = int(np.nanmax(lay["liftoff_roller"]))
    rollers = results.roller_reactions.shape[1]
    assert page.text("lay-liftoff_roller-max") == f"roller {last + 1} of {rollers}"
    assert page.value("lay-liftoff_roller-max") == last  # the Python index, from 0
    assert results.roller_reactions[np.nanargmax(lay["liftoff_roller"]), last] > 0.0  # it carries the pipe


def test_a_pipelay_run_in_waves_is_stationary_after_its_ramp() -> None:
    """examples/j_lay_waves.toml for 300 s (its waves built up over 30 s): the window starts at the end of
    the build-up or later, within the first half of the rest, and the top tension there is stationary."""
    scenario, results = _example("j_lay_waves", 300.0)
    start, end, said = steady_window(results, scenario.model, scenario)
    print(said)
    assert scenario.model.sea.waves.ramp == 30.0
    assert 30.0 - 1e-9 <= start <= 30.0 + 0.5 * (300.0 - 30.0) and end == pytest.approx(300.0)
    assert "sea.waves.ramp" in said
    inside = results.time >= start - 1e-9
    found = stationarity(results.lay_summary()["top_tension"][inside], 0.2)
    assert found.periods >= 30 and abs(found.trend) <= 0.25


def test_the_stage_table_shows_labels_and_units(tmp_path: Path) -> None:
    """A staged J-lay (tests/test_scenario_stages.py, 50 s): the stage table's columns are labelled, forces in
    kN and strains in percent, each cell keeping the stage summary's SI value and unit; its first stage (20 s,
    the spectra's window) is too short for spectra, which the page says."""
    from test_scenario_stages import STAGED

    scenario = parse_scenario(tomllib.loads(STAGED), "staged.toml")
    simulation = scenario.model.simulation(
        state=scenario.model.static(), dt=scenario.dt, stages=scenario.stages
    )
    results = simulation.run(scenario.t_end, progress=False)
    page = parse(
        run_report(results, tmp_path / "staged.html", scenario=scenario, replay=False),
        scenario.source["title"],
    )
    summary = results.stage_summary(scenario.model)
    table = page.text("stages")
    assert "largest top tension (kN)" in table and "largest strain (%)" in table and "start (s)" in table
    # a J-lay tower has no stinger: its lay summary has no overbend, lift-off roller or tip clearance
    lay = page.text("lay-summary")
    assert "departure angle" in lay and "sagbend strain" in lay
    assert "overbend" not in lay and "lift-off roller" not in lay and "tip clearance" not in lay
    assert "top_tension_max" not in table
    for k in range(3):
        top = float(summary["top_tension_max"][k])
        assert page.value(f"stage-{k}-top_tension_max") == top
        assert page.text(f"stage-{k}-top_tension_max") == number(top / 1e3)
        assert page.attributes[f"stage-{k}-top_tension_max"]["data-unit"] == "N"
        assert page.text(f"stage-{k}-strain_max") == number(100.0 * float(summary["strain_max"][k]))
    assert "spectra and most probable maxima refused: results: the top tension from t = 0 s" in page.text(
        "series"
    )


# --- a sweep ---------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def swept(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Any]:
    """Two sea states of the scenario in 40 s runs, and two cases with a negative wall thickness that fail on
    their worker (InputError from the factory)."""
    pytest.importorskip("distributed")
    data = tomllib.loads(SCENARIO)
    data["solver"]["t_end"] = 40.0
    factory = functools.partial(apply_overrides, data)
    folder = tmp_path_factory.mktemp("sweep") / "out"
    over = {"sea.waves.hs": [1.5, 2.5], "pipe.wall_thickness": [0.03, -0.01]}
    done = pl.sweep(factory, over, output=folder, workers=1, progress=False)
    return folder, done


@pytest.fixture(scope="module")
def swept_report(swept: tuple[Path, Any]) -> Path:
    """The sweep's report, with the replay of its worst case by each statistic."""
    return sweep_report(swept[0], replays=1)


def test_sweep_report_ranks_links_replays_and_lists_failures(
    swept: tuple[Path, Any], swept_report: Path
) -> None:
    folder, done = swept
    written = swept_report
    assert written == folder / "report.html"
    page = parse(written, "pipelay sweep report: partial")
    summary = done.summary
    assert [page.text(f"count-{k}") for k in ("cases", "finished", "failed")] == ["4", "2", "2"]

    # The failures, with their messages.
    assert len(done.failures) == 2
    messages = [page.text(f"failure-{k}-error") for k in range(2)]
    assert sorted(messages) == sorted(done.failures.values())
    assert all(message.startswith("InputError: pipe.wall_thickness") for message in messages)

    # The ranking follows the summary; the worst case of each statistic has its replay, linked relatively.
    worst = set()
    for name in ("utilisation_max", "top_tension_max", "strain_max"):
        values = summary[name].values.ravel()
        order = np.argsort(-np.where(np.isfinite(values), values, -np.inf))[:2]
        assert [page.value(f"worst-{name}-{rank}-{name}") for rank in range(2)] == values[order].tolist()
        names = summary["case"].values.ravel()[order].tolist()
        assert [page.attributes[f"worst-{name}-{rank}"]["data-case"] for rank in range(2)] == names
        assert f"worst-{name}-2" not in page.attributes  # two cases finished
        worst.add(names[0])
        assert page.text(f"worst-{name}-0-replay") == "replay"
    replays = {path.stem for path in (folder / "cases").glob("*.html")}
    assert replays == worst
    links = [link for link in page.links if link.endswith(".html")]
    assert {(written.parent / link).resolve() for link in links} == {
        (folder / "cases" / f"{name}.html").resolve() for name in worst
    }
    assert all((written.parent / link).is_file() for link in links)

    # A map per statistic with values, and every case in the summary table.
    statistics = [n for n in STATISTICS if n in summary and np.isfinite(summary[n].values).any()]
    assert page.figures == [f"operability-{name}" for name in statistics]
    assert all(source.startswith("data:image/png;base64,") for source in page.images)
    assert [page.attributes[f"case-{k}"]["data-case"] for k in range(4)] == summary[
        "case"
    ].values.ravel().tolist()
    assert page.value("case-0-top_tension_max") == summary["top_tension_max"].values[0, 0]
    # Labelled, in the units people read; the SI value and unit in the cell's data.
    assert page.text("case-0-top_tension_max") == number(summary["top_tension_max"].values[0, 0] / 1e3)
    assert page.attributes["case-0-top_tension_max"]["data-unit"] == "N"
    assert page.text("case-0-strain_max") == number(100.0 * summary["strain_max"].values[0, 0])
    table = page.text("summary")
    assert "largest top tension (kN)" in table and "largest strain (%)" in table and "(N)" not in table


def test_a_one_key_sweep_has_lines_and_a_folder_without_summary_is_refused(
    swept: tuple[Path, Any], tmp_path: Path
) -> None:
    folder, done = swept
    one = done.summary.isel({"pipe.wall_thickness": 0}, drop=True)
    one.attrs["swept_keys"] = '["sea.waves.hs"]'
    (tmp_path / "one").mkdir()
    one.to_netcdf(tmp_path / "one" / "summary.nc", engine="h5netcdf")
    (tmp_path / "one" / "cases").symlink_to(folder / "cases")
    page = parse(
        sweep_report(tmp_path / "one", tmp_path / "one.html", replays=0), "pipelay sweep report: partial"
    )
    assert len(page.figures) == len([n for n in STATISTICS if n in one and np.isfinite(one[n].values).any()])
    assert not [link for link in page.links if link.endswith(".html")]
    assert page.text("count-cases") == "2" and page.text("count-failed") == "0"

    with pytest.raises(pl.InputError, match="^folder: no summary.nc in"):
        sweep_report(tmp_path / "nothing")
    with pytest.raises(pl.InputError, match="^replays"):
        sweep_report(folder, replays=-1)


# --- in a browser ----------------------------------------------------------------------------------------


def test_the_reports_open_in_a_browser_without_errors_and_the_replay_draws(
    report: Path, swept_report: Path
) -> None:
    """No console or page error; the replay's WebGL canvas draws: hiding it changes much of the plot."""
    with open_page(report) as (page, errors):
        assert page.title() == TITLE
        assert page.locator("figure.plot img").count() == 7
        plot = "#replay .js-plotly-plot"
        wait_for_plotly(page, plot)
        drawn = screenshot(page, plot).astype(np.int64)
        page.evaluate(
            "document.querySelectorAll('#replay canvas').forEach(c => c.style.visibility = 'hidden')"
        )
        page.wait_for_timeout(300)
        bare = screenshot(page, plot).astype(np.int64)
        # The scene (its light background, grid, seabed and pipe) covers a good part of the plot (13 %).
        assert np.mean(np.abs(drawn - bare).max(axis=2) > 8) > 0.05
        assert not errors, errors
    with open_page(swept_report) as (page, errors):
        assert page.locator("#worst table").count() == 3
        assert not errors, errors
