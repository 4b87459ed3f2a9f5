"""Statistics of simulated responses: per-run extremes, response spectra and the most probable maximum.

* `top_tension(results)`: the top tension at every record, the effective tension the tensioner, the tower or
  the top support holds (the axial force of the line's top element; not the reaction |F_B|).
* `extremes(results, ...)`: the largest and smallest top tension (``top_tension_max``, ``top_tension_min``:
  the top tension above), the largest reaction at B |F_B| (``reaction_B_max``), the largest strain, bending
  moment and effective axial force and (optionally) the largest DNV-ST-F101 utilisation of a run, each with
  its time (and element).
* `utilisation(results, ...)`: the DNV-ST-F101 (or a user check's) utilisation of every element at every
  record.
* `response_spectrum(series, dt)`: the one-sided power spectral density of a time series by Welch's method,
  with the spectral moments m0, m2, m4, the mean zero up-crossing period Tz and the bandwidth ε.
* `stationarity(series, dt)`: whether a record is long enough and stationary enough for its most probable
  maximum (the test below); `stationary_part(series, dt)`: where a record's start-up transient has settled.
* `most_probable_maximum(series, dt, duration)`: the most probable maximum (MPM) of a response over a storm
  of `duration` (default 3 h) estimated from a shorter (or equally long) record by one of three methods.

The first three are those of `pipelay.analysis.extremes` (the statistics of a run), re-exported here; the
others, the statistics of a time series, are defined here.

Units are those of the series (N, N·m, m, …) and seconds; frequencies are in Hz.

The stationarity test
---------------------
A record is taken as a sample of one stationary process (`stationarity`) when

* it is long enough: at least `MIN_PERIODS` (30) mean zero up-crossing periods Tz of the response (Tz from its
  spectrum), and at least `MIN_SAMPLES` samples;
* it has no trend: the least-squares line through it rises or falls over the record by at most
  `TREND_TOLERANCE` (0.25) standard deviations σ of the record;
* its spread holds: the standard deviations of its two halves differ by at most a factor `SPREAD_RATIO` (2).

The tolerances are loose enough for a Gaussian sea: of 300 independent records of a JONSWAP elevation (Hs 4 m,
Tp 10 s, γ = 3.3) 30 Tz long (240 s), the largest trend was 0.14 σ and the halves' deviations were within a
factor 1.79 for 99 % of them (one record reached 2.15 and is refused). A start-up transient fails them: a decaying oscillation loses its spread from one half to the other,
a settling tension drifts (the calm-water start of an S-lay: a trend of 0.75 σ and more over its first 200 s).
`most_probable_maximum` refuses a record that fails the test.

Which MPM method when
---------------------
The most probable maximum is the mode of the distribution of the largest value over the duration. All three
estimates assume the record is a sample of a **stationary** process (one sea state, after the start-up
transient: drop it before, `stationary_part` finds where) that represents the whole duration.

* ``"gumbel"`` (default): fit a Gumbel distribution to the maxima of equal blocks of the record and scale
  it to the duration. It makes no assumption about the response's distribution (it suits non-Gaussian,
  nonlinear responses such as the tension of a pipe that lifts off the seabed or rollers) but assumes the block
  maxima are **independent** and identically distributed and already in the Gumbel (type I) domain: blocks
  must be long compared with the response's period and its correlation time (many cycles, tens of Tz). It
  is most reliable when the record is as long as the duration (e.g. a 3 h simulation split into 10 blocks).
  Scaled from short blocks to a much longer duration it is conservative for Gaussian-like responses: the
  Gumbel scale of the maxima of n cycles falls like 1/√(2 ln n), and a fit to short blocks carries the larger
  scale up to the duration (for a JONSWAP elevation, 10 blocks of 2 min scaled to 3 h come out 4–6 % high
  on average, with a scatter of about ±10 % from one 20 min record to another; 20 blocks of 1 min about
  11 % high).
* ``"rayleigh"``: mean + σ√(2 ln N) with N = duration/Tz zero up-crossings. For a **Gaussian** response,
  narrow- or broad-band (it counts up-crossings, not peaks); the quickest estimate and stable from short
  records (±3 % from 20 min). Taking the up-crossings of high levels as independent (Poisson) makes it
  slightly conservative for broad-band responses, whose exceedances cluster (about 3 % above the mode of
  the maxima of 30 simulated 3 h records for a JONSWAP elevation, ε ≈ 0.66), and it is unconservative for
  responses with heavier-than-Gaussian tails.
* ``"weibull"``: fit a 3-parameter Weibull distribution to the peaks (local maxima above the mean) and take
  the level exceeded once on average over the duration. A compromise for moderately non-Gaussian responses
  from records too short for block maxima; it assumes independent peaks and fits the whole body of the peak
  distribution, so its tail is only as good as the fit there (for a broad-band Gaussian elevation it comes
  out 5–8 % above the Rayleigh value).

References
----------
* P. D. Welch, "The use of fast Fourier transform for the estimation of power spectra", IEEE Trans. Audio
  Electroacoustics 15(2), 1967, 70–73.
* S. O. Rice, "Mathematical analysis of random noise", Bell System Technical Journal 23–24, 1944–45:
  the zero up-crossing rate 1/Tz = √(m2/m0) of a Gaussian process (moments in Hz).
* D. E. Cartwright, M. S. Longuet-Higgins, "The statistical distribution of the maxima of a random function",
  Proc. R. Soc. London A 237, 1956, 212–232: the bandwidth ε = √(1 − m2²/(m0 m4)).
* M. S. Longuet-Higgins, "On the statistical distribution of the heights of sea waves", J. Marine Research
  11(3), 1952, 245–266; DNV-RP-C205 "Environmental conditions and environmental loads", §3.5.9 (maximum wave
  height in a stationary sea state): the most probable largest of N Rayleigh amplitudes, σ√(2 ln N).
* A. Naess, T. Moan, "Stochastic Dynamics of Marine Structures", Cambridge University Press, 2013, Ch. 7
  (extreme values from up-crossing rates, Gumbel asymptotics).
* E. J. Gumbel, "Statistics of Extremes", Columbia University Press, 1958.

Imports of pipelay: the engine (`pipelay._core`, its InputError), `pipelay.analysis.checks` (its wording of
input errors) and `pipelay.analysis.extremes`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pipelay._core import InputError

# One way of wording input errors across the package's Python modules.
from pipelay.analysis.checks import _Described, _input_error, _number
from pipelay.analysis.extremes import extremes, top_tension, utilisation

__all__ = [
    "METHODS",
    "MIN_PERIODS",
    "SETTLING_STEPS",
    "SPREAD_RATIO",
    "TREND_TOLERANCE",
    "MostProbableMaximum",
    "ResponseSpectrum",
    "Stationarity",
    "extremes",
    "most_probable_maximum",
    "response_spectrum",
    "stationarity",
    "stationary_part",
    "top_tension",
    "utilisation",
]

FloatArray = NDArray[np.float64]

METHODS = ("gumbel", "rayleigh", "weibull")
"""The methods of `most_probable_maximum`."""

MIN_BLOCKS = 10
"""Fewest blocks the Gumbel method fits."""

MIN_PEAKS = 30
"""Fewest peaks above the mean the Weibull method fits (three parameters)."""

MIN_SAMPLES = 16
"""Fewest samples of a series and of a Welch segment."""

MIN_PERIODS = 30
"""Fewest mean zero up-crossing periods Tz a stationary record spans (`stationarity`)."""

TREND_TOLERANCE = 0.25
"""Largest rise or fall of a stationary record's least-squares line over the record, in standard deviations of
the record (`stationarity`)."""

SPREAD_RATIO = 2.0
"""Largest ratio of the standard deviations of a stationary record's two halves (`stationarity`)."""

SETTLING_STEPS = 20
"""`stationary_part` tries starts every 1/20 of the record, over its first half."""


# --- spectrum --------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ResponseSpectrum:
    """One-sided power spectral density of a series and its spectral moments.

    Unpacks as ``frequency, density = response_spectrum(series, dt)``.

    Attributes
    ----------
    frequency : ndarray (k,)
        Frequencies f (Hz), 0 to the Nyquist frequency 1/(2 dt).
    density : ndarray (k,)
        One-sided PSD S(f) (unit²/Hz): ∫₀^∞ S(f) df is the variance.
    mean : float
        Mean of the series (unit).
    m0, m2, m4 : float
        Spectral moments m_n = ∫ f^n S(f) df (unit²·Hz^n), by the sum over the Welch bins times their width
        (Parseval's sum: m0 is the averaged windowed variance).
    tz : float
        Mean zero up-crossing period Tz = √(m0/m2) (s) (Rice; moments in Hz, so no 2π).
    bandwidth : float
        Spectral bandwidth ε = √(1 − m2²/(m0 m4)) (0: narrow-band, 1: white), Cartwright & Longuet-Higgins.
    segment : float
        Length of the Welch segments (s).
    """

    frequency: FloatArray
    density: FloatArray
    mean: float
    m0: float
    m2: float
    m4: float
    tz: float
    bandwidth: float
    segment: float

    @property
    def std(self) -> float:
        """Standard deviation σ = √m0 (unit)."""
        return math.sqrt(self.m0)

    @property
    def significant(self) -> float:
        """Significant double amplitude 4√m0 (unit): Hs for a surface elevation."""
        return 4.0 * math.sqrt(self.m0)

    def __iter__(self) -> Iterator[FloatArray]:
        yield self.frequency
        yield self.density


def response_spectrum(series: ArrayLike, dt: float, *, segment: float | None = None) -> ResponseSpectrum:
    """One-sided PSD of `series` by Welch's method, with its spectral moments, Tz and bandwidth.

    The series is cut into segments of `segment` seconds overlapping by half; each is detrended (its mean
    removed), tapered with a Hann window and Fourier transformed, and the periodograms are averaged
    (``scipy.signal.welch``, scaling "density"). Spectral moments m_n = Σ f_k^n S(f_k) Δf (n = 0, 2, 4), the
    mean zero up-crossing period Tz = √(m0/m2) and the bandwidth ε = √(1 − m2²/(m0 m4)).

    Parameters
    ----------
    series : array-like (T,)
        Samples of a response at the constant time step `dt` (any unit), finite.
    dt : float
        Time step (s) > 0.
    segment : float or None
        Length of the Welch segments (s), at most the record (T·dt); None: an eighth of the record (which
        averages 15 half-overlapping segments). Longer segments resolve frequency finer (Δf = 1/segment),
        shorter ones average more. At least 16 samples.

    Returns
    -------
    ResponseSpectrum
        Unpacks to (frequency (Hz), density (unit²/Hz)); also m0, m2, m4, tz (s), bandwidth, mean.

    Raises
    ------
    pipelay.InputError
        If `series` is not a finite 1-D series of at least 16 samples with some variation, or `dt` or
        `segment` is out of range.
    """
    values = _series("series", series)
    step = _number("dt", dt, positive=True)
    return _spectrum(values, step, segment)


def _spectrum(values: FloatArray, step: float, segment: float | None) -> ResponseSpectrum:
    from scipy import signal

    record = values.size * step
    if segment is None:
        samples = max(values.size // 8, MIN_SAMPLES)
    else:
        length = _number("segment", segment, positive=True)
        samples = round(length / step)
        if samples < MIN_SAMPLES or samples > values.size:
            raise _input_error(
                "segment",
                segment,
                f"from {MIN_SAMPLES * step:g} s ({MIN_SAMPLES} samples) to the record, {record:g} s",
                "is out of range",
            )
    frequency, density = signal.welch(
        values, fs=1.0 / step, window="hann", nperseg=samples, detrend="constant"
    )
    width = frequency[1] - frequency[0]
    m0, m2, m4 = (float(np.sum(frequency**n * density) * width) for n in (0, 2, 4))
    if not (m0 > 0.0 and m2 > 0.0):
        raise _input_error("series", _Described("a constant series"), "a series that varies", "is")
    bandwidth = math.sqrt(max(0.0, 1.0 - m2 * m2 / (m0 * m4)))
    return ResponseSpectrum(
        frequency=_frozen(frequency),
        density=_frozen(density),
        mean=float(np.mean(values)),
        m0=m0,
        m2=m2,
        m4=m4,
        tz=math.sqrt(m0 / m2),
        bandwidth=bandwidth,
        segment=samples * step,
    )


# --- stationarity ----------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Stationarity:
    """What `stationarity` measured of a record that passed its test (see the module docstring).

    Attributes
    ----------
    record : float
        Length of the record (s): samples × dt.
    tz : float
        Mean zero up-crossing period Tz of the record (s), from its spectrum (`response_spectrum`).
    periods : float
        Tz periods in the record, record / Tz (≥ `MIN_PERIODS`).
    mean, std : float
        Mean and standard deviation σ of the record (unit of the series).
    trend : float
        Rise (> 0) or fall of the record's least-squares line from its first to its last sample, in σ (at most
        `TREND_TOLERANCE` either way).
    halves : tuple of float
        Standard deviations of the record's first and second halves (unit), within a factor `SPREAD_RATIO`.
    """

    record: float
    tz: float
    periods: float
    mean: float
    std: float
    trend: float
    halves: tuple[float, float]


def stationarity(series: ArrayLike, dt: float) -> Stationarity:
    """Tests that a record is long enough and stationary enough for its most probable maximum: at least
    `MIN_PERIODS` mean zero up-crossing periods Tz long, a least-squares line that moves by at most
    `TREND_TOLERANCE` standard deviations over the record, and halves whose standard deviations differ by at
    most a factor `SPREAD_RATIO` (see the module docstring for why these numbers).

    Parameters
    ----------
    series : array-like (T,)
        Samples of a response at the constant time step `dt` (any unit), finite.
    dt : float
        Time step (s) > 0.

    Returns
    -------
    Stationarity
        The measures of the test, all passed.

    Raises
    ------
    pipelay.InputError
        Naming `series` and saying which part of the test it fails (too short, a trend, a changing spread), or
        if it is not a finite 1-D series of at least `MIN_SAMPLES` samples that varies; naming `dt` if it is
        not a number > 0.
    """
    return _stationarity(_series("series", series), _number("dt", dt, positive=True))


def _stationarity(values: FloatArray, step: float) -> Stationarity:
    spectrum = _spectrum(values, step, None)
    record = values.size * step
    periods = record / spectrum.tz
    if periods < MIN_PERIODS:
        raise _input_error(
            "series",
            _Described(f"a record of {record:g} s, {periods:.3g} times its Tz = {spectrum.tz:.3g} s,"),
            f"at least {MIN_PERIODS} mean zero up-crossing periods Tz",
            "is too short",
        )
    std = float(np.std(values))
    centred = (np.arange(values.size) - 0.5 * (values.size - 1)) * step  # the samples' times less their mean
    slope = float(np.dot(centred, values) / np.dot(centred, centred))
    trend = slope * (values.size - 1) * step / std
    if abs(trend) > TREND_TOLERANCE:
        raise _input_error(
            "series",
            _Described(f"a record whose least-squares line moves by {trend:+.3g} σ over its {record:g} s"),
            f"at most {TREND_TOLERANCE:g} σ either way, a stationary record",
            "has a trend",
        )
    half = values.size // 2
    halves = (float(np.std(values[:half])), float(np.std(values[half:])))
    ratio = max(halves) / min(halves) if min(halves) > 0.0 else math.inf
    if ratio > SPREAD_RATIO:
        raise _input_error(
            "series",
            _Described(
                f"a record whose halves have standard deviations {halves[0]:.4g} and {halves[1]:.4g}"
                f" (a factor {ratio:.3g})"
            ),
            f"a factor of at most {SPREAD_RATIO:g}, a stationary record",
            "is not stationary",
        )
    return Stationarity(
        record=record,
        tz=spectrum.tz,
        periods=periods,
        mean=float(np.mean(values)),
        std=std,
        trend=trend,
        halves=halves,
    )


def stationary_part(series: ArrayLike, dt: float) -> tuple[int, Stationarity]:
    """Where a record's start-up transient has settled: the first of the starts 0, T/`SETTLING_STEPS`,
    2T/`SETTLING_STEPS`, … up to half the record (T samples) from which the rest of the record passes
    `stationarity`, and what it measured there.

    Parameters
    ----------
    series : array-like (T,)
        Samples of a response at the constant time step `dt` (any unit), finite.
    dt : float
        Time step (s) > 0.

    Returns
    -------
    tuple of int and Stationarity
        The index of the first sample of the stationary part, and its `stationarity`.

    Raises
    ------
    pipelay.InputError
        Naming `series` when no start in its first half leaves a stationary record: the reason the whole
        record failed, and the starts tried; or as `stationarity` for a series or `dt` that is not usable.
    """
    values = _series("series", series)
    step = _number("dt", dt, positive=True)
    stride = max(1, values.size // SETTLING_STEPS)
    first: Exception | None = None
    for start in range(0, values.size // 2 + 1, stride):
        if values.size - start < MIN_SAMPLES:
            break
        try:
            return start, _stationarity(values[start:], step)
        except InputError as error:
            first = first or error
    raise InputError(f"{first}; nor does any later start up to half the record (every {stride * step:g} s)")


# --- most probable maximum -------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class MostProbableMaximum:
    """The most probable maximum of a response over a duration; ``float(mpm)`` is its value.

    Attributes
    ----------
    value : float
        The MPM (unit of the series).
    method : str
        "gumbel", "rayleigh" or "weibull".
    duration : float
        Duration the maximum is taken over (s).
    record : float
        Length of the record it was estimated from (s).
    parameters : dict
        The fit: for "gumbel" ``location`` μ and ``scale`` β of the block maxima (unit), ``block`` (s),
        ``blocks`` (count fitted) and ``n`` = duration/block; for "rayleigh" ``mean``, ``std`` σ (unit),
        ``tz`` (s) and ``cycles`` N = duration/Tz; for "weibull" ``shape`` k, ``location`` x₀, ``scale`` λ
        (unit), ``peaks`` (count fitted), ``peak_rate`` (1/s) and ``expected_peaks`` over the duration.
    """

    value: float
    method: str
    duration: float
    record: float
    parameters: dict[str, float] = field(default_factory=dict)

    def __float__(self) -> float:
        return self.value


def most_probable_maximum(
    series: ArrayLike,
    dt: float,
    duration: float = 10800.0,
    method: str = "gumbel",
    *,
    block: float | None = None,
) -> MostProbableMaximum:
    """Most probable maximum (the mode of the distribution of the largest value) of a stationary response
    over `duration`, estimated from the record `series`. For the minimum, pass ``-series`` and negate.

    Methods (see the module docstring for which to use when):

    * ``"gumbel"``: the record is cut into b = ⌊record/block⌋ blocks (a remainder at the end is dropped),
      a Gumbel distribution F(x) = exp(−exp(−(x − μ)/β)) is fitted to the block maxima by maximum likelihood
      (``scipy.stats.gumbel_r.fit``). Gumbel is max-stable: the maximum over n = duration/block independent
      blocks is Gumbel(μ + β ln n, β), whose mode is **MPM = μ + β ln n** (Gumbel 1958). Assumes stationarity
      and independent, identically distributed block maxima.
    * ``"rayleigh"``: **MPM = x̄ + σ √(2 ln N)**, N = duration/Tz, with σ = √m0 and Tz = √(m0/m2) from
      `response_spectrum`. For a Gaussian process the up-crossings of a high level x form a Poisson process of
      rate exp(−(x − x̄)²/2σ²)/Tz (Rice), so P(max ≤ x) = exp(−N exp(−(x − x̄)²/2σ²)) with that mode
      (Longuet-Higgins 1952; DNV-RP-C205 §3.5.9, where H_mp = Hs √(½ ln N) is twice this amplitude;
      Naess & Moan 2013).
    * ``"weibull"``: the peaks (samples greater than the one before and at least the one after, above the
      mean) are fitted by a 3-parameter Weibull distribution F(x) = 1 − exp(−((x − x₀)/λ)^k) (maximum
      likelihood, ``scipy.stats.weibull_min.fit``); with ν the peaks per second of the record and
      N_p = ν·duration the peaks expected over the duration, the MPM is the level exceeded by one of them on
      average, N_p (1 − F(x)) = 1: **MPM = x₀ + λ (ln N_p)^(1/k)** (for independent peaks the mode of the
      largest of N_p is this level as N_p grows).

    Parameters
    ----------
    series : array-like (T,)
        Samples of the response at the constant time step `dt` (any unit), finite, after any start-up
        transient: a record that fails `stationarity` (shorter than 30 Tz, with a trend or a changing
        spread) is refused.
    dt : float
        Time step (s) > 0.
    duration : float
        Duration the maximum is taken over (s) > 0, default 3 h; it may be longer than the record.
    method : {"gumbel", "rayleigh", "weibull"}
        Estimator, default "gumbel".
    block : float or None
        Block length (s) of the Gumbel method, at most the duration; None: a tenth of the record (the longest
        blocks that still give 10). Ignored by the other methods.

    Returns
    -------
    MostProbableMaximum
        ``float(result)`` is the MPM; ``result.parameters`` holds the fit.

    Raises
    ------
    pipelay.InputError
        Naming the argument: `series` not a finite 1-D series, not stationary or too short (`stationarity`:
        30 mean zero up-crossing periods; 10 blocks for Gumbel, 30 peaks for Weibull), `dt`, `duration`,
        `block` out of range or `method` unknown.
    """
    values = _series("series", series)
    step = _number("dt", dt, positive=True)
    span = _number("duration", duration, positive=True)
    if not isinstance(method, str) or method not in METHODS:
        raise _input_error("method", method, ", ".join(METHODS), "is not a method")
    _stationarity(values, step)
    record = values.size * step
    if method == "gumbel":
        return _gumbel(values, step, span, record, block)
    if method == "rayleigh":
        return _rayleigh(values, step, span, record)
    return _weibull(values, step, span, record)


def _gumbel(
    values: FloatArray, step: float, span: float, record: float, block: float | None
) -> MostProbableMaximum:
    from scipy import stats

    if block is None:
        samples = values.size // MIN_BLOCKS  # ≥ 6: a stationary record has ≥ 2 samples a Tz, 30 Tz
    else:
        length = _number("block", block, positive=True)
        samples = round(length / step)
        if samples < 2:
            raise _input_error("block", block, f"at least 2 samples ({2 * step:g} s)", "is too short")
        if values.size // samples < MIN_BLOCKS:
            raise _input_error(
                "block",
                block,
                f"at most a tenth of the record ({record / MIN_BLOCKS:g} s) for at least {MIN_BLOCKS} blocks",
                f"leaves only {values.size // samples} blocks",
            )
    count = values.size // samples
    length = samples * step
    if span < length:
        raise _input_error("duration", span, f"at least the block length, {length:g} s", "is too short")
    maxima = values[: count * samples].reshape(count, samples).max(axis=1)
    if np.ptp(maxima) <= 0.0:
        raise _input_error("series", _Described("equal block maxima"), "block maxima that vary", "has")
    location, scale = (float(v) for v in stats.gumbel_r.fit(maxima))
    n = span / length
    return MostProbableMaximum(
        value=location + scale * math.log(n),
        method="gumbel",
        duration=span,
        record=record,
        parameters={"location": location, "scale": scale, "block": length, "blocks": count, "n": n},
    )


def _rayleigh(values: FloatArray, step: float, span: float, record: float) -> MostProbableMaximum:
    spectrum = _spectrum(values, step, None)
    cycles = span / spectrum.tz
    if cycles <= 1.0:
        raise _input_error("duration", span, f"longer than Tz = {spectrum.tz:.6g} s", "is too short")
    value = spectrum.mean + spectrum.std * math.sqrt(2.0 * math.log(cycles))
    return MostProbableMaximum(
        value=value,
        method="rayleigh",
        duration=span,
        record=record,
        parameters={"mean": spectrum.mean, "std": spectrum.std, "tz": spectrum.tz, "cycles": cycles},
    )


def _weibull(values: FloatArray, step: float, span: float, record: float) -> MostProbableMaximum:
    from scipy import stats

    mean = float(np.mean(values))
    inner = values[1:-1]
    peaks = inner[(inner > values[:-2]) & (inner >= values[2:]) & (inner > mean)]
    if peaks.size < MIN_PEAKS:
        raise _input_error(
            "series",
            _Described(f"a record with {peaks.size} peaks above the mean"),
            f"at least {MIN_PEAKS} peaks",
            "is too short",
        )
    rate = peaks.size / record
    expected = rate * span
    if expected <= 1.0:
        raise _input_error(
            "duration", span, f"longer than the mean time between peaks, {1.0 / rate:.6g} s", "is too short"
        )
    with np.errstate(all="ignore"):
        shape, location, scale = (float(v) for v in stats.weibull_min.fit(peaks))
    if not (math.isfinite(shape) and math.isfinite(location) and shape > 0.0 and scale > 0.0):
        raise _input_error("series", _Described("peaks"), "peaks a Weibull distribution fits", "are")
    value = location + scale * math.log(expected) ** (1.0 / shape)
    return MostProbableMaximum(
        value=value,
        method="weibull",
        duration=span,
        record=record,
        parameters={
            "shape": shape,
            "location": location,
            "scale": scale,
            "peaks": peaks.size,
            "peak_rate": rate,
            "expected_peaks": expected,
        },
    )


# --- helpers ---------------------------------------------------------------------------------------------


def _series(argument: str, series: ArrayLike) -> FloatArray:
    """`series` as a finite 1-D float array of at least MIN_SAMPLES samples, else an input error."""
    try:
        values = np.asarray(series, dtype=np.float64)
    except (TypeError, ValueError):
        raise _input_error(
            argument, _Described(f"a {type(series).__name__}"), "a 1-D array of numbers", "is not numeric"
        ) from None
    if values.ndim != 1:
        raise _input_error(
            argument, _Described(f"an array of shape {values.shape}"), "a 1-D array (T,)", "is not 1-D"
        )
    if values.size < MIN_SAMPLES:
        raise _input_error(
            argument,
            _Described(f"a series of {values.size} samples"),
            f"at least {MIN_SAMPLES}",
            "is too short",
        )
    bad = np.count_nonzero(~np.isfinite(values))
    if bad:
        raise _input_error(
            argument,
            _Described(f"a series of {values.size} samples"),
            "finite samples only",
            f"has {bad} NaN or infinite ones",
        )
    return values


def _frozen(values: ArrayLike) -> FloatArray:
    """A read-only float copy of `values`."""
    array = np.array(values, dtype=np.float64)
    array.flags.writeable = False
    return array
