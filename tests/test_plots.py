"""The figures of ``pipelay.plots`` on short real runs, with a vessel (the paper's scenario, 40 s) and without
(the driven pipe of the energy example, 2 s): files written as PNG, axes, units in the labels, the requested
times in the legends, the plotted data, and errors."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from matplotlib.figure import Figure
from pipelay import plots

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import energy_verification
import jensen2009 as paper

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
REFERENCE = [780.0, 0.0, np.nan, np.nan, np.nan, 0.0]  # the PD's η_ref in x, y, ψ (m, rad); NaN: not drawn


@pytest.fixture(scope="module")
def vessel_run() -> tuple[pl.State, pl.Results]:
    """The paper's PD scenario (n = 10), statics and 40 s at Δt = 0.5 s: records at 0, 0.5, …, 40 s."""
    model = paper.scenario(paper.controllers()["PD"], 10)
    state = model.static()
    return state, model.simulation(state=state, dt=0.5).run(40.0, progress=False)


@pytest.fixture(scope="module")
def pipe_run() -> tuple[pl.State, pl.Results]:
    """The driven pipe without a vessel (n = 20, straight at rest), 2 s at Δt = 0.05 s."""
    model = energy_verification.model()
    state = model.rest()
    return state, model.simulation(state=state, dt=0.05).run(2.0, progress=False)


def assert_png(path: Path) -> None:
    """A real picture: PNG signature and more than 10 kB."""
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) > 10_000, len(data)


def legend_texts(axis) -> list[str]:
    """The texts of an axes' legend."""
    return [text.get_text() for text in axis.get_legend().get_texts()]


@pytest.mark.parametrize(
    ("run", "times", "depth"), [("vessel_run", (0.0, 20.0, 40.0), 800.0), ("pipe_run", (0.0, 1.0, 2.0), None)]
)
def test_shape(run: str, times: tuple[float, ...], depth: float | None, tmp_path: Path, request) -> None:
    """Side and plan views at the requested times; the sea surface and seabed only with a depth."""
    _, results = request.getfixturevalue(run)
    path = tmp_path / "shape.png"
    figure = plots.shape(results, times=times, path=path, depth=depth)
    assert isinstance(figure, Figure)
    assert_png(path)
    side, plan = figure.axes
    assert len(figure.axes) == 2
    assert "(m)" in side.get_xlabel() and "−z (m)" in side.get_ylabel() and "y (m)" in plan.get_ylabel()
    for axis in (side, plan):
        assert [f"t = {t:g} s" for t in times] == legend_texts(axis)[: len(times)]
    assert any("sea surface" in text for text in legend_texts(side)) == (depth is not None)
    # The side view plots elevation −z of the nodes at the last requested time.
    np.testing.assert_allclose(side.lines[len(times) - 1].get_ydata(), -results.positions[-1, :, 2])


def test_shape_shows_the_nearest_record(vessel_run) -> None:
    """A time between records shows the nearest record, labelled with its own time; repeats are dropped."""
    _, results = vessel_run
    figure = plots.shape(results, times=(19.9, 20.1))
    assert legend_texts(figure.axes[0]) == ["t = 20 s"]
    with pytest.raises(ValueError, match="times"):
        plots.shape(results, times=())


def test_vessel_motion(vessel_run, tmp_path: Path) -> None:
    """Six panels of η in m and degrees; η_ref dotted only where it is given (not NaN)."""
    _, results = vessel_run
    path = tmp_path / "vessel_motion.png"
    figure = plots.vessel_motion(results, reference=REFERENCE, path=path)
    assert_png(path)
    assert len(figure.axes) == 6
    labels = [axis.get_ylabel() for axis in figure.axes]
    units = ["(m)", "(deg)", "(m)", "(deg)", "(m,", "(deg)"]  # subplot order: row by row
    assert all(unit in label for unit, label in zip(units, labels, strict=True))
    assert "(s)" in figure.axes[-1].get_xlabel()
    with_reference = [axis.get_legend() is not None for axis in figure.axes]
    assert with_reference == [True, False, True, False, False, True]  # x, φ, y, θ, z, ψ
    np.testing.assert_allclose(figure.axes[5].lines[0].get_ydata(), np.degrees(results.eta[:, 5]))


def test_vessel_motion_needs_a_vessel(pipe_run, vessel_run) -> None:
    """No vessel, or a reference of the wrong shape: ValueError naming the problem."""
    with pytest.raises(ValueError, match="vessel"):
        plots.vessel_motion(pipe_run[1])
    with pytest.raises(ValueError, match="reference"):
        plots.vessel_motion(vessel_run[1], reference=[780.0, 0.0])


def test_the_set_point_is_drawn_where_the_controller_holds_the_vessel(vessel_run) -> None:
    """`pipelay run`'s vessel figure draws η_ref, labelled as the DP set-point, only in the degrees of freedom
    K_p holds, in e as η: for examples/jensen2009.toml (kp = [5e5, 5e5, 0, 0, 0, 0]) at x = 780 m and y = 0,
    and not z = 0 against the vessel's z = −800 m (heave is free, kp_z = 0). A 6×6 K_p holds the rows that are
    not zero; a lay-tension loop moves the set-point in x and y, which are then not drawn."""
    from pipelay.cli import _reference
    from pipelay.scenario import load_scenario, parse_scenario

    examples = Path(__file__).resolve().parents[1] / "examples"
    reference = _reference(load_scenario(examples / "jensen2009.toml"))
    assert reference is not None
    assert reference[:2] == [780.0, 0.0] and np.isnan(reference[2:]).all()
    _, results = vessel_run
    figure = plots.vessel_motion(results, reference=reference)
    x, _, y, _, z, _ = figure.axes
    for axis, value in ((x, 780.0), (y, 0.0)):
        assert axis.lines[1].get_label() == "η_ref (DP set-point)"
        np.testing.assert_array_equal(axis.lines[1].get_ydata(), np.full(len(results.time), value))
    assert len(z.lines) == 1 and z.get_legend() is None
    assert np.all(z.lines[0].get_ydata() < -799.0)  # the vessel's z, the only line there

    data = tomllib.loads((examples / "s_lay.toml").read_text())
    data["controller"]["kp"] = np.diag([2e5, 2e5, 0.0, 0.0, 0.0, 3.5e7]).tolist()
    matrix = _reference(parse_scenario(data))
    assert matrix is not None and matrix[:2] == [660.0, 0.0] and matrix[5] == 0.0
    assert np.isnan(matrix[2:5]).all()
    data["controller"]["tension"] = {"target": 1e6, "gain": 3e-7}
    moving = _reference(parse_scenario(data))
    assert moving is not None and np.isnan(moving[:5]).all() and moving[5] == 0.0


def test_top_tension_on_the_vessel(vessel_run, tmp_path: Path) -> None:
    """At the vessel's end: the pipe's force on the vessel, χ turned into e (here β = 0, so by the end
    node's rotation), in kN."""
    _, results = vessel_run
    path = tmp_path / "top_tension.png"
    figure = plots.top_tension(results, path=path)
    assert_png(path)
    (axis,) = figure.axes
    assert "(kN)" in axis.get_ylabel() and "(s)" in axis.get_xlabel()
    assert "vessel" in axis.get_title()
    force = np.einsum("tij,tj->ti", results.rotations[:, -1], results.chi[:, :3]) / 1e3
    top, magnitude, horizontal, vertical = (line.get_ydata() for line in axis.lines)
    # First the top tension, the effective tension of the top element (the lay summary's), below |F_B|.
    np.testing.assert_array_equal(top, results.lay_summary()["top_tension"] / 1e3)
    assert np.all(top < magnitude)
    np.testing.assert_allclose(magnitude, np.linalg.norm(force, axis=1))
    np.testing.assert_allclose(horizontal, np.hypot(force[:, 0], force[:, 1]), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(vertical, force[:, 2], rtol=1e-9, atol=1e-9)
    assert np.all(vertical > 0.0)  # the hanging pipe pulls the vessel down (+e3)


def test_top_tension_on_a_support(pipe_run) -> None:
    """Without a vessel: the reaction on the support; a bad end is a ValueError."""
    _, results = pipe_run
    figure = plots.top_tension(results, end="A")
    assert "support at end A" in figure.axes[0].get_title()
    np.testing.assert_allclose(
        figure.axes[0].lines[0].get_ydata(), np.linalg.norm(results.reaction("A")[:, :3], axis=1) / 1e3
    )
    with pytest.raises(ValueError, match="end"):
        plots.top_tension(results, end="C")


@pytest.mark.parametrize("run", ["vessel_run", "pipe_run"])
def test_tension_and_bending_of_results(run: str, tmp_path: Path, request) -> None:
    """Two panels against the midpoints' arc length, one curve per requested time."""
    _, results = request.getfixturevalue(run)
    times = (results.time[0], results.time[-1])
    path = tmp_path / "tension_bending.png"
    figure = plots.tension_and_bending(results, times=times, path=path)
    assert_png(path)
    tension, bending = figure.axes
    assert "(kN)" in tension.get_ylabel() and "(kN·m)" in bending.get_ylabel()
    assert "(m)" in bending.get_xlabel()
    for axis in (tension, bending):
        assert legend_texts(axis) == [f"t = {t:g} s" for t in times]
    np.testing.assert_allclose(tension.lines[1].get_ydata(), results.tension[-1] / 1e3)
    moment = results.section_forces[-1, :, 4:]
    np.testing.assert_allclose(bending.lines[1].get_ydata(), np.hypot(moment[:, 0], moment[:, 1]) / 1e3)


def test_tension_and_bending_of_a_state(pipe_run) -> None:
    """A State: one curve at its time; arc length of the midpoints of the straight 100 m pipe of 20
    elements at rest: 2.5, 7.5, …, 97.5 m. Times with a State are an error."""
    state, _ = pipe_run
    figure = plots.tension_and_bending(state)
    assert len(figure.axes) == 2
    assert legend_texts(figure.axes[0]) == ["t = 0 s"]
    np.testing.assert_allclose(figure.axes[0].lines[0].get_xdata(), np.arange(2.5, 100.0, 5.0))
    with pytest.raises(ValueError, match="times"):
        plots.tension_and_bending(state, times=(0.0,))


@pytest.mark.parametrize(("run", "vessel"), [("vessel_run", True), ("pipe_run", False)])
def test_energy(run: str, vessel: bool, tmp_path: Path, request) -> None:
    """Energy changes, work and dissipation in kJ or MJ; the balance residual in J, at round-off."""
    _, results = request.getfixturevalue(run)
    path = tmp_path / "energy.png"
    figure = plots.energy(results, path=path)
    assert_png(path)
    top, bottom = figure.axes
    assert "(kJ)" in top.get_ylabel() or "(MJ)" in top.get_ylabel()
    assert "(J)" in bottom.get_ylabel() and "(s)" in bottom.get_xlabel()
    texts = legend_texts(top)
    assert "supplied work W" in texts and "dissipated D" in texts
    assert ("Δ vessel kinetic" in texts) == vessel
    residual = bottom.lines[0].get_ydata()
    scale = np.max(np.abs(results.energy["total"]))
    assert np.max(np.abs(residual)) < 1e-9 * scale


@pytest.mark.parametrize(("run", "count"), [("vessel_run", 5), ("pipe_run", 4)])
def test_all_figures(run: str, count: int, tmp_path: Path, request) -> None:
    """Every applicable figure under its fixed name; the vessel's only with a vessel."""
    _, results = request.getfixturevalue(run)
    written = plots.all_figures(results, tmp_path / "figures", reference=REFERENCE, depth=800.0)
    names = {"shape.png", "top_tension.png", "tension_bending.png", "energy.png"}
    if count == 5:
        names.add("vessel_motion.png")
    assert len(written) == count
    assert {path.name for path in written} == names
    assert {path.name for path in (tmp_path / "figures").iterdir()} == names
    for path in written:
        assert_png(path)
