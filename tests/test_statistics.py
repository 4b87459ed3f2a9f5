"""pipelay.statistics: response spectra, most probable maxima and the extremes of a run.

References: a Gaussian sea synthesised from JONSWAP components (its spectral moments are known exactly from
the components, and the maxima of many independent 3 h records give the extreme distribution empirically),
block maxima of i.i.d. exponential samples (Gumbel with location ln m and scale 1), the engine's own strain
and DNV-ST-F101 checks of a state, and direct numpy reductions.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay import statistics as st
from pipelay.checks import dnv_st_f101

HS = 4.0  # m
TP = 10.0  # s
DT = 0.5  # s
STORM = 10800.0  # s, 3 h
SHORT = 1200.0  # s, 20 min
SEEDS = range(100, 130)  # 30 independent 3 h records


def _sea(seed: int) -> pl.Waves:
    return pl.Waves.jonswap(HS, TP, components=200, seed=seed)


def _moments(waves: pl.Waves) -> tuple[float, float, float]:
    """m0, m2, m4 of the components in ω (rad/s): m_n = Σ a²/2 ω^n."""
    amplitude, omega = waves.components[:2]
    m0, m2, m4 = (float(np.sum(amplitude**2 / 2.0 * omega**n)) for n in (0, 2, 4))
    return m0, m2, m4


@pytest.fixture(scope="module")
def storms() -> list[np.ndarray]:
    """The surface elevation of 30 independent 3 h records (seeds 100…129) at 0.5 s."""
    time = np.arange(0.0, STORM, DT)
    return [_sea(seed).elevation(time) for seed in SEEDS]


# --- 1. spectrum -----------------------------------------------------------------------------------------


def test_spectrum_of_a_jonswap_sea_gives_hs_tz_and_bandwidth() -> None:
    """A 3 h JONSWAP record: Hs = 4√m0 of the Welch spectrum within 3 % of the sea's Hs, Tz = √(m0/m2) (Hz)
    within 3 % of 2π√(m0/m2) of the components (rad/s), the bandwidth within 5 %; the spectrum unpacks."""
    waves = _sea(0)
    series = waves.elevation(np.arange(0.0, STORM, DT))
    spectrum = st.response_spectrum(series, DT)
    frequency, density = spectrum
    m0, m2, m4 = _moments(waves)
    tz = 2.0 * math.pi * math.sqrt(m0 / m2)
    bandwidth = math.sqrt(1.0 - m2 * m2 / (m0 * m4))
    print(
        f"Hs {spectrum.significant:.4f} m (sea {waves.hs:.4f}); Tz {spectrum.tz:.4f} s (components {tz:.4f}); "
        f"ε {spectrum.bandwidth:.4f} ({bandwidth:.4f}); segment {spectrum.segment:g} s"
    )
    assert frequency[0] == 0.0 and frequency[-1] == pytest.approx(1.0 / (2.0 * DT))
    assert density.shape == frequency.shape
    assert spectrum.significant == pytest.approx(waves.hs, rel=0.03)
    assert spectrum.tz == pytest.approx(tz, rel=0.03)
    assert spectrum.bandwidth == pytest.approx(bandwidth, rel=0.05)


def test_spectrum_of_a_sine() -> None:
    """A sine of amplitude 2 and period 10 s: m0 = a²/2 = 2 and Tz = 10 s (1 %), the peak at 0.1 Hz, ε ≈ 0."""
    time = np.arange(0.0, 2000.0, 0.1)
    spectrum = st.response_spectrum(3.0 + 2.0 * np.sin(2.0 * math.pi * time / 10.0), 0.1, segment=200.0)
    peak = spectrum.frequency[np.argmax(spectrum.density)]
    print(
        f"sine: m0 {spectrum.m0:.5f}, Tz {spectrum.tz:.5f} s, peak {peak:.4f} Hz, ε {spectrum.bandwidth:.3f}"
    )
    assert spectrum.m0 == pytest.approx(2.0, rel=0.01)
    assert spectrum.tz == pytest.approx(10.0, rel=0.01)
    assert spectrum.mean == pytest.approx(3.0, abs=1e-3)
    assert peak == pytest.approx(0.1)
    assert spectrum.segment == 200.0
    assert spectrum.bandwidth < 0.2


# --- 2. most probable maximum ----------------------------------------------------------------------------


def test_mpm_of_a_gaussian_sea_against_the_maxima_of_30_storms(storms: list[np.ndarray]) -> None:
    """The 3 h MPM of a JONSWAP sea (Hs 4 m, Tp 10 s, ε ≈ 0.66) from 20 min records against the maxima of 30
    independent 3 h records: their mean, and their mode (the empirical MPM, from a Gumbel fit to the 30
    maxima; below the mean by 0.577β).

    * Rayleigh from one 20 min record (another seed) within 10 % of the empirical mean; averaged over the
      first 20 min of the 30 records, within 10 % of the mean, within 2 % of the exact σ√(2 ln N) of the
      components, and between the empirical mode and 10 % above it: the Poisson up-crossing estimate is
      conservative for a broad-band sea (exceedances cluster), by about as much as the mode lies below the
      mean, so here it lands on the mean rather than slightly below it.
    * Gumbel (10 blocks) and Weibull agree with Rayleigh within 10 % (averages over the 30 records), Gumbel
      both from 20 min records (biased high: short blocks) and from the whole 3 h records (within 5 % of the
      empirical mode: the same information, fitted per record).
    """
    from scipy import stats

    maxima = np.array([series.max() for series in storms])
    empirical = float(maxima.mean())
    mode, beta = stats.gumbel_r.fit(maxima)
    m0, m2, _ = _moments(_sea(0))
    sigma = math.sqrt(m0)
    cycles = STORM / (2.0 * math.pi * math.sqrt(m0 / m2))
    exact = sigma * math.sqrt(2.0 * math.log(cycles))

    short = _sea(0).elevation(np.arange(0.0, SHORT, DT))
    single = st.most_probable_maximum(short, DT, STORM, method="rayleigh")
    count = round(SHORT / DT)

    def average(method: str, samples: int) -> float:
        return float(
            np.mean([float(st.most_probable_maximum(s[:samples], DT, method=method)) for s in storms])
        )

    rayleigh = average("rayleigh", count)
    gumbel_short = average("gumbel", count)
    weibull = average("weibull", count)
    gumbel_storm = average("gumbel", len(storms[0]))
    print(
        f"3 h maxima of 30 records: mean {empirical:.4f} m (std {maxima.std():.4f}), Gumbel mode {mode:.4f} "
        f"(β {beta:.4f}); exact Rayleigh MPM {exact:.4f} m (σ {sigma:.4f}, N {cycles:.0f})"
    )
    print(
        f"MPM from 20 min: Rayleigh {float(single):.4f} (one record, Tz {single.parameters['tz']:.3f} s); "
        f"averages over 30: Rayleigh {rayleigh:.4f}, Gumbel {gumbel_short:.4f}, Weibull {weibull:.4f}; "
        f"Gumbel from the 3 h records {gumbel_storm:.4f}"
    )
    assert single.method == "rayleigh" and single.duration == STORM and single.record == SHORT
    assert float(single) == pytest.approx(empirical, rel=0.10)
    assert rayleigh == pytest.approx(empirical, rel=0.10)
    assert rayleigh == pytest.approx(exact, rel=0.02)
    assert mode < empirical
    assert mode < rayleigh < 1.10 * mode
    assert gumbel_short == pytest.approx(rayleigh, rel=0.10)
    assert gumbel_storm == pytest.approx(rayleigh, rel=0.10)
    assert gumbel_storm == pytest.approx(mode, rel=0.05)
    assert weibull == pytest.approx(rayleigh, rel=0.10)


def test_gumbel_fit_of_exponential_block_maxima() -> None:
    """The maximum of m = 1000 i.i.d. Exp(1) samples is Gumbel with location ln m and scale 1 (to O(1/m)):
    4000 blocks fit location within 1 % and scale within 4 %; the MPM over 10⁶ samples is ln 10⁶ (1 %)."""
    samples = np.random.default_rng(7).exponential(1.0, 1000 * 4000)
    mpm = st.most_probable_maximum(samples, 1.0, duration=1e6, block=1000.0)
    fit = mpm.parameters
    print(
        f"Gumbel fit: location {fit['location']:.4f} (ln 1000 = {math.log(1000):.4f}), scale {fit['scale']:.4f}; "
        f"MPM over 1e6 samples {float(mpm):.4f} (ln 1e6 = {math.log(1e6):.4f})"
    )
    assert fit["blocks"] == 4000 and fit["block"] == 1000.0 and fit["n"] == pytest.approx(1000.0)
    assert fit["location"] == pytest.approx(math.log(1000.0), rel=0.01)
    assert fit["scale"] == pytest.approx(1.0, rel=0.04)
    assert float(mpm) == pytest.approx(math.log(1e6), rel=0.01)


# --- 3. stationarity -------------------------------------------------------------------------------------


def test_a_stationary_sea_is_accepted_and_gives_the_gaussian_mpm() -> None:
    """A 1 h JONSWAP record (Hs 4 m: σ = 1 m, Tz = 8.00 s from the components) passes the stationarity test
    (about 450 Tz, no trend, halves alike) and its 3 h Rayleigh MPM is within 3 % of the exact σ√(2 ln N),
    N = 3 h/Tz, of the components."""
    waves = _sea(0)
    series = waves.elevation(np.arange(0.0, 3600.0, DT))
    m0, m2, _ = _moments(waves)
    tz = 2.0 * math.pi * math.sqrt(m0 / m2)
    exact = math.sqrt(m0) * math.sqrt(2.0 * math.log(STORM / tz))
    found = st.stationarity(series, DT)
    mpm = st.most_probable_maximum(series, DT, STORM, "rayleigh")
    print(f"{found}; Rayleigh MPM {float(mpm):.4f} m, exact {exact:.4f} m")
    assert found.tz == pytest.approx(tz, rel=0.03)
    assert found.periods == pytest.approx(3600.0 / tz, rel=0.03) and found.periods > st.MIN_PERIODS
    assert abs(found.trend) < st.TREND_TOLERANCE
    assert max(found.halves) / min(found.halves) < st.SPREAD_RATIO
    assert float(mpm) == pytest.approx(exact, rel=0.03)


def test_a_decaying_transient_is_refused() -> None:
    """A free oscillation decaying over the record, 3 e^(−t/150 s) sin(2πt/8 s) for 600 s: its halves'
    standard deviations differ by e^(300/150) = 7.4 > 2, so `stationarity` and `most_probable_maximum` refuse
    it, naming `series` and saying why."""
    time = np.arange(0.0, 600.0, 0.2)
    series = 3.0 * np.exp(-time / 150.0) * np.sin(2.0 * math.pi * time / 8.0)
    for call in (lambda: st.stationarity(series, 0.2), lambda: st.most_probable_maximum(series, 0.2)):
        with pytest.raises(pl.InputError) as error:
            call()
        print(error.value)
        assert str(error.value).startswith("series: ") and "is not stationary" in str(error.value)
        assert f"a factor {math.exp(2.0):.3g}" in str(error.value)


def test_a_settling_start_is_found_and_left_out() -> None:
    """A sea (σ = 1 m) on a settling offset 10σ e^(−t/60 s), 2400 s: the whole record has a trend and is
    refused; `stationary_part` finds the first start of those tried every 120 s that leaves a stationary
    record, later than 0 and within the first half, where the offset is below 1.4σ; from there the 3 h
    Rayleigh MPM is within 3 % of the sea's exact one."""
    waves = _sea(1)
    time = np.arange(0.0, 2400.0, DT)
    offset = 10.0 * np.exp(-time / 60.0)
    series = waves.elevation(time) + offset
    with pytest.raises(pl.InputError, match="has a trend"):
        st.stationarity(series, DT)
    first, found = st.stationary_part(series, DT)
    start = time[first]
    m0, m2, _ = _moments(waves)
    exact = math.sqrt(m0) * math.sqrt(2.0 * math.log(STORM / (2.0 * math.pi * math.sqrt(m0 / m2))))
    mpm = float(st.most_probable_maximum(series[first:], DT, STORM, "rayleigh"))
    print(
        f"settled at t = {start:g} s (offset {offset[first]:.3f} σ): {found}; MPM {mpm:.4f}, exact {exact:.4f}"
    )
    assert 0.0 < start <= 1200.0 and start % 120.0 == 0.0
    assert offset[first] < 1.4
    with pytest.raises(pl.InputError):
        st.stationarity(series[first - round(120.0 / DT) :], DT)  # the start tried before it
    assert mpm == pytest.approx(exact, rel=0.03)
    with pytest.raises(pl.InputError, match="nor does any later start"):
        st.stationary_part(3.0 * np.exp(-time / 600.0) * np.sin(2.0 * math.pi * time / 8.0), DT)


def test_a_short_record_is_refused() -> None:
    """20 Tz of a stationary sea (160 s) is fewer than the 30 mean zero up-crossing periods asked for."""
    series = _sea(1).elevation(np.arange(0.0, 160.0, DT))
    for method in st.METHODS:
        with pytest.raises(
            pl.InputError, match=r"^series: a record of 160 s, .* is too short; allowed: at least 30"
        ):
            st.most_probable_maximum(series, DT, method=method)


# --- 4. extremes of a run --------------------------------------------------------------------------------

SECTION = pl.Section.pipe(0.3, 0.02, contents_density=0.0, drag=(0.1, 1.0), added_mass=(0.0, 1.0))


def _smooth(t: float, ramp: float) -> float:
    s = min(max(t / ramp, 0.0), 1.0)
    return s * s * (3.0 - 2.0 * s)


def _pulse(t: float) -> float:
    """0.5 m/s for 15 s with 5 s ramps: 7.5 m paid out."""
    return 0.5 * (_smooth(t, 5.0) - _smooth(t - 15.0, 5.0))


@pytest.fixture(scope="module")
def paying_out() -> tuple[pl.Model, pl.Simulation, pl.Results]:
    """A 60 m pipe hanging in 300 m of water from end B, driven sideways (2 m at 0.5 rad/s) while 7.5 m are
    paid out: the mesh grows from 12 to 13 elements, the early records are NaN-padded."""
    model = pl.Model(pl.Rod.straight((0, 0, 60), (0, 0, 0), 12, SECTION), sea=pl.Sea(300.0))
    model.drive("B", position=lambda t: np.array([2.0 * math.sin(0.5 * t), 0.0, 0.0]))
    model.pay_out("B", speed=_pulse)
    simulation = model.simulation(model.static(), dt=0.1)
    return model, simulation, simulation.run(25.0, progress=False)


def _reference(values: np.ndarray, time: np.ndarray, largest: bool = True) -> tuple[float, float, int]:
    """Value, time and element of the nan-aware extreme of (T, n) values."""
    index = np.nanargmax(values) if largest else np.nanargmin(values)
    k, element = np.unravel_index(index, values.shape)
    return float(values[k, element]), float(time[k]), int(element)


def test_extremes_of_a_pay_out_run_match_numpy(
    paying_out: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """Through NaN padding the extremes equal nan-aware numpy reductions (value, time, element); the strain
    formula equals the engine's State.strain and the DNV utilisation the check of the final state."""
    model, simulation, results = paying_out
    forces = results.section_forces
    time = results.time
    assert np.isnan(forces[0]).any() and not np.isnan(forces[-1]).any()
    found = st.extremes(results, model=model, checks={"safety_class": "low"})
    print({key: round(value, 6) for key, value in found.items()})

    # No vessel: the top tension is the axial force of the element at end B, each record's last element (12
    # at first, 13 at the end), not the reaction |F_B|, the largest of which has its own key.
    last = np.array([np.flatnonzero(np.isfinite(row[:, 0]))[-1] for row in forces])
    assert last[0] == 11 and last[-1] == 12
    top = forces[np.arange(len(forces)), last, 0]
    np.testing.assert_array_equal(st.top_tension(results), top)
    assert found["top_tension_max"] == top.max() and found["top_tension_max_time"] == time[np.argmax(top)]
    assert found["top_tension_min"] == top.min() and found["top_tension_min_time"] == time[np.argmin(top)]
    reaction = np.linalg.norm(results.reaction("B")[:, :3], axis=1)
    assert (
        found["reaction_B_max"] == reaction.max()
        and found["reaction_B_max_time"] == time[np.argmax(reaction)]
    )
    assert found["reaction_B_max"] != found["top_tension_max"]
    assert "lay_top_tension_max" not in found
    for key, values, largest in [
        ("tension_max", forces[:, :, 0], True),
        ("tension_min", forces[:, :, 0], False),
        ("moment_max", np.hypot(forces[:, :, 4], forces[:, :, 5]), True),
    ]:
        value, at, element = _reference(values, time, largest)
        assert (found[key], found[f"{key}_time"], found[f"{key}_element"]) == (value, at, element), key

    ei2, ei3 = SECTION.EI
    strain = forces[:, :, 0] / SECTION.EA + 0.15 * np.hypot(forces[:, :, 4] / ei2, forces[:, :, 5] / ei3)
    value, at, element = _reference(strain, time)
    assert found["strain_max"] == pytest.approx(value, rel=1e-14)
    assert (found["strain_max_time"], found["strain_max_element"]) == (at, element)
    np.testing.assert_allclose(strain[-1], simulation.state.strain, rtol=1e-12)

    records: list[Any] = []

    def keep(record: Any) -> Any:
        records.append(record)
        return dnv_st_f101(record, safety_class="low")

    same = st.extremes(results, model=model, checks=keep)
    final = dnv_st_f101(simulation.state, safety_class="low")
    counts = [record.section_forces.shape[0] for record in records]
    print(f"elements per record {counts[0]} … {counts[-1]}; utilisation max {found['utilisation_max']:.5f}")
    assert len(records) == len(results) and counts[0] == 12 and counts[-1] == 13
    assert records[-1].positions.shape == (14, 3)
    np.testing.assert_allclose(records[-1].strain, final.strain, rtol=1e-12)
    for key in ("utilisation_max", "load_controlled_max", "displacement_controlled_max"):
        assert same[key] == found[key] and found[f"{key}_time"] == same[f"{key}_time"], key
    np.testing.assert_allclose(
        max(final.max().values()), np.max(np.maximum(final.load_controlled, final.displacement_controlled))
    )
    assert found["utilisation_max"] == max(found["load_controlled_max"], found["displacement_controlled_max"])
    assert found["utilisation_max"] >= max(final.max().values())
    # The utilisation of every element at every record: the last row is the final state's, NaN where the
    # record had no such element yet, and its largest value is the extremes'.
    every = st.utilisation(results, model=model, checks={"safety_class": "low"})
    assert every.shape == results.section_forces.shape[:2]
    assert np.isnan(every[0, -1]) and np.isfinite(every[-1]).all()
    np.testing.assert_allclose(every[-1], np.maximum(final.load_controlled, final.displacement_controlled))
    assert np.nanmax(every) == found["utilisation_max"]


def test_extremes_without_a_section_and_with_a_scalar_check(
    paying_out: tuple[pl.Model, pl.Simulation, pl.Results],
) -> None:
    """No section: no strain (and tension/moment as before); a callable returning one number per record."""
    _, _, results = paying_out
    found = st.extremes(results, checks=lambda record: float(np.nanmax(np.abs(record.tension))) / 1e5)
    assert "strain_max" not in found and "load_controlled_max" not in found
    assert found["utilisation_max"] == pytest.approx(np.nanmax(np.abs(results.section_forces[:, :, 0])) / 1e5)
    assert found["utilisation_max_element"] == -1


def test_extremes_of_a_j_lay_run_take_the_lay_top_tension() -> None:
    """A J-lay vessel in a JONSWAP sea under DP: the top tension's extremes are the lay summary's top tension's
    nanmax/nanmin (the tension at the tower), not those of the reaction |F_B| (``reaction_B_max``)."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (300.0, 0.0, 0.0), 30, SECTION)
    sea = pl.Sea(50.0, seabed=pl.Seabed(stiffness=1e5), waves=pl.Waves.jonswap(2.0, 8.0, seed=3))
    model = pl.Model(rod, sea)
    model.pin("A")
    pid = pl.PID(kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=[298.0, 0, 0, 0, 0, 0])
    lay = pl.JLay(position=(-20.0, 0.0, -10.0), angle=0.6)
    model.attach_vessel("B", pl.Vessel.osv(), eta=[298.0, 0, -50.0, 0, 0, 0], controller=pid, lay=lay)
    results = model.simulation(model.static(), dt=0.2).run(20.0, progress=False)
    found = st.extremes(results, section=SECTION, sea=sea)
    summary = results.lay_summary()
    assert summary is not None
    held = summary["top_tension"]
    reaction = np.linalg.norm(results.reaction("B")[:, :3], axis=1)
    print(
        f"J-lay: top tension {found['top_tension_min']:.0f} … {found['top_tension_max']:.0f} N "
        f"(reaction at B up to {found['reaction_B_max']:.0f} N), strain {found['strain_max']:.3e}"
    )
    np.testing.assert_array_equal(st.top_tension(results), held)
    assert found["top_tension_max"] == np.nanmax(held)
    assert found["top_tension_min"] == np.nanmin(held)
    assert found["top_tension_max_time"] == results.time[np.nanargmax(held)]
    assert found["reaction_B_max"] == reaction.max() > found["top_tension_max"]
    assert "lay_top_tension_max" not in found


# --- 5. bad input ----------------------------------------------------------------------------------------

_WAVE = np.sin(np.arange(0.0, 600.0, 0.5))  # 1200 samples, period 2π s


def _results_stub() -> Any:
    """A Results-like object: 3 records of a 2-element pipe."""
    forces = np.ones((3, 2, 6))
    return SimpleNamespace(
        time=np.arange(3.0),
        section_forces=forces,
        positions=np.zeros((3, 3, 3)),
        reaction=lambda end: np.ones((3, 6)),
        lay_summary=lambda: None,
    )


@pytest.mark.parametrize(
    ("call", "argument"),
    [
        (lambda: st.response_spectrum(np.r_[_WAVE, math.nan], 0.5), "series"),
        (lambda: st.response_spectrum(np.ones((40, 2)), 0.5), "series"),
        (lambda: st.response_spectrum(_WAVE[:10], 0.5), "series"),
        (lambda: st.response_spectrum(np.zeros(100), 0.5), "series"),
        (lambda: st.response_spectrum(_WAVE, 0.0), "dt"),
        (lambda: st.response_spectrum(_WAVE, 0.5, segment=1000.0), "segment"),
        (lambda: st.most_probable_maximum(_WAVE, math.inf), "dt"),
        (lambda: st.most_probable_maximum(_WAVE, 0.5, duration=-1.0), "duration"),
        (lambda: st.most_probable_maximum(_WAVE, 0.5, method="gauss"), "method"),
        (lambda: st.most_probable_maximum(_WAVE, 0.5, block=120.0), "block"),
        (lambda: st.most_probable_maximum(_WAVE, 0.5, duration=30.0), "duration"),
        (lambda: st.most_probable_maximum(_WAVE[:18], 0.5), "series"),
        (lambda: st.most_probable_maximum(_WAVE[:100], 0.5, method="rayleigh"), "series"),
        (lambda: st.most_probable_maximum(_WAVE[:100], 0.5, method="weibull"), "series"),
        (lambda: st.most_probable_maximum(_WAVE, 0.5, duration=3.0, method="rayleigh"), "duration"),
        (lambda: st.extremes(_results_stub(), checks=42), "checks"),  # type: ignore[arg-type]
        (lambda: st.extremes(_results_stub(), checks={}), "section"),
        (
            lambda: st.extremes(
                _results_stub(), section=SimpleNamespace(EA=-1.0, EI=1.0, outer_diameter=0.3)
            ),
            "section.EA",
        ),
        (
            lambda: st.extremes(_results_stub(), section=SimpleNamespace(EA=1.0, outer_diameter=0.3)),
            "section.EI",
        ),
        (lambda: st.extremes(_results_stub(), checks=lambda record: np.ones(5)), "checks"),
    ],
)
def test_bad_input_names_the_argument(call: Callable[[], object], argument: str) -> None:
    """Bad input raises pl.InputError (a ValueError) whose message starts with the argument's name."""
    with pytest.raises(pl.InputError) as error:
        call()
    print(error.value)
    assert str(error.value).startswith(f"{argument}: ")


@pytest.mark.parametrize("block", [None, 7 * 12])
def test_the_utilisation_of_all_records_at_once_is_each_records_check(
    block: int | None, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A run whose records all have every element is checked in blocks of records (by default 65 536 element
    values; here also 7 records of 12 elements, the last block shorter): the same numbers, to the bit, as
    `dnv_st_f101` of each record (the tests' DP vessel in waves, with its sea's pressure)."""
    import tomllib

    from dp_in_waves import scenario_text
    from pipelay.analysis import checks
    from pipelay.scenario import parse_scenario

    if block is not None:
        monkeypatch.setattr(checks, "RECORDS_BLOCK_ELEMENTS", block)

    scenario = parse_scenario(tomllib.loads(scenario_text("all records at once", t_end=20.0)))
    model = scenario.model
    results = model.simulation(model.static(), dt=scenario.dt).run(20.0, progress=False)
    together = st.utilisation(results, model=model, checks={"safety_class": "low"})
    one_by_one = st.utilisation(
        results, model=model, checks=lambda record: dnv_st_f101(record, safety_class="low")
    )
    assert together.shape == (len(results), 12) and np.isfinite(together).all()
    assert np.array_equal(together, one_by_one)
