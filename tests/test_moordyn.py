"""Peer-code comparison with MoorDyn v2 (lumped-mass mooring-line code): top tension of a driven line.

The case (``moordyn_case.py`` has every number and how the two models are matched): a 250 m, 90 mm steel wire
rope (40 kg/m, EA = 400 MN, submerged weight 328.4 N/m, Cd = 1.2 normal, Ca = 1) hangs in 200 m of water
between a fixed point A and a top point B 150 m across and 190 m up (10 m below the surface), no seabed
contact. From rest, B is driven in surge (8 m) and heave (2 m) at a 10 s period with amplitudes ramped up over
10 s, to t = 25 s; the top tension |F_B| then swings between 64 and 228 kN. MoorDyn: EI = 0, BA = 0, RK4.
pipelay: EI = 10 N·m² (a cable), energy–momentum integrator.

Resolution (both converged, see the numbers below): n = 100 elements in both codes; pipelay dt = 0.025 s,
MoorDyn dt = 5e-4 s (its explicit scheme's stability limit at n = 100 is ≈ 1.1e-3 s). At this resolution the
two histories differ by at most 0.17 % of the mean (rms 0.05 %), the static top tensions by 0.004 %; the
tolerances asserted are 3 % and 0.5 %. Convergence, measured when written as the max over the run of the
difference in top tension, relative to the mean tension:

* pipelay time step, n = 100: dt = 0.1 / 0.05 / 0.025 / 0.01 s against dt = 0.005 s: 1.08 / 0.32 / 0.085 /
  0.030 % (second order);
* pipelay mesh, dt = 0.005 s: n = 25 / 50 / 100 against n = 200: 1.78 / 0.61 / 0.15 % (second order);
* MoorDyn time step, n = 100: dt = 5e-4 against 2.5e-4 s: 0.004 %; n = 50: 1.5e-3 against 5e-4 s: 0.025 %;
* MoorDyn mesh: n = 50 against 100: 0.40 %, n = 100 against 200: 0.15 %;
* pipelay against MoorDyn at equal n (fine dt): n = 50: 0.56 %, n = 100: 0.14 %, n = 200: 0.04 %; static
  top tensions at n = 100: 99142.2 N and 99138.3 N (Irvine's elastic catenary, the n → ∞ limit: 99146.3 N).

pipelay's recorded reaction at t_{k+1} is its step's algorithmic (midpoint) force, so the pipelay history is
compared at the step midpoints t_k + dt/2 (``moordyn_case.run_pipelay``); read at t_{k+1}, the same pipelay
run differs from MoorDyn by ≈ 1.7 % of the mean here (3.4 % at dt = 0.05 s), a first-order time lag.
"""

from __future__ import annotations

import numpy as np
import pytest
from irvine import irvine_catenary
from moordyn_case import CASE, Run, max_relative_error, run_moordyn, run_pipelay

pytest.importorskip("moordyn")

ELEMENTS = 100
DT_PIPELAY = 0.025  # s
DT_MOORDYN = 5.0e-4  # s


@pytest.fixture(scope="module")
def runs() -> tuple[Run, Run]:
    """The pipelay and MoorDyn runs of the case at the converged resolution."""
    return run_pipelay(ELEMENTS, DT_PIPELAY), run_moordyn(ELEMENTS, DT_MOORDYN)


def test_static_top_tension_agrees(runs: tuple[Run, Run]) -> None:
    """Static top tensions: pipelay and MoorDyn within 0.5 % of each other, and both within 0.1 % of Irvine's
    elastic catenary (the continuum limit; the rope's EI is negligible)."""
    ours, theirs = runs
    assert abs(ours.static_tension / theirs.static_tension - 1.0) < 0.005, (
        ours.static_tension,
        theirs.static_tension,
    )
    irvine = irvine_catenary(
        length=CASE.length, span=CASE.x0, rise=CASE.rise, weight=CASE.submerged_weight, ea=CASE.ea
    ).tension_b
    for value in (ours.static_tension, theirs.static_tension):
        assert abs(value / irvine - 1.0) < 0.001, (value, irvine)


def test_top_tension_history_agrees(runs: tuple[Run, Run]) -> None:
    """The top-tension histories agree to 3 % of the mean tension at every instant (MoorDyn interpolated at
    pipelay's sample times), over a run that is truly dynamic: the tension more than doubles."""
    ours, theirs = runs
    assert ours.time[-1] == pytest.approx(CASE.t_end - DT_PIPELAY / 2) and theirs.time[-1] == pytest.approx(
        CASE.t_end
    )
    swing = (theirs.tension.max() - theirs.tension.min()) / np.mean(theirs.tension)
    assert swing > 1.0, swing
    error = max_relative_error(ours, theirs)
    assert error < 0.03, error
