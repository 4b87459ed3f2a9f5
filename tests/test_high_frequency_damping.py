"""High-frequency damping of the line's strains: `model.simulation(..., high_frequency_damping=ξ)`.

The case: a 20 m steel pipe (0.6 m × 25 mm), one element, clamped at end A, in vacuum without gravity, pulled
along its axis at end B by 1 MN from rest. Its one axial mode (ω = √(EA/(L m_B)), m_B the end's lumped mass)
rings about the static force.

References: the damped midpoint rule's amplification of a mode the step cannot resolve (ωΔt ≫ 1): with the
damping stress ξ C ΔΓ the scheme is the θ-method with θ = ½ + ξ on the stiffness, whose amplification tends to
−(1 − 2ξ)/(1 + 2ξ); of a mode the step resolves (ωΔt ≪ 1): the damping ratio ξωΔt/2 of a stiffness-proportional
damping β = ξΔt; the discrete energy ledger E(t) − E(0) = W(t) − D(t), the damping's work in D.
"""

from __future__ import annotations

import math

import numpy as np
import pipelay as pl
import pytest

PIPE = pl.Section.pipe(outer_diameter=0.6, wall_thickness=0.025)
LENGTH, FORCE = 20.0, 1e6


def _pulled(damping: float, dt: float, t_end: float) -> pl.Results:
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (LENGTH, 0.0, 0.0), 1, PIPE)
    model = pl.Model(rod, gravity=0.0)
    model.clamp("A")
    model.point_load("B", force=(FORCE, 0.0, 0.0))
    simulation = model.simulation(model.rest(), dt=dt, high_frequency_damping=damping)
    return simulation.run(t_end, progress=False)


def _axial_mode() -> float:
    """ω of the element's axial mode (rad/s): EA/L on the end's half of the element's mass."""
    ea = PIPE.EA
    return math.sqrt(ea / LENGTH / (0.5 * PIPE.mass * LENGTH))


@pytest.mark.parametrize("damping", [0.0, 0.1, 0.25])
def test_a_mode_the_step_cannot_resolve_decays_by_the_theta_methods_factor(damping: float) -> None:
    """At Δt = 2 s (ωΔt ≈ 700) the end's axial force swings about 1 MN from step to step; each swing is the
    one before times −(1 − 2ξ)/(1 + 2ξ) (−1, −2/3, −1/3) over the first three steps to 2 % (measured 0.15 % at
    most; the rest is the phase the step still turns by): without damping the ringing stays, with it it dies.
    The ledger closes to 1e-10 of the work supplied (measured 1e-12)."""
    results = _pulled(damping, 2.0, 10.0)
    swing = results.section_forces[1:, 0, 0] - FORCE
    ratios = swing[1:4] / swing[:3]
    expected = -(1.0 - 2.0 * damping) / (1.0 + 2.0 * damping)
    print(f"\nξ = {damping}: ratios {np.round(ratios, 4)}, expected {expected:.4f}")
    np.testing.assert_allclose(ratios, expected, rtol=0.02)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-10 * np.abs(results.supplied_work).max()
    assert (results.dissipated[-1] > 0.0) == (damping > 0.0)


def test_a_mode_the_step_resolves_keeps_most_of_its_energy() -> None:
    """At Δt = 1e-4 s (ωΔt ≈ 0.035) the same mode rings for many periods: with ξ = 0.1 its amplitude decays at the
    damping ratio ξωΔt/2 = 0.0018, to within 10 % (fitted from the swing's peaks over ten periods), and it keeps
    over 85 % of its amplitude after ten periods (e^(−2π·10·0.0018) = 0.89)."""
    omega = _axial_mode()
    dt = 1e-4
    period = 2.0 * math.pi / omega
    results = _pulled(0.1, dt, 10.5 * period)
    swing = results.section_forces[1:, 0, 0] - FORCE
    time = results.time[1:]
    peaks = [np.abs(swing[(time >= k * period) & (time < (k + 1) * period)]).max() for k in range(10)]
    ratio = np.polyfit(np.arange(10) * period, np.log(peaks), 1)[0] / -omega
    expected = 0.1 * omega * dt / 2.0
    print(
        f"\nωΔt = {omega * dt:.4f}: damping ratio {ratio:.5f}, expected {expected:.5f}; kept {peaks[-1] / peaks[0]:.3f}"
    )
    assert ratio == pytest.approx(expected, rel=0.1)
    assert peaks[-1] / peaks[0] > 0.85


def test_the_damping_must_be_finite_and_not_negative() -> None:
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (LENGTH, 0.0, 0.0), 1, PIPE)
    model = pl.Model(rod, gravity=0.0)
    model.clamp("A")
    for bad in (-0.1, math.inf, math.nan):
        with pytest.raises(pl.InputError, match="high_frequency_damping"):
            model.simulation(model.rest(), dt=0.1, high_frequency_damping=bad)


def test_the_ledger_stays_exact_through_pay_out() -> None:
    """A hanging pipe paid out at 0.5 m/s for 30 s (the growing element's damping work is booked once, as
    dissipation, not as what pay-out brings in): E(t) − E(0) = W(t) − D(t) to 1e-12 of the energy with ξ = 0.1
    as without (measured 1.3e-13)."""
    model = pl.Model(pl.Rod.straight((0, 0, 100.0), (0, 0, 0), 20, PIPE), sea=pl.Sea(300.0))
    model.drive("B", position=lambda t: np.zeros(3))
    model.pay_out("B", speed=0.5)
    results = model.simulation(model.static(), dt=0.2, high_frequency_damping=0.1).run(30.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    print(
        f"\nbalance {np.abs(balance).max():.2e} J of {np.abs(energy).max():.2e} J; damped {results.dissipated[-1]:.0f} J"
    )
    assert results.length[-1] == pytest.approx(115.0)
    assert results.dissipated[-1] > 0.0
    assert np.abs(balance).max() < 1e-12 * np.abs(energy).max()
