"""Spectral fatigue: the damage of a stationary Gaussian stress process from its power spectral density.

* `spectral_damage(frequency, psd, curve, duration)`: the damage over `duration` of a process of one-sided
  PSD S(f), by Dirlik's (1985) cycle distribution or the narrow-band (Rayleigh) one;
* `series_spectral_damage(series, dt, curve)`: the same with the PSD of a time series estimated by Welch's
  method (`pipelay.analysis.statistics.response_spectrum`).

Damage
------
The expected damage over a duration T of a stationary process is

    D = T ν ∫₀^∞ p_a(s) / N(2 s) ds

with s the cycle amplitude (half the stress range), p_a its probability density, N the S-N curve (cycles to
failure at the range Δσ = 2 s, two slopes allowed) and ν the rate of cycles:

* ``"dirlik"``: p_a is Dirlik's empirical amplitude density (a weighted sum of one exponential and two
  Rayleigh densities, from the moments m0, m1, m2, m4) and ν the rate of peaks m_p = √(m4/m2) (Hz, moments
  in rad/s as FLife computes them; 1/(2π) √(M4/M2) with moments in Hz). Close to rainflow counting for
  narrow- and broad-band processes alike.
* ``"narrow_band"``: p_a is the Rayleigh density s/m0 exp(−s²/(2 m0)) and ν the mean zero up-crossing
  rate ν0+ = √(m2/m0) (Hz, 1/(2π) with moments in rad/s): exact for a narrow-band process, conservative for
  a broad-band one (it gives every up-crossing a cycle of the envelope's amplitude).

The moments, rates and densities are those of FLife (``FLife.SpectralData``, ``FLife.Dirlik(...).get_PDF``,
``FLife.Narrowband(...).get_PDF``), whose densities are of amplitudes: ``get_life(C, k)`` takes C and k of
an amplitude curve N = C s^(−k), so a range curve N = ā Δσ^(−m) is C = ā/2^m, k = m. The integral is taken
in z = s/√m0 with ``scipy.integrate.quad`` on each segment of the curve, split at the switch amplitude
(relative tolerance 1e-10): one-slope results agree with FLife's closed forms to round-off and two-slope
narrow-band ones with the closed form in incomplete gamma functions (tests/test_fatigue_core.py).

Units: frequency in Hz, PSD in MPa²/Hz (one-sided: ∫₀^∞ S df is the variance), duration in s, stress in
MPa. The process' mean does not enter (the curves take no mean-stress effect).

References
----------
* T. Dirlik, *Application of computers in fatigue analysis*, PhD thesis, University of Warwick, 1985.
* J. W. Miles, "On structural fatigue under random loading", J. Aeronautical Sciences 21(11), 1954,
  753–762 (the narrow-band damage).
* DNV-RP-C203 (2016) App.D (the narrow-band damage of a Rayleigh stress distribution).
* A. Zorman, J. Slavič, M. Boltežar, "Vibration fatigue by spectral methods — A review with open-source
  support", Mechanical Systems and Signal Processing 190, 2023, 110149 (FLife).

FLife is imported in the functions that need it (its import takes about a second).

Imports of pipelay: `pipelay.analysis.checks` (its input errors), `pipelay.analysis.statistics` (the
spectrum of a series) and `pipelay.analysis.fatigue.curves` and `.counting`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pipelay.analysis.checks import _Described, _input_error, _number
from pipelay.analysis.fatigue.counting import _finite_vector
from pipelay.analysis.fatigue.curves import SNCurve
from pipelay.analysis.statistics import _series, response_spectrum

__all__ = ["SPECTRAL_METHODS", "series_spectral_damage", "spectral_damage"]

FloatArray = NDArray[np.float64]

SPECTRAL_METHODS = ("dirlik", "narrow_band")
"""The methods of `spectral_damage` and `series_spectral_damage`."""

RELATIVE_TOLERANCE = 1e-10
"""Relative tolerance of each quadrature of the damage integral."""


def spectral_damage(
    frequency: ArrayLike,
    psd: ArrayLike,
    curve: SNCurve,
    duration: float,
    *,
    method: str = "dirlik",
) -> float:
    """Fatigue damage over `duration` of a stationary Gaussian stress process of one-sided PSD `psd`.

    Parameters
    ----------
    frequency : array-like (k,)
        Frequencies f (Hz), finite, ≥ 0 and strictly increasing, k ≥ 2.
    psd : array-like (k,)
        One-sided PSD S(f) of the stress (MPa²/Hz) at `frequency`, finite and ≥ 0. The moments are its
        trapezoidal integrals over `frequency`.
    curve : SNCurve
        The S-N curve (stress range in MPa), one or two slopes.
    duration : float
        Exposure time (s) ≥ 0.
    method : {"dirlik", "narrow_band"}
        The amplitude distribution and cycle rate (see the module's text).

    Returns
    -------
    float
        Miner's damage D over `duration` (dimensionless). 0 for a PSD of zeros, or with no content above
        0 Hz (a constant stress, no cycles).

    Raises
    ------
    pipelay.InputError
        If the arrays are not 1-D of equal length, hold NaN, inf or negative values, the frequencies are not
        increasing from ≥ 0, `curve` is not an SNCurve, `duration` < 0 or `method` is unknown.
    """
    f, s = _spectrum(frequency, psd)
    _check_curve(curve)
    span = _number("duration", duration, minimum=0.0, allowed="a duration >= 0 (s)")
    _check_method(method)
    return span * _damage_rate(f, s, curve, method)


def series_spectral_damage(
    series: ArrayLike,
    dt: float,
    curve: SNCurve,
    duration: float | None = None,
    *,
    method: str = "dirlik",
    segment: float | None = None,
) -> float:
    """Spectral fatigue damage of a stress history: `spectral_damage` of its Welch PSD estimate.

    The PSD is ``pipelay.analysis.statistics.response_spectrum(series, dt, segment=segment)``: one-sided, in
    MPa²/Hz against frequency in Hz (its integral is the variance of the series), so it is used as it is.

    Parameters
    ----------
    series : array-like (T,)
        Stress (MPa) at the constant time step `dt`, finite, at least 16 samples.
    dt : float
        Time step (s) > 0.
    curve : SNCurve
        The S-N curve (stress range in MPa).
    duration : float or None
        Exposure time (s) ≥ 0; None: the record's length T·dt.
    method : {"dirlik", "narrow_band"}
        As in `spectral_damage`.
    segment : float or None
        Length of the Welch segments (s); None: an eighth of the record (see `response_spectrum`).

    Returns
    -------
    float
        Miner's damage over `duration`; 0 for a constant series.

    Raises
    ------
    pipelay.InputError
        If `series` is not a finite 1-D series of at least 16 samples, `dt`, `duration` or `segment` is out
        of range, `curve` is not an SNCurve or `method` is unknown.
    """
    values = _series("series", series)
    step = _number("dt", dt, positive=True, allowed="a time step > 0 (s)")
    _check_curve(curve)
    _check_method(method)
    if duration is None:
        span = values.size * step
    else:
        span = _number("duration", duration, minimum=0.0, allowed="a duration >= 0 (s), or None")
    if np.all(values == values[0]):
        return 0.0
    spectrum = response_spectrum(values, step, segment=segment)
    return span * _damage_rate(np.asarray(spectrum.frequency), np.asarray(spectrum.density), curve, method)


# --- the damage integral ---------------------------------------------------------------------------------


def _damage_rate(frequency: FloatArray, psd: FloatArray, curve: SNCurve, method: str) -> float:
    """Damage per second ν ∫ p_a(s)/N(2s) ds (1/s)."""
    import FLife  # type: ignore[import-untyped]

    if not np.any(psd[frequency > 0.0] > 0.0):
        return 0.0
    data = FLife.SpectralData(input={"PSD": psd, "f": frequency})
    sigma = math.sqrt(float(data.moments[0]))
    if sigma == 0.0:  # a PSD so small that its variance underflows
        return 0.0
    estimator: Any
    if method == "dirlik":
        with np.errstate(divide="ignore", invalid="ignore"):  # a line spectrum: checked below
            estimator, rate = FLife.Dirlik(data), float(data.m_p)
        q, r = float(estimator.coeff[7]), float(estimator.coeff[4])
        if not (np.all(np.isfinite(estimator.coeff)) and q > 0.0 and r != 0.0):
            raise _input_error(
                "psd",
                _Described(f"a spectrum of irregularity factor α2 = {float(data.alpha2):.6g}"),
                'a spectrum of some width for method "dirlik", or method "narrow_band" for a single line',
                "leaves Dirlik's coefficients undefined",
            )
    else:
        estimator, rate = FLife.Narrowband(data), float(data.nu)

    def density(z: float) -> float:
        """Density of the normalised amplitude z = s/σ."""
        return float(estimator.get_PDF(sigma * z)) * sigma

    # Segments of the curve in z: [0, z_switch) on the second segment (below the switch), [z_switch, ∞) on
    # the first; one segment [0, ∞) for one slope. On segment i, 1/N(2 σ z) = (2 σ z f_t)^m_i / ā_i.
    switch = curve.switch_stress_range
    if switch is None:
        pieces = [(0.0, math.inf, 0)]
    else:
        z_switch = switch / (2.0 * sigma)
        pieces = [(0.0, z_switch, 1), (z_switch, math.inf, 0)]
    total = 0.0
    for lower, upper, index in pieces:
        m, log_a = curve.slopes[index], curve.log_a[index]
        moment = _moment(density, m, lower, upper)
        # (2 σ f_t)^m / ā in logarithms: stress levels and ā span many decades.
        total += 10.0 ** (m * math.log10(2.0 * sigma * curve.thickness_factor) - log_a) * moment
    return rate * total


def _moment(density: Callable[[float], float], m: float, lower: float, upper: float) -> float:
    """∫ density(z) z^m dz from `lower` to `upper` (∞ allowed) by ``scipy.integrate.quad``.

    The mass of the integrand lies at z of order 1 to 10 (z = s/σ); a finite interval reaching far beyond
    is split at z = 1/4, 1/2, 1, 2, … so that the adaptive rule cannot step over it; an infinite one is
    mapped onto (0, 1] by quad itself (QAGI).
    """
    from scipy import integrate  # type: ignore[import-untyped]

    def integrand(z: float) -> float:
        return density(z) * z**m

    if upper <= lower:
        return 0.0
    if math.isinf(upper):
        value, _ = integrate.quad(integrand, lower, upper, epsabs=0.0, epsrel=RELATIVE_TOLERANCE, limit=200)
    else:
        points = [0.25 * 2.0**k for k in range(16) if lower < 0.25 * 2.0**k < upper] or None
        value, _ = integrate.quad(
            integrand, lower, upper, epsabs=0.0, epsrel=RELATIVE_TOLERANCE, limit=200, points=points
        )
    return float(value)


# --- validation ------------------------------------------------------------------------------------------


def _spectrum(frequency: ArrayLike, psd: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """`frequency` and `psd` as checked float arrays."""
    f = _finite_vector("frequency", frequency, "frequencies (Hz) >= 0, strictly increasing, at least 2")
    s = _finite_vector("psd", psd, "one-sided PSD values (MPa²/Hz) >= 0, one per frequency")
    if f.size < 2:
        raise _input_error(
            "frequency", _Described(f"{f.size} frequenc{'y' if f.size == 1 else 'ies'}"), "at least 2", "is"
        )
    if s.size != f.size:
        raise _input_error(
            "psd",
            _Described(f"an array of {s.size} values"),
            f"one value per frequency ({f.size} frequencies)",
            "has another length than frequency",
        )
    if f[0] < 0.0:
        raise _input_error(
            "frequency",
            _Described(f"an array starting at {float(f[0])!r} Hz"),
            "frequencies >= 0 (Hz, one-sided), strictly increasing",
            "starts below 0",
        )
    if np.any(np.diff(f) <= 0.0):
        index = int(np.flatnonzero(np.diff(f) <= 0.0)[0])
        raise _input_error(
            "frequency",
            _Described(f"an array with {float(f[index + 1])!r} Hz after {float(f[index])!r} Hz"),
            "frequencies >= 0 (Hz), strictly increasing",
            "is not strictly increasing",
        )
    if np.any(s < 0.0):
        index = int(np.flatnonzero(s < 0.0)[0])
        raise _input_error(
            "psd",
            _Described(f"an array holding {float(s[index])!r} at {float(f[index])!r} Hz"),
            "one-sided PSD values (MPa²/Hz) >= 0",
            "has a negative value",
        )
    return f, s


def _check_curve(curve: object) -> None:
    if not isinstance(curve, SNCurve):
        raise _input_error(
            "curve",
            _Described(f"a {type(curve).__name__}"),
            "an SNCurve (SNCurve.dnv(...), SNCurve.user(...))",
        )


def _check_method(method: object) -> None:
    if not isinstance(method, str) or method not in SPECTRAL_METHODS:
        raise _input_error("method", method, ", ".join(SPECTRAL_METHODS), "is not a spectral method")
