"""S-N curves: the number of cycles N to failure at a stress range Δσ, by DNV-RP-C203 or a user's curve.

``SNCurve.dnv(name, environment, thickness=...)`` builds the design S-N curves of DNVGL-RP-C203 *Fatigue
design of offshore steel structures* (April 2016 edition) Sec.2.4; ``SNCurve.user(slopes, log_a)`` a curve
of one or two straight lines in log-log axes. ``curve.cycles(Δσ)`` and its inverse ``curve.stress_range(N)``
evaluate them.

Equation
--------
On each segment i (DNV-RP-C203 eq. (2.4.1) and, with the thickness effect, eq. (2.4.3)):

    log N = log ā_i − m_i log(Δσ (t/t_ref)^k)

with Δσ the stress range (MPa), ā_i the intercept of the design curve with the log N axis (log10, stress in
MPa), m_i the negative inverse slope, t the thickness through which a crack will grow, t_ref the reference
thickness (25 mm for welded connections other than tubular joints) and k the thickness exponent. The
factor (t/t_ref)^k applies only where t > t_ref and is 1 otherwise. A two-slope curve uses (m_1, ā_1) for
N ≤ the switch (10^7 cycles in air, 10^6 in seawater with cathodic protection), that is for Δσ at or above
the switch stress range, and (m_2 = 5, ā_2) below it.

Tables
------
DNVGL-RP-C203 (April 2016) Table 2-1 (in air), Table 2-2 (seawater with cathodic protection) and Table
2-4 (free corrosion, one slope m = 3), classes B1 … W3; the values stand unchanged in the 2019 and 2021
editions. The October 2024 edition of DNV-RP-C203 revised the B1–C2 curves in air and with cathodic
protection: the values here are the 2016 ones. The tabled log ā values are rounded to three decimals, so
the two segments of a DNV curve meet at the switch only to within about 0.1 % in stress (a step of up to
about 0.5 % in N there); the segment is chosen by the switch stress range of the first segment.

Units: stress range in MPa (N/mm²), cycles dimensionless, thickness in m.

Imports of pipelay: `pipelay.analysis.checks` (its input errors).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pipelay.analysis.checks import _Described, _input_error, _number

__all__ = ["DNV_CLASSES", "ENVIRONMENTS", "SNCurve"]

FloatArray = NDArray[np.float64]

ENVIRONMENTS = ("air", "seawater_cp", "free_corrosion")
"""The environments of `SNCurve.dnv`: in air, in seawater with cathodic protection, free corrosion."""

FATIGUE_LIMIT_CYCLES = 1e7
"""N at which `SNCurve.fatigue_limit` is read (DNV-RP-C203 Table 2-1's "fatigue limit at 10^7 cycles")."""

REFERENCE_THICKNESS = 0.025
"""DNV-RP-C203's reference thickness t_ref for welded connections other than tubular joints (m)."""

_SECOND_SLOPE = 5.0
"""m_2 of every two-slope DNV-RP-C203 curve."""

# Table 2-1 (air): class -> (m1, log a1 for N <= 1e7, log a2 for N > 1e7 with m2 = 5, fatigue limit at
# 1e7 cycles (MPa), thickness exponent k).
_AIR: dict[str, tuple[float, float, float, float, float]] = {
    "B1": (4.0, 15.117, 17.146, 106.97, 0.0),
    "B2": (4.0, 14.885, 16.856, 93.59, 0.0),
    "C": (3.0, 12.592, 16.320, 73.10, 0.05),
    "C1": (3.0, 12.449, 16.081, 65.50, 0.10),
    "C2": (3.0, 12.301, 15.835, 58.48, 0.15),
    "D": (3.0, 12.164, 15.606, 52.63, 0.20),
    "E": (3.0, 12.010, 15.350, 46.78, 0.20),
    "F": (3.0, 11.855, 15.091, 41.52, 0.25),
    "F1": (3.0, 11.699, 14.832, 36.84, 0.25),
    "F3": (3.0, 11.546, 14.576, 32.75, 0.25),
    "G": (3.0, 11.398, 14.330, 29.24, 0.25),
    "W1": (3.0, 11.261, 14.101, 26.32, 0.25),
    "W2": (3.0, 11.107, 13.845, 23.39, 0.25),
    "W3": (3.0, 10.970, 13.617, 21.05, 0.25),
}

# Table 2-2 (seawater with cathodic protection): class -> log a1 for N <= 1e6 (m1 as in air); for N > 1e6
# m2 = 5 and log a2 as in air, and so the fatigue limit at 1e7 and k.
_SEAWATER_CP: dict[str, float] = {
    "B1": 14.917,
    "B2": 14.685,
    "C": 12.192,
    "C1": 12.049,
    "C2": 11.901,
    "D": 11.764,
    "E": 11.610,
    "F": 11.455,
    "F1": 11.299,
    "F3": 11.146,
    "G": 10.998,
    "W1": 10.861,
    "W2": 10.707,
    "W3": 10.570,
}

# Table 2-4 (free corrosion): class -> log a of the one slope m = 3 (k as in air).
_FREE_CORROSION: dict[str, float] = {
    "B1": 12.436,
    "B2": 12.262,
    "C": 12.115,
    "C1": 11.972,
    "C2": 11.824,
    "D": 11.687,
    "E": 11.533,
    "F": 11.378,
    "F1": 11.222,
    "F3": 11.068,
    "G": 10.921,
    "W1": 10.784,
    "W2": 10.630,
    "W3": 10.493,
}

DNV_CLASSES: tuple[str, ...] = tuple(_AIR)
"""The DNV-RP-C203 S-N classes, B1 … W3."""

DNV_FATIGUE_LIMITS: dict[str, float] = {name: row[3] for name, row in _AIR.items()}
"""The fatigue limit at 10^7 cycles of each class as DNV-RP-C203 Table 2-1 prints it (MPa), air and CP."""

DNV_THICKNESS_EXPONENTS: dict[str, float] = {name: row[4] for name, row in _AIR.items()}
"""The thickness exponent k of each class (DNV-RP-C203 Tables 2-1, 2-2, 2-4)."""

_SWITCH_CYCLES = {"air": 1e7, "seawater_cp": 1e6}


@dataclass(frozen=True)
class SNCurve:
    """An S-N curve of one or two slopes: N = ā_i (Δσ·thickness_factor)^(−m_i) on segment i.

    Build it with `SNCurve.dnv` or `SNCurve.user`; direct construction checks the same things as `user`
    except continuity (the DNV tables meet at their switch only to rounding).

    Attributes
    ----------
    name : str
        The DNV class ("D", …) or the user's name.
    slopes : tuple of float
        m_1 (and m_2): the negative inverse slopes of the segments, > 0.
    log_a : tuple of float
        log10 ā_1 (and log10 ā_2) of the segments, stress range in MPa.
    switch_cycles : float or None
        N at which the slope changes (segment 1 for N ≤ switch_cycles); None for one slope.
    thickness_factor : float
        (t/t_ref)^k ≥ 1 multiplying the stress range; 1.0 where t ≤ t_ref or no thickness was given.
    environment : str or None
        "air", "seawater_cp" or "free_corrosion" for a DNV curve; None for a user's curve.
    """

    name: str
    slopes: tuple[float, ...]
    log_a: tuple[float, ...]
    switch_cycles: float | None = None
    thickness_factor: float = 1.0
    environment: str | None = None

    def __post_init__(self) -> None:
        slopes = _values("slopes", self.slopes, positive=True)
        log_a = _values("log_a", self.log_a)
        if len(log_a) != len(slopes):
            raise _input_error(
                "log_a",
                self.log_a,
                f"as many values as slopes ({len(slopes)})",
                f"has {len(log_a)} value{'s' if len(log_a) != 1 else ''}",
            )
        if len(slopes) == 1:
            if self.switch_cycles is not None:
                raise _input_error("switch_cycles", self.switch_cycles, "None for a curve of one slope")
            switch = None
        else:
            switch = _number("switch_cycles", self.switch_cycles, positive=True)
        factor = _number("thickness_factor", self.thickness_factor, positive=True)
        object.__setattr__(self, "slopes", slopes)
        object.__setattr__(self, "log_a", log_a)
        object.__setattr__(self, "switch_cycles", switch)
        object.__setattr__(self, "thickness_factor", factor)

    # --- construction ------------------------------------------------------------------------------------

    @classmethod
    def dnv(
        cls,
        name: str,
        environment: str = "air",
        *,
        thickness: float | None = None,
        thickness_exponent: float | None = None,
        reference_thickness: float = REFERENCE_THICKNESS,
    ) -> SNCurve:
        """The DNV-RP-C203 (2016) design S-N curve of class `name` in `environment`.

        Parameters
        ----------
        name : str
            S-N class, one of `DNV_CLASSES`: "B1", "B2", "C", "C1", "C2", "D", "E", "F", "F1", "F3", "G",
            "W1", "W2", "W3".
        environment : {"air", "seawater_cp", "free_corrosion"}
            Table 2-1 (two slopes, switch at 10^7 cycles), Table 2-2 (two slopes, switch at 10^6 cycles) or
            Table 2-4 (one slope m = 3).
        thickness : float or None
            Thickness through which a crack will grow, t (m) > 0; None: no thickness effect.
        thickness_exponent : float or None
            Thickness exponent k ≥ 0 in place of the table's (e.g. for a ground weld or a tubular joint);
            None: the table's k of the class.
        reference_thickness : float
            t_ref (m) > 0: 0.025 (welded connections other than tubular joints); 0.016 for tubular joints.

        Returns
        -------
        SNCurve
            With thickness_factor (t/t_ref)^k where t > t_ref, else 1.

        Raises
        ------
        pipelay.InputError
            For an unknown class or environment, or a thickness, exponent or reference thickness out of range.
        """
        if not isinstance(name, str) or name not in _AIR:
            raise _input_error("name", name, ", ".join(DNV_CLASSES), "is not a DNV-RP-C203 S-N class")
        if not isinstance(environment, str) or environment not in ENVIRONMENTS:
            raise _input_error(
                "environment", environment, ", ".join(ENVIRONMENTS), "is not a DNV-RP-C203 environment"
            )
        t_ref = _number(
            "reference_thickness", reference_thickness, positive=True, allowed="a thickness > 0 (m)"
        )
        if thickness_exponent is None:
            k = DNV_THICKNESS_EXPONENTS[name]
        else:
            k = _number("thickness_exponent", thickness_exponent, minimum=0.0)
        factor = 1.0
        if thickness is not None:
            t = _number("thickness", thickness, positive=True, allowed="a thickness > 0 (m), or None")
            if t > t_ref:
                factor = (t / t_ref) ** k
        m1, log_a1, log_a2, _, _ = _AIR[name]
        if environment == "free_corrosion":
            return cls(name, (3.0,), (_FREE_CORROSION[name],), None, factor, environment)
        if environment == "seawater_cp":
            log_a1 = _SEAWATER_CP[name]
        return cls(
            name, (m1, _SECOND_SLOPE), (log_a1, log_a2), _SWITCH_CYCLES[environment], factor, environment
        )

    @classmethod
    def user(cls, slopes: ArrayLike, log_a: ArrayLike, *, name: str = "user") -> SNCurve:
        """A user's S-N curve of one or two segments, N = ā_i Δσ^(−m_i), Δσ in MPa.

        Parameters
        ----------
        slopes : sequence of 1 or 2 floats
            m_1 (the segment of the high stress ranges, short lives) and m_2, each > 0 and m_1 ≠ m_2.
        log_a : sequence of as many floats
            log10 ā_i of each segment (stress range in MPa), finite.
        name : str
            A name for the curve.

        Returns
        -------
        SNCurve
            With two segments, the switch is where the two lines meet: log N_sw = (m_2 log ā_1 − m_1 log
            ā_2)/(m_2 − m_1), so the curve is continuous by construction. No thickness factor, no environment.

        Raises
        ------
        pipelay.InputError
            If a slope is not > 0, a log_a is not finite, the lengths differ or are not 1 or 2, or the two
            lines do not meet (equal slopes).
        """
        m = _values("slopes", slopes, positive=True)
        a = _values("log_a", log_a)
        if len(a) != len(m):
            raise _input_error("log_a", a, f"as many values as slopes ({len(m)})", f"has {len(a)}")
        if not isinstance(name, str):
            raise _input_error("name", name, "a string", "is not a string")
        if len(m) == 1:
            return cls(name, m, a)
        (m1, m2), (a1, a2) = m, a
        if m1 == m2:
            raise _input_error(
                "slopes",
                m,
                "two different slopes (two lines of equal slope do not meet), or one slope",
                "has equal slopes",
            )
        log_switch = (m2 * a1 - m1 * a2) / (m2 - m1)
        switch = 10.0**log_switch
        if not (math.isfinite(switch) and switch > 0.0):
            raise _input_error(
                "log_a",
                a,
                "lines that meet at a finite number of cycles",
                f"puts the switch at 10^{log_switch:g} cycles",
            )
        return cls(name, m, a, switch)

    # --- evaluation --------------------------------------------------------------------------------------

    @property
    def switch_stress_range(self) -> float | None:
        """Δσ at the switch (MPa): where the first segment reaches `switch_cycles`; None for one slope."""
        if self.switch_cycles is None:
            return None
        return (
            10.0 ** ((self.log_a[0] - math.log10(self.switch_cycles)) / self.slopes[0])
            / self.thickness_factor
        )

    @property
    def fatigue_limit(self) -> float:
        """Δσ at N = 10^7 cycles (MPa), thickness factor included."""
        return float(self.stress_range(FATIGUE_LIMIT_CYCLES))

    @overload
    def cycles(self, stress_range: float) -> float: ...
    @overload
    def cycles(self, stress_range: ArrayLike) -> float | FloatArray: ...

    def cycles(self, stress_range: ArrayLike) -> float | FloatArray:
        """Cycles to failure N at `stress_range`.

        Parameters
        ----------
        stress_range : float or array-like
            Stress range Δσ (MPa) ≥ 0, finite.

        Returns
        -------
        float or ndarray
            N (same shape as the input; a float for a scalar); inf for a range of 0.

        Raises
        ------
        pipelay.InputError
            If a stress range is negative, NaN or infinite.
        """
        ranges = _array("stress_range", stress_range, "stress ranges (MPa) >= 0, finite")
        effective = ranges * self.thickness_factor
        with np.errstate(divide="ignore"):
            log_s = np.log10(effective)
        log_n = self.log_a[0] - self.slopes[0] * log_s
        if self.switch_cycles is not None:
            switch = self.switch_stress_range
            assert switch is not None
            below = ranges < switch
            log_n = np.where(below, self.log_a[1] - self.slopes[1] * log_s, log_n)
        with np.errstate(over="ignore"):
            result: FloatArray = np.power(10.0, log_n)
        return float(result) if result.ndim == 0 else result

    @overload
    def stress_range(self, cycles: float) -> float: ...
    @overload
    def stress_range(self, cycles: ArrayLike) -> float | FloatArray: ...

    def stress_range(self, cycles: ArrayLike) -> float | FloatArray:
        """Stress range Δσ (MPa) at which the curve gives `cycles` to failure: the inverse of `cycles`.

        Parameters
        ----------
        cycles : float or array-like
            N > 0; +inf gives 0 (the inverse of ``cycles(0)``).

        Returns
        -------
        float or ndarray
            Δσ (MPa), same shape as the input.

        Raises
        ------
        pipelay.InputError
            If a number of cycles is not > 0 or is NaN.
        """
        counts = _array("cycles", cycles, "numbers of cycles > 0 (inf allowed)", positive=True)
        with np.errstate(divide="ignore"):
            log_n = np.log10(counts)
        log_s = (self.log_a[0] - log_n) / self.slopes[0]
        if self.switch_cycles is not None:
            beyond = counts > self.switch_cycles
            log_s = np.where(beyond, (self.log_a[1] - log_n) / self.slopes[1], log_s)
        result: FloatArray = np.power(10.0, log_s) / self.thickness_factor
        return float(result) if result.ndim == 0 else result


# --- validation ------------------------------------------------------------------------------------------


def _values(argument: str, values: object, *, positive: bool = False) -> tuple[float, ...]:
    """`values` as a tuple of 1 or 2 finite floats (> 0 if `positive`), else an input error."""
    allowed = f"1 or 2 finite numbers{' > 0' if positive else ''}"
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise _input_error(argument, values, allowed, "is not numeric") from None
    if array.ndim != 1 or array.size not in (1, 2):
        raise _input_error(argument, values, allowed, "is not 1 or 2 numbers")
    if not np.all(np.isfinite(array)):
        raise _input_error(argument, values, allowed, "is not finite")
    if positive and not np.all(array > 0.0):
        raise _input_error(argument, values, allowed, "is not positive")
    return tuple(float(value) for value in array)


def _array(argument: str, values: ArrayLike, allowed: str, *, positive: bool = False) -> FloatArray:
    """`values` as a float array; each ≥ 0 and finite (or > 0, +inf allowed, if `positive`)."""
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise _input_error(
            argument, _Described(f"a {type(values).__name__}"), allowed, "is not numeric"
        ) from None
    if positive:
        bad = np.isnan(array) | ~(array > 0.0)
    else:
        bad = ~np.isfinite(array) | (array < 0.0)
    if np.any(bad):
        first = float(np.atleast_1d(array)[np.atleast_1d(bad)][0])
        if math.isnan(first):
            kind = "NaN"
        elif math.isinf(first):
            kind = "infinite"
        else:
            kind = "negative" if first < 0.0 else "zero"
        if array.ndim == 0:
            raise _input_error(argument, first, allowed, f"is {kind}")
        raise _input_error(argument, _Described("an array"), allowed, f"holds a {kind} value ({first!r})")
    return array
