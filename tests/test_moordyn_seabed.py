"""Peer-code comparison with MoorDyn v2 with seabed contact: top tension and touchdown of a driven line lying
partly on the seabed.

The case (``moordyn_seabed_case.py`` has every number, how the two codes' seabeds are matched and the
convergence study): the 400 m, 90 mm steel wire rope of ``moordyn_case`` (w = 328.4 N/m, EA = 400 MN) anchored
on a flat seabed in 160 m of water, its top B 340 m across and 150 m up, 132 m of it laid; seabed kBot = 3 MPa/m
(1.2 mm of penetration), cBot = 80 kPa·s/m (about critical), no friction. From rest, B is driven in surge (3 m)
and heave (2 m) at a 10 s period, amplitudes ramped over 10 s, to t = 25 s: the top tension swings between 79
and 131 kN and the touchdown runs over 32 m (116 to 148 m from A).

Resolution: n = 200 elements in both codes (2 m); pipelay dt = 0.025 s, MoorDyn dt = 5e-4 s (RK4; 1e-3 s is
unstable at n = 200). Measured when written: the histories differ by at most 0.77 % of the mean (rms 0.20 %),
the touchdowns by at most 0.97 m (mean 0.11 m), the static top tensions by 0.002 %. MoorDyn's own errors at
this resolution: 0.04 % from its time step (against dt/2), 0.61 % (touchdown 0.87 m) from its mesh (against
n = 400); pipelay's: 0.86 % from its time step (against 0.005 s), 0.59 % from its mesh (against n = 800). The
tolerances: 2 % max and 0.5 % rms for the tension, one element (2 m) for the touchdown, 0.5 % for the static
tension. Runtime ≈ 13 s (MoorDyn's initial-condition solve ≈ 8 s of it).
"""

from __future__ import annotations

import math

import numpy as np
import pipelay
import pytest
from moordyn_seabed_case import (
    SEABED_CASE,
    SeabedRun,
    max_relative_error,
    rms_relative_error,
    run_moordyn,
    run_pipelay,
)

pytest.importorskip("moordyn")
if not hasattr(pipelay, "Seabed"):
    pytest.skip("pipelay has no seabed contact yet", allow_module_level=True)

ELEMENTS = 200
DT_PIPELAY = 0.025  # s
DT_MOORDYN = 5.0e-4  # s
ELEMENT = SEABED_CASE.length / ELEMENTS  # element length (m)


@pytest.fixture(scope="module")
def runs() -> tuple[SeabedRun, SeabedRun]:
    """The pipelay and MoorDyn runs of the case at the converged resolution."""
    return run_pipelay(ELEMENTS, DT_PIPELAY), run_moordyn(ELEMENTS, DT_MOORDYN)


def test_static_state_agrees(runs: tuple[SeabedRun, SeabedRun]) -> None:
    """Static top tensions: pipelay and MoorDyn within 0.5 % of each other and both within 0.1 % of the
    elastic catenary with a laid part on a rigid frictionless seabed (the continuum limit; 1.2 mm of
    penetration and the rope's EI change it by less than 1e-5); the touchdowns within one element of each other
    and of the catenary's."""
    from seabed_reference import laid_catenary

    ours, theirs = runs
    assert abs(ours.static_tension / theirs.static_tension - 1.0) < 0.005, (
        ours.static_tension,
        theirs.static_tension,
    )
    case = SEABED_CASE
    reference = laid_catenary(case.length, case.x0, case.rise, case.submerged_weight, case.ea)
    top = math.hypot(reference.horizontal, case.submerged_weight * reference.suspended_length)
    for value in (ours.static_tension, theirs.static_tension):
        assert abs(value / top - 1.0) < 0.001, (value, top)
    assert ours.touchdown_arc_length is not None and theirs.touchdown_arc_length is not None
    ours_td, theirs_td = float(ours.touchdown_arc_length[0]), float(theirs.touchdown_arc_length[0])
    assert abs(ours_td - theirs_td) < ELEMENT, (ours_td, theirs_td)
    for value in (ours_td, theirs_td):
        assert abs(value - reference.laid_length) < ELEMENT, (value, reference.laid_length)


def test_top_tension_history_agrees(runs: tuple[SeabedRun, SeabedRun]) -> None:
    """The top-tension histories agree to 2 % of the mean tension at every instant and to 0.5 % rms (MoorDyn
    interpolated at pipelay's step midpoints), over a run where the tension swings by half its mean."""
    ours, theirs = runs
    assert ours.time[-1] == pytest.approx(SEABED_CASE.t_end - DT_PIPELAY / 2)
    assert theirs.time[-1] == pytest.approx(SEABED_CASE.t_end)
    swing = (theirs.tension.max() - theirs.tension.min()) / np.mean(theirs.tension)
    assert swing > 0.4, swing
    error = max_relative_error(ours, theirs)
    assert error < 0.02, error
    rms = rms_relative_error(ours, theirs)
    assert rms < 0.005, rms


def test_touchdown_history_agrees(runs: tuple[SeabedRun, SeabedRun]) -> None:
    """The touchdown (the last point on the seabed seen from A, found the same way in both) moves over more
    than 25 m, and the two codes' touchdowns agree to one element at every MoorDyn sample (every 0.05 s;
    pipelay's interpolated there), and so do their extremes."""
    ours, theirs = runs
    assert ours.touchdown_time is not None and ours.touchdown_arc_length is not None
    assert theirs.touchdown_time is not None and theirs.touchdown_arc_length is not None
    assert np.all(np.isfinite(ours.touchdown_arc_length)) and np.all(np.isfinite(theirs.touchdown_arc_length))
    travel = np.ptp(theirs.touchdown_arc_length)
    assert travel > 25.0, travel
    at = np.interp(theirs.touchdown_time, ours.touchdown_time, ours.touchdown_arc_length)
    gap = float(np.max(np.abs(at - theirs.touchdown_arc_length)))
    assert gap < ELEMENT, gap
    for extreme in (np.min, np.max):
        ours_x, theirs_x = extreme(ours.touchdown_arc_length), extreme(theirs.touchdown_arc_length)
        assert abs(ours_x - theirs_x) < ELEMENT, (ours_x, theirs_x)
