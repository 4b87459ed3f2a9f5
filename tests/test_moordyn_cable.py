"""The cable element (`pl.Section.cable`: tension only, 3 DOFs per node) against MoorDyn v2, against the rod
with EI = 10 N·m² that imitates a cable in ``test_moordyn.py``, and its conservation in free flight.

The driven case is ``moordyn_case.py``'s (a 250 m, 90 mm steel wire rope in 200 m of water, its top driven in
surge and heave to t = 25 s, the top tension swinging between 64 and 228 kN), with ``Case(cable=True)``:
the same d, mass, EA, drag and added mass on cable elements. Resolution: n = 100 in both codes, pipelay
dt = 0.025 s, MoorDyn dt = 5e-4 s (RK4, BA = 0), both converged (``test_moordyn.py`` has the convergence
study). MoorDyn starts from its own initial-condition solve cut at 60 s of relaxation at dt = l/c (l the
segment length, c the axial wave speed), which leaves its static top tension 0.054 % below equilibrium;
measured when written, the histories against MoorDyn from a 300 s solve differ by the same max 0.170 % and
rms 0.048 % of the mean to three digits, so the shorter solve changes nothing asserted here.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pipelay as pl
import pytest
from irvine import irvine_catenary
from moordyn_case import (
    CASE,
    Run,
    axial_wave_time,
    max_relative_error,
    moordyn_initial,
    run_moordyn,
    run_pipelay,
)

ELEMENTS = 100
DT_PIPELAY = 0.025  # s
DT_MOORDYN = 5.0e-4  # s
CABLE = replace(CASE, cable=True)


def rms_relative_error(run: Run, reference: Run) -> float:
    """rms of T − T_ref over the run, the reference interpolated at ``run.time``, relative to the mean of the
    reference (-)."""
    ref = np.interp(run.time, reference.time, reference.tension)
    return float(np.sqrt(np.mean((run.tension - ref) ** 2)) / np.mean(reference.tension))


@pytest.fixture(scope="module")
def runs() -> tuple[Run, Run, Run]:
    """The cable, the EI = 10 rod and MoorDyn on the driven wire rope (≈ 2.5 s in all)."""
    pytest.importorskip("moordyn")
    initial, _ = moordyn_initial(ELEMENTS, axial_wave_time(ELEMENTS), ic_time=60.0)
    theirs = run_moordyn(ELEMENTS, DT_MOORDYN, initial=initial)
    return run_pipelay(ELEMENTS, DT_PIPELAY, CABLE), run_pipelay(ELEMENTS, DT_PIPELAY), theirs


def test_cable_top_tension_history_agrees_with_moordyn(runs: tuple[Run, Run, Run]) -> None:
    """Top tension |F_B| of the cable against MoorDyn (interpolated at pipelay's step midpoints): rms within
    1 % of the mean tension, max within 0.5 %, over a run whose tension more than doubles.

    Measured when written: rms 0.048 %, max 0.170 % (the rod's max: 0.170 %). The max is the two codes'
    discretisation error: at fine dt they differ by 0.56 / 0.14 / 0.04 % at n = 50 / 100 / 200
    (``test_moordyn.py``), and pipelay's dt = 0.025 s adds 0.085 %; 0.5 % leaves a factor 3. Either bound fails
    for a modelling error of the cable's section (measured, each alone, against this MoorDyn run): normal drag
    −5 %: rms 1.66 %, max 4.65 %; mass +1 %: rms 1.05 %, max 1.46 %; axial added mass 0 instead of 1: max
    1.57 %; EA −5 %: max 0.66 %."""
    cable, _, theirs = runs
    assert cable.time[-1] == pytest.approx(CASE.t_end - DT_PIPELAY / 2)
    assert theirs.time[-1] == pytest.approx(CASE.t_end)
    swing = (theirs.tension.max() - theirs.tension.min()) / np.mean(theirs.tension)
    assert swing > 1.0, swing  # measured 1.43
    rms = rms_relative_error(cable, theirs)
    assert rms < 0.01, rms
    error = max_relative_error(cable, theirs)
    assert error < 0.005, error


def test_cable_agrees_with_the_rod_that_imitates_it(runs: tuple[Run, Run, Run]) -> None:
    """The cable and the rod with EI = GJ = 10 N·m² (bending length ≤ 5 cm against 2.5 m elements) on the same
    mesh and steps: static top tensions within 1e-6 and histories within 1e-4 of the mean, at every sample.

    Measured when written: static 99142.158 N (cable) and 99142.154 N (rod), 3.5e-8 apart; histories at most
    8.5e-6 of the mean apart (1.4e-4 at n = 50). What remains is the rod's bending stiffness and rotational
    inertia, which the cable has not. A 10 % error in the cable's added mass (Ca = 0.9 across and along) moves
    it by 6.4e-3. The cable is within 1e-4 of Irvine's elastic catenary (99146.3 N; measured −4.2e-5, the
    O(h²) mesh error)."""
    cable, rod, _ = runs
    assert abs(cable.static_tension / rod.static_tension - 1.0) < 1e-6, (
        cable.static_tension,
        rod.static_tension,
    )
    np.testing.assert_array_equal(cable.time, rod.time)
    error = max_relative_error(cable, rod)
    assert error < 1e-4, error
    irvine = irvine_catenary(
        length=CASE.length, span=CASE.x0, rise=CASE.rise, weight=CASE.submerged_weight, ea=CASE.ea
    ).tension_b
    assert abs(cable.static_tension / irvine - 1.0) < 1e-4, (cable.static_tension, irvine)


# Free flight of a cable in vacuum.

FLIGHT_LENGTH = 300.0  # m
FLIGHT_AXIS = np.array([0.6, 0.0, 0.8])
FLIGHT_SECTION = pl.Section.cable(diameter=0.09, mass=40.0, EA=4.0e8)  # the wire rope above
RELEASE = 2.0  # s: the loads act up to here


def loads_on(t: float) -> float:
    """1 up to t = RELEASE, then 0: the loads stop at once, so the cable is released in full stretch."""
    return 1.0 if t <= RELEASE else 0.0


def flying_cable(elements: int = 30) -> pl.Model:
    """A 300 m cable inclined by atan(4/3), no sea, no gravity; its ends pulled apart along it by ±1 MN and
    across it (55 kN at B, 25 kN at A, both sideways, and 20 kN out of plane at B) up to t = 2 s."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), tuple(FLIGHT_LENGTH * FLIGHT_AXIS), elements, FLIGHT_SECTION)
    model = pl.Model(rod, gravity=0.0)
    side, out = np.array([0.0, 1.0, 0.0]), np.cross(FLIGHT_AXIS, [0.0, 1.0, 0.0])
    model.point_load("B", force=tuple(1e6 * FLIGHT_AXIS + 5e4 * side + 2e4 * out), scale=loads_on)
    model.point_load("A", force=tuple(-1e6 * FLIGHT_AXIS - 2.5e4 * side), scale=loads_on)
    return model


def test_cable_free_flight_conserves_energy_and_momentum() -> None:
    """Loaded to t = 2 s, released in stretch and flown on to t = 3 s, then 1100 steps of Δt = 0.05 s of free
    flight: total energy constant to 1e-9 relative, linear and angular momentum to 1e-12,
    nothing supplied or dissipated, while the cable whips: it goes slack and taut again (the slack branch of
    the discrete gradient), its strain energy swings through more than 10 % of the total, and its chord turns
    by more than 2 rad. In the loaded phase, E(t) − E(0) = W(t) to 1e-10 of the work.

    Measured when written (0.1 s): energy drift 4.4e-11 (per step at most 4.7e-12, a random walk of
    round-off and Newton's tolerance), linear momentum 7e-16, angular 1e-15; loaded-phase balance 4.8e-12;
    E = 8.21e5 J, strain energy 0 to 1.16e5 J (14 % of E); 95 % of the element samples slack, 73 % of the
    records with an element above 10 kN (at most 2.0 MN); chord turned 2.79 rad. A cable carries no
    compression: slack elements report a tension of exactly 0."""
    model = flying_cable()
    sim = model.simulation(state=model.rest(), dt=0.05)
    loaded = sim.run(3.0, progress=False)
    work = loaded.supplied_work
    balance = np.max(np.abs(loaded.energy["total"] - loaded.energy["total"][0] - work)) / np.max(np.abs(work))
    assert balance < 1e-10, balance
    energy = sim.state.energy()["total"]
    linear = np.array(sim.linear_momentum())
    angular = np.array(sim.angular_momentum())
    assert energy > 5e5 and np.linalg.norm(linear) > 5e4 and np.linalg.norm(angular) > 5e6
    res = sim.run(58.0, progress=False, record_every=10)
    assert len(res) == 111
    drift = np.max(np.abs(res.energy["total"] - energy)) / energy
    assert drift < 1e-9, drift
    dlinear = np.linalg.norm(np.array(sim.linear_momentum()) - linear) / np.linalg.norm(linear)
    dangular = np.linalg.norm(np.array(sim.angular_momentum()) - angular) / np.linalg.norm(angular)
    assert dlinear < 1e-12, dlinear
    assert dangular < 1e-12, dangular
    assert abs(res.supplied_work[-1]) < 1e-9 * energy and res.dissipated[-1] == 0.0
    # It whips: strain energy exchanged with kinetic, slack and taut elements, a large rotation.
    strain = res.energy["pipe_strain"]
    assert strain.max() - strain.min() > 0.1 * energy, (strain.min(), strain.max())
    tension = res.tension
    assert np.mean(tension == 0.0) > 0.5 and np.mean(np.any(tension > 1e4, axis=1)) > 0.5
    assert tension.min() == 0.0, tension.min()
    chord = res.positions[:, -1] - res.positions[:, 0]
    cosine = np.dot(chord[0], chord[-1]) / (np.linalg.norm(chord[0]) * np.linalg.norm(chord[-1]))
    assert math.acos(np.clip(cosine, -1.0, 1.0)) > 2.0
