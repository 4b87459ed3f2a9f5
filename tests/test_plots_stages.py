"""The figures of a staged lay (``pipelay.plots.stages``) on a short J-lay run through three stages (lay with
pay-out, hand-over to the A&R winch, lowering on the wire): the plotted data equal the results', one shaded
span and one label per stage, the files `all_figures` adds for a staged run only, and the error for a run
without stages."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay import plots
from pipelay._core import InputError
from pipelay.analysis.stages import head_positions, wire_segments

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
DEPTH = 150.0
STAGES = ("lay", "hand-over", "lower")


def _model() -> pl.Model:
    """A 600 m pipe of 60 elements pinned on the seabed at end A, in 150 m of water, held by a J-lay tower
    (exit 10 m below the vessel's origin, 0.2 rad from vertical) of an OSV with an A&R winch (10 m wire
    elements, a 5 t laydown head)."""
    pipe = pl.Section.pipe(
        outer_diameter=0.6, wall_thickness=0.025, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0)
    )
    wire = pl.Section.cable(diameter=0.08, mass=28.0, EA=5.5e8, drag=(0.0, 1.2), added_mass=(0.0, 1.0))
    rod = pl.Rod.straight((0, 0, 0), (600.0, 0, 0), 60, pipe)
    model = pl.Model(rod, pl.Sea(DEPTH, seabed=pl.Seabed(stiffness=1e5, friction=0.5, mobilisation=0.02)))
    model.pin("A")
    angle = 0.2
    exit_ = np.array([0.0, 0.0, -10.0])
    along = np.array([np.sin(angle), 0.0, -np.cos(angle)])
    head = pl.Clump(mass=5000.0, volume=0.8, drag_area=1.0, added_mass=1.0)
    winch = pl.Winch(exit_ + 5.0 * along, wire=wire, element_length=10.0, head=head)
    eta = [480.0, 0.0, -DEPTH, 0.0, 0.0, 0.0]
    controller = pl.PID(kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=eta)
    model.attach_vessel(
        "B",
        pl.Vessel.osv(),
        eta=eta,
        lay=pl.JLay(position=tuple(exit_), angle=angle),
        controller=controller,
        winch=winch,
    )
    return model


@pytest.fixture(scope="module")
def staged() -> tuple[pl.Model, pl.Results]:
    """The model and its run from statics through the three stages at Δt = 0.5 s (60 s, 121 records)."""
    model = _model()
    stages = pl.Stages(
        [
            pl.Stage(STAGES[0], duration=20.0, pay_out=0.3, route_speed=0.3),
            pl.Stage(STAGES[1], duration=10.0, hold="winch"),
            pl.Stage(STAGES[2], duration=30.0, winch_speed=0.5, route_speed=0.5),
        ]
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)  # the sagbend yields: not what these tests check
        state = model.static()
        results = model.simulation(state, dt=0.5, stages=stages).run(progress=False)
    return model, results


@pytest.fixture(scope="module")
def unstaged() -> pl.Results:
    """The same model run 2 s without stages."""
    model = _model()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        state = model.static()
        return model.simulation(state, dt=0.5).run(2.0, progress=False)


def _last_records(results: pl.Results) -> list[int]:
    """The last record of each stage."""
    return [int(np.flatnonzero(results.stage == k)[-1]) for k in range(len(results.stage_names))]


def _line(axis, label: str):
    """The one line of an axes with this label."""
    (line,) = [line for line in axis.lines if line.get_label() == label]
    return line


def _by_gid(axis, gid: str):
    """The one line of an axes with this gid, or None."""
    found = [line for line in axis.lines if line.get_gid() == gid]
    assert len(found) <= 1
    return found[0] if found else None


def test_the_run_has_the_stages(staged) -> None:
    """What the figures rest on: three stages over 0–20–30–60 s, the wire joined at the hand-over only."""
    model, results = staged
    assert results.stage_names == list(STAGES)
    np.testing.assert_array_equal(results.stage_starts, [0.0, 20.0, 30.0, 60.0])
    wires = wire_segments(results, model)
    assert wires == {1}
    has_wire = np.isin(results.segment, list(wires)).any(axis=1)
    assert not has_wire[results.stage == 0].any()
    assert has_wire[results.stage == 2].all()


def test_stage_tensions(staged, tmp_path: Path) -> None:
    """The top tension equals the lay summary's (kN, exactly); the wire's curve is the largest axial force over
    the wire's elements, NaN before the hand-over; one shaded span per stage over its times, alternately
    shaded, labelled with its name; dotted lines at the two inner boundaries."""
    model, results = staged
    path = tmp_path / "stage_tensions.png"
    figure = plots.stage_tensions(results, path=path, model=model)
    assert path.read_bytes()[:8] == PNG_SIGNATURE
    (axis,) = figure.axes
    assert "(kN)" in axis.get_ylabel() and "(s)" in axis.get_xlabel()

    top = _line(axis, "top tension")
    np.testing.assert_array_equal(top.get_xdata(), results.time)
    np.testing.assert_array_equal(top.get_ydata(), results.lay_summary()["top_tension"] / 1e3)

    is_wire = np.isin(results.segment, list(wire_segments(results, model)))
    axial = np.where(is_wire, results.section_forces[:, :, 0], np.nan)
    wire = _line(axis, "A&R wire, largest").get_ydata()
    before = ~is_wire.any(axis=1)
    assert before.sum() == np.count_nonzero(results.stage == 0)  # the lay stage's 41 records, t = 0 … 20 s
    assert np.all(np.isnan(wire[before]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN rows before the hand-over
        expected = np.nanmax(axial, axis=1) / 1e3
    np.testing.assert_allclose(wire[~before], expected[~before], rtol=0, atol=0)
    assert np.nanmax(wire) > 2 * np.max(top.get_ydata()[before])  # the wire carries more than the tower did

    spans = axis.patches
    assert len(spans) == len(STAGES)
    starts = results.stage_starts
    for k, span in enumerate(spans):  # a Rectangle from the stage's start to its end (s)
        np.testing.assert_array_equal([span.get_x(), span.get_x() + span.get_width()], starts[k : k + 2])
    colours = [span.get_facecolor() for span in spans]
    assert colours[0] != colours[1] and colours[0] == colours[2]
    assert [text.get_text() for text in axis.texts] == list(STAGES)
    np.testing.assert_allclose([text.get_position()[0] for text in axis.texts], [10.0, 25.0, 45.0])
    boundaries = [line for line in axis.lines if line.get_linestyle() == ":"]
    assert [line.get_xdata()[0] for line in boundaries] == [20.0, 30.0]


def test_stage_tensions_without_the_model(staged) -> None:
    """Without the model the wire is found from the segments: the same curve."""
    model, results = staged
    with_model = _line(plots.stage_tensions(results, model=model).axes[0], "A&R wire, largest")
    without = _line(plots.stage_tensions(results).axes[0], "A&R wire, largest")
    np.testing.assert_array_equal(without.get_ydata(), with_model.get_ydata())


def test_stage_configurations(staged, tmp_path: Path) -> None:
    """Per stage, the line at its last record: pipe (solid) and wire (dashed) together are that record's
    nodes, x and −z; the wire's nodes are those of the wire's elements; the head ● is head_positions there
    (none in the lay stage, before the hand-over); seabed at 0 and sea surface at the depth."""
    model, results = staged
    path = tmp_path / "stage_configurations.png"
    figure = plots.stage_configurations(results, path=path, depth=DEPTH, model=model)
    assert path.read_bytes()[:8] == PNG_SIGNATURE
    (axis,) = figure.axes
    assert "(m)" in axis.get_xlabel() and "−z (m)" in axis.get_ylabel()
    heads = head_positions(results, model)
    wires = list(wire_segments(results, model))
    last = _last_records(results)
    assert [results.time[r] for r in last] == [20.0, 30.0, 60.0]
    for k, r in enumerate(last):
        nodes = results.positions[r]
        nodes = nodes[np.all(np.isfinite(nodes), axis=1)]
        pipe = _by_gid(axis, f"pipe:{k}")
        wire = _by_gid(axis, f"wire:{k}")
        head = _by_gid(axis, f"head:{k}")
        assert pipe.get_label() == f"{STAGES[k]} (t = {results.time[r]:g} s)"
        assert pipe.get_linestyle() == "-"
        px, pz = pipe.get_xdata(), pipe.get_ydata()
        if k == 0:
            assert wire is None and head is None
            np.testing.assert_array_equal(px, nodes[:, 0])
            np.testing.assert_array_equal(pz, -nodes[:, 2])
            continue
        assert wire.get_linestyle() == "--" and wire.get_color() == pipe.get_color()
        wx, wz = wire.get_xdata(), wire.get_ydata()
        np.testing.assert_array_equal(np.where(np.isfinite(px), px, wx), nodes[:, 0])
        np.testing.assert_array_equal(np.where(np.isfinite(pz), pz, wz), -nodes[:, 2])
        is_wire = np.isin(results.segment[r, : len(nodes) - 1], wires)
        first = int(np.argmax(is_wire))  # the head: the wire's first node
        assert np.all(is_wire[first:]) and not np.any(is_wire[:first])
        assert np.all(np.isfinite(wx[first:])) and np.all(np.isnan(wx[:first]))
        assert np.all(np.isfinite(px[: first + 1])) and np.all(np.isnan(px[first + 1 :]))
        np.testing.assert_array_equal(head.get_xdata(), [heads[r, 0]])
        np.testing.assert_array_equal(head.get_ydata(), [-heads[r, 2]])
        np.testing.assert_array_equal(heads[r], nodes[first])
    assert _line(axis, "seabed (z = 0)").get_ydata()[0] == 0.0
    assert _line(axis, f"sea surface (−z = {DEPTH:g} m)").get_ydata()[0] == DEPTH
    assert not any(
        "sea surface" in line.get_label() for line in plots.stage_configurations(results).axes[0].lines
    )


def test_all_figures_adds_the_stages(staged, unstaged, tmp_path: Path) -> None:
    """all_figures writes the two stage figures, last, for a staged run, and not for one without stages."""
    _, results = staged
    written = plots.all_figures(results, tmp_path / "staged", depth=DEPTH)
    assert [path.name for path in written[-2:]] == ["stage_tensions.png", "stage_configurations.png"]
    for path in written[-2:]:
        data = path.read_bytes()
        assert data[:8] == PNG_SIGNATURE and len(data) > 10_000
    assert {path.name for path in (tmp_path / "staged").iterdir()} == {path.name for path in written}
    plain = plots.all_figures(unstaged, tmp_path / "plain", depth=DEPTH)
    stage_files = {"stage_tensions.png", "stage_configurations.png"}
    assert not stage_files & {path.name for path in written[:-2]}
    assert {path.name for path in plain} <= {path.name for path in written[:-2]}  # no pay-out: no track
    assert not stage_files & {path.name for path in (tmp_path / "plain").iterdir()}


@pytest.mark.parametrize("figure", [plots.stage_tensions, plots.stage_configurations])
def test_a_run_without_stages(figure, unstaged) -> None:
    """Results of a run without stages: pl.InputError naming `results` and the figure."""
    assert unstaged.stage is None
    with pytest.raises(InputError, match=rf"^results: .*\({figure.__name__}\).*without stages"):
        figure(unstaged)
