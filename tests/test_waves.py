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
    waves = pl.Sea(depth, waves=pl.Waves.regular(2.0, period, ramp=0.0)).waves
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
    sea = pl.Sea(depth, waves=pl.Waves.regular(height, period, ramp=0.0))
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
        ("ramp", lambda: pl.Waves.regular(1.0, 9.0, ramp=-1.0)),
        ("frequencies", lambda: pl.Waves.spectrum([0.5, 0.4], [1.0, 1.0])),
        ("densities", lambda: pl.Waves.spectrum([0.4, 0.5], [1.0, float("nan")])),
    ],
)
def test_bad_sea_states(argument: str, build) -> None:
    with pytest.raises(pl.InputError) as caught:
        build()
    assert str(caught.value).startswith(f"{argument}:")


def test_the_sea_builds_up_over_its_ramp() -> None:
    """By default a sea builds up over one peak period: η = r(t) η_full with r = 3τ² − 2τ³, τ = t/T."""
    full = pl.Waves.regular(2.0, 8.0, ramp=0.0)
    ramped = pl.Waves.regular(2.0, 8.0)
    assert ramped.ramp == 8.0
    t = np.linspace(0.0, 16.0, 33)
    tau = np.clip(t / 8.0, 0.0, 1.0)
    assert np.abs(ramped.elevation(t) - (3 * tau**2 - 2 * tau**3) * full.elevation(t)).max() < 1e-12
    assert pl.Waves.jonswap(2.0, 9.0).ramp == pytest.approx(9.0, rel=0.05)


def test_osv_raos_have_the_long_wave_limit_and_the_heave_resonance() -> None:
    """The OSV's Capytaine RAOs: heave → 1 and pitch → k in long head seas; in beam seas the heave RAO peaks
    near the heave period 2π√((M33 + A33)/G33) of the vessel's own matrices (6.6 s), within 10 %."""
    raos = pl.Vessel.osv().raos
    assert raos is not None
    assert raos.values.shape == (len(raos.periods), len(raos.headings), 6)
    assert raos.frequencies == pytest.approx(2 * np.pi / raos.periods)
    long = raos.at(30.0, 180.0)
    assert abs(long[2]) == pytest.approx(1.0, abs=0.01)
    assert abs(long[4]) == pytest.approx((2 * np.pi / 30.0) ** 2 / G, rel=0.01)
    vessel = pl.Vessel.osv()
    natural = 2 * np.pi * np.sqrt(vessel.M[2, 2] / vessel.G[2, 2])
    periods = np.linspace(4.0, 10.0, 121)
    peak = periods[np.argmax([abs(raos.at(t, 90.0)[2]) for t in periods])]
    print(f"beam-sea heave RAO peak {peak:.2f} s; 2π√(M33/G33) = {natural:.2f} s")
    assert peak == pytest.approx(natural, rel=0.10)


def _rao_file(path, heave: str = "1.0") -> str:
    header = "period_s,heading_deg," + ",".join(
        f"{dof}_amp,{dof}_phase" for dof in ("surge", "sway", "heave", "roll", "pitch", "yaw")
    )
    rows = [f"{t},{h},0,0,0,0,{heave},3.14159,0,0,0,0,0,0" for t in (4, 40) for h in (0, 180)]
    path.write_text("\n".join([header, *rows]) + "\n")
    return str(path)


def test_user_raos_from_a_file(tmp_path) -> None:
    """A user table is read from CSV and interpolated; NaN in it, a missing file, and a sea outside it are
    InputErrors naming what is wrong."""
    raos = pl.Raos.read(_rao_file(tmp_path / "raos.csv"))
    assert list(raos.periods) == [4.0, 40.0] and list(raos.headings) == [0.0, 180.0]
    assert raos.at(10.0, 90.0)[2] == pytest.approx(-1.0, abs=1e-5)
    vessel = pl.Vessel(pl.Vessel.osv().M, pl.Vessel.osv().D, pl.Vessel.osv().G, raos=raos)
    assert vessel.raos is not None and vessel.raos.at(10.0, 0.0)[2] == pytest.approx(-1.0, abs=1e-5)
    with pytest.raises(pl.InputError, match="heave_amp.*finite"):
        pl.Raos.read(_rao_file(tmp_path / "nan.csv", heave="nan"))
    with pytest.raises(pl.InputError, match="^path: "):
        pl.Raos.read(tmp_path / "missing.csv")
    with pytest.raises(pl.InputError, match=r"period: must lie in the RAO table's periods \[4, 40\] s"):
        raos.at(2.0, 0.0)


def _vessel_holding_a_short_rod(waves: pl.Waves, depth: float = 200.0) -> pl.Model:
    """The OSV holding a light 1 m rod at CO, in `waves`."""
    section = pl.Section(1e3, 1e3, 1.0, 1.0, 1e-6, inertia=(1e-6, 1e-6, 1e-6))
    rod = pl.Rod.straight((-1.0, 0.0, -depth), (0.0, 0.0, -depth), 1, section)
    model = pl.Model(rod, sea=pl.Sea(depth, waves=waves))
    model.attach_vessel("B", pl.Vessel.osv(), eta=(0.0, 0.0, -depth, 0.0, 0.0, 0.0))
    return model


def test_vessel_in_long_waves_heaves_with_the_surface() -> None:
    """In a long head sea (T = 25 s, heading 180°) the hold point at CO heaves with the surface (z down:
    z − z0 = −η) to 2 % of the amplitude, and so does the vessel's recorded η (its total motion), while its
    low-frequency pose stays put."""
    waves = pl.Waves.regular(2.0, 25.0, direction=np.pi)
    model = _vessel_holding_a_short_rod(waves)
    state = model.static()
    results = model.simulation(state, dt=0.1).run(100.0, progress=False)
    heave = results.positions[:, -1, 2] - results.positions[0, -1, 2]
    surface = model.sea.waves.elevation(results.time)
    late = results.time > 30.0
    error = np.abs(heave + surface)[late].max()
    print(f"largest heave {np.abs(heave[late]).max():.4f} m; largest |heave + η| {error:.4f} m")
    assert np.abs(heave[late]).max() == pytest.approx(1.0, abs=0.03)
    assert error < 0.02
    assert np.abs(results.eta_low_frequency[:, 2] - results.eta_low_frequency[0, 2]).max() < 0.01
    total = results.eta[:, 2] - results.eta_low_frequency[:, 2]
    assert np.abs(total + surface)[late].max() < 0.02


def test_a_sea_outside_the_vessels_rao_table_is_refused() -> None:
    """A 40 s swell is longer than the OSV's table (3–30 s): the simulation names the waves and the range."""
    model = _vessel_holding_a_short_rod(pl.Waves.regular(1.0, 40.0))
    with pytest.raises(pl.InputError, match=r"^waves: .*\[3, 30\] s, got a peak period of 40\.000 s"):
        model.simulation(model.static(), dt=0.1)


def test_j_lay_waves_example_keeps_its_ledger() -> None:
    """The first 60 s of examples/j_lay_waves.toml: the tower exit moves with the vessel in the waves while
    the DP's low-frequency pose stays within 0.1 m, and E − E0 = supplied − dissipated to 1e-9 of E."""
    from pathlib import Path

    from pipelay.scenario import load_scenario

    scenario = load_scenario(Path(__file__).resolve().parents[1] / "examples" / "j_lay_waves.toml")
    state = scenario.model.static()
    results = scenario.model.simulation(state, dt=scenario.dt).run(60.0, progress=False)
    hang_off = results.positions[:, -1, :]
    late = results.time > 30.0
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    print(
        f"hang-off heave σ {hang_off[late, 2].std():.3f} m; low-frequency offset "
        f"{np.abs(results.eta_low_frequency[:, :2] - results.eta_low_frequency[0, :2]).max():.3f} m; "
        f"balance {np.abs(balance).max():.2e} J of {np.abs(energy).max():.3e} J"
    )
    assert hang_off[late, 2].std() > 0.1
    assert np.abs(results.eta_low_frequency[:, :2] - results.eta_low_frequency[0, :2]).max() < 0.1
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()


def test_seas_beyond_the_theory_are_refused_naming_the_limit() -> None:
    """A regular wave of H/L ≈ 1.3 (H 50 m, T 5 s) breaks: the model refuses it, naming Miche's limit (5.57 m
    here); a JONSWAP sea of Hs 30 m at Tp 4 s is far steeper than DNV-RP-C205 allows (S_p = 1.2 > 1/15); a
    swell higher than 0.78 of the depth breaks too; the limits themselves are accepted."""
    section = pl.Section.pipe(0.3, 0.02)
    rod = pl.Rod.straight((0, 0, 0), (0, 0, -100), 4, section)
    with pytest.raises(pl.InputError, match=r"^waves: must not break: H ≤ .*= 5\.57\d m \(Miche"):
        pl.Model(rod, pl.Sea(800.0, waves=pl.Waves.regular(50.0, 5.0)))
    pl.Model(rod, pl.Sea(800.0, waves=pl.Waves.regular(5.5, 5.0)))
    with pytest.raises(pl.InputError, match=r"^hs: must keep the sea within DNV-RP-C205's steepness limit"):
        pl.Waves.jonswap(30.0, 4.0)
    pl.Waves.jonswap(6.6, 8.0)
    with pytest.raises(pl.InputError, match=r"^waves: must not break: .*0\.78 h"):
        pl.Model(rod, pl.Sea(10.0, waves=pl.Waves.regular(9.0, 20.0)))


def test_a_run_in_waves_resumes_bit_for_bit(tmp_path) -> None:
    """examples/j_lay_waves.toml to 40 s, checkpointed, then on to 45 s: the resumed run (its vessel's
    low-frequency acceleration, from which the predictor moves the tower exit, in the checkpoint) repeats
    the uninterrupted one to the bit."""
    from pathlib import Path

    from pipelay.scenario import load_scenario

    model = load_scenario(Path(__file__).resolve().parents[1] / "examples" / "j_lay_waves.toml").model
    simulation = model.simulation(model.static(), dt=0.1)
    simulation.run(40.0, progress=False)
    path = simulation.checkpoint(tmp_path / "state.npz")
    straight_on = simulation.run(45.0, progress=False)
    resumed = pl.resume(model, path).run(45.0, progress=False)
    for name in ("positions", "rotations", "velocities", "tension", "eta", "nu"):
        assert np.array_equal(getattr(straight_on, name), getattr(resumed, name)), name
    assert np.array_equal(straight_on.iterations, resumed.iterations)
