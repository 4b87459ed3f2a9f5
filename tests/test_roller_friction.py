"""Roller friction: a straight pipe on a flat stinger of V boxes whose rollers are locked (Coulomb μ) or turn
against a rolling resistance, held by the tensioner and pulled from its far end. Statics take the pipe sliding
out over the rollers (paying out), so the tension falls toward the tensioner by μ ΣN over locked rollers and by
f_r ΣN over free-turning ones (N each roller's normal force). A run paying the pipe out over them keeps that
difference while it slides, and its energy ledger closes with the friction's dissipation booked."""

from __future__ import annotations

import numpy as np
import pipelay as pl
import pytest

THETA = np.radians(30.0)
SECTION = pl.Section.pipe(0.6, 0.03, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0))
DEPTH = 100.0
# The tensioner 10 m forward of CO, the pipe's centre 5 m above the waterline; the boxes' stations R/cos θ
# below it (a pipe of radius R rests that high in a V), on a stinger flat to 2e-5 m over its 40 m.
TENSIONER = np.array([10.0, 0.0, -5.0])
STATION_Z = TENSIONER[2] + 0.3 / np.cos(THETA)
PULL = 50e3  # N at end A, away from the vessel


def _model(box: pl.RollerBox, speed: float | None = None, aft: float = 46.0) -> pl.Model:
    """The pipe (in 2 m elements) from `aft` m aft of CO (46: its free end 11 m beyond the last box) to the
    tensioner, on 5 boxes 10 m apart, pulled aft at end A; paid out at `speed` (m/s, ramped in over 2 s) if
    given."""
    x_vessel = 500.0
    start = (x_vessel - aft, 0.0, -DEPTH + TENSIONER[2])
    end = (x_vessel + TENSIONER[0], 0.0, -DEPTH + TENSIONER[2])
    elements = round((aft + TENSIONER[0]) / 2.0)
    model = pl.Model(pl.Rod.straight(start, end, elements, SECTION), sea=pl.Sea(DEPTH))
    stinger = pl.Stinger(1e7, 40.0, 5, origin=(5.0, 0.0, STATION_Z), boxes=[box] * 5)
    lay = pl.SLay(tensioner=TENSIONER, stinger=stinger)
    pid = pl.PID(
        kp=[2e5, 2e5, 0, 0, 0, 3.5e7],
        kd=[4e6, 4e6, 0, 0, 0, 7e8],
        reference=[x_vessel, 0.0, 0.0, 0.0, 0.0, 0.0],
        bumpless=True,
    )
    model.attach_vessel("B", pl.Vessel.osv(), eta=[x_vessel, 0.0, -DEPTH, 0, 0, 0], controller=pid, lay=lay)
    model.point_load(0, force=(-PULL, 0.0, 0.0))
    if speed is not None:
        model.pay_out("B", speed=lambda t: speed * min(t / 2.0, 1.0))
    return model


def _normal_sum(state: pl.State) -> float:
    """ΣN: the rollers' normal forces (N)."""
    return float(np.sum(state.roller_reactions))


def _top(box: pl.RollerBox) -> tuple[float, float]:
    """The top tension (N) and ΣN (N) of the static state on `box`es."""
    state = _model(box).static()
    return state.lay_summary()["top_tension"], _normal_sum(state)


@pytest.mark.parametrize(
    ("box", "coefficient"),
    [
        (pl.RollerBox(kind="v", half_angle=THETA, friction=0.3, locked=True), 0.3),
        (pl.RollerBox(kind="v", half_angle=THETA, friction=0.3, rolling_resistance=0.05), 0.05),
    ],
    ids=["locked", "free-turning"],
)
def test_static_tension_falls_toward_the_tensioner_by_the_friction(
    box: pl.RollerBox, coefficient: float
) -> None:
    """The friction lowers the tension at the tensioner by f ΣN (f = μ locked, f_r free-turning) from the
    frictionless boxes' (which pass the whole pull, to the pipe's slope at the tensioner: 7e-4), to 1e-5."""
    frictionless, _ = _top(pl.RollerBox(kind="v", half_angle=THETA))
    assert frictionless == pytest.approx(PULL, rel=1e-3)
    top, normal = _top(box)
    assert normal > 60e3  # the pipe's submerged weight, 1.28 kN/m over 56 m, on rollers at 30°
    ratio = (frictionless - top) / (coefficient * normal)
    print(f"f = {coefficient}: ΣN {normal / 1e3:.2f} kN, T_top {top / 1e3:.3f} kN, ratio {ratio:.6f}")
    assert ratio == pytest.approx(1.0, abs=1e-5)


def test_paying_out_over_locked_rollers_slides_against_mu_n_and_closes_the_ledger() -> None:
    """Paid out at 0.2 m/s over locked rollers (μ = 0.3), the pipe slides: after the ramp the tension at the
    tensioner is μ ΣN below the pull on average (within 1 %; it rings, sticking and slipping, within the step's
    resolution), the friction dissipates μ ΣN times the length paid out (within 5 %), and the ledger closes to
    1e-10 of the stored energy."""
    model = _model(pl.RollerBox(kind="v", half_angle=THETA, friction=0.3, locked=True), speed=0.2)
    results = model.simulation(dt=0.05).run(8.0, progress=False)
    lay = results.lay_summary()
    assert lay is not None
    normal = results.roller_reactions.sum(axis=1)
    late = results.time > 4.0
    ratio = np.mean(PULL - lay["top_tension"][late]) / (0.3 * np.mean(normal[late]))
    paid = 0.2 * (8.0 - 1.0)  # the speed ramps in over the first 2 s
    work = 0.3 * np.mean(normal) * paid
    print(
        f"mean (T_A − T_top)/(μ ΣN) while sliding {ratio:.4f}; dissipated {results.dissipated[-1]:.0f} J of μΣN·Δs {work:.0f} J"
    )
    assert ratio == pytest.approx(1.0, abs=0.01)
    assert results.dissipated[-1] == pytest.approx(work, rel=0.05)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.max(np.abs(balance)) < 1e-10 * np.max(np.abs(energy)), np.max(np.abs(balance))


@pytest.mark.parametrize("aft", [36.0, 38.0, 40.0])
def test_a_free_end_just_beyond_the_last_box_rests_in_it(aft: float) -> None:
    """The pipe's free end 1 to 5 m beyond the last box: statics find it resting in every box's V (each V roller
    pressed, as F/(2 cos θ) of the box's load, within 1e-4), not wedged between the V's lower ends as Newton's
    steps of a whole contact reach once left it."""
    state = _model(pl.RollerBox(kind="v", half_angle=THETA), aft=aft).static()
    supports = np.array(state.roller_supports)
    for box in range(5):
        rollers = state.roller_reaction_vectors[supports == box]
        share = np.linalg.norm(rollers, axis=1)
        assert np.all(share > 0.0) and share[0] == pytest.approx(share[1], rel=1e-4), (box, share)
        assert np.linalg.norm(rollers.sum(axis=0)) == pytest.approx(2 * np.cos(THETA) * share[0], rel=1e-4)


def test_bad_friction_is_refused() -> None:
    """A negative or NaN coefficient names the argument."""
    with pytest.raises(pl.InputError, match="friction"):
        pl.RollerBox(friction=-0.1)
    with pytest.raises(pl.InputError, match="rolling_resistance"):
        pl.RollerBox(rolling_resistance=float("nan"))
    with pytest.raises(pl.InputError, match="friction"):
        pl.SLay(tensioner=TENSIONER, friction=-1.0)
