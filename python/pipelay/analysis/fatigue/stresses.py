"""Hot-spot stress histories of a run: axial and bending stress at points around the steel wall.

At element midpoint e and the point at angle θ around the section (measured in the section's plane from the
material direction d2 toward d3, the point y = r (cos θ d2 + sin θ d3)), the stress is

    σ(t, e, θ) = SCF · [ N_w / A_s + r (M2 sin θ − M3 cos θ) / I ]

(plane sections: the longitudinal strain at y is Γ1 + K2 y3 − K3 y2; DNV-RP-C203 Sec. 2.3, nominal stress
times the stress concentration factor of the detail), with

* N_w = S + p_i A_i − p_e A_e the true wall force (S the effective axial force the model computes, positive
  in tension; p_e = ρ_w g (water depth + z) at the midpoint's depth, A_e = π D²/4, A_i = π (D − 2t)²/4: the
  relation `pipelay.analysis.checks` documents);
* A_s = π (D² − (D − 2t)²)/4 and I = π (D⁴ − (D − 2t)⁴)/64 of the steel tube (D its outer diameter, t its wall);
* r the radius of the surface the hot spots lie on: D/2 ("outer", the weld cap's toe) or D/2 − t ("inner",
  the root of a weld made from outside).

Every element stands for the girth welds within it (the stress at its midpoint is theirs): the damage along
the line is then that of a weld at any position, which is how lay fatigue is assessed when joints are short
compared with the elements. The material frame turns with the pipe (torsion), so each point is a material
point of the wall. SI units: Pa, N, N·m, m.

Imports of pipelay: `pipelay.analysis.checks` (its input errors).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pipelay.analysis.checks import GRAVITY, _Described, _input_error, _number

__all__ = ["HotSpotStresses", "hot_spot_stresses"]

FloatArray = NDArray[np.float64]

SURFACES = ("outer", "inner")


@dataclass(frozen=True, eq=False)
class HotSpotStresses:
    """The stress at points around the wall of every element of a run, over a window of its records.

    Attributes
    ----------
    time : ndarray (T,)
        The records' times (s).
    stress : ndarray (T, n, points)
        Longitudinal stress σ (Pa) at each record, element and point; NaN for an element without a steel wall
        (a cable).
    angles : ndarray (points,)
        The points' angles θ (rad) from d2 toward d3.
    segment_of : ndarray (n,) of int
        Each element's segment.
    arc_length : ndarray (n,)
        Each element midpoint's distance along the line from end A at the window's first record (m).
    """

    time: FloatArray
    stress: FloatArray
    angles: FloatArray
    segment_of: NDArray[np.int64]
    arc_length: FloatArray


def hot_spot_stresses(
    results: Any,
    *,
    points: int = 8,
    scf: float | Sequence[float] = 1.0,
    surface: str = "outer",
    internal_pressure: float = 0.0,
    start: float | None = None,
    pipe_walls: Sequence[tuple[float, float] | None] | None = None,
    water: tuple[float, float] | None = None,
) -> HotSpotStresses:
    """The stress histories at `points` hot spots around the wall of every element (see the module).

    Parameters
    ----------
    results : pipelay.Results
        A run (``time``, ``section_forces``, ``positions``, ``segment``, ``pipe_walls``, ``water``).
    points : int
        Hot spots around the circumference, evenly spaced from θ = 0 (≥ 1; default 8).
    scf : float or sequence of float
        Stress concentration factor (≥ 1) of the welds, one for the whole line or one per segment.
    surface : {"outer", "inner"}
        The wall's surface the hot spots lie on.
    internal_pressure : float
        p_i (Pa, ≥ 0): 0 for an empty pipe.
    start : float or None
        Records before this time (s) are left out (the start-up transient); None: all records.
    pipe_walls : sequence or None
        Each segment's (outer diameter, wall thickness) (m) or None; None: ``results.pipe_walls``.
    water : (depth, density) or None
        The sea (m, kg/m³); None: ``results.water`` (no external pressure if that is None too).

    Returns
    -------
    HotSpotStresses

    Raises
    ------
    pipelay.InputError
        A bad argument; results whose line changes within the window (pay-out: fatigue needs the same
        elements throughout); no segment with a steel wall.
    """
    count = int(_number("points", points, minimum=1, allowed="a whole number ≥ 1"))
    if count != points:
        raise _input_error("points", points, "a whole number ≥ 1")
    if surface not in SURFACES:
        raise _input_error("surface", surface, ", ".join(SURFACES))
    p_i = _number("internal_pressure", internal_pressure, minimum=0.0)
    walls = list(results.pipe_walls if pipe_walls is None else pipe_walls)
    if water is None:
        water = results.water

    time = np.asarray(results.time, dtype=np.float64)
    first = 0 if start is None else int(np.searchsorted(time, _number("start", start), side="left"))
    if time.size - first < 2:
        raise _input_error(
            "start",
            start,
            f"a time before the last record's minus one record ({time[-2]:g} s)",
            "leaves no window",
        )
    forces = np.asarray(results.section_forces, dtype=np.float64)[first:]
    positions = np.asarray(results.positions, dtype=np.float64)[first:]
    segments = np.asarray(results.segment, dtype=np.float64)[first:]
    if not np.isfinite(forces).all() or not (segments == segments[0]).all():
        raise _input_error(
            "results",
            _Described("records whose line changes (pay-out) or has missing values within the window"),
            "the same elements at every record: a standby, or a start after the pay-out ends",
        )
    segment_of = segments[0].astype(np.int64)
    if not walls:
        raise _input_error(
            "pipe_walls",
            _Described("(not recorded with these results)"),
            "each segment's (outer diameter, wall thickness) (m): give pipe_walls=",
            "is missing",
        )
    if segment_of.max() >= len(walls):
        raise _input_error("pipe_walls", walls, f"one entry per segment ({segment_of.max() + 1})")
    factors = _per_segment_scf(scf, len(walls))

    diameter = np.full(len(walls), np.nan)
    thickness = np.full(len(walls), np.nan)
    for k, wall in enumerate(walls):
        if wall is not None:
            diameter[k] = _number(f"pipe_walls[{k}][0]", wall[0], positive=True)
            thickness[k] = _number(f"pipe_walls[{k}][1]", wall[1], positive=True, allowed="a thickness ≤ D/2")
            if 2.0 * thickness[k] > diameter[k]:
                raise _input_error(f"pipe_walls[{k}]", wall, "a wall thickness ≤ half the outer diameter")
    if np.isnan(diameter[segment_of]).all():
        raise _input_error(
            "pipe_walls",
            walls,
            "a steel wall for at least one segment of the line",
            "has none for any element",
        )
    d, t, factor = diameter[segment_of], thickness[segment_of], factors[segment_of]
    inner = d - 2.0 * t
    steel_area = math.pi / 4.0 * (d**2 - inner**2)
    second_moment = math.pi / 64.0 * (d**4 - inner**4)
    radius = d / 2.0 if surface == "outer" else d / 2.0 - t

    midpoints = 0.5 * (positions[:, 1:, :] + positions[:, :-1, :])
    wall_force = forces[:, :, 0] + p_i * math.pi / 4.0 * inner**2
    if water is not None:
        depth, density = float(water[0]), float(water[1])
        external = density * GRAVITY * np.maximum(depth + midpoints[:, :, 2], 0.0)
        wall_force = wall_force - external * math.pi / 4.0 * d**2

    angles = 2.0 * math.pi * np.arange(count) / count
    bending = forces[:, :, 4, None] * np.sin(angles) - forces[:, :, 5, None] * np.cos(angles)
    stress = factor[:, None] * (
        (wall_force / steel_area)[:, :, None] + (radius / second_moment)[:, None] * bending
    )
    chords = np.linalg.norm(np.diff(positions[0], axis=0), axis=1)
    arc_length = np.cumsum(chords) - 0.5 * chords
    return HotSpotStresses(
        time=time[first:],
        stress=stress,
        angles=angles,
        segment_of=segment_of,
        arc_length=arc_length,
    )


def _per_segment_scf(scf: float | Sequence[float], segments: int) -> FloatArray:
    """The stress concentration factor of each segment (≥ 1)."""
    given = [scf] if isinstance(scf, (int, float)) else list(scf)
    if len(given) not in (1, segments):
        raise _input_error("scf", scf, f"one factor, or one per segment ({segments})")
    factors = [
        _number("scf", value, minimum=1.0, allowed="a stress concentration factor ≥ 1") for value in given
    ]
    return np.array(factors * segments if len(factors) == 1 else factors)
