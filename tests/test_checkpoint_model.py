"""Checkpoints that know their model: a resume into a model that differs from the one saved is refused, naming
the part that differs, unless the change is allowed; the same model resumes bit for bit."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import jensen2009 as paper


def _model(
    controller: str = "PD",
    force: float = 6e5,
    current: float = -0.8,
    clamp: float = 0.0,
    ea: float | None = None,
) -> pl.Model:
    """The paper's model (examples/jensen2009.py) with the given controller, environmental force (N), surface
    current (m/s, along e2), seabed end's x (m) and EA (N)."""
    section = paper.pipe_section()
    if ea is not None:
        section = pl.Section(EA=ea, GA=1e9, GJ=1e11, EI=1e11, mass=section.mass, outer_diameter=0.6)
    rod = pl.Rod.straight((clamp, 0, 0), (paper.LENGTH, 0, 0), 10, section)
    sea = pl.Sea(paper.DEPTH, current=pl.Current.linear((0.0, current, 0.0), start=10.0))
    model = pl.Model(rod, sea)
    model.clamp("A")
    model.attach_vessel(
        "B",
        pl.Vessel.osv(),
        eta=[730.0, 0.0, -paper.DEPTH, 0.0, 0.0, 0.0],
        controller=paper.controllers()[controller],
        environment=[pl.Force([0.0, force, 0.0, 0.0, 0.0, 0.0], start=10.0)],
    )
    return model


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, pl.Results]:
    """The paper's PD scenario run to 20 s and checkpointed; and the run continued straight on to 30 s."""
    model = _model()
    simulation = model.simulation(state=model.static(), dt=0.25)
    simulation.run(20.0, progress=False)
    path = simulation.checkpoint(tmp_path_factory.mktemp("checkpoint") / "state.npz")
    return path, simulation.run(30.0, progress=False)


def test_the_same_model_resumes_bit_for_bit(saved) -> None:
    path, straight_on = saved
    resumed = pl.resume(_model(), path).run(30.0, progress=False)
    assert np.array_equal(resumed.positions, straight_on.positions)
    assert np.array_equal(resumed.eta, straight_on.eta)


@pytest.mark.parametrize(
    ("change", "parts"),
    [
        (lambda: _model(controller="PID"), ["controller"]),
        (lambda: _model(force=5e5), ["environment"]),
        (lambda: _model(current=-0.7), ["sea"]),
        (lambda: _model(clamp=0.01), ["line", "supports"]),
    ],
)
def test_a_different_model_is_refused_naming_the_part(saved, change, parts: list[str]) -> None:
    """A model of the same size but another controller, environmental force, current or seabed end (the line
    and its clamp 1 cm along): pl.InputError naming the parts that differ; with allow=parts the deliberate
    change resumes, and after the controller's start at 30 s no longer runs as the original model does."""
    path, _ = saved
    named = ", ".join(parts)
    with pytest.raises(
        pl.InputError, match=rf"^model: must be the model .*differs from the checkpoint's in {named}$"
    ):
        pl.resume(change(), path)
    changed = pl.resume(change(), path, allow=parts).run(40.0, progress=False)
    original = pl.resume(_model(), path).run(40.0, progress=False)
    assert not np.array_equal(changed.positions[-1], original.positions[-1])


def test_allow_names_parts_of_a_model(saved) -> None:
    path, _ = saved
    with pytest.raises(pl.InputError, match=r"^allow: must name parts of a model: line, sea"):
        pl.resume(_model(), path, allow=["mesh"])
