"""Peer-code comparison with MoorDyn v2 with its seabed: a line partly laid on the seabed, top driven, the
touchdown moving along the seabed (``moordyn_seabed_case.py`` has the case and how the codes are matched:
the same kBot, cBot on the diameter, penetration of the centreline, no friction).

Measured when written, n = 100 in both codes (pipelay Δt = 0.025 s, MoorDyn Δt = 5e-4 s, RK4): static top
tension 103 203.0 N and 103 199.8 N (3.0e-5 apart); top-tension histories within 2.2 % of the mean tension;
the touchdown swings between 116.17 and 148.02 m from A in pipelay, 116.08 and 148.02 m in MoorDyn.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("moordyn")

from moordyn_seabed_case import max_relative_error, run_moordyn, run_pipelay

ELEMENTS = 100


@pytest.fixture(scope="module")
def runs() -> tuple[object, object]:
    return run_pipelay(ELEMENTS, 0.025), run_moordyn(ELEMENTS, 5e-4)


def test_static_top_tension_agrees(runs: tuple[object, object]) -> None:
    pipelay, moordyn = runs
    assert pipelay.static_tension == pytest.approx(moordyn.static_tension, rel=2e-4)  # type: ignore[attr-defined]


def test_top_tension_histories_agree(runs: tuple[object, object]) -> None:
    pipelay, moordyn = runs
    assert max_relative_error(pipelay, moordyn) < 0.04  # type: ignore[arg-type]


def test_touchdown_moves_alike(runs: tuple[object, object]) -> None:
    """The touchdown's range over the run agrees within half an element (2 m)."""
    pipelay, moordyn = runs
    ours = np.asarray(pipelay.touchdown_arc_length)  # type: ignore[attr-defined]
    theirs = np.asarray(moordyn.touchdown_arc_length)  # type: ignore[attr-defined]
    assert np.nanmax(ours) - np.nanmin(ours) > 20.0  # the touchdown does move
    assert abs(np.nanmin(ours) - np.nanmin(theirs)) < 2.0
    assert abs(np.nanmax(ours) - np.nanmax(theirs)) < 2.0
