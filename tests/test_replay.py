"""The 3-D replay (`pipelay.plots.replay`) and the video (`pipelay.plots.video`) of real runs.

The references: the run's own records (positions, section forces, η), the engine's roller positions of the
static state, R(η) written out here (zyx Euler angles), the waves' elevation from `model.sea.waves`; in the
browser (headless Chromium, WebGL on SwiftShader) what the page shows, screenshot against screenshot.

The runs: a DP vessel holding a 12-element pipe in a JONSWAP sea (the scenario of test_fatigue_damage.py,
60 s), the S-lay of examples/s_lay.toml cut to 40 elements (rollers) and the J-lay of j_lay_waves.toml cut
to 28 elements (a tower); a fraction of a second each.
"""

from __future__ import annotations

import itertools
import tomllib
from pathlib import Path
from types import SimpleNamespace

import imageio_ffmpeg
import numpy as np
import pipelay as pl
import pytest
from browser import changed_fraction, distinct_colours, open_page, settled_screenshot, wait_for_plotly
from dp_in_waves import scenario_text
from pipelay.analysis import extremes
from pipelay.plots.replay import COLOURS, replay, replay_html
from pipelay.plots.video import video
from pipelay.scenario import apply_overrides, parse_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

# The tests' DP vessel in waves (tests/dp_in_waves.py): 12 elements, 800 m of water, 150 records of 0.4 s.
DP_SCENARIO = scenario_text("replay test: DP vessel in waves, pipe on the seabed")

TRACES = ("seabed", "sea surface", "pipe", "vessel", "rollers", "tower", "touchdown")


def _run(data: dict, t_end: float, record_every: int, dt: float | None = None) -> tuple[pl.Results, pl.Model]:
    scenario = parse_scenario(data)
    model = scenario.model
    state = model.static()
    simulation = model.simulation(state=state, dt=dt or scenario.dt)
    return simulation.run(t_end, record_every=record_every), model


@pytest.fixture(scope="module")
def dp() -> tuple[pl.Results, pl.Model]:
    return _run(tomllib.loads(DP_SCENARIO), 60.0, 2)


@pytest.fixture(scope="module")
def s_lay() -> tuple[pl.Results, pl.Model, pl.State]:
    # Without bumpless transfer, the PID drops the holding thrust at its start and the vessel (and its rollers)
    # moves; the example's own DP holds it within centimetres.
    overrides = {"rod.elements": 40, "controller.bumpless": False}
    data = apply_overrides(tomllib.loads((EXAMPLES / "s_lay.toml").read_text()), overrides)
    scenario = parse_scenario(data)
    static = scenario.model.static()
    results = scenario.model.simulation(state=static, dt=0.2).run(12.0, record_every=2)
    return results, scenario.model, static


@pytest.fixture(scope="module")
def j_lay() -> tuple[pl.Results, pl.Model]:
    data = apply_overrides(
        tomllib.loads((EXAMPLES / "j_lay_waves.toml").read_text()),
        {"rod.elements": 28, "sea.waves.components": 40},
    )
    return _run(data, 20.0, 5, dt=0.2)


def rotation(eta: np.ndarray) -> np.ndarray:
    """R(η) = Rz(ψ) Ry(θ) Rx(φ), body to e, written out as Fossen does."""
    phi, theta, psi = eta[3:6]
    rx = np.array([[1, 0, 0], [0, np.cos(phi), -np.sin(phi)], [0, np.sin(phi), np.cos(phi)]])
    ry = np.array([[np.cos(theta), 0, np.sin(theta)], [0, 1, 0], [-np.sin(theta), 0, np.cos(theta)]])
    rz = np.array([[np.cos(psi), -np.sin(psi), 0], [np.sin(psi), np.cos(psi), 0], [0, 0, 1]])
    return rz @ ry @ rx


def trace(figure, name: str) -> int:
    """The index of the trace called `name`."""
    names = [t.name for t in figure.data]
    assert name in names, f"no trace {name!r} in {names}"
    return names.index(name)


def frame_points(figure, frame: int, name: str) -> np.ndarray:
    """The points (m, 3) of trace `name` in a frame, in frame e (the elevation turned back into z)."""
    index = trace(figure, name)
    data = figure.frames[frame].data[list(figure.frames[frame].traces).index(index)]
    points = np.column_stack(
        [np.asarray(data.x, float), np.asarray(data.y, float), -np.asarray(data.z, float)]
    )
    return points


def matched_records(figure, results: pl.Results) -> list[int]:
    """The record each frame shows: the record at the time of its slider step, checked to be the one whose
    positions the frame's pipe has (to 1 cm)."""
    steps = figure.layout.sliders[0].steps
    assert [s.args[0][0] for s in steps] == [f.name for f in figure.frames]  # a step a frame, in order
    records = []
    for j, step in enumerate(steps):
        k = int(np.argmin(np.abs(results.time - float(step.label))))
        assert abs(results.time[k] - float(step.label)) < 1e-3
        pipe = frame_points(figure, j, "pipe")
        nodes = results.positions[k][np.all(np.isfinite(results.positions[k]), axis=1)]
        assert pipe.shape == nodes.shape
        np.testing.assert_allclose(pipe, nodes, atol=0.0051, err_msg=f"frame {j} is not record {k}")
        records.append(k)
    return records


# --- the figure --------------------------------------------------------------------------------------------


def test_the_frames_are_the_records_decimated_with_the_tension_on_the_nodes(dp) -> None:
    results, model = dp
    figure = replay(results, model, max_frames=40, title="DP")
    count = len(results.time)
    assert count > 40
    records = matched_records(figure, results)
    assert len(figure.frames) == 40
    assert records[0] == 0 and records[-1] == count - 1
    assert all(b > a for a, b in itertools.pairwise(records))  # in order, without repeats
    gaps = np.diff(records)
    assert gaps.max() - gaps.min() <= 1  # evenly spaced

    # the colour: N1 (kN) on the nodes, the average of the elements either side, an end element's at an end
    tension = results.section_forces[:, :, 0] / 1e3
    pipe = trace(figure, "pipe")
    for j, k in enumerate(records):
        expected = np.concatenate(
            [[tension[k, 0]], 0.5 * (tension[k, 1:] + tension[k, :-1]), [tension[k, -1]]]
        )
        shown = np.asarray(figure.frames[j].data[list(figure.frames[j].traces).index(pipe)].line.color, float)
        np.testing.assert_allclose(shown, expected, rtol=6e-4)

    # one colour scale over the whole run (every record, not only those shown) with its unit
    line = figure.data[pipe].line
    on_nodes = np.concatenate(
        [tension[:, :1], 0.5 * (tension[:, 1:] + tension[:, :-1]), tension[:, -1:]], axis=1
    )
    assert line.cmin <= on_nodes.min() and line.cmax >= on_nodes.max()
    assert (line.cmin, line.cmax) == pytest.approx((tension.min(), tension.max()), rel=1e-12)
    # the range is the run's, not only the frames': two frames, the same scale
    two = replay(results, model, max_frames=2).data[pipe].line
    assert (two.cmin, two.cmax) == (line.cmin, line.cmax)
    shown = tension[[0, -1]]
    assert shown.min() > tension.min() or shown.max() < tension.max()
    assert "kN" in line.colorbar.title.text

    layout = figure.layout
    title = layout.title.text
    assert "DP" in title and "tension" in title and f"{results.time[-1]:g}" in title
    assert [layout.scene.xaxis.title.text, layout.scene.yaxis.title.text] == ["x (m)", "y (m)"]
    assert "−z (m)" in layout.scene.zaxis.title.text
    # the controls: play/pause, the speeds, the camera presets, a slider of the frames' times
    labels = [b.label for menu in layout.updatemenus for b in menu.buttons]
    for wanted in ("▶ play", "❚❚ pause", "▶ ×1", "▶ ×2", "▶ ×4", "side", "plan", "along the pipe"):
        assert wanted in labels
    speeds = [
        b.args[1]["frame"]["duration"] for menu in layout.updatemenus for b in menu.buttons if "×" in b.label
    ]
    assert speeds[0] == 2 * speeds[1] == 4 * speeds[2]
    # a true aspect ratio: the box's sides in proportion to the axes' ranges
    scene = layout.scene
    spans = np.array([np.ptp(scene.xaxis.range), np.ptp(scene.yaxis.range), np.ptp(scene.zaxis.range)])
    ratio = np.array([scene.aspectratio.x, scene.aspectratio.y, scene.aspectratio.z])
    np.testing.assert_allclose(ratio / ratio[0], spans / spans[0], rtol=1e-9)


def test_the_vessel_the_sea_and_the_seabed(dp) -> None:
    results, model = dp
    figure = replay(results, model, max_frames=12)
    records = matched_records(figure, results)
    eta = results.eta
    length = model.vessel.length
    body = None
    for j, k in enumerate(records):
        hull = frame_points(figure, j, "vessel")
        here = (hull - eta[k, :3]) @ rotation(eta[k])  # R(η)ᵀ (p − η[:3]), row by row
        if body is None:
            body = here
            # an outline of the vessel's length, centred on CO
            assert np.ptp(body[:, 0]) == pytest.approx(length, abs=0.02)
            assert 0.5 * (body[:, 0].max() + body[:, 0].min()) == pytest.approx(0.0, abs=0.02)
            assert 0.5 * (body[:, 1].max() + body[:, 1].min()) == pytest.approx(0.0, abs=0.02)
        np.testing.assert_allclose(here, body, atol=0.02)  # the same hull at every pose: it follows η
    assert np.abs(eta[records[-1], :2] - eta[0, :2]).max() > 0.05  # and η did move

    # the sea surface at depth + the waves' elevation (up) at each frame's time; the seabed flat at 0
    waves, depth = model.sea.waves, model.sea.depth
    sea = trace(figure, "sea surface")
    assert sea in figure.frames[0].traces
    x, y = np.asarray(figure.data[sea].x, float), np.asarray(figure.data[sea].y, float)
    largest = 0.0
    for j, k in enumerate(records):
        surface = np.asarray(figure.frames[j].data[list(figure.frames[j].traces).index(sea)].z, float)
        assert surface.shape == (len(y), len(x))
        for jy, ix in ((0, 0), (3, 17), (len(y) - 1, len(x) - 1), (12, 5)):
            elevation = float(waves.elevation(results.time[k], x[ix], y[jy])[0])
            assert surface[jy, ix] == pytest.approx(depth + elevation, abs=0.006)
            largest = max(largest, abs(elevation))
    assert largest > 0.1  # the waves are there: the sign is checked, not 0 = −0
    seabed = np.asarray(figure.data[trace(figure, "seabed")].z, float)
    np.testing.assert_array_equal(seabed, 0.0)
    assert "seabed" not in [figure.data[i].name for i in figure.frames[0].traces]  # static: sent once

    # the touchdown marker where the results have one
    touchdown = results.touchdown
    for j, k in enumerate(records):
        point = frame_points(figure, j, "touchdown")
        if np.all(np.isfinite(touchdown[k])):
            np.testing.assert_allclose(point[0], touchdown[k], atol=0.006)
        else:
            assert len(point) == 0


def test_the_rollers_move_with_the_vessel(s_lay) -> None:
    results, model, static = s_lay
    figure = replay(results, model, max_frames=8, colour="moment")
    records = matched_records(figure, results)
    assert records[0] == 0
    # frame 0 is the static state: its rollers are the engine's
    np.testing.assert_allclose(frame_points(figure, 0, "rollers"), static.roller_positions, atol=0.006)
    body = (static.roller_positions - static.eta[:3]) @ rotation(static.eta)
    eta = results.eta
    for j, k in enumerate(records):
        np.testing.assert_allclose(
            frame_points(figure, j, "rollers"), eta[k, :3] + body @ rotation(eta[k]).T, atol=0.006
        )
    moved = frame_points(figure, len(records) - 1, "rollers") - frame_points(figure, 0, "rollers")
    assert np.abs(moved).max() > 0.5
    assert "tower" not in [t.name for t in figure.data]
    moment = np.hypot(results.section_forces[:, :, 4], results.section_forces[:, :, 5]) / 1e3
    line = figure.data[trace(figure, "pipe")].line
    assert line.cmax == pytest.approx(moment.max(), rel=1e-3) and "kN·m" in line.colorbar.title.text


def test_a_j_lay_tower_runs_up_the_pipes_end(j_lay) -> None:
    results, model = j_lay
    figure = replay(results, model, max_frames=5, colour="utilisation")
    records = matched_records(figure, results)
    tangent = results.rotations[:, -1, :, 0]
    for j, k in enumerate(records):
        base, top = frame_points(figure, j, "tower")
        np.testing.assert_allclose(base, results.positions[k, -1], atol=0.006)
        np.testing.assert_allclose((top - base) / 30.0, tangent[k], atol=1e-3)
        assert top[2] < base[2] - 25.0  # up (e3 points down)
    assert "rollers" not in [t.name for t in figure.data]
    utilisation = extremes.utilisation(results, model=model, checks={})
    line = figure.data[trace(figure, "pipe")].line
    assert line.cmax == pytest.approx(np.nanmax(utilisation), rel=1e-3)
    assert "safety class medium" in figure.layout.title.text  # the basis under the title
    # the parameters given are those coloured by, and said so
    low = replay(results, model, max_frames=5, colour="utilisation", checks={"safety_class": "low"})
    lower = extremes.utilisation(results, model=model, checks={"safety_class": "low"})
    assert low.data[trace(low, "pipe")].line.cmax == pytest.approx(np.nanmax(lower), rel=1e-3)
    assert np.nanmax(lower) < np.nanmax(utilisation) and "safety class low" in low.layout.title.text


def test_without_a_model_the_results_alone_are_drawn(dp) -> None:
    results, _ = dp
    figure = replay(results, max_frames=3, colour="moment")
    names = [t.name for t in figure.data]
    assert names == ["seabed", "sea surface", "pipe", "vessel", "touchdown"]
    body = (frame_points(figure, 0, "vessel") - results.eta[0, :3]) @ rotation(results.eta[0])
    assert np.ptp(body[:, 0]) == pytest.approx(80.0, abs=0.02)  # the default hull
    # a flat sea at results.water's depth, sent once (no waves known)
    sea = trace(figure, "sea surface")
    assert sea not in figure.frames[0].traces
    np.testing.assert_array_equal(np.asarray(figure.data[sea].z, float), results.water[0])
    for frame in figure.frames:
        for data in frame.data:
            for axis in ("x", "y", "z"):
                assert np.all(np.isfinite(np.asarray(getattr(data, axis), float)))


def test_a_record_without_its_last_nodes_draws_the_nodes_it_has(dp) -> None:
    """Pay-out: the records before the mesh grew are NaN beyond their last node (end B)."""
    results, model = dp
    positions, forces = results.positions.copy(), results.section_forces.copy()
    half = len(results.time) // 2
    positions[:half, -3:] = np.nan
    forces[:half, -3:] = np.nan
    grown = SimpleNamespace(
        time=results.time, positions=positions, section_forces=forces, eta=results.eta,
        touchdown=results.touchdown, water=results.water, segment=results.segment,
    )  # fmt: skip
    figure = replay(grown, model, max_frames=2)
    pipe = trace(figure, "pipe")
    first, last = (f.data[list(f.traces).index(pipe)] for f in figure.frames)
    assert len(first.x) == len(first.line.color) == positions.shape[1] - 3
    assert len(last.x) == len(last.line.color) == positions.shape[1]
    tension = forces[0, :, 0] / 1e3
    assert float(first.line.color[-1]) == pytest.approx(tension[-4], rel=6e-4)  # end B's element's value
    assert np.all(np.isfinite(np.asarray(first.x, float))) and np.all(
        np.isfinite(np.asarray(first.line.color))
    )
    div = replay_html(grown, model, max_frames=2, full_html=False)
    assert div.lstrip().startswith("<div") and "Plotly.newPlot" in div and "plotly.js v" not in div


# --- bad input ---------------------------------------------------------------------------------------------


def test_bad_input_names_the_argument(dp, s_lay) -> None:
    results, model = dp
    with pytest.raises(
        pl.InputError, match=r'colour: "temperature" is not allowed; allowed: tension, moment'
    ):
        replay(results, model, colour="temperature")
    with pytest.raises(pl.InputError, match=r'colour: "utilisation" needs a model'):
        replay(results, colour="utilisation")
    with pytest.raises(pl.InputError, match=r'colour: "strain" needs a model'):
        replay_html(results, colour="strain")
    for bad in (1, 0, 2.5, True):
        with pytest.raises(pl.InputError, match=r"max_frames: .* an integer >= 2"):
            replay(results, model, max_frames=bad)
    with pytest.raises(pl.InputError, match=r"view: "):
        video(results, "never.mp4", model, view="top")
    assert set(COLOURS) == {"tension", "moment", "strain", "utilisation"}
    # strain: the section's N1/EA + (d/2)|κ|, in %
    s_results, s_model, _ = s_lay
    figure = replay(s_results, s_model, max_frames=2, colour="strain")
    section = s_model.rod.section
    f = s_results.section_forces
    ei2, ei3 = section.EI
    strain = 100 * (
        f[..., 0] / section.EA + 0.5 * section.outer_diameter * np.hypot(f[..., 4] / ei2, f[..., 5] / ei3)
    )
    assert figure.data[trace(figure, "pipe")].line.cmax == pytest.approx(strain.max(), rel=1e-3)


# --- in the browser ----------------------------------------------------------------------------------------


def test_the_page_draws_and_answers_the_slider_and_the_cameras(dp, tmp_path: Path) -> None:
    """The slider is moved by clicks on its rail (real mouse events), the camera by a click on a preset."""
    results, model = dp
    page_path = tmp_path / "run.html"
    replay(results, model, max_frames=30, path=page_path)
    text = page_path.read_text(encoding="utf-8")
    assert "plotly.js v" in text and "<html>" in text  # self-contained: plotly.js inline
    assert not any(p.name.endswith(".part") for p in tmp_path.iterdir())
    canvas = ".js-plotly-plot .gl-container canvas"
    with open_page(page_path) as (page, errors):
        wait_for_plotly(page)
        first = settled_screenshot(page, canvas)
        assert distinct_colours(first) > 200 and first.std() > 10.0, "the 3-D scene looks blank"

        rail = page.locator(".slider-rail-rect").first.bounding_box()
        active = "() => document.querySelector('.js-plotly-plot')._fullLayout.sliders[0].active"

        def click(fraction: float) -> np.ndarray:
            page.mouse.click(rail["x"] + fraction * rail["width"], rail["y"] + rail["height"] / 2)
            return settled_screenshot(page, canvas)

        early = click(0.1)
        early_frame = page.evaluate(active)
        late = click(0.9)
        late_frame = page.evaluate(active)
        again = click(0.1)
        assert early_frame < late_frame and page.evaluate(active) == early_frame
        assert changed_fraction(early, late) > 1e-3, "moving the slider did not change the picture"
        assert changed_fraction(early, again) < 1e-4, "the same frame drew differently"

        page.get_by_text("plan", exact=True).click()
        plan = settled_screenshot(page, canvas)
        assert changed_fraction(again, plan) > 0.05, "the plan camera did not change the picture"
        assert errors == []


# --- the video ---------------------------------------------------------------------------------------------


def test_the_video_has_the_frames_asked(s_lay, tmp_path: Path) -> None:
    results, model, _ = s_lay
    assert len(results.time) > 12
    path = video(results, tmp_path / "run.mp4", model, max_frames=12, fps=10, dpi=50, view="both")
    assert path == tmp_path / "run.mp4" and path.stat().st_size > 1000
    assert [p.name for p in tmp_path.iterdir()] == ["run.mp4"]  # the temporary renamed into place
    frames, seconds = imageio_ffmpeg.count_frames_and_secs(path)
    assert frames == 12 and seconds == pytest.approx(1.2, abs=0.05)
    reader = imageio_ffmpeg.read_frames(path)
    meta = next(reader)
    assert meta["codec"] == "h264" and meta["size"] == (640, 360)
    width, height = meta["size"]
    images = [np.frombuffer(f, np.uint8).reshape(height, width, 3) for f in reader]
    assert len(images) == 12
    below_title = slice(int(0.08 * height), height)  # the title's time changes anyway: compare the drawing
    assert changed_fraction(images[0][below_title], images[-1][below_title], tolerance=40) > 1e-4


def test_pipelay_view_and_report_read_the_scenario_the_file_keeps(tmp_path: Path) -> None:
    """`pipelay run` then `pipelay view` (replay and video) and `pipelay report`: the replay built from the file
    alone draws the rollers of the scenario it keeps, exactly as the API's replay with the scenario's model; a
    file that keeps no scenario still gives a replay (without rollers) and says so."""
    from pipelay import cli
    from pipelay.results import load
    from pipelay.scenario import load_scenario

    data = tomllib.loads((EXAMPLES / "s_lay.toml").read_text())
    text = (EXAMPLES / "s_lay.toml").read_text()
    text = text.replace(f"elements = {data['rod']['elements']}", "elements = 40")
    text = text.replace(f"t_end = {data['solver']['t_end']}", "t_end = 2.0")
    text = "\n".join(line for line in text.splitlines() if not line.startswith("plot_times"))
    (tmp_path / "s_lay.toml").write_text(text)
    run = tmp_path / "run.nc"
    assert cli.main(["run", str(tmp_path / "s_lay.toml"), "-o", str(run), "--no-progress"]) == 0
    assert cli.main(["view", str(run), "--video", str(tmp_path / "run.mp4"), "--frames", "6"]) == 0
    page = (tmp_path / "run.html").read_text().replace(" ", "")
    assert '"name":"rollers"' in page  # the rollers of the scenario kept in the file
    assert (tmp_path / "run.mp4").stat().st_size > 1000
    model = load_scenario(tmp_path / "s_lay.toml").model
    assert any(t.name == "rollers" for t in replay(load(run), model, max_frames=6).data)
    assert cli.main(["report", str(run)]) == 0
    report = (tmp_path / "run-report.html").read_text()
    assert "S-lay" in report and "plotly" in report
    bare = load(run).to_netcdf(tmp_path / "bare.nc")
    assert cli.main(["view", str(bare), "-o", str(tmp_path / "bare.html")]) == 0
    assert '"name":"rollers"' not in (tmp_path / "bare.html").read_text().replace(" ", "")
