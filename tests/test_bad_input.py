"""Bad input raises ``pl.InputError`` (a ValueError) whose message names the argument at fault.

Each case builds what it needs and, if building succeeds, solves: an error found late (at ``model.static()``)
still counts, as long as it is an InputError naming the argument. No case may crash the interpreter.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pipelay as pl
import pytest

NAN = math.nan
INF = math.inf


def section(**overrides: object) -> pl.Section:
    """A valid section (N, N·m², kg/m) with some arguments replaced."""
    args: dict[str, object] = {"EA": 1.0e6, "GA": 1.0e6, "GJ": 1.0e3, "EI": 1.0e3, "mass": 1.0}
    args.update(overrides)
    return pl.Section(**args)


def pipe(**overrides: object) -> pl.Section:
    """A valid 0.6 m × 15 mm steel pipe section with some arguments replaced."""
    args: dict[str, object] = {"outer_diameter": 0.6, "wall_thickness": 0.015}
    args.update(overrides)
    return pl.Section.pipe(**args)


def straight(elements: int = 4, start: object = (0.0, 0.0, 0.0), end: object = (10.0, 0.0, 0.0)) -> pl.Rod:
    """A straight 10 m rod along e1."""
    return pl.Rod.straight(start, end, elements, section())


def rod_from(nodes: object) -> pl.Rod:
    """A rod from explicit nodes."""
    return pl.Rod(nodes, section())


def model(sea: pl.Sea | None = None, gravity: float = 9.81) -> pl.Model:
    """A valid 4-element cantilever, clamped at A."""
    m = pl.Model(straight(), sea=sea, gravity=gravity)
    m.clamp("A")
    return m


def solve(build: Callable[[], object]) -> Callable[[], object]:
    """Build, and if the result is a model, solve it (so that late validation is also exercised)."""

    def run() -> object:
        built = build()
        if isinstance(built, pl.Model):
            return built.static()
        if isinstance(built, pl.Sea):
            return model(sea=built).static()
        if isinstance(built, pl.Current):
            return model(sea=pl.Sea(100.0, current=built)).static()
        if isinstance(built, pl.Rod):
            m = pl.Model(built, gravity=0.0)
            m.clamp("A")
            return m.static()
        return built

    return run


def with_load(**kwargs: object) -> pl.Model:
    """The cantilever with one point load."""
    m = model()
    m.point_load(**kwargs)
    return m


def clamped_b(**kwargs: object) -> pl.Model:
    """The cantilever with B clamped as well."""
    m = model()
    m.clamp("B", **kwargs)
    return m


def pinned_b(**kwargs: object) -> pl.Model:
    """The cantilever with B pinned as well."""
    m = model()
    m.pin("B", **kwargs)
    return m


def static_with(steps: object) -> object:
    """Solve the cantilever with a given number of load steps."""
    return model().static(steps=steps)


CASES = [
    # Section: stiffness and mass must be finite and > 0
    pytest.param(lambda: section(EA=0.0), "EA", id="EA-zero"),
    pytest.param(lambda: section(EA=-1.0e6), "EA", id="EA-negative"),
    pytest.param(lambda: section(EA=NAN), "EA", id="EA-nan"),
    pytest.param(lambda: section(EA=INF), "EA", id="EA-inf"),
    pytest.param(lambda: section(GA=0.0), "GA", id="GA-zero"),
    pytest.param(lambda: section(GA=(1.0e6, -1.0)), "GA", id="GA-pair-negative"),
    pytest.param(lambda: section(GJ=-5.0), "GJ", id="GJ-negative"),
    pytest.param(lambda: section(GJ=NAN), "GJ", id="GJ-nan"),
    pytest.param(lambda: section(EI=0.0), "EI", id="EI-zero"),
    pytest.param(lambda: section(EI=(1.0e3, 0.0)), "EI", id="EI-pair-zero"),
    pytest.param(lambda: section(EI=-INF), "EI", id="EI-minus-inf"),
    pytest.param(lambda: section(mass=0.0), "mass", id="mass-zero"),
    pytest.param(lambda: section(mass=-1.0), "mass", id="mass-negative"),
    pytest.param(lambda: section(mass=NAN), "mass", id="mass-nan"),
    pytest.param(lambda: section(inertia=(-1.0, 0.0, 0.0)), "inertia", id="inertia-negative"),
    pytest.param(lambda: section(outer_diameter=-0.1), "outer_diameter", id="outer_diameter-negative"),
    pytest.param(lambda: section(displaced_area=NAN), "displaced_area", id="displaced_area-nan"),
    pytest.param(lambda: section(drag=(0.0, -1.0)), "drag", id="drag-negative"),
    pytest.param(lambda: section(added_mass=(NAN, 1.0)), "added_mass", id="added_mass-nan"),
    # Section.pipe
    pytest.param(lambda: pipe(outer_diameter=0.0), "outer_diameter", id="pipe-od-zero"),
    pytest.param(lambda: pipe(wall_thickness=0.0), "wall_thickness", id="pipe-wt-zero"),
    pytest.param(lambda: pipe(wall_thickness=0.4), "wall_thickness", id="pipe-wt-above-radius"),
    pytest.param(lambda: pipe(density=-7850.0), "density", id="pipe-density-negative"),
    pytest.param(lambda: pipe(youngs_modulus=NAN), "youngs_modulus", id="pipe-E-nan"),
    pytest.param(lambda: pipe(poisson_ratio=0.5), "poisson_ratio", id="pipe-nu-half"),
    pytest.param(lambda: pipe(contents_density=-1.0), "contents_density", id="pipe-contents-negative"),
    # Rod.straight
    pytest.param(lambda: straight(elements=0), "elements", id="straight-zero-elements"),
    pytest.param(lambda: straight(elements=-2), "elements", id="straight-negative-elements"),
    pytest.param(lambda: straight(end=(0.0, 0.0, 0.0)), ("start", "end"), id="straight-coincident-ends"),
    pytest.param(lambda: straight(start=(NAN, 0.0, 0.0)), "start", id="straight-start-nan"),
    pytest.param(lambda: straight(end=(10.0, INF, 0.0)), "end", id="straight-end-inf"),
    # Rod(nodes)
    pytest.param(lambda: rod_from(np.zeros((1, 3))), "nodes", id="nodes-zero-elements"),
    pytest.param(
        lambda: rod_from(np.array([[0.0, 0, 0], [1.0, 0, 0], [1.0, 0, 0], [2.0, 0, 0]])),
        "nodes",
        id="nodes-coincident",
    ),
    pytest.param(
        lambda: rod_from(np.array([[0.0, 0, 0], [NAN, 0, 0], [2.0, 0, 0]])), "nodes", id="nodes-nan"
    ),
    pytest.param(
        lambda: rod_from(np.array([[0.0, 0, 0], [1.0, 0, 0], [2.0, 0, -INF]])), "nodes", id="nodes-inf"
    ),
    pytest.param(lambda: rod_from(np.array([[0.0, 0.0], [1.0, 0.0]])), "nodes", id="nodes-wrong-shape"),
    # Sea and current
    pytest.param(lambda: pl.Sea(NAN), "depth", id="sea-depth-nan"),
    pytest.param(lambda: pl.Sea(INF), "depth", id="sea-depth-inf"),
    pytest.param(lambda: pl.Sea(0.0), "depth", id="sea-depth-zero"),
    pytest.param(lambda: pl.Sea(-100.0), "depth", id="sea-depth-negative"),
    pytest.param(lambda: pl.Sea(100.0, density=NAN), "density", id="sea-density-nan"),
    pytest.param(lambda: pl.Current.uniform((NAN, 0.0, 0.0)), "velocity", id="current-uniform-nan"),
    pytest.param(lambda: pl.Current.linear((0.0, INF, 0.0)), "surface_velocity", id="current-linear-inf"),
    # Model and supports
    pytest.param(lambda: model(gravity=NAN), "gravity", id="gravity-nan"),
    pytest.param(lambda: model(gravity=INF), "gravity", id="gravity-inf"),
    pytest.param(lambda: model().clamp("C"), "end", id="clamp-unknown-end"),
    pytest.param(lambda: model().pin("C"), "end", id="pin-unknown-end"),
    pytest.param(lambda: model().clamp(""), "end", id="clamp-empty-end"),
    pytest.param(lambda: clamped_b(position=(NAN, 0.0, 0.0)), "position", id="clamp-position-nan"),
    pytest.param(lambda: clamped_b(position=(1.0, 2.0)), "position", id="clamp-position-short"),
    pytest.param(lambda: clamped_b(rotation=2.0 * np.eye(3)), "rotation", id="clamp-rotation-not-orthogonal"),
    pytest.param(
        lambda: clamped_b(rotation=np.diag([1.0, 1.0, -1.0])), "rotation", id="clamp-rotation-reflection"
    ),
    pytest.param(lambda: clamped_b(rotation=np.full((3, 3), NAN)), "rotation", id="clamp-rotation-nan"),
    pytest.param(lambda: pinned_b(position=(0.0, INF, 0.0)), "position", id="pin-position-inf"),
    # Point loads
    pytest.param(lambda: with_load(node=5), "node", id="load-node-past-end"),
    pytest.param(lambda: with_load(node=-6), "node", id="load-node-before-start"),
    pytest.param(lambda: with_load(node="C"), "node", id="load-node-unknown-end"),
    pytest.param(lambda: with_load(node="B", force=(NAN, 0.0, 0.0)), "force", id="load-force-nan"),
    pytest.param(lambda: with_load(node="B", force=(1.0, 2.0)), "force", id="load-force-short"),
    pytest.param(lambda: with_load(node=2, moment=(0.0, 0.0, INF)), "moment", id="load-moment-inf"),
    # Solver settings
    pytest.param(lambda: static_with(0), "steps", id="steps-zero"),
    pytest.param(lambda: static_with(-3), "steps", id="steps-negative"),
]


@pytest.mark.parametrize(("build", "argument"), CASES)
def test_bad_input_names_the_argument(build: Callable[[], object], argument: str | tuple[str, ...]) -> None:
    """The call (or the solve that follows it) raises pl.InputError, a ValueError, naming ``argument``."""
    with pytest.raises(pl.InputError) as info:
        solve(build)()
    assert isinstance(info.value, ValueError)
    message = str(info.value)
    names = (argument,) if isinstance(argument, str) else argument
    assert any(name in message for name in names), message


def test_valid_baseline_solves() -> None:
    """The valid cantilever that the cases above spoil does solve: under a small tip force P = 0.01 N along e3
    (no gravity) its tip deflects by P L³/(3 EI) + P L/GA = 3.334e-3 m, to 3 % with 4 elements."""
    m = model(gravity=0.0)
    m.point_load("B", force=(0.0, 0.0, 0.01))
    state = m.static()
    expected = 0.01 * 10.0**3 / (3.0 * 1.0e3) + 0.01 * 10.0 / 1.0e6
    assert state.positions[-1, 2] == pytest.approx(expected, rel=0.03)


def test_error_types() -> None:
    """InputError is a ValueError and ConvergenceError a RuntimeError, as the API promises."""
    assert issubclass(pl.InputError, ValueError)
    assert issubclass(pl.ConvergenceError, RuntimeError)
