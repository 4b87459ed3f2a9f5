"""Station keeping as DP engineers design it: thrust allocation, thruster rates, the passive observer, wind,
current and wave drift on the hull, and the vessel's total motion in waves."""

from __future__ import annotations

import math
import re

import numpy as np
import pipelay as pl
import pytest
from scipy.optimize import lsq_linear

OSV = pl.Vessel.osv()
# PD and PID gains by pole placement on diag(M) (MSS supply vessel, ω_n = 0.1, 0.1, 0.2 rad/s, ζ = 1).
M = np.diag(OSV.M)
OMEGA = np.array([0.1, 0.1, 0, 0, 0, 0.2])
KP = OMEGA**2 * M
KD = 2 * OMEGA * M
SLACK_WEIGHT = 1e6  # the allocation's slack weight (vessel/allocation.rs)


def _model(
    vessel: pl.Vessel = OSV,
    *,
    sea: pl.Sea | None = None,
    reference: list[float] | None = None,
    hull_loads: bool = False,
    **pid: object,
) -> pl.Model:
    """The vessel carrying a light 10 m rod hanging from CO (22 kg/m submerged, with drag and rotational
    damping so that the waves do not whip it) under PD control about `reference`."""
    section = pl.Section(
        EA=1e7,
        GA=1e7,
        GJ=1e4,
        EI=1e4,
        mass=30.0,
        outer_diameter=0.1,
        drag=[1.2, 0.0],
        rotational_damping=1e3,
    )
    model = pl.Model(pl.Rod.straight((10, 0, 10), (10, 0, 0), 4, section), sea or pl.Sea(100.0))
    controller = pl.PID(kp=KP, kd=KD, reference=reference or [10, 0, 0, 0, 0, 0.0], **pid)
    model.attach_vessel(
        "B",
        vessel,
        eta=[10, 0, -100, 0, 0, 0.0],
        angle=[0, -math.pi / 2, 0],
        controller=controller,
        hull_loads=hull_loads,
    )
    return model


def _run(model: pl.Model, t_end: float, dt: float = 0.5) -> pl.Results:
    return model.simulation(model.static(), dt=dt).run(t_end, progress=False)


def _body(eta: np.ndarray) -> np.ndarray:
    """The body frame R(φ, θ, ψ) = R_z(ψ) R_y(θ) R_x(φ) of a pose."""
    (cf, sf), (ct, st), (cp, sp) = ((math.cos(a), math.sin(a)) for a in eta[3:6])
    rz = np.array([[cp, -sp, 0], [sp, cp, 0], [0, 0, 1]])
    ry = np.array([[ct, 0, st], [0, 1, 0], [-st, 0, ct]])
    rx = np.array([[1, 0, 0], [0, cf, -sf], [0, sf, cf]])
    return rz @ ry @ rx


def _azimuth_vessel() -> pl.Vessel:
    """The OSV with two bow tunnels and two stern azimuth thrusters of 400 kN, slewing at 0.1 rad/s and
    ramping at 20 kN/s."""
    thrusters = [
        pl.Thruster("tunnel", (30.0, 0.0), 200e3, time_constant=1.0),
        pl.Thruster("tunnel", (22.0, 0.0), 200e3, time_constant=1.0),
        *[
            pl.Thruster("azimuth", (-35.0, y), 400e3, thrust_rate=20e3, azimuth_rate=0.1, time_constant=2.0)
            for y in (7.0, -7.0)
        ],
    ]
    return pl.Vessel(OSV.M, OSV.D, OSV.G, M_RB=OSV.M_RB, raos=OSV.raos, length=83.0, thrusters=thrusters)


@pytest.mark.parametrize("vessel", [OSV, _azimuth_vessel()], ids=["mss", "azimuths"])
def test_a_feasible_command_is_delivered(vessel: pl.Vessel) -> None:
    """A command within the thrusters' capacity is delivered to 1e-6 of it (in fact to ~1e-9)."""
    tau = np.array([3e5, -1.5e5, 0, 0, 0, 2e6])
    allocation = vessel.allocate(tau)
    error = np.abs(allocation.tau - tau).max() / np.abs(tau).max()
    print(f"relative error {error:.2e}")
    assert error < 1e-6
    assert not allocation.saturated
    for thruster, thrust in zip(vessel.thrusters, allocation.thrust, strict=True):
        assert -thruster.reverse_thrust * (1 + 1e-9) <= thrust <= thruster.max_thrust * (1 + 1e-9)


def test_an_infeasible_command_equals_an_independent_solution_of_the_same_qp() -> None:
    """Beyond the tunnels' 800 kN in sway the allocation saturates; its thrusts equal scipy's bounded least
    squares of the same problem, min ½|u|² + ½ρ|Bu − τ|² (forces scaled by the largest thruster, moments by it
    times the longest arm, ρ = 1e6), to 1e-6 of the largest thruster."""
    tau = np.array([1e5, 1.2e6, 0, 0, 0, -4e6])
    allocation = OSV.allocate(tau)
    assert allocation.saturated
    thrusters = OSV.thrusters
    force = max(t.max_thrust for t in thrusters)
    arm = max(1.0, *(math.hypot(*t.position) for t in thrusters))
    columns = []
    for t in thrusters:
        lx, ly = t.position
        columns.append([0.0, 1.0, lx / arm] if t.kind == "tunnel" else [1.0, 0.0, -ly / arm])
    b = np.array(columns).T
    target = np.array([tau[0], tau[1], tau[5] / arm]) / force
    a = np.vstack([np.eye(len(thrusters)), math.sqrt(SLACK_WEIGHT) * b])
    rhs = np.concatenate([np.zeros(len(thrusters)), math.sqrt(SLACK_WEIGHT) * target])
    lower = [-t.reverse_thrust / force for t in thrusters]
    upper = [t.max_thrust / force for t in thrusters]
    reference = lsq_linear(a, rhs, bounds=(lower, upper), tol=1e-14, lsmr_tol="auto", max_iter=10000)
    difference = np.abs(allocation.thrust - reference.x * force).max() / force
    print(f"|Clarabel − scipy| / max thrust = {difference:.2e}")
    assert difference < 1e-6


def test_thrust_and_azimuth_rates_hold_every_step() -> None:
    """A 30 m step of the set-point across the bow: the azimuth thrusters never turn faster than 0.1 rad/s nor
    change thrust faster than 20 kN/s, every thruster stays within its capacity, and the vessel gets there."""
    vessel = _azimuth_vessel()
    model = _model(vessel, reference=[10, 30, 0, 0, 0, 0.2], allocation="qp", start=5.0)
    dt = 0.5
    results = _run(model, 400.0, dt)
    thrust, azimuth = results.thrust, results.azimuth
    assert thrust is not None and azimuth is not None and thrust.shape == (len(results.time), 4)
    turn = np.abs(np.angle(np.exp(1j * np.diff(azimuth[:, 2:], axis=0))))
    ramp = np.abs(np.diff(thrust[:, 2:], axis=0))
    print(f"largest turn {turn.max() / dt:.4f} rad/s, thrust rate {ramp.max() / dt:.0f} N/s")
    assert turn.max() <= 0.1 * dt * (1 + 1e-9)
    assert ramp.max() <= 20e3 * dt * (1 + 1e-9)
    assert turn.max() > 0.05 * dt  # the limits were reached, not idle
    for k, t in enumerate(vessel.thrusters):
        assert thrust[:, k].max() <= t.max_thrust * (1 + 1e-9)
        assert thrust[:, k].min() >= -t.reverse_thrust * (1 + 1e-9)
    assert results.eta[-1, 1] == pytest.approx(30.0, abs=0.5)
    # Delivered τ is the thrusters' own: τ = Σ f (cos α, sin α, l_x sin α − l_y cos α).
    last = results.tau[-1]
    x = sum(f * math.cos(a) for f, a in zip(thrust[-1], azimuth[-1], strict=True))
    assert last[0] == pytest.approx(x, rel=1e-9, abs=1e-6)


def _observed(noise: tuple[float, float, float]) -> pl.Results:
    """The OSV in a JONSWAP sea (Hs 3 m, Tp 9 s, 45° off the bow), held by the PD with allocation on the
    passive observer's estimate from measurements with noise `noise`, for 600 s."""
    waves = pl.Waves.jonswap(3.0, 9.0, direction=math.radians(135.0), seed=5, components=200)
    observer = pl.Observer.passive(noise=noise, seed=1)
    model = _model(sea=pl.Sea(100.0, waves=waves), allocation="qp", observer=observer)
    return _run(model, 600.0)


def _rms(values: np.ndarray) -> np.ndarray:
    return np.sqrt(np.mean(values**2, axis=0))


@pytest.mark.parametrize("noise", [0.0, 0.5])
def test_the_observer_filters_the_wave_frequency_motion(noise: float) -> None:
    """The observer's low-frequency estimate in x and y, after 200 s: without noise its RMS error is 14–15 %
    of the RMS wave-frequency motion it filters out (0.35 and 0.29 m; its notch passes λ/ζ_n = 10 % at the
    peak), asserted < 20 %; with 0.5 m of position noise, 30 % of the raw measurement's deviation from the
    low-frequency pose, asserted < 40 %; the controller on the estimate holds the vessel within 1 m."""
    results = _observed((noise, noise, noise / 100.0))
    late = results.time > 200.0
    estimate, low, wave = results.eta_estimate, results.eta_low_frequency, results.eta_wave_frequency
    assert estimate is not None and low is not None and wave is not None
    error = _rms(estimate[late][:, :2] - low[late][:, :2])
    motion = _rms(wave[late][:, :2])
    measured = np.sqrt(motion**2 + noise**2)
    print(f"noise {noise} m: RMS estimate error {error} m, wave-frequency motion {motion} m")
    assert np.all(motion > 0.2)
    assert np.all(error < (0.2 * motion if noise == 0.0 else 0.4 * measured))
    assert np.abs(low[late][:, :2] - [10.0, 0.0]).max() < 1.0


def test_mean_wind_force_is_half_rho_v_squared_c_a() -> None:
    """A steady 20 m/s beam wind from port on the OSV held by PD: at rest, the controller's thrust and the
    pipe's force balance ½ρ_aV²C(γ) of the wind table at the relative angle (90° less the PD's yaw offset,
    in the heeled body frame): yaw to 1e-4, sway to 3e-4."""
    wind = pl.Wind(20.0, direction=math.pi / 2, spectrum=None)
    model = _model(sea=pl.Sea(100.0, wind=wind), hull_loads=True)
    results = _run(model, 900.0)
    balance = -(results.tau[-1] + results.chi[-1])
    # The wind relative to the vessel, in its body frame: the PD leaves a small yaw offset (0.6°), and the
    # wind heels the vessel (0.6°).
    relative = _body(results.eta[-1]).T @ [0.0, 20.0, 0.0]
    expected = OSV.wind_coefficients.load(1.226, relative[:2])
    print(f"wind load {balance[[0, 1, 5]]} vs ½ρV²CA {expected[[0, 1, 5]]}")
    # The thrust's tilt with the heel brings in a little heave, whose restoring the body frame's sway sees:
    # φ² of the load (1.5e-4).
    assert balance[1] == pytest.approx(expected[1], rel=3e-4)
    assert balance[5] == pytest.approx(expected[5], rel=1e-4)
    assert abs(balance[0] - expected[0]) < 1e-3 * abs(expected[1])


def test_mean_drift_in_a_regular_wave_is_the_table_s() -> None:
    """A regular beam wave (H 3 m, T 8 s) on the OSV held by PD: averaged over whole periods, the controller's
    thrust and the pipe's force balance a²D(8 s, 90°) of the drift table, in sway to 2 %."""
    waves = pl.Waves.regular(3.0, 8.0, direction=math.pi / 2, ramp=20.0)
    model = _model(sea=pl.Sea(100.0, waves=waves), hull_loads=True)
    results = _run(model, 800.0)
    late = results.time > 800.0 - 400.0
    balance = -(results.tau[late] + results.chi[late]).mean(axis=0)
    expected = 1.5**2 * OSV.drift_coefficients.at(8.0, 90.0)
    print(f"mean drift {balance[[0, 1, 5]]} vs a²D {expected[[0, 1, 5]]}")
    assert balance[1] == pytest.approx(expected[1], rel=0.02)


def test_the_total_motion_heaves_with_a_long_wave() -> None:
    """In a 30 s regular wave of 1 m amplitude the OSV follows the surface: results.eta (the total motion)
    heaves by the wave's amplitude to 2 %, the low-frequency pose by less than 2 cm."""
    waves = pl.Waves.regular(2.0, 30.0, direction=math.pi, ramp=30.0)
    results = _run(_model(sea=pl.Sea(100.0, waves=waves)), 300.0)
    late = results.time > 180.0
    heave = results.eta[late][:, 2]
    amplitude = 0.5 * (heave.max() - heave.min())
    low = results.eta_low_frequency[late][:, 2]
    print(f"heave amplitude {amplitude:.4f} m, low-frequency {0.5 * (low.max() - low.min()):.4f} m")
    assert amplitude == pytest.approx(1.0, rel=0.02)
    assert 0.5 * (low.max() - low.min()) < 0.02


def test_the_energy_ledger_holds_with_the_whole_loop() -> None:
    """Allocation, observer, gusting wind, current and waves on the hull: the pipe–vessel system's energy
    changes by the work supplied (thrust delivered, environment, waves) less what is dissipated, step by step
    to 1e-6 of the work supplied."""
    waves = pl.Waves.jonswap(2.0, 8.0, direction=math.radians(150.0), seed=2, components=100)
    sea = pl.Sea(
        100.0,
        current=pl.Current.uniform([0.0, 0.5, 0.0]),
        waves=waves,
        wind=pl.Wind(15.0, direction=math.radians(120.0), seed=3),
    )
    observer = pl.Observer.passive(noise=(0.2, 0.2, 0.002), seed=4)
    results = _run(_model(sea=sea, hull_loads=True, allocation="qp", observer=observer), 200.0)
    energy = results.energy["total"]
    balance = energy - energy[0] - (results.supplied_work - results.dissipated)
    scale = np.abs(results.supplied_work).max()
    print(f"ledger error {np.abs(balance).max():.3e} J of {scale:.3e} J supplied")
    assert scale > 1e3
    assert np.abs(balance).max() < 1e-6 * scale


def test_station_keeping_records_survive_a_file(tmp_path) -> None:
    """The new series are written to netCDF and read back, streamed or not."""
    observer = pl.Observer.passive(noise=(0.1, 0.1, 0.001), seed=1)
    model = _model(allocation="qp", observer=observer, reference=[12, 1, 0, 0, 0, 0.0])
    results = _run(model, 20.0)
    path = results.to_netcdf(tmp_path / "run.nc")
    loaded = pl.load(path)
    streamed_path = tmp_path / "streamed.nc"
    model.simulation(model.static(), dt=0.5).run(20.0, progress=False, output=streamed_path)
    streamed = pl.load(streamed_path)
    for name in ("thrust", "azimuth", "eta_estimate", "eta_low_frequency", "tau_commanded", "eta"):
        assert np.array_equal(getattr(loaded, name), getattr(results, name)), name
        assert np.array_equal(getattr(streamed, name), getattr(results, name)), name


@pytest.mark.parametrize(
    ("build", "argument"),
    [
        (
            lambda: pl.Vessel(OSV.M, OSV.D, OSV.G, length=60.0, thrusters=OSV.thrusters),
            "thrusters[4].position",
        ),
        (lambda: pl.Vessel(OSV.M, OSV.D, OSV.G, thrusters=OSV.thrusters), "length"),
        (lambda: pl.Thruster("tunnel", (0, 0), -1.0), "max_thrust"),
        (lambda: pl.Thruster("bow", (0, 0), 1.0), "kind"),
        (lambda: pl.Thruster("azimuth", (0, 0), 1.0, reverse_thrust=1.0), "reverse_thrust"),
        (lambda: pl.HullCoefficients([0.0, 90.0], [[np.nan] * 6, [0.0] * 6]), "values[0]"),
        (lambda: pl.PID(kp=KP, kd=KD, reference=np.zeros(6), allocation="lp"), "allocation"),
        (lambda: pl.Observer.passive(noise=(-1, 0, 0)), "noise"),
        (lambda: pl.Wind(-3.0), "speed"),
        (lambda: pl.Wind(10.0, spectrum="API"), "spectrum"),
        (lambda: _model(pl.Vessel(OSV.M, OSV.D, OSV.G), allocation="qp"), "allocation"),
        (
            lambda: _model(
                pl.Vessel(OSV.M, OSV.D, OSV.G), sea=pl.Sea(100.0, wind=pl.Wind(10.0)), hull_loads=True
            ),
            "wind_coefficients",
        ),
    ],
)
def test_bad_station_keeping_input_names_the_argument(build, argument: str) -> None:
    with pytest.raises(pl.InputError, match="^" + re.escape(argument)):
        build()


def test_a_drift_table_with_nan_is_refused(tmp_path) -> None:
    """A NaN in a drift table names the table, the line and the column."""
    path = tmp_path / "drift.csv"
    path.write_text(
        "period_s,heading_deg,surge,sway,heave,roll,pitch,yaw\n5,0,1,2,0,0,0,0\n10,0,nan,1,0,0,0,0\n"
    )
    with pytest.raises(pl.InputError, match=r"^drift_coefficients: line 3, column \"surge\""):
        pl.DriftCoefficients.read(path)
