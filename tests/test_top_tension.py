"""One top tension: the effective tension the tensioner, the tower or the top support holds, the same number in
the Python statistics, the extremes, a sweep's statistics, `pipelay run`'s summary, the figure and the report.

References, read from the results directly: for an S-lay and a J-lay (examples/s_lay.toml and
examples/j_lay_waves.toml, 20 s) the lay summary's ``top_tension`` (the engine's axial force of the element at
the tensioner or the tower); for a flooded pipe hanging between two pins (examples/hanging_pipe.toml, 5 s) the
effective axial force N1 of the element at end B, from ``section_forces``. None is the reaction's magnitude
|F_B|, which also carries the shear and, for the S-lay, the pipe's pull beyond the tensioner: each differs from
it.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay import plots
from pipelay.analysis.statistics import extremes, top_tension
from pipelay.analysis.sweep import _Recorded, case_statistics, run, start
from pipelay.cli import _run_summary
from pipelay.report import run_report
from pipelay.report.html import number
from pipelay.scenario import parse_scenario
from test_report import parse

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture(scope="module", params=["s_lay", "j_lay_waves", "hanging_pipe"])
def streamed(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """The example run as `pipelay run` runs it (streamed to a results file that keeps its scenario), the
    results read back, and the reference top tension (T,) (N)."""
    data = tomllib.loads((EXAMPLES / f"{request.param}.toml").read_text(encoding="utf-8"))
    data.pop("output", None)
    if request.param == "hanging_pipe":
        data["solver"] = {"dt": 0.1, "t_end": 5.0}
    else:
        data["solver"]["t_end"] = 20.0
    scenario = parse_scenario(data, f"{request.param}.toml")
    path = tmp_path_factory.mktemp(request.param) / "run.nc"
    run(start(scenario), scenario, path)
    results = pl.load(path)
    summary = results.lay_summary()
    if request.param != "hanging_pipe":
        assert summary is not None
        reference = np.asarray(summary["top_tension"])
    else:
        assert summary is None  # no vessel
        reference = results.section_forces[:, -1, 0]  # the element at end B
    return {"kind": request.param, "scenario": scenario, "path": path, "results": results, "top": reference}


def test_the_top_tension_is_the_tension_held_not_the_reaction(streamed: dict[str, Any]) -> None:
    """`top_tension` is the reference exactly; the reaction |F_B| exceeds it (by 8 % at the start of the S-lay,
    0.5 % for the J-lay, by the weight of half an element for the hanging pipe)."""
    results, reference = streamed["results"], streamed["top"]
    top = top_tension(results)
    reaction = np.linalg.norm(results.reaction("B")[:, :3], axis=1)
    print(f"{streamed['kind']}: top tension {top.max():.1f} N, |F_B| {reaction.max():.1f} N")
    np.testing.assert_array_equal(top, reference)
    assert np.all(reaction > top * 1.001)


def test_every_consumer_shows_the_same_top_tension(streamed: dict[str, Any], tmp_path: Path) -> None:
    """The extremes, a sweep's case statistics (read from the file), `pipelay run`'s summary lines, the
    top_tension figure's first curve and the report's cells all give the reference's extremes; the reaction
    is shown beside them under its own name."""
    results, reference, path = streamed["results"], streamed["top"], streamed["path"]
    model = streamed["scenario"].model
    reaction = np.linalg.norm(results.reaction("B")[:, :3], axis=1)

    found = extremes(results, model=model)
    assert (found["top_tension_max"], found["top_tension_min"]) == (reference.max(), reference.min())
    assert found["reaction_B_max"] == reaction.max()
    assert "lay_top_tension_max" not in found

    statistics = case_statistics(_Recorded.read(path), model)
    assert (statistics["top_tension_max"], statistics["top_tension_min"]) == (
        reference.max(),
        reference.min(),
    )
    assert statistics["reaction_B_max"] == reaction.max()

    text = _run_summary(path)
    print(text)
    lines = {line[:24].strip(): line[24:].strip() for line in text.splitlines()}
    assert lines["top tension"] == f"{reference.min() / 1e3:10.1f} … {reference.max() / 1e3:.1f} kN".strip()
    assert (
        lines["reaction at B |F_B|"]
        == f"{reaction.min() / 1e3:10.1f} … {reaction.max() / 1e3:.1f} kN".strip()
    )
    assert not any(line.startswith("lay: top tension") for line in text.splitlines())
    # The overbend strain is printed for a stinger only: not for a J-lay tower.
    assert ("lay: overbend strain" in text) == (streamed["kind"] == "s_lay")

    figure = plots.top_tension(results)
    (axis,) = figure.axes
    np.testing.assert_array_equal(axis.lines[0].get_ydata(), reference / 1e3)
    assert axis.lines[0].get_label() == "top tension" and axis.lines[1].get_label() == "reaction at B |F_B|"
    np.testing.assert_allclose(axis.lines[1].get_ydata(), reaction / 1e3, rtol=1e-12)

    page = parse(run_report(path, tmp_path / "run.html", replay=False), streamed["scenario"].source["title"])
    assert page.value("extreme-top_tension_max") == reference.max()
    assert page.text("extreme-top_tension_max") == number(reference.max() / 1e3)  # in kN
    assert page.value("extreme-reaction_B_max") == reaction.max()
    assert "largest reaction at B |F_B|" in page.text("extremes")
