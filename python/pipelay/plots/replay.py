"""The 3-D replay of a run in the browser: a plotly figure with a frame per record (decimated), the pipe coloured
by its tension, bending moment, strain or DNV-ST-F101 utilisation, the vessel's hull, its rollers or J-lay
tower, the seabed, the sea surface with its waves and the touchdown point; play, pause, speed, a time slider
and camera presets. `replay_html` gives the HTML, one self-contained document (plotly.js inline: it opens
offline, without a server) or a ``<div>`` to embed.

Usage::

    from pipelay.plots.replay import replay, replay_html

    figure = replay(results, model, colour="moment", path="run.html")   # also writes run.html
    figure.show()                                                         # or in Jupyter: just `figure`
    html = replay_html(results, model, full_html=False)                   # a <div> for another page

Coordinates: frame e has e3 pointing down; the figure plots (x, y, −z), elevations in m above the seabed end
(z = 0), so the sea surface is at elevation depth, as the 2-D figures do (their side view x against −z, their
plan view x against y: like them the 3-D view is the mirror image of the sea seen from above with e3 down).

What the model adds to what the results give (the pipe, the vessel's pose η, the touchdown point and
`results.water`): the vessel's length, its rollers or tower, the seabed's bathymetry, the waves and the pipe's
section (for strain and utilisation). Without it: an 80 m hull, a flat seabed at z = 0 and a flat sea at the
depth of `results.water`.

`prepare` computes what both this replay and `pipelay.plots.video` draw (`Scene`).

Imports of pipelay: the engine (`pipelay._core`), `pipelay.analysis.checks` (the wording of input errors),
`pipelay.analysis.extremes` (strain and utilisation) and `pipelay.results.atomic` (the atomic write).
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import plotly.graph_objects as go

from pipelay._core import Model, Results
from pipelay.analysis.checks import _Described, _input_error, describe_parameters
from pipelay.analysis.extremes import _section_stiffness, _strain
from pipelay.analysis.extremes import utilisation as _utilisation
from pipelay.results.atomic import _atomic_write

__all__ = ["COLOURS", "replay", "replay_html"]

COLOURS = ("tension", "moment", "strain", "utilisation")
"""What the pipe can be coloured by: the effective tension N₁ (kN), the bending moment |M| = √(M₂² + M₃²)
(kN·m), the largest longitudinal strain at the outer fibre N₁/EA + (d_o/2)|κ| (%; needs a model) and the
DNV-ST-F101 utilisation (1; needs a model whose section is a Section.pipe)."""

_COLOUR_LABELS = {
    "tension": ("effective tension N₁", "kN", 1e-3),
    "moment": ("bending moment |M|", "kN·m", 1e-3),
    "strain": ("strain ε", "%", 1e2),
    "utilisation": ("DNV-ST-F101 utilisation", "1", 1.0),
}

DEFAULT_VESSEL_LENGTH = 80.0
"""Length of the hull drawn when neither the model nor the vessel says (m)."""

FRAME_MS = 100
"""Duration of a frame at speed ×1 (ms): 10 frames a second; ×2 and ×4 halve and quarter it."""

TOWER_LENGTH = 30.0
"""Length of the J-lay tower drawn from the pipe's end up along its tangent (m)."""

# the first camera's eye, in units of the box's diagonal: from port, astern of end A and above
_OBLIQUE = 1.55 * np.array([-0.4, -0.85, 0.34])
_GRID = 25  # points a side of the seabed's and the sea's grids
_FloatArray = npt.NDArray[np.float64]
_PathLike = str | os.PathLike[str]


# --- what is drawn ----------------------------------------------------------------------------------------


@dataclass
class Scene:
    """What a replay draws, in plot coordinates (x, y, elevation −z) (m), for F frames.

    Attributes:
        records: the index of each frame's record (F,), the first and last included.
        time: each frame's time (F,) (s).
        pipe: each frame's nodes (m_k, 3), the nodes the record has (NaN padding of pay-out dropped).
        values: each frame's colour at those nodes (m_k,), in `unit` (element values averaged onto the nodes).
        colour, label, unit: what the colour is ("tension", ...), its name and unit.
        cmin, cmax: the colour scale's range: the elements' smallest and largest values over every record of
            the run (in `unit`; the nodes' averages lie within).
        hull: each frame's hull outline (P, 3), one path, or None without a vessel.
        equipment: "rollers", "roller boxes", "tower" or None, and each frame's points (k, 3) (roller boxes:
            each roller's top line's ends and a NaN row; the tower: its two ends); for an articulated stinger
            "rollers and hinged sections" (or "roller boxes and …"), the rollers turned with their sections
            followed by each section's hinge and end and a NaN row.
        touchdown: each frame's touchdown point (1, 3) or (0, 3) where the record has none; None without a seabed.
        grid_x, grid_y: the seabed's and sea's grid (nx,), (ny,) (m).
        seabed: the seabed's elevation on the grid (ny, nx) (m).
        depth: the water depth (m), or None when neither the model nor the results say.
        sea: the sea surface's elevation on the grid (F, ny, nx) (depth + the waves' elevation at each frame's
            time), or None without a depth.
        waves: whether the sea surface moves (the model has waves).
        bounds: the plotted box ((x0, x1), (y0, y1), (z0, z1)) (m).
        along: the pipe's horizontal direction from end A to end B (2,), unit, at the first frame.
        basis: what the "utilisation" colour assumes (`pl.checks.describe_parameters`), "" for the others.
    """

    records: npt.NDArray[np.int64]
    time: _FloatArray
    pipe: list[_FloatArray]
    values: list[_FloatArray]
    colour: str
    label: str
    unit: str
    cmin: float
    cmax: float
    hull: list[_FloatArray] | None
    equipment: tuple[str, list[_FloatArray]] | None
    touchdown: list[_FloatArray] | None
    grid_x: _FloatArray
    grid_y: _FloatArray
    seabed: _FloatArray
    depth: float | None
    sea: _FloatArray | None
    waves: bool
    bounds: tuple[tuple[float, float], tuple[float, float], tuple[float, float]]
    along: _FloatArray
    basis: str = ""


def rotation(eta: npt.ArrayLike) -> _FloatArray:
    """R(η) (3, 3), body to frame e, of the zyx Euler angles η[3:6] = (φ, θ, ψ): Rz(ψ) Ry(θ) Rx(φ)."""
    phi, theta, psi = np.asarray(eta, dtype=np.float64)[3:6]
    cf, sf, ct, st, cp, sp = np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    return np.array(
        [
            [cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st],
            [sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf],
            [-st, ct * sf, ct * cf],
        ]
    )


def hull_outline(length: float) -> _FloatArray:
    """The hull's wire-frame in the body frame (x forward, y starboard, z down; origin CO at midships on the
    waterline) (P, 3) (m), one path: the waterline, the deck at the freeboard length/14 above it and the
    vertical edges between, a pointed bow over the forward 20 %, beam length/4.4."""
    half, beam, freeboard = 0.5 * length, length / 4.4, length / 14.0
    shoulder = 0.3 * length
    plan = np.array(
        [[-half, -beam / 2], [shoulder, -beam / 2], [half, 0.0], [shoulder, beam / 2], [-half, beam / 2]]
    )
    # waterline w0..w4, w0; up to the deck d0 and round it, each corner's vertical edge drawn down and up again
    order = [("w", 0), ("w", 1), ("w", 2), ("w", 3), ("w", 4), ("w", 0), ("d", 0)]
    for j in (1, 2, 3, 4):
        order += [("d", j), ("w", j), ("d", j)]
    order.append(("d", 0))
    return np.array([[plan[j, 0], plan[j, 1], 0.0 if level == "w" else -freeboard] for level, j in order])


def _frames(count: int, max_frames: int) -> npt.NDArray[np.int64]:
    """Indices of at most `max_frames` records of `count`, evenly spaced, the first and last included."""
    if count <= max_frames:
        return np.arange(count, dtype=np.int64)
    return np.unique(np.round(np.linspace(0.0, count - 1, max_frames)).astype(np.int64))


def _check_max_frames(max_frames: object) -> int:
    if isinstance(max_frames, bool) or not isinstance(max_frames, (int, np.integer)) or max_frames < 2:
        raise _input_error(
            "max_frames", max_frames, "an integer >= 2 (the first and last records are always shown)"
        )
    return int(max_frames)


def _element_values(
    results: Results, model: Model | None, colour: str, checks: Mapping[str, Any] | None
) -> tuple[_FloatArray, str, str]:
    """The colour's values (T, n) at the elements (in its unit; NaN where a record had no such element), its
    label and unit; `checks`: the parameters of the utilisation (None: the checks' defaults)."""
    if colour not in COLOURS:
        raise _input_error("colour", colour, ", ".join(COLOURS))
    label, unit, scale = _COLOUR_LABELS[colour]
    forces = np.asarray(results.section_forces, dtype=np.float64)
    if colour == "tension":
        return scale * forces[:, :, 0], label, unit
    if colour == "moment":
        return scale * np.hypot(forces[:, :, 4], forces[:, :, 5]), label, unit
    if model is None:
        needs = "its section's EA, EI and outer diameter" if colour == "strain" else "a Section.pipe"
        raise _input_error(
            "colour",
            colour,
            f"tension or moment without a model; {colour} needs the model of the run ({needs})",
            "needs a model",
        )
    if colour == "strain":
        return scale * _strains(results, model, forces), label, unit
    section = model.rod.section
    if getattr(section, "wall_thickness", None) is None:
        raise _input_error(
            "colour",
            colour,
            "tension, moment or strain; utilisation needs a model whose section has a wall thickness "
            "(Section.pipe)",
            "needs a pipe's wall",
        )
    values = _utilisation(results, model=model, checks=dict(checks or {}))
    return scale * np.asarray(values, dtype=np.float64), label, unit


def _strains(results: Results, model: Model, forces: _FloatArray) -> _FloatArray:
    """ε = N₁/EA + (d_o/2)|κ| (T, n) with each element's segment's section (a cable's: N₁/EA)."""
    sections = list(model.rod.sections)
    segment = np.asarray(results.segment, dtype=np.float64)
    strain = np.full(forces.shape[:2], np.nan)
    for index, section in enumerate(sections):
        mine = segment == index if len(sections) > 1 else np.isfinite(forces[:, :, 0])
        if getattr(section, "is_cable", False):
            strain[mine] = forces[:, :, 0][mine] / float(section.EA)
        else:
            strain[mine] = _strain(forces[mine], *_section_stiffness(section))
    return strain


def _on_nodes(values: _FloatArray) -> _FloatArray:
    """Element values (T, n) put on the nodes (T, n + 1): the average of the two elements beside a node, the
    end element's at an end (and at the last node a record of a pay-out run has); NaN beyond."""
    pad = np.full((values.shape[0], 1), np.nan)
    left = np.concatenate([pad, values], axis=1)
    right = np.concatenate([values, pad], axis=1)
    with np.errstate(invalid="ignore"):
        both = 0.5 * (left + right)
    return np.where(np.isfinite(both), both, np.where(np.isfinite(left), left, right))


def _significant(values: _FloatArray, digits: int = 4) -> _FloatArray:
    """`values` rounded to `digits` significant digits."""
    values = np.asarray(values, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        exponent = np.floor(np.log10(np.abs(values)))
    exponent = np.where(np.isfinite(exponent), exponent, 0.0)
    scale = 10.0 ** (digits - 1 - exponent)
    return np.round(values * scale) / scale


def _lay_equipment(model: Model | None) -> tuple[str, _FloatArray] | None:
    """The rollers (k, 3), the roller boxes' rollers (their top lines' ends, each pair followed by a NaN row:
    (3k, 3)) or the tower (its two ends (2, 3)) in the body frame, from the model at rest.

    A tower is drawn for a vessel without rollers whose end of the pipe is held away from CO (more than 1 m)
    with its tangent steeper than 30° in the body frame: a J-lay tower's exit (the model does not say which
    lay equipment it has)."""
    if model is None or model.vessel is None:
        return None
    rest = model.rest()
    if rest.eta is None:
        return None
    eta = np.asarray(rest.eta, dtype=np.float64)
    turn = rotation(eta)
    rollers = rest.roller_positions
    lines = rest.roller_lines
    if lines is not None and len(lines) > 0 and np.any(np.ptp(lines, axis=1) > 0.0):
        # Roller boxes: each roller's top line, the lines apart (NaN breaks a line in a trace).
        gaps = np.full((len(lines), 1, 3), np.nan)
        points = np.concatenate([np.asarray(lines, dtype=np.float64), gaps], axis=1).reshape(-1, 3)
        return "roller boxes", (points - eta[:3]) @ turn
    if rollers is not None and len(rollers) > 0:
        return "rollers", (np.asarray(rollers, dtype=np.float64) - eta[:3]) @ turn
    positions = np.asarray(rest.positions, dtype=np.float64)
    tangents = np.asarray(rest.rotations, dtype=np.float64)[:, :, 0]
    ends = [(positions[-1], tangents[-1]), (positions[0], -tangents[0])]  # tangents pointing out of the pipe
    end, out = min(ends, key=lambda e: float(np.linalg.norm(e[0] - eta[:3])))
    body = turn.T @ (end - eta[:3])
    direction = turn.T @ out
    if np.linalg.norm(body) <= 1.0 or abs(direction[2]) < math.sin(math.radians(30.0)):
        return None
    return "tower", np.array([body, body + TOWER_LENGTH * direction])


def _sections(model: Model | None) -> tuple[_FloatArray, _FloatArray] | None:
    """An articulated stinger's hinges and sections' ends (h, 3) each, in the body frame at rest; None
    without."""
    if model is None or model.vessel is None:
        return None
    rest = model.rest()
    lines = rest.section_lines
    if lines is None or rest.eta is None:
        return None
    eta = np.asarray(rest.eta, dtype=np.float64)
    body = (np.asarray(lines, dtype=np.float64) - eta[:3]) @ rotation(eta)
    return body[:, 0], body[:, 1]


def _hinged(points: _FloatArray, hinges: _FloatArray, angles: _FloatArray) -> _FloatArray:
    """Body-frame points (n, 3) of an articulated stinger at rest, turned by the hinge `angles` (h,): a point
    aft of hinge j and not of hinge j + 1 (its x below the first's, the stinger running aft) rides on section
    j and turns about each hinge from j back to the first (about b2; positive: aft end down)."""
    out = np.array(points, dtype=np.float64, copy=True)
    section = np.full(len(out), -1)
    for j, hinge in enumerate(hinges):
        section[out[:, 0] < hinge[0] - 1e-9] = j
    for i in range(len(hinges) - 1, -1, -1):
        c, s = math.cos(angles[i]), math.sin(angles[i])
        turn = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
        moving = section >= i
        out[moving] = hinges[i] + (out[moving] - hinges[i]) @ turn.T
    return out


def _flip(points: _FloatArray) -> _FloatArray:
    """Points of frame e (…, 3) in plot coordinates (x, y, −z)."""
    out = np.array(points, dtype=np.float64, copy=True)
    out[..., 2] *= -1.0
    return out


def _bounds(
    pipe: list[_FloatArray], extras: list[_FloatArray], depth: float | None
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The plotted area's x and y ranges (m): everything drawn with a 5 % margin, y widened to at least 30 %
    of the x range so that the seabed and the sea read as planes."""
    points = np.concatenate([p[:, :2] for p in pipe + extras if len(p)], axis=0)
    low, high = np.nanmin(points, axis=0), np.nanmax(points, axis=0)  # NaN: the gaps between lines
    span = float(max(high[0] - low[0], 1.0))
    margin = 0.05 * span
    x = (float(low[0]) - margin, float(high[0]) + margin)
    centre = 0.5 * float(low[1] + high[1])
    half = max(0.5 * float(high[1] - low[1]) + margin, 0.15 * (x[1] - x[0]))
    return x, (centre - half, centre + half)


def prepare(
    results: Results,
    model: Model | None,
    colour: str,
    max_frames: int,
    checks: Mapping[str, Any] | None = None,
) -> Scene:
    """What the replay and the video draw of `results` (see `Scene`); `checks`: the parameters of the
    "utilisation" colour (keyword arguments of `pl.checks.dnv_st_f101`; None: its defaults).

    Raises:
        pipelay.InputError: `colour` unknown or not computable from the inputs, `max_frames` < 2, or results
            without records.
    """
    max_frames = _check_max_frames(max_frames)
    if not isinstance(colour, str) or colour not in COLOURS:
        raise _input_error("colour", colour, ", ".join(COLOURS))
    time = np.asarray(results.time, dtype=np.float64)
    if len(time) == 0:
        raise _input_error("results", _Described("results of 0 records"), "a run with records", "has")
    elements, label, unit = _element_values(results, model, colour, checks)
    nodes_all = _on_nodes(elements)
    records = _frames(len(time), max_frames)
    positions = np.asarray(results.positions, dtype=np.float64)

    pipe, values = [], []
    for k in records:
        valid = np.all(np.isfinite(positions[k]), axis=1)
        pipe.append(_flip(positions[k][valid]))
        values.append(nodes_all[k][valid[: nodes_all.shape[1]]])
    # the scale: the elements' extremes, so that a peak the nodes' averages smooth is on it
    finite = elements[np.isfinite(elements)]
    cmin, cmax = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if cmax <= cmin:
        cmin, cmax = cmin - 0.5 * max(abs(cmin), 1e-9), cmax + 0.5 * max(abs(cmax), 1e-9)
    values = [np.where(np.isfinite(v), v, cmin) for v in values]

    eta = None if results.eta is None else np.asarray(results.eta, dtype=np.float64)[records]
    hull = equipment = None
    if eta is not None:
        length = None if model is None or model.vessel is None else model.vessel.length
        outline = hull_outline(float(length) if length else DEFAULT_VESSEL_LENGTH)
        turns = [rotation(e) for e in eta]
        hull = [_flip(e[:3] + outline @ r.T) for e, r in zip(eta, turns, strict=True)]
        gear = _lay_equipment(model)
        if gear is not None:
            kind, body = gear
            angles = results.hinge_angles
            sections = _sections(model)
            if angles is not None and sections is not None:
                # An articulated stinger: its sections (hinge to end, NaN apart) and rollers turned by each
                # frame's hinge angles.
                hinges, ends = sections
                lines = np.stack([hinges, ends, np.full_like(hinges, np.nan)], axis=1).reshape(-1, 3)
                shapes = [_hinged(np.vstack([body, lines]), hinges, a) for a in np.asarray(angles)[records]]
                kind = f"{kind} and hinged sections"
            else:
                shapes = [body] * len(eta)
            equipment = (kind, [_flip(e[:3] + b @ r.T) for e, r, b in zip(eta, turns, shapes, strict=True)])

    touchdown = None
    if results.touchdown is not None:
        points = np.asarray(results.touchdown, dtype=np.float64)[records]
        touchdown = [_flip(p[None, :]) if np.all(np.isfinite(p)) else np.zeros((0, 3)) for p in points]

    sea_model = None if model is None else model.sea
    depth: float | None = None
    if sea_model is not None:
        depth = float(sea_model.depth)
    elif results.water is not None:
        depth = float(results.water[0])

    extras = (hull or []) + (equipment[1] if equipment else [])
    (x0, x1), (y0, y1) = _bounds(pipe, extras, depth)
    grid_x, grid_y = np.linspace(x0, x1, _GRID), np.linspace(y0, y1, _GRID)
    seabed = np.zeros((_GRID, _GRID))
    bed = None if sea_model is None else sea_model.seabed
    if bed is not None:
        bathymetry = bed.bathymetry
        seabed = np.array([[-bathymetry.elevation(float(x), float(y)) for x in grid_x] for y in grid_y])

    waves = None if sea_model is None else sea_model.waves
    sea = None
    if depth is not None:
        sea = np.full((len(records), _GRID, _GRID), depth)
        if waves is not None:
            t = time[records]
            for j, y in enumerate(grid_y):
                for i, x in enumerate(grid_x):
                    sea[:, j, i] += np.asarray(waves.elevation(t, float(x), float(y)), dtype=np.float64)

    heights = [p[:, 2] for p in pipe + extras if len(p)] + [seabed.ravel()]
    if sea is not None:
        heights.append(sea.ravel())
    z = np.concatenate(heights)
    z = z[np.isfinite(z)]  # NaN: the gaps between the roller boxes' lines
    z_span = float(max(z.max() - z.min(), 1.0))
    bounds = ((x0, x1), (y0, y1), (float(z.min()) - 0.03 * z_span, float(z.max()) + 0.03 * z_span))

    first = pipe[0]
    chord = first[-1, :2] - first[0, :2] if len(first) > 1 else np.array([1.0, 0.0])
    along = chord / np.linalg.norm(chord) if np.linalg.norm(chord) > 0 else np.array([1.0, 0.0])
    return Scene(
        records=records,
        time=time[records],
        pipe=pipe,
        values=values,
        colour=colour,
        label=label,
        unit=unit,
        cmin=cmin,
        cmax=cmax,
        hull=hull,
        equipment=equipment,
        touchdown=touchdown,
        grid_x=grid_x,
        grid_y=grid_y,
        seabed=seabed,
        depth=depth,
        sea=sea,
        waves=waves is not None,
        bounds=bounds,
        along=along,
        basis=describe_parameters(checks) if colour == "utilisation" else "",
    )


# --- the plotly figure ------------------------------------------------------------------------------------


def _xyz(points: _FloatArray) -> dict[str, Any]:
    """x, y, z of points (m, 3) rounded to 1 cm, as float32 (sent as binary: 4 bytes a number)."""
    rounded = np.round(points, 2).astype(np.float32)
    return {"x": rounded[:, 0], "y": rounded[:, 1], "z": rounded[:, 2]}


def _dynamic(scene: Scene, k: int) -> list[dict[str, Any]]:
    """The moving traces' data of frame k, in the order of `_traces` after the static ones."""
    data: list[dict[str, Any]] = []
    if scene.waves and scene.sea is not None:
        data.append({"type": "surface", "z": np.round(scene.sea[k], 2).astype(np.float32)})
    colour = _significant(scene.values[k]).astype(np.float32)
    data.append({"type": "scatter3d", **_xyz(scene.pipe[k]), "line": {"color": colour}})
    if scene.hull is not None:
        data.append({"type": "scatter3d", **_xyz(scene.hull[k])})
    if scene.equipment is not None:
        data.append({"type": "scatter3d", **_xyz(scene.equipment[1][k])})
    if scene.touchdown is not None:
        data.append({"type": "scatter3d", **_xyz(scene.touchdown[k])})
    return data


def _traces(scene: Scene) -> tuple[list[Any], list[int]]:
    """The figure's traces at the first frame, and the indices of those that move."""
    flat = {"showscale": False, "hoverinfo": "skip", "lighting": {"ambient": 0.9, "diffuse": 0.3}}
    traces: list[Any] = [
        go.Surface(
            x=scene.grid_x,
            y=scene.grid_y,
            z=np.round(scene.seabed, 2).astype(np.float32),
            surfacecolor=np.zeros_like(scene.seabed, dtype=np.float32),
            colorscale=[[0.0, "#a88b5f"], [1.0, "#a88b5f"]],
            name="seabed",
            **flat,
        )
    ]
    moving: list[int] = []
    if scene.sea is not None:
        if scene.waves:
            moving.append(len(traces))
        traces.append(
            go.Surface(
                x=scene.grid_x,
                y=scene.grid_y,
                z=np.round(scene.sea[0], 2).astype(np.float32),
                surfacecolor=np.zeros(scene.sea[0].shape, dtype=np.float32),
                colorscale=[[0.0, "#2f7fc1"], [1.0, "#2f7fc1"]],
                opacity=0.35,
                name="sea surface",
                **flat,
            )
        )
    first = _dynamic(scene, 0)
    start = 1 if scene.waves and scene.sea is not None else 0
    moving += list(range(len(traces), len(traces) + len(first) - start))
    pipe, *others = first[start:]
    traces.append(
        go.Scatter3d(
            x=pipe["x"],
            y=pipe["y"],
            z=pipe["z"],
            mode="lines",
            name="pipe",
            line={
                "color": pipe["line"]["color"],
                "colorscale": "Viridis",
                "cmin": scene.cmin,
                "cmax": scene.cmax,
                "width": 6,
                "showscale": True,
                "colorbar": {"title": {"text": f"{scene.label} ({scene.unit})", "side": "right"}},
            },
            hovertemplate="x %{x:.1f} m, y %{y:.1f} m, −z %{z:.1f} m<br>%{line.color:.4g} "
            + scene.unit
            + "<extra>pipe</extra>",
        )
    )
    rest = iter(others)
    if scene.hull is not None:
        hull = next(rest)
        traces.append(
            go.Scatter3d(
                x=hull["x"], y=hull["y"], z=hull["z"], mode="lines", name="vessel",
                line={"color": "#222222", "width": 4}, hoverinfo="skip",
            )
        )  # fmt: skip
    if scene.equipment is not None:
        gear = next(rest)
        kind = scene.equipment[0]
        styles: dict[str, dict[str, Any]] = {
            "rollers": {"mode": "markers", "marker": {"color": "#e8590c", "size": 3}},
            "roller boxes": {"mode": "lines", "line": {"color": "#e8590c", "width": 5}, "connectgaps": False},
        }
        # An articulated stinger's rollers run into its sections' lines: all drawn as lines, gaps kept.
        if kind.endswith("hinged sections"):
            styles[kind] = {
                "mode": "lines+markers",
                "line": {"color": "#e8590c", "width": 4},
                "marker": {"size": 2},
            }
        style = styles.get(kind, {"mode": "lines", "line": {"color": "#7a7a7a", "width": 8}})
        traces.append(
            go.Scatter3d(x=gear["x"], y=gear["y"], z=gear["z"], name=kind, hoverinfo="skip", **style)
        )
    if scene.touchdown is not None:
        td = next(rest)
        traces.append(
            go.Scatter3d(
                x=td["x"], y=td["y"], z=td["z"], mode="markers", name="touchdown",
                marker={"color": "#d62728", "size": 5, "symbol": "diamond"}, hoverinfo="skip",
            )
        )  # fmt: skip
    return traces, moving


def _cameras(scene: Scene, aspect: dict[str, float]) -> dict[str, dict[str, Any]]:
    """The camera presets: side (looking along e2, horizontal), plan (from above), along the pipe (from beyond
    end B looking back toward end A), in plotly's scene coordinates (the box of `aspect`)."""
    reach = 1.25 * max(aspect.values())
    (x0, x1), (y0, y1), _ = scene.bounds
    u = np.array([scene.along[0] * aspect["x"] / (x1 - x0), scene.along[1] * aspect["y"] / (y1 - y0)])
    u /= np.linalg.norm(u)
    up = {"x": 0.0, "y": 0.0, "z": 1.0}
    centre = {"x": 0.0, "y": 0.0, "z": 0.0}
    return {
        "side": {"eye": {"x": 0.0, "y": -reach, "z": 0.0}, "up": up, "center": centre, "projection": {"type": "perspective"}},
        "plan": {"eye": {"x": 0.0, "y": 0.0, "z": 1.1 * reach}, "up": {"x": 0.0, "y": 1.0, "z": 0.0}, "center": centre, "projection": {"type": "perspective"}},
        "along the pipe": {
            "eye": {"x": float(u[0]) * 1.3 * reach, "y": float(u[1]) * 1.3 * reach, "z": 0.1 + 0.9 * aspect["z"]},
            "up": up, "center": centre, "projection": {"type": "perspective"},
        },
    }  # fmt: skip


def _figure(scene: Scene, title: str | None) -> go.Figure:
    traces, moving = _traces(scene)
    names = [f"frame {j}" for j in range(len(scene.records))]
    frames = [go.Frame(name=name, data=_dynamic(scene, j), traces=moving) for j, name in enumerate(names)]
    (x0, x1), (y0, y1), (z0, z1) = scene.bounds
    spans = np.array([x1 - x0, y1 - y0, z1 - z0])
    ratio = spans / spans.max()
    aspect = {"x": float(ratio[0]), "y": float(ratio[1]), "z": float(ratio[2])}
    cameras = _cameras(scene, aspect)

    def animate(names: list[str] | None, duration: int) -> list[Any]:
        return [
            names,
            {
                "mode": "immediate",
                "fromcurrent": True,
                "frame": {"duration": duration, "redraw": True},
                "transition": {"duration": 0},
            },
        ]

    t0, t1 = float(scene.time[0]), float(scene.time[-1])
    heading = title if title is not None else "Pipelay replay"
    text = f"{heading}: t = {t0:g} to {t1:g} s, the pipe coloured by {scene.label} ({scene.unit})"
    if scene.basis:
        text += f"<br><sub>{scene.basis}</sub>"
    steps = [
        {"method": "animate", "label": f"{t:g}", "args": animate([name], 0)}
        for name, t in zip(names, scene.time, strict=True)
    ]
    many = len(steps) > 12
    button = {"type": "buttons", "direction": "left", "showactive": False, "pad": {"r": 6, "t": 6}}
    layout = go.Layout(
        title={"text": text, "x": 0.5, "xanchor": "center"},
        margin={"l": 0, "r": 0, "t": 50, "b": 0},
        showlegend=True,
        legend={"x": 0.0, "y": 0.9, "xanchor": "left", "yanchor": "top", "bgcolor": "rgba(255,255,255,0.6)"},
        scene={
            "xaxis": {"title": {"text": "x (m)"}, "range": [x0, x1], "autorange": False},
            "yaxis": {"title": {"text": "y (m)"}, "range": [y0, y1], "autorange": False},
            "zaxis": {"title": {"text": "elevation −z (m)"}, "range": [z0, z1], "autorange": False},
            "aspectmode": "manual",
            "aspectratio": aspect,
            "camera": {
                "eye": dict(zip("xyz", (float(c) for c in _OBLIQUE * np.linalg.norm(ratio)), strict=True)),
                "up": {"x": 0.0, "y": 0.0, "z": 1.0},
            },
        },
        updatemenus=[
            {
                **button,
                "x": 0.0,
                "y": 0.0,
                "xanchor": "left",
                "yanchor": "top",
                "buttons": [
                    {"label": "▶ play", "method": "animate", "args": animate(None, FRAME_MS)},
                    {
                        "label": "❚❚ pause",
                        "method": "animate",
                        "args": [
                            [None],
                            {
                                "mode": "immediate",
                                "frame": {"duration": 0, "redraw": False},
                                "transition": {"duration": 0},
                            },
                        ],
                    },
                ],
            },
            {
                **button,
                "x": 0.0,
                "y": 1.0,
                "xanchor": "left",
                "yanchor": "top",
                "buttons": [
                    {"label": f"▶ ×{s}", "method": "animate", "args": animate(None, FRAME_MS // s)}
                    for s in (1, 2, 4)
                ],
            },
            {
                **button,
                "x": 1.0,
                "y": 1.0,
                "xanchor": "right",
                "yanchor": "top",
                "buttons": [
                    {"label": name, "method": "relayout", "args": [{"scene.camera": camera}]}
                    for name, camera in cameras.items()
                ],
            },
        ],
        sliders=[
            {
                "active": 0,
                "x": 0.17,
                "len": 0.8,
                "y": 0.0,
                "yanchor": "top",
                "pad": {"t": 6, "b": 6},
                "currentvalue": {
                    "prefix": "t = ",
                    "suffix": " s",
                    "visible": True,
                    "font": {"color": "#222"},
                },
                "font": {"color": "rgba(0,0,0,0)" if many else "#222"},
                "ticklen": 0 if many else 4,
                "minorticklen": 0 if many else 2,
                "tickcolor": "rgba(0,0,0,0)" if many else "#333",
                "transition": {"duration": 0},
                "steps": steps,
            }
        ],
    )
    return go.Figure(data=traces, layout=layout, frames=frames)


def replay(
    results: Results,
    model: Model | None = None,
    *,
    colour: str = "tension",
    max_frames: int = 300,
    title: str | None = None,
    path: _PathLike | None = None,
    checks: Mapping[str, Any] | None = None,
) -> go.Figure:
    """The 3-D replay of a run: a plotly figure with a frame per record (at most `max_frames`).

    Each frame shows the pipe (a line coloured by `colour`, one colour scale over the whole run with its colour
    bar), the vessel's hull at the record's pose η (the model's vessel length, else 80 m), its rollers or J-lay
    tower moving with it, the touchdown point, the seabed (the model's bathymetry, else flat at z = 0) and the
    sea surface (at elevation depth plus the model's waves at the frame's time). Controls: play and pause, the
    speeds ×1, ×2 and ×4 (100, 50 and 25 ms a frame; each starts playing), a time slider labelled with t (s)
    and camera presets (side, plan, along the pipe); the aspect ratio is true.

    Args:
        results: a run (in memory or `pipelay.load`).
        model: the run's model, for what the results do not say (see the module); None: without it.
        colour: one of `COLOURS`: "tension" (N₁, kN), "moment" (|M|, kN·m), "strain" (%, needs `model`),
            "utilisation" (DNV-ST-F101 with `checks`, needs `model` with a Section.pipe).
        max_frames: the most frames (≥ 2): the records are decimated evenly, the first and last kept.
        title: the title's first part (default "Pipelay replay"); the run's time span and the colour follow.
        path: also write the figure there as one self-contained HTML file (`replay_html`), atomically.
        checks: keyword arguments of `pl.checks.dnv_st_f101` for the "utilisation" colour (a scenario's
            ``Scenario.checks``); None: its defaults.

    Returns:
        The figure (`figure.show()`, or displayed by Jupyter). Its numbers are sent with limited precision:
        positions rounded to 1 cm, colours to 4 significant digits, as float32.

    Raises:
        pipelay.InputError: an unknown `colour` or one the inputs cannot give, `max_frames` < 2.
    """
    figure = _figure(prepare(results, model, colour, max_frames, checks), title)
    if path is not None:
        text = _html(figure, full_html=True)

        def write(temporary: Path) -> None:
            temporary.write_text(text, encoding="utf-8")
            mask = os.umask(0)
            os.umask(mask)
            os.chmod(temporary, 0o666 & ~mask)  # a page to share: the usual permissions, not mkstemp's 0600

        _atomic_write(Path(path), write)
    return figure


def replay_html(
    results: Results,
    model: Model | None = None,
    *,
    full_html: bool = True,
    colour: str = "tension",
    max_frames: int = 300,
    title: str | None = None,
    checks: Mapping[str, Any] | None = None,
) -> str:
    """The replay (`replay`) as HTML.

    ``full_html=True``: one self-contained document with plotly.js inline (about 4.8 MB more): it opens offline
    from a file, without a server. ``full_html=False``: a ``<div>`` and its ``<script>`` for embedding in a page
    that already loads plotly.js once, before the div, e.g. ``<script>`` + ``plotly.offline.get_plotlyjs()`` +
    ``</script>`` in its head (the plotly.js that comes with the installed plotly) — several replays on one page
    share it.
    """
    figure = _figure(prepare(results, model, colour, max_frames, checks), title)
    return _html(figure, full_html=full_html)


def _html(figure: go.Figure, *, full_html: bool) -> str:
    text: str = figure.to_html(
        include_plotlyjs=full_html,
        full_html=full_html,
        auto_play=False,
        default_height="94vh" if full_html else "720px",
        config={"displaylogo": False, "responsive": True},
    )
    return text
