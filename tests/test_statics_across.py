"""Statics with a current across the pipe's vertical plane, on the project's own examples (issue 43's
reproduction): `examples/j_lay_waves.toml` and `examples/s_lay.toml` with a uniform current acting from t = 0.

References: continuity (a faint current of 1e-4 m/s leaves the in-plane state to within a millimetre); the drag's
direction (the suspended span is pushed downstream, the laid pipe stays on its line at the pinned end); and the
physical check every converged state passes (the pipe on the stinger, the vessel upright)."""

from __future__ import annotations

import math
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import apply_overrides, parse_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _static(name: str, speed: float, heading_deg: float) -> pl.State:
    """The example's static state with a uniform current of `speed` (m/s) toward `heading_deg` from t = 0."""
    document = tomllib.loads((EXAMPLES / name).read_text())
    heading = math.radians(heading_deg)
    current = {"kind": "uniform", "velocity": [speed * math.cos(heading), speed * math.sin(heading), 0.0]}
    document.setdefault("sea", {})["current"] = current
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        return parse_scenario(apply_overrides(document, {})).model.static()


@pytest.mark.parametrize("name", ["j_lay_waves.toml", "s_lay.toml"])
def test_a_faint_current_across_leaves_the_in_plane_state(name: str) -> None:
    """1e-4 m/s at 90° (the issue's failing case, residual 7.8e5 at load factor 0): every node within 1 mm of
    the state with the current along the lay (0°), which stays in the lay plane to 1e-6 m."""
    along = _static(name, 1e-4, 0.0)
    across = _static(name, 1e-4, 90.0)
    assert np.abs(along.positions[:, 1]).max() < 1e-6
    assert np.abs(across.positions - along.positions).max() < 1e-3


@pytest.mark.parametrize("name", ["j_lay_waves.toml", "s_lay.toml"])
@pytest.mark.parametrize("heading", [45.0, 90.0, 135.0, 270.0])
def test_a_current_across_pushes_the_span_downstream(name: str, heading: float) -> None:
    """0.5 m/s toward 45°, 90°, 135° and 270°: statics converge; the suspended span's largest sideways offset is
    downstream (the sign of the current's cross component) and at least 0.1 m; the pinned laid end stays put;
    the top tension within 10 % of the in-plane state's."""
    state = _static(name, 0.5, heading)
    plane = _static(name, 0.0, 0.0)
    cross = math.sin(math.radians(heading))
    offsets = state.positions[:, 1]
    largest = offsets[np.argmax(np.abs(offsets))]
    assert np.sign(largest) == np.sign(cross) and abs(largest) > 0.1
    assert np.linalg.norm(state.positions[0]) < 1e-9
    top = state.lay_summary()["top_tension"]
    assert top == pytest.approx(plane.lay_summary()["top_tension"], rel=0.1)
