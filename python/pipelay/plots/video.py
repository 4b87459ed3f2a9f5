"""The video of a run: a matplotlib animation of what the 3-D replay shows, in a side elevation (x against −z),
a plan (x against y) or both, written as an H.264 MP4 by ffmpeg (the binary of imageio-ffmpeg) or as a GIF.

Usage::

    from pipelay.plots.video import video

    video(results, "run.mp4", model, colour="moment", fps=20, view="both")

Each frame shows the pipe coloured like the replay (one colour scale over the run, with its colour bar), the
vessel's hull at the record's pose, its rollers or J-lay tower, the touchdown point, and in the side view the
seabed under the line and the sea surface (with the waves at the frame's time when the model has them); the
title says the time. Drawn on an Agg canvas (pyplot is not used) and written atomically: to a temporary file
in the same folder, renamed into place when complete.

Imports of pipelay: `pipelay.plots.replay` (what is drawn) and `pipelay.analysis.checks` (input errors).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np
from matplotlib.animation import AbstractMovieWriter, FFMpegWriter, PillowWriter
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from pipelay._core import Model, Results
from pipelay.analysis.checks import _input_error
from pipelay.plots.replay import Scene, prepare

__all__ = ["VIEWS", "video"]

VIEWS = ("side", "plan", "both")
"""The views of a video: the side elevation (x against −z), the plan (x against y), both (side above plan)."""

_SUFFIXES = (".mp4", ".m4v", ".mov", ".mkv", ".gif")
_SEA_POINTS = 200  # points of the side view's sea surface line


def _positive(argument: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _input_error(argument, value, "a finite number > 0")
    number = float(value)
    if not np.isfinite(number) or number <= 0.0:
        raise _input_error(argument, value, "a finite number > 0")
    return number


def _even(inches: float, dpi: float) -> float:
    """A figure size (inches) of an even number of pixels at `dpi` (H.264 in yuv420p needs even sizes)."""
    pixels = 2 * max(round(inches * dpi / 2), 8)
    return (pixels + 0.25) / dpi  # a quarter pixel over: Agg truncates the size


class _Panel:
    """One view's artists, updated frame by frame."""

    def __init__(self, axis: Axes, scene: Scene, norm: Normalize, vertical: int) -> None:
        self.axis, self.scene, self.vertical = axis, scene, vertical  # vertical: 2 (side, −z) or 1 (plan, y)
        self.pipe = LineCollection([], cmap="viridis", norm=norm, linewidths=2.2, zorder=3)
        axis.add_collection(self.pipe)
        self.hull = Line2D([], [], color="#222222", linewidth=1.2, zorder=4)
        axis.add_line(self.hull)
        self.gear: Line2D | None = None
        if scene.equipment is not None:
            rollers = scene.equipment[0] == "rollers"
            roller_like = scene.equipment[0].startswith("roller")
            self.gear = Line2D(
                [], [], color="#e8590c" if roller_like else "#7a7a7a", marker="o" if rollers else "",
                markersize=2.5, linestyle="none" if rollers else "-", linewidth=3.0, zorder=5,
                label=scene.equipment[0],
            )  # fmt: skip
            axis.add_line(self.gear)
        self.touchdown = Line2D(
            [], [], color="#d62728", marker="v", markersize=7, linestyle="none", zorder=6, label="touchdown"
        )
        axis.add_line(self.touchdown)

    def update(self, k: int) -> None:
        scene, v = self.scene, self.vertical
        nodes = scene.pipe[k]
        points = nodes[:, [0, v]]
        self.pipe.set_segments(list(np.stack([points[:-1], points[1:]], axis=1)) if len(points) > 1 else [])
        values = scene.values[k]
        self.pipe.set_array(0.5 * (values[:-1] + values[1:]) if len(values) > 1 else np.zeros(0))
        if scene.hull is not None:
            self.hull.set_data(scene.hull[k][:, 0], scene.hull[k][:, v])
        if self.gear is not None and scene.equipment is not None:
            gear = scene.equipment[1][k]
            self.gear.set_data(gear[:, 0], gear[:, v])
        if scene.touchdown is not None:
            td = scene.touchdown[k]
            self.touchdown.set_data(td[:, 0], td[:, v])


def _side_lines(scene: Scene, model: Model | None) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """The side view's x (N,), the seabed's elevation under the line y = the pipe's mean y (N,) and the sea
    surface's elevation (F, N) (None without a depth)."""
    (x0, x1), _, _ = scene.bounds
    x = np.linspace(x0, x1, _SEA_POINTS)
    y = float(np.mean(scene.pipe[0][:, 1]))
    sea_model = None if model is None else model.sea
    bed = None if sea_model is None else sea_model.seabed
    seabed = np.zeros_like(x)
    if bed is not None:
        seabed = np.array([-bed.bathymetry.elevation(float(xi), y) for xi in x])
    if scene.depth is None:
        return x, seabed, None
    sea = np.full((len(scene.time), len(x)), scene.depth)
    waves = None if sea_model is None else sea_model.waves
    if waves is not None:
        for i, xi in enumerate(x):
            sea[:, i] += np.asarray(waves.elevation(scene.time, float(xi), y), dtype=np.float64)
    return x, seabed, sea


def video(
    results: Results,
    path: str | os.PathLike[str],
    model: Model | None = None,
    *,
    colour: str = "tension",
    fps: float = 20,
    max_frames: int = 600,
    dpi: float = 100,
    view: str = "side",
    checks: Mapping[str, Any] | None = None,
) -> Path:
    """Writes the video of a run: a frame per record (at most `max_frames`, evenly decimated, the first and
    last kept), 1280 × 720 pixels at dpi 100.

    Args:
        results: a run (in memory or `pipelay.load`).
        path: the file: .mp4 (also .m4v, .mov, .mkv), H.264 in yuv420p by imageio-ffmpeg's ffmpeg; or .gif
            (Pillow).
        model: the run's model, for the vessel's length, its rollers or tower, the bathymetry, the waves and the
            section (see `pipelay.plots.replay`); None: without it.
        colour: what colours the pipe, one of `pipelay.plots.replay.COLOURS`.
        fps: frames per second of the video.
        max_frames: the most frames (≥ 2).
        dpi: resolution (the figure is 12.8 × 7.2 inches).
        view: "side" (x against elevation −z, true scale), "plan" (x against y) or "both".
        checks: keyword arguments of `pl.checks.dnv_st_f101` for the "utilisation" colour; None: its defaults.

    Returns:
        The path written.

    Raises:
        pipelay.InputError: a bad `colour`, `max_frames`, `fps`, `dpi`, `view` or suffix of `path`.
    """
    target = Path(path)
    if target.suffix.lower() not in _SUFFIXES:
        raise _input_error(
            "path", str(path), "a file ending in " + ", ".join(_SUFFIXES), "has no video suffix"
        )
    if not isinstance(view, str) or view not in VIEWS:
        raise _input_error("view", view, ", ".join(VIEWS))
    fps = _positive("fps", fps)
    dpi = _positive("dpi", dpi)
    scene = prepare(results, model, colour, max_frames, checks)

    figure = Figure(figsize=(_even(12.8, dpi), _even(7.2, dpi)), dpi=dpi, layout="constrained")
    FigureCanvasAgg(figure)
    views = ["side", "plan"] if view == "both" else [view]
    (x0, x1), (y0, y1), (z0, z1) = scene.bounds
    # both views: one above the other for a wide side view (shallow water), side by side for a tall one
    wide = (x1 - x0) > 2.0 * (z1 - z0)
    shape = (len(views), 1) if wide else (1, len(views))
    axes = figure.subplots(*shape, squeeze=False).ravel().tolist()
    norm = Normalize(scene.cmin, scene.cmax)
    panels = []
    sea_line = None
    sea = None
    for axis, name in zip(axes, views, strict=True):
        axis.set_xlim(x0, x1)
        axis.set_xlabel("x (m)")
        axis.grid(alpha=0.3)
        if name == "side":
            xs, seabed, sea = _side_lines(scene, model)
            axis.fill_between(xs, seabed, z0, color="#a88b5f", alpha=0.6, linewidth=0)
            axis.plot(xs, seabed, color="saddlebrown", linewidth=1.2, label="seabed")
            if sea is not None:
                (sea_line,) = axis.plot(xs, sea[0], color="tab:blue", linewidth=1.2, label="sea surface")
                sea_line.set_xdata(xs)
            axis.set_ylim(z0, z1)
            axis.set_aspect("equal", adjustable="box")
            axis.set_ylabel("elevation above seabed −z (m)")
            panels.append(_Panel(axis, scene, norm, 2))
        else:
            axis.set_ylim(y0, y1)
            axis.set_ylabel("y (m)")
            panels.append(_Panel(axis, scene, norm, 1))
        if name == views[0]:
            axis.legend(fontsize=8, loc="upper left")
    figure.colorbar(ScalarMappable(norm=norm, cmap="viridis"), ax=axes, label=f"{scene.label} ({scene.unit})")
    heading = figure.suptitle("")

    def draw(k: int) -> None:
        for panel in panels:
            panel.update(k)
        if sea_line is not None and sea is not None:
            sea_line.set_ydata(sea[k])
        heading.set_text(f"t = {scene.time[k]:.1f} s   (pipe coloured by {scene.label})")

    draw(0)
    figure.canvas.draw()
    figure.set_layout_engine("none")  # the layout of the first frame for all: no jitter, and faster

    writer: AbstractMovieWriter
    gif = target.suffix.lower() == ".gif"
    if gif:
        writer = PillowWriter(fps=fps)  # type: ignore[arg-type]  # a float rate is fine
    else:
        writer = FFMpegWriter(
            fps=fps,  # type: ignore[arg-type]  # ffmpeg's -r takes a float rate
            codec="libx264",
            extra_args=["-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"],
        )
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, name = tempfile.mkstemp(
        prefix=f".{target.name}.", suffix=f".part{target.suffix}", dir=target.parent
    )
    os.close(handle)
    temporary = Path(name)
    try:
        settings: Any = {} if gif else {"animation.ffmpeg_path": _ffmpeg()}
        with matplotlib.rc_context(settings), writer.saving(figure, str(temporary), dpi):
            for k in range(len(scene.records)):
                draw(k)
                writer.grab_frame()
        os.chmod(temporary, 0o666 & ~_umask())
        os.replace(temporary, target)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return target


def _ffmpeg() -> str:
    import imageio_ffmpeg

    return str(imageio_ffmpeg.get_ffmpeg_exe())


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
