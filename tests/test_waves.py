"""Waves: sea states, their kinematics, and the loads they put on the pipe.

References: the dispersion relation solved independently (scipy), the JONSWAP spectrum's own Hs and peak, the
analytic inertia force on a fixed vertical cylinder, and the energy ledger."""

from __future__ import annotations

import numpy as np
import pipelay as pl
import pytest
from scipy.optimize import brentq
from scipy.signal import welch

G = 9.81


def _wave_number(omega: float, depth: float) -> float:
    return brentq(lambda k: G * k * np.tanh(k * depth) - omega**2, 1e-9, 10 * omega**2 / G + 10)


@pytest.mark.parametrize(("period", "depth"), [(6.0, 800.0), (10.0, 50.0), (20.0, 15.0)])
def test_a_regular_wave_travels_with_the_dispersion_relation(period: float, depth: float) -> None:
    """η(t, x) = (H/2) cos(kx − ωt) with ω² = g k tanh(kh), in deep, intermediate and shallow water."""
    waves = pl.Sea(depth, waves=pl.Waves.regular(2.0, period)).waves
    omega = 2 * np.pi / period
    k = _wave_number(omega, depth)
    t = np.linspace(0.0, 3 * period, 61)
    for x in (0.0, 37.0, 250.0):
        expected = np.cos(k * x - omega * t)
        assert np.abs(waves.elevation(t, x) - expected).max() < 1e-9


def test_jonswap_record_has_its_significant_height_and_peak() -> None:
    """Three hours of a JONSWAP Hs 2.5 m, Tp 9 s sea (400 components): 4σ(η) within 3 % of Hs and the Welch
    spectrum's peak within 5 % of 1/Tp; another seed gives another record of the same Hs."""
    waves = pl.Waves.jonswap(2.5, 9.0, components=400, seed=3)
    t = np.arange(0.0, 3 * 3600.0, 0.5)
    eta = waves.elevation(t)
    realised = 4 * eta.std()
    frequency, density = welch(eta, fs=2.0, nperseg=4096)
    peak = frequency[np.argmax(density)]
    print(f"Hs realised {realised:.3f} m; spectral peak {1 / peak:.2f} s")
    assert realised == pytest.approx(2.5, rel=0.03)
    assert peak == pytest.approx(1 / 9.0, rel=0.05)
    other = pl.Waves.jonswap(2.5, 9.0, components=400, seed=4).elevation(t)
    assert 4 * other.std() == pytest.approx(2.5, rel=0.03)
    assert np.abs(other - eta).max() > 1.0


def test_inertia_force_on_a_fixed_vertical_cylinder() -> None:
    """A rigid vertical cylinder (d = 1 m, C_a = 1) from the seabed to the mean level in 50 m of water under a
    regular wave (H 2 m, T 10 s), drag off: the supports carry the Morison inertia force
    ρ(1 + C_a)A ∫ u̇ ds = ρ(1 + C_a)A a ω²/k sin θ; checked where η = 0 (no stretching), to 0.1 %."""
    depth, height, period, diameter = 50.0, 2.0, 10.0, 1.0
    section = pl.Section(
        1e14, 1e14, 1e14, 1e14, 100.0, outer_diameter=diameter, drag=(0, 0), added_mass=(0, 1)
    )
    sea = pl.Sea(depth, waves=pl.Waves.regular(height, period))
    model = pl.Model(pl.Rod.straight((0, 0, 0), (0, 0, -depth), 50, section), sea=sea)
    model.clamp("A")
    model.clamp("B")
    results = model.simulation(model.static(), dt=0.05).run(30.0, progress=False)
    force = results.reaction("A")[1:, 0] + results.reaction("B")[1:, 0]
    middle = results.time[1:] - 0.025  # reactions are step means, at the steps' midpoints
    omega = 2 * np.pi / period
    k = _wave_number(omega, depth)
    amplitude = 1025.0 * 2.0 * np.pi / 4 * diameter**2 * 0.5 * height * omega**2 / k
    expected = amplitude * np.sin(-omega * middle)
    at_zero_elevation = np.abs(np.cos(omega * middle)) < 0.02
    error = np.abs(force - expected)[at_zero_elevation].max() / amplitude
    print(f"inertia force amplitude {amplitude:.1f} N; largest error where η = 0: {error:.2e}")
    assert at_zero_elevation.sum() >= 4
    assert error < 1e-3


def test_energy_ledger_closes_with_waves() -> None:
    """A 120 m pipe hanging from a clamped top in 100 m of water under a JONSWAP sea with spreading and a
    current, drag and inertia on: E − E0 = supplied − dissipated to 1e-9 of E over 60 s."""
    section = pl.Section.pipe(0.4, 0.02, contents_density=1025.0, drag=(0.1, 1.2), added_mass=(0.0, 1.0))
    waves = pl.Waves.jonswap(4.0, 8.0, spreading=6.0, seed=2, components=50)
    sea = pl.Sea(100.0, current=pl.Current.uniform([0.5, 0.2, 0.0]), waves=waves)
    model = pl.Model(pl.Rod.straight((60, 0, -20), (0, 0, -100), 30, section), sea=sea)
    model.clamp("B")
    results = model.simulation(model.static(), dt=0.1).run(60.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    scale = np.abs(energy).max()
    print(
        f"balance {np.abs(balance).max():.3e} J of {scale:.3e} J; supplied {results.supplied_work[-1]:.3e} J"
    )
    assert np.abs(balance).max() < 1e-9 * scale
    assert np.abs(results.supplied_work).max() > 1e3


@pytest.mark.parametrize(
    ("argument", "build"),
    [
        ("hs", lambda: pl.Waves.jonswap(0.0, 9.0)),
        ("hs", lambda: pl.Waves.jonswap(-1.0, 9.0)),
        ("tp", lambda: pl.Waves.jonswap(2.0, float("nan"))),
        ("gamma", lambda: pl.Waves.jonswap(2.0, 9.0, gamma=0.5)),
        ("components", lambda: pl.Waves.jonswap(2.0, 9.0, components=0)),
        ("spreading", lambda: pl.Waves.jonswap(2.0, 9.0, spreading=-2.0)),
        ("height", lambda: pl.Waves.regular(0.0, 9.0)),
        ("period", lambda: pl.Waves.regular(1.0, float("inf"))),
        ("frequencies", lambda: pl.Waves.spectrum([0.5, 0.4], [1.0, 1.0])),
        ("densities", lambda: pl.Waves.spectrum([0.4, 0.5], [1.0, float("nan")])),
    ],
)
def test_bad_sea_states(argument: str, build) -> None:
    with pytest.raises(pl.InputError) as caught:
        build()
    assert str(caught.value).startswith(f"{argument}:")
