"""Checkpoints: a simulation's complete state saved to a file (numpy ``.npz``, written atomically) and resumed
from it exactly, as if the run had not stopped. Importing it makes `checkpoint` the method
``Simulation.checkpoint``.

Imports of pipelay: the engine (`pipelay._core`) and `pipelay.results.atomic`.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from pipelay._core import InputError, Model, Simulation, Stages
from pipelay.results.atomic import _atomic_write

__all__ = ["checkpoint", "resume"]


def checkpoint(simulation: Simulation, path: str | os.PathLike[str]) -> Path:
    """Saves the simulation's complete state (atomically, numpy ``.npz``) so that ``resume`` continues it
    exactly as if it had not stopped."""
    arrays = simulation._checkpoint()
    target = Path(path)

    def write(temporary: Path) -> None:
        with open(temporary, "wb") as stream:
            np.savez(stream, **arrays)

    _atomic_write(target, write)
    return target


def resume(
    model: Model,
    path: str | os.PathLike[str],
    stages: Stages | None = None,
    *,
    allow: Sequence[str] = (),
) -> Simulation:
    """The simulation saved by ``checkpoint``, continued on `model` through `stages`, those the original ran
    through (a pl.Stages; None for a run without stages).

    The checkpoint stores a fingerprint of the model it was saved from, part by part ("line", "sea",
    "gravity", "supports", "point_loads", "attachments", "pay_out", "vessel", "controller", "environment"):
    resuming into a model that differs raises `pl.InputError` naming the parts, unless they are in `allow` (a
    deliberate change, which then no longer continues the original run exactly). The time step and the time
    come from the checkpoint; the end time is the new run's (``Simulation.run(t_end)``)."""
    target = Path(path)
    if not target.is_file():
        raise InputError(f"path: no checkpoint file at {str(target)!r}")
    with np.load(target) as data:
        arrays = {key: data[key] for key in data.files}
    return Simulation._restore(model, arrays, stages, list(allow))


def _attach() -> None:
    """Makes `checkpoint` a method of the engine's Simulation: ``Simulation.checkpoint``."""

    def simulation_checkpoint(self: Simulation, path: str | os.PathLike[str]) -> Path:
        """Save the complete state (atomically); pl.resume continues it exactly."""
        return checkpoint(self, path)

    Simulation.checkpoint = simulation_checkpoint  # type: ignore[attr-defined]


_attach()
