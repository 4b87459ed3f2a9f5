"""Lay on a curve: a pipe laid along a curved route stays there only while the seabed's lateral friction holds
the residual bottom tension H, which pulls each metre of a curve of radius R inward with H/R. It holds where
R > H/(μ_l W) (μ_l the lateral friction coefficient, W the submerged weight per metre) and slides inward where
not.

```python
pl.curve_lay.minimum_radius(tension, submerged_weight, lateral_friction)   # R_min = H/(μ_l W) (m)
pl.curve_lay.lateral_friction_utilisation(state, lateral_friction)          # (n + 1,) per node, NaN off the seabed
pl.curve_lay.route_deviation(state, route)                                  # (n + 1,) m from the planned route
```

Imports of pipelay: the engine and `pipelay.analysis.checks` (`_number`).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

import pipelay as pl
from pipelay.analysis.checks import _number

FloatArray = npt.NDArray[np.float64]


def minimum_radius(tension: float, submerged_weight: float, lateral_friction: float) -> float:
    """The least radius (m) of a curve that holds a pipe of `submerged_weight` (N/m) under the residual bottom
    tension `tension` (N) on a seabed of lateral friction coefficient `lateral_friction`: H/(μ_l W)."""
    tension = _number("tension", tension, minimum=0.0)
    weight = _number("submerged_weight", submerged_weight, positive=True)
    friction = _number("lateral_friction", lateral_friction, positive=True)
    return tension / (friction * weight)


def lateral_friction_utilisation(state: pl.State, lateral_friction: float) -> FloatArray:
    """The lateral friction each node of `state` uses (n + 1,): the seabed's force across the pipe, horizontal and
    normal to its tangent, over μ_l times the seabed's vertical force on the node (1: the friction is fully
    mobilised and the pipe slides or is about to; NaN where the node is off the seabed). For a flat seabed,
    whose normal is vertical."""
    friction = _number("lateral_friction", lateral_friction, positive=True)
    reaction = state.seabed_reaction
    if reaction is None:
        raise pl.InputError("state: has no seabed, so no seabed friction to use")
    positions = np.asarray(state.positions)
    tangent = np.gradient(positions, axis=0)
    across = np.cross([0.0, 0.0, 1.0], tangent)
    across /= np.maximum(np.linalg.norm(across, axis=1, keepdims=True), 1e-300)
    normal = -reaction[:, 2]  # e3 points down: the seabed pushes up
    lateral = np.abs(np.einsum("ij,ij->i", reaction, across))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(normal > 0.0, lateral / (friction * normal), np.nan)


def route_deviation(state: pl.State, route: npt.ArrayLike) -> FloatArray:
    """Each node's horizontal distance (m) from the planned route, the polyline through `route` (k, 2) (x, y in
    e, m; k ≥ 2): how far the pipe lies from where it was meant to be laid (n + 1,)."""
    points = np.asarray(route, dtype=float)
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < 2 or not np.all(np.isfinite(points)):
        raise pl.InputError(
            f"route: must be (k, 2) finite points (x, y) with k ≥ 2, got shape {points.shape}"
        )
    xy = np.asarray(state.positions)[:, :2]
    start, end = points[:-1], points[1:]
    chord = end - start
    length2 = np.maximum(np.einsum("ij,ij->i", chord, chord), 1e-300)
    # The foot on each segment of each node, clamped to the segment: (n + 1, k − 1).
    t = np.clip(np.einsum("nkj,kj->nk", xy[:, None, :] - start[None], chord) / length2, 0.0, 1.0)
    foot = start[None] + t[..., None] * chord[None]
    return np.min(np.linalg.norm(xy[:, None, :] - foot, axis=2), axis=1)
