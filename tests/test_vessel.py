"""The DP vessel on the pipe through the Python API: the paper's scenario (passivity, PD bias and the PID),
statics with holding thrust and with an active controller, and bad vessel input."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import jensen2009 as paper


@pytest.fixture(scope="module")
def runs() -> dict[str, tuple[pl.State, pl.Results, float]]:
    """The paper's PD and PID runs (n = 10, Δt = 0.1 s, 200 s)."""
    return {name: paper.run(name, c, 10, 0.1) for name, c in paper.controllers().items()}


def test_passivity_inequality_holds_at_every_step(runs) -> None:
    """E(t) − E(0) − W(t) ≤ solver tolerance at every recorded step (W: work of thrust, environment and
    current), and the dissipation never decreases: the discrete passivity certificate. Tolerance: 1e-9 of
    the energy scale (the gravity potential, ~8e8 J; Newton stops at 1e-10 relative residual)."""
    for _, results, _ in runs.values():
        energy = results.energy["total"]
        excess = energy - energy[0] - results.supplied_work
        scale = np.max(np.abs(energy)) + np.max(np.abs(results.supplied_work))
        assert np.max(excess) <= 1e-9 * scale, np.max(excess)
        assert results.passivity_margin() == pytest.approx(np.max(excess), abs=1e-9 * scale)
        assert np.all(np.diff(results.dissipated) >= 0.0)
        np.testing.assert_allclose(excess, -results.dissipated, atol=1e-9 * scale)


def test_pid_removes_the_sway_bias_of_the_pd(runs) -> None:
    """Under the environmental force and the current in sway, the PD settles with a bias of about a metre;
    the PID's integral removes most of it (PD: 1.10 m, PID: 0.12 m at 200 s)."""
    pd_offset = abs(runs["PD"][1].eta[-1, 1])
    pid_offset = abs(runs["PID"][1].eta[-1, 1])
    assert pd_offset > 0.5
    assert pid_offset < 0.25 * pd_offset
    # The PD has settled: its sway over the last 20 s changes by less than 1 cm.
    tail = runs["PD"][1].eta[-200:, 1]
    assert np.ptp(tail) < 0.01


def test_static_vessel_holds_the_pipe(runs) -> None:
    """The static state: x, y, ψ at η, within the holding springs' give of 1e-4 m per MN of the pipe's pull;
    the holding thrust in surge balances the pipe's horizontal force (the pipe, in compression near the
    vessel, pushes it forward: negative holding thrust)."""
    state = runs["PD"][0]
    body = state.rotations[-1]  # β = 0: the pipe's end frame is the body frame
    thrust = body @ state.tau[:3]
    pipe = body @ state.chi[:3]
    give = 1e-4 * np.linalg.norm(pipe) / 1e6
    np.testing.assert_allclose(state.eta[[0, 1, 5]], [730.0, 0.0, 0.0], rtol=0.0, atol=give)
    assert abs(state.eta[0] - 730.0) > 0.01 * give  # held by a spring, not fixed
    assert thrust[0] + pipe[0] == pytest.approx(0.0, abs=1e-6 * np.linalg.norm(pipe))
    assert state.tau[0] < 0.0 < pipe[0]
    # At the vessel's end the reaction is the pipe's force on the vessel, in e.
    np.testing.assert_allclose(state.reaction("B")[:3], pipe, rtol=1e-12, atol=1e-6)
    results = runs["PD"][1]
    body = results.rotations[-1, -1]
    np.testing.assert_allclose(
        results.reaction("B")[-1, :3], body @ results.chi[-1, :3], rtol=1e-12, atol=1e-6
    )
    assert -800.1 < state.eta[2] < -799.9 and 0.0 < state.eta[4] < 0.2


def test_active_controller_settles_the_static_vessel() -> None:
    """With a PD active at t = 0, surge settles where K_p x̃ balances the pipe: x̃ = −τ_hold/K_p (linearised)."""
    held = paper.scenario(pl.PID(**paper.PD, reference=paper.ETA_REF, start=30.0))
    hold = held.static()
    controlled = paper.scenario(pl.PID(**paper.PD, reference=[730.0, 0, 0, 0, 0, 0], start=0.0))
    state = controlled.static()
    assert state.eta[0] == pytest.approx(730.0 - hold.tau[0] / 0.5e6 * -1.0 * -1.0, rel=0.0, abs=0.2)


@pytest.mark.parametrize(
    ("build", "argument"),
    [
        (lambda: pl.Vessel(-np.eye(6), np.eye(6), np.zeros((6, 6))), "M"),
        (lambda: pl.Vessel(np.eye(6), -np.eye(6), np.zeros((6, 6))), "D"),
        (lambda: pl.Vessel(np.eye(6), np.eye(6), np.eye(6)), "G"),
        (lambda: pl.Vessel(np.eye(5), np.eye(6), np.zeros((6, 6))), "M"),
        (lambda: pl.Vessel(np.full((6, 6), np.nan), np.eye(6), np.zeros((6, 6))), "M"),
        (lambda: pl.PID(kp=[1, 2, 3], kd=np.zeros(6), reference=np.zeros(6)), "kp"),
        (lambda: pl.PID(kp=np.zeros(6), kd=np.zeros(6)), "reference"),
        (lambda: pl.Force([1.0, 2.0]), "value"),
    ],
)
def test_bad_vessel_input_names_the_argument(build, argument: str) -> None:
    with pytest.raises(pl.InputError, match=argument):
        build()


def test_a_vessel_needs_a_sea() -> None:
    rod = pl.Rod.straight((0, 0, 0), (10, 0, 0), 2, paper.pipe_section())
    with pytest.raises(pl.InputError, match="sea"):
        pl.Model(rod).attach_vessel("B", pl.Vessel.osv(), eta=np.zeros(6))


def test_an_end_cannot_carry_both_a_vessel_and_a_support() -> None:
    """Clamping the vessel's end, or attaching a vessel to a clamped end, is refused naming the end."""
    model = paper.scenario(paper.controllers()["PD"])
    with pytest.raises(pl.InputError, match="end"):
        model.clamp("B")
    with pytest.raises(pl.InputError, match="end"):
        model.attach_vessel("A", pl.Vessel.osv(), eta=np.zeros(6))


@pytest.mark.parametrize(
    ("z", "shown"),
    [
        (120.0, "z = 120 m, 240 m below the surface"),  # e3 taken as pointing up: the vessel under the seabed
        (0.0, "z = 0 m, 120 m below the surface"),  # on the seabed
        (-135.0, "z = -135 m, 15 m above the surface"),  # floating in the air
    ],
)
def test_a_vessel_off_the_sea_surface_is_refused(z: float, shown: str) -> None:
    """In 120 m of water the surface is z = −120 m (e3 down, the seabed at z = 0): η's z must lie within 10 m
    of it, [−130, −110] m; the error names `eta`, the value and what is allowed."""
    rod = pl.Rod.straight((0, 0, 0), (200, 0, -120), 10, pl.Section.pipe(0.3, 0.02))
    model = pl.Model(rod, sea=pl.Sea(120.0))
    with pytest.raises(pl.InputError) as refused:
        model.attach_vessel("B", pl.Vessel.osv(), eta=[200.0, 0.0, z, 0.0, 0.0, 0.0])
    message = str(refused.value)
    assert message.startswith("eta: ") and message.endswith(f"got {shown}")
    assert "sea surface z = −depth = -120 m within 10 m: in [-130, -110] m" in message
    assert model.vessel is None
    for afloat in (-130.0, -120.0, -110.0):
        model.attach_vessel("B", pl.Vessel.osv(), eta=[200.0, 0.0, afloat, 0.0, 0.0, 0.0])


def test_a_rod_held_by_nothing_has_no_statics() -> None:
    rod = pl.Rod.straight((0, 0, 0), (10, 0, 0), 2, paper.pipe_section())
    with pytest.raises(pl.InputError, match="supports"):
        pl.Model(rod, gravity=9.81).static()
