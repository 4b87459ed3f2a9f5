"""Code checks of a pipelay state against DNV-ST-F101 (Submarine pipeline systems, DNV, 2021 edition).

`dnv_st_f101(state, ...)` evaluates, element by element, the local-buckling limit states of DNV-ST-F101
Sec.5 [5.4.6] "Local buckling – combined loading criteria" and returns a `Utilisation` (unity = limit):

* the **load-controlled condition** (bending moment, effective axial force and pressure), in its
  internal-overpressure form where p_i > p_e and its external-overpressure form otherwise;
* the **displacement-controlled condition** (longitudinal strain and pressure), as the strain demand over
  the allowable strain.

`propagation_buckling(state, ...)` evaluates Sec.5 [5.4.5] "Propagation buckling" with the same parameters and
returns a `Propagation`: p_e − p_min ≤ p_pr/(γ_m γ_SC) with p_pr = 35 f_y α_fab (t₂/D)^2.5 (valid for
15 < D/t₂ < 45), its utilisation γ_m γ_SC (p_e − p_min)/p_pr per element, and where buckle arrestors are needed.
Both take their defaults from `DEFAULTS`, and pressures as below.

Units and frame
---------------
SI throughout: m, N, N·m, Pa. The state is in the model's inertial frame e: origin at the pipe's seabed end,
e3 pointing down, the sea surface the plane z = −water_depth. The depth of a point below the surface is
therefore h = max(water_depth + z, 0), the external (hydrostatic) pressure ``p_e = ρ_w g h`` with g = 9.81 m/s²
(points above the surface, on the vessel, see no pressure), and the internal pressure by default that of the
contents open to the surface, ``p_i = ρ_c g h`` (`contents_pressure`; ρ_c the section's ``contents_density``,
0 for an empty pipe), or one pressure given for the whole pipe. Forces are evaluated at element midpoints, so
the pressures use the midpoint depth.

Effective axial force
---------------------
The model applies buoyancy as a distributed load on the centreline (the pipe carries its submerged weight),
not as pressure on the pipe's actual surface. The axial force the model computes is therefore the
*effective* axial force (Sparks' effective tension), which is exactly DNV's S:

    S = N − p_i·A_i + p_e·A_e        (DNV-ST-F101 Sec.4; positive in tension)

with N the true pipe-wall force (positive in tension), A_i = π(D − 2t)²/4 and A_e = π D²/4. So the design
effective axial force S_Sd of the criteria is directly ``state.tension`` (= n1 of ``state.section_forces``),
and the wall force follows as

    N = S + p_i·A_i − p_e·A_e,

reported as `Utilisation.wall_tension` (nominal t). A pipe hanging in still water with zero effective tension
at its lower end has there a *compressive* wall force −p_e·A_e. The criteria square S, so its sign enters
only through the reported values. (The criteria of DNV-ST-F101 are formulated in the effective force; see
L. Collberg & E. Levold, "DNV GL-ST-F101 combined loading criterion – background and derivation",
OMAE2016-54238.)

Equations (references)
----------------------
The 2021 edition (DNV-ST-F101) keeps the Sec.5 layout of the 2017 edition (DNVGL-ST-F101). Numbers marked
(2017) are those of the 2017 edition; numbers marked (2010) are those of the predecessor DNV-OS-F101 (October
2010) Sec.5 D600, which has the same combined-loading criteria: the 2021 edition places them in [5.4.6],
possibly under other equation numbers.

* Characteristic strength  f_y = (SMYS − f_y,temp)·α_U,  f_u = (SMTS − f_u,temp)·α_U
  — Sec.5 [5.3.3.2] eqs. (5.4), (5.5) (2017); α_U = 0.96 (no supplementary requirement U), Table 5-3.
  The same de-rating f_temp is used for f_y and f_u (the C-Mn de-rating curve of Sec.5 [5.3.3] is common).
* Partial factors: γ_m = 1.15 (ULS), Table 5-1; γ_SC = 1.04 / 1.14 / 1.26 (low / medium / high,
  local buckling), Table 5-2; α_fab (seamless 1.00, UO/TRB/ERW/HFW 0.93, UOE 0.85), Table 5-4 (2017).
  DNV classifies temporary phases such as installation, when the pipe holds no hydrocarbons, as safety
  class *low* (Sec.2 safety class classification); the default here is the more conservative "medium".
* Wall thickness t₂ of the buckling criteria: t prior to operation (``condition="installation"``), and
  t − t_corr in operation (``condition="operation"``) — Sec.5 [5.3], characteristic wall thickness.
* Burst pressure  p_b(t) = 2t/(D − t) · f_cb · 2/√3,  f_cb = min(f_y, f_u/1.15) — [5.4.2.2] eq. (5.8) (2017).
* Characteristic collapse pressure p_c — [5.4.4.2] eqs. (5.11)–(5.14) (2017):
  (p_c − p_el)(p_c² − p_p²) = p_c·p_el·p_p·O₀·D/t,  p_el = 2E(t/D)³/(1 − ν²),  p_p = f_y·α_fab·2t/D,
  O₀ ≥ 0.005; solved in closed form (the smallest positive root of the cubic, cf. Sec.13 [13.4.7]
  eq. (13.10), 2017).
* Plastic capacities S_p = f_y·π·(D − t)·t and M_p = f_y·(D − t)²·t — eqs. (5.20), (5.21) (2010).
* Flow stress parameter α_c = (1 − β) + β·f_u/f_y with β = 0.5 (D/t₂ < 15), (60 − D/t₂)/90 (15 ≤ D/t₂ ≤ 60),
  0 (D/t₂ > 60) — eqs. (5.22), (5.24) (2010); pressure factor α_p = 1 − β for (p_i − p_e)/p_b < 2/3, else
  1 − 3β(1 − (p_i − p_e)/p_b) — eq. (5.23) (2010).
* Load-controlled condition, internal overpressure (p_i > p_e) — eq. (5.19) (2010):
  {γ_m γ_SC |M_Sd|/(α_c M_p) + (γ_m γ_SC S_Sd/(α_c S_p))²}² + (α_p (p_i − p_e)/(α_c p_b))² ≤ 1;
  external overpressure (p_e ≥ p_i) — eq. (5.28) (2010):
  {γ_m γ_SC |M_Sd|/(α_c M_p) + (γ_m γ_SC S_Sd/(α_c S_p))²}² + (γ_m γ_SC (p_e − p_min)/p_c)² ≤ 1.
  Both with M_p, S_p, p_b, p_c at t₂; valid for D/t₂ ≤ 45 (the internal form also for |S_Sd|/S_p < 0.4).
  `Utilisation.load_controlled` is the left-hand side.
* Displacement-controlled condition — eqs. (5.29), (5.30) (2010) and the external-overpressure criterion
  of the same subsection:
  ε_Sd ≤ ε_c(t₂, p_min − p_e)/γ_ε for p_min ≥ p_e, with
  ε_c(t, p_min − p_e) = 0.78·(t/D − 0.01)·(1 + 5.75 (p_min − p_e)/p_b(t))·α_h^−1.5·α_gw;
  (ε_Sd/(ε_c(t₂, 0)/γ_ε))^0.8 + (p_e − p_min)/(p_c(t₂)/(γ_m γ_SC)) ≤ 1 for p_e > p_min.
  γ_ε = 2.0 / 2.5 / 3.3 (low / medium / high). α_h = (R_t0.5/R_m)_max is taken as 0.93 and the girth weld
  factor α_gw as 1.0 for D/t₂ ≤ 20, falling linearly to 0.6 at D/t₂ = 60 (Sec.13, commentary figure).
  `Utilisation.displacement_controlled` is ε_Sd / ε_allow, where ε_allow is the strain at which the
  criterion reaches unity at the element's pressure:
  ε_allow = ε_c(t₂, 0)/γ_ε · (1 − γ_m γ_SC (p_e − p_min)/p_c)^1.25 under external overpressure. Unity of the
  ratio is unity of the criterion. ``strain_limit`` replaces ε_allow by a fixed allowable strain (e.g. an
  overbend strain criterion specified for the lay); DNV's simplified laying (overbend) criteria are not
  built in.

Assumptions
-----------
* The state's forces, moments and strains are taken as the design load effects: DNV's load effect factors
  (γ_F, γ_E, γ_c, Sec.4) are not applied — factor the loads before, or scale the result.
* The internal pressure p_i is, by default, that of the section's contents open to the sea surface,
  ρ_c g h at each element's depth h below the surface (a flooded pipe: p_i = p_e; an empty one: 0), or one
  pressure given for the whole pipe (``internal_pressure``, a design or lay pressure); it is p_i of the
  internal-overpressure criteria and p_min (minimum sustained internal pressure) of the external ones.
* The defaults of every parameter live in `DEFAULTS`; a scenario's ``[checks]`` table overrides them for the
  command line, the figures, the report and sweeps alike, so that each shows the same utilisation.
* The strain demand is |state.strain| (largest longitudinal strain at the outer fibre, axial + bending).

Imports of pipelay: only the engine's ``InputError``, when an error is raised (the module reads a state by its
attributes, so it also loads from its file without the engine).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "DEFAULTS",
    "GRADES",
    "Propagation",
    "Utilisation",
    "contents_pressure",
    "describe_parameters",
    "dnv_st_f101",
    "propagation_buckling",
]

FloatArray = NDArray[np.float64]

GRAVITY = 9.81
"""Acceleration of gravity used for hydrostatic pressure (m/s²)."""

RECORDS_BLOCK_ELEMENTS = 1 << 16
"""Element values (records × elements) checked at once when every record of a run is checked."""

GRADES: dict[str, tuple[float, float]] = {
    "X52": (360e6, 460e6),
    "X56": (390e6, 490e6),
    "X60": (415e6, 520e6),
    "X65": (450e6, 535e6),
    "X70": (485e6, 570e6),
    "X80": (555e6, 625e6),
}
"""Line pipe grade (API 5L / ISO 3183 L360 … L555, as tabulated by DNV) -> (SMYS, SMTS) in Pa."""

DEFAULT_GRADE = "X65"
"""The grade checked where neither the call nor the section names one."""

GAMMA_M = 1.15
"""Material resistance factor γ_m for the ultimate limit state (DNV-ST-F101 Table 5-1)."""

GAMMA_SC: dict[str, float] = {"low": 1.04, "medium": 1.14, "high": 1.26}
"""Safety class resistance factor γ_SC for local buckling, collapse and load-controlled checks (Table 5-2)."""

GAMMA_EPSILON: dict[str, float] = {"low": 2.0, "medium": 2.5, "high": 3.3}
"""Resistance strain factor γ_ε of the displacement-controlled condition, by safety class."""

ALPHA_FAB: dict[str, float] = {"seamless": 1.00, "uoe": 0.85, "uo_tre": 0.93, "welded": 0.93}
"""Fabrication factor α_fab (Table 5-4): seamless; UOE; UO / TRB (uo_tre); ERW / HFW (welded)."""

ALPHA_U = 0.96
"""Material strength factor α_U without supplementary requirement U (Table 5-3)."""

ALPHA_H = 0.93
"""Assumed maximum yield-to-tensile ratio α_h = (R_t0.5/R_m)_max of C-Mn line pipe."""

CONDITIONS = ("installation", "operation")

DEFAULTS: dict[str, Any] = {
    "grade": None,
    "wall_thickness": None,
    "safety_class": "medium",
    "internal_pressure": None,
    "fabrication": "seamless",
    "corrosion_allowance": 0.0,
    "ovality": 0.005,
    "temperature_derating": 0.0,
    "condition": "installation",
    "strain_limit": None,
}
"""The parameters of every check where neither the call nor the scenario's ``[checks]`` table sets them, in one
place: the section's grade (X65 without one) and wall thickness; safety class medium (DNV classifies
installation as low: set ``safety_class = "low"`` to use it); the internal pressure of the section's contents
(`contents_pressure`); a seamless pipe; installation (no corrosion allowance deducted); DNV's minimum ovality
0.5 %; no temperature de-rating; DNV's strain resistance."""
DEFAULT_YOUNGS_MODULUS = 207e9
DEFAULT_POISSON_RATIO = 0.3

_Check = Literal["load_controlled", "displacement_controlled"]


@dataclass(frozen=True, eq=False)
class Utilisation:
    """DNV-ST-F101 local-buckling utilisations of a state, per element (unity = limit).

    Arrays have one entry per element (n,) and are read-only; scalars are the capacities and factors used.

    Attributes
    ----------
    load_controlled : ndarray (n,)
        Left-hand side of the load-controlled combined loading criterion (internal-overpressure form where
        p_i > p_e, external-overpressure form otherwise). Dimensionless.
    displacement_controlled : ndarray (n,)
        Strain demand over allowable strain, |ε| / ε_allow (inf where the pressure alone exhausts the
        capacity). Dimensionless.
    moment : ndarray (n,)
        Bending moment |M| = hypot(m2, m3) (N·m).
    effective_axial_force : ndarray (n,)
        Effective axial force S (N), positive in tension: the model's axial force n1.
    wall_tension : ndarray (n,)
        True pipe-wall force N = S + p_i A_i − p_e A_e (N), positive in tension, nominal wall thickness.
    external_pressure : ndarray (n,)
        Hydrostatic pressure p_e at the element midpoints (Pa).
    strain : ndarray (n,)
        Strain demand |ε| (dimensionless).
    allowable_strain : ndarray (n,)
        Allowable strain ε_allow at each element's pressure, or ``strain_limit`` (dimensionless).
    alpha_p : ndarray (n,)
        Pressure factor α_p of the internal-overpressure criterion (used where p_i > p_e).
    plastic_moment, plastic_axial_force : float
        M_p (N·m) and S_p (N) at t₂.
    collapse_pressure, burst_pressure : float
        Characteristic collapse pressure p_c and burst pressure p_b at t₂ (Pa).
    smys, smts, f_y, f_u : float
        Specified and characteristic (de-rated, × α_U) yield and tensile strengths (Pa).
    outer_diameter, wall_thickness, t2 : float
        D, nominal t and the t₂ of the criteria (m).
    internal_pressure : ndarray (n,)
        p_i = p_min at the element midpoints (Pa): the one given, or that of the section's contents.
    gamma_m, gamma_sc, gamma_epsilon, alpha_c, alpha_u, alpha_fab, alpha_h, alpha_gw, beta : float
        Factors used.
    grade, safety_class, fabrication, condition : str
        The choices made.
    basis : str
        Those choices and the pressures in one line, to state beside every utilisation shown (e.g.
        "DNV-ST-F101, X65, safety class medium (γ_SC 1.14), seamless (α_fab 1.00), installation, p_i 0 (empty),
        p_e hydrostatic (1025 kg/m³)").
    notes : tuple of str
        Where the state lies outside the stated validity of the criteria.
    segment_of : ndarray (n,) of int or None
        For a line of several segments, each element's segment; None for a line of one.
    segments : tuple of Utilisation or None
        For a line of several segments, each segment's own checks (over its elements alone; None for a
        cable's segment, which has no steel wall to check). The scalars above (capacities, factors, grade)
        are then those of the governing segment, the one holding the largest load-controlled utilisation;
        the per-element arrays cover the whole line, a cable's elements with utilisations 0.
    """

    load_controlled: FloatArray
    displacement_controlled: FloatArray
    moment: FloatArray
    effective_axial_force: FloatArray
    wall_tension: FloatArray
    external_pressure: FloatArray
    strain: FloatArray
    allowable_strain: FloatArray
    alpha_p: FloatArray
    plastic_moment: float
    plastic_axial_force: float
    collapse_pressure: float
    burst_pressure: float
    smys: float
    smts: float
    f_y: float
    f_u: float
    outer_diameter: float
    wall_thickness: float
    t2: float
    internal_pressure: FloatArray
    gamma_m: float
    gamma_sc: float
    gamma_epsilon: float
    alpha_c: float
    alpha_u: float
    alpha_fab: float
    alpha_h: float
    alpha_gw: float
    beta: float
    grade: str
    safety_class: str
    fabrication: str
    condition: str
    basis: str = ""
    notes: tuple[str, ...] = field(default=())
    segment_of: NDArray[np.int64] | None = None
    segments: tuple[Utilisation | None, ...] = field(default=())

    def max(self) -> dict[str, float]:
        """Largest utilisation of each check, {"load_controlled": …, "displacement_controlled": …}."""
        return {
            "load_controlled": float(np.max(self.load_controlled)),
            "displacement_controlled": float(np.max(self.displacement_controlled)),
        }

    def worst_element(self, check: _Check | None = None) -> int:
        """Index of the element with the largest utilisation.

        Parameters
        ----------
        check : {"load_controlled", "displacement_controlled"} or None
            The check to rank by; None (default) ranks by the larger of the two at each element.

        Returns
        -------
        int
            Element index (0 at end A, the seabed end).
        """
        if check is None:
            values = np.maximum(self.load_controlled, self.displacement_controlled)
        elif check == "load_controlled":
            values = self.load_controlled
        elif check == "displacement_controlled":
            values = self.displacement_controlled
        else:
            raise _input_error("check", check, "load_controlled, displacement_controlled or None")
        return int(np.argmax(values))


def dnv_st_f101(
    state: Any,
    *,
    grade: str | None = DEFAULTS["grade"],
    wall_thickness: float | None = DEFAULTS["wall_thickness"],
    safety_class: str = DEFAULTS["safety_class"],
    internal_pressure: float | None = DEFAULTS["internal_pressure"],
    fabrication: str = DEFAULTS["fabrication"],
    corrosion_allowance: float = DEFAULTS["corrosion_allowance"],
    ovality: float = DEFAULTS["ovality"],
    temperature_derating: float = DEFAULTS["temperature_derating"],
    condition: str = DEFAULTS["condition"],
    strain_limit: float | None = DEFAULTS["strain_limit"],
) -> Utilisation:
    """Local-buckling checks of DNV-ST-F101 Sec.5 [5.4.6] for every element of `state`.

    Parameters
    ----------
    state : State-like
        Provides ``section_forces`` (n, 6) (N, N·m; material frame, midpoints), ``tension`` (n,) (N, the
        effective axial force, positive in tension), ``positions`` (n + 1, 3) (m, frame e, e3 down),
        ``strain`` (n,) (largest longitudinal strain), ``water_depth`` (m, or None: no sea),
        ``water_density`` (kg/m³) and ``section`` with ``outer_diameter`` (m), ``wall_thickness`` (m or
        None), ``youngs_modulus`` (Pa or None: 207e9) and ``poisson_ratio`` (or None: 0.3).
    grade : str or None
        Line pipe grade, a key of `GRADES` ("X52" … "X80"); None takes ``state.section.grade`` (the grade
        given to ``pl.Section.pipe``), or "X65" where the section has none.
    wall_thickness : float or None
        Nominal wall thickness t (m); None takes ``state.section.wall_thickness``.
    safety_class : {"low", "medium", "high"}
        Sets γ_SC and γ_ε. DNV normally classifies installation as "low".
    internal_pressure : float or None
        Local internal pressure p_i, also the minimum sustained internal pressure p_min (Pa, ≥ 0), the same at
        every element (a design or lay pressure); None takes that of the section's contents at each element,
        ρ_c g h with h its depth below the surface (`contents_pressure`: 0 for an empty pipe).
    fabrication : {"seamless", "uoe", "uo_tre", "welded"}
        Sets the fabrication factor α_fab of the collapse pressure.
    corrosion_allowance : float
        t_corr (m, ≥ 0), deducted from t in operation only.
    ovality : float
        Out-of-roundness O₀ = (D_max − D_min)/D, at least 0.005 (DNV's minimum).
    temperature_derating : float
        De-rating f_y,temp = f_u,temp of the strengths (Pa, ≥ 0).
    condition : {"installation", "operation"}
        Installation (prior to operation): t₂ = t; operation: t₂ = t − t_corr.
    strain_limit : float or None
        Allowable strain (> 0) replacing DNV's strain resistance in the displacement-controlled check.

    Returns
    -------
    Utilisation

    Raises
    ------
    pipelay.InputError
        If an argument or a state attribute is missing, of the wrong type, shape or value.
    """
    options = _options(
        grade=grade,
        wall_thickness=wall_thickness,
        safety_class=safety_class,
        internal_pressure=internal_pressure,
        fabrication=fabrication,
        corrosion_allowance=corrosion_allowance,
        ovality=ovality,
        temperature_derating=temperature_derating,
        condition=condition,
        strain_limit=strain_limit,
    )
    forces = _state_array(state, "section_forces", (None, 6))
    n = forces.shape[0]
    if n == 0:
        raise _input_error(
            "state.section_forces", _Described("an array of 0 elements"), "at least one element", "is empty"
        )
    tension = _state_array(state, "tension", (n,))
    positions = _state_array(state, "positions", (n + 1, 3))
    strain = np.abs(_state_array(state, "strain", (n,)))

    water = _water(state, positions)
    segment_of = _attribute(state, "segment_of", "state", required=False)
    sections = _attribute(state, "sections", "state", required=False)
    if segment_of is None or sections is None or len(sections) <= 1:
        section = _attribute(state, "section", "state")
        return _check_section(section, "state.section", forces, tension, strain, water, options)
    return _check_segments(list(sections), np.asarray(segment_of), forces, tension, strain, water, options)


@dataclass(frozen=True, eq=False)
class Propagation:
    """DNV-ST-F101 propagation buckling along a pipe, per element (arrays (n,), read-only).

    Attributes
    ----------
    utilisation : ndarray (n,)
        γ_m γ_SC (p_e − p_min)/p_pr, at least 0 (1 = limit: beyond it a local buckle, once started, runs along
        the pipe); 0 for a cable's elements. Dimensionless.
    propagation_pressure : ndarray (n,)
        p_pr = 35 f_y α_fab (t₂/D)^2.5 of each element's section (Pa); NaN for a cable's elements.
    external_pressure, internal_pressure : ndarray (n,)
        p_e and p_i = p_min at the element midpoints (Pa).
    gamma_m, gamma_sc : float
        The factors of the criterion.
    safety_class : str
        The safety class chosen.
    basis : str
        The parameters and pressures in one line, to state beside the utilisation.
    arrestors : str or None
        Where buckle arrestors are needed (the utilisation exceeds 1), in words; None where it nowhere does.
    notes : tuple of str
        Where the pipe lies outside the criterion's stated validity (15 < D/t₂ < 45).
    """

    utilisation: FloatArray
    propagation_pressure: FloatArray
    external_pressure: FloatArray
    internal_pressure: FloatArray
    gamma_m: float
    gamma_sc: float
    safety_class: str
    basis: str
    arrestors: str | None
    notes: tuple[str, ...] = field(default=())

    def max(self) -> float:
        """The largest utilisation along the pipe."""
        return float(np.max(self.utilisation))

    def worst_element(self) -> int:
        """Index of the element with the largest utilisation (0 at end A)."""
        return int(np.argmax(self.utilisation))


def propagation_buckling(
    state: Any,
    *,
    grade: str | None = DEFAULTS["grade"],
    wall_thickness: float | None = DEFAULTS["wall_thickness"],
    safety_class: str = DEFAULTS["safety_class"],
    internal_pressure: float | None = DEFAULTS["internal_pressure"],
    fabrication: str = DEFAULTS["fabrication"],
    corrosion_allowance: float = DEFAULTS["corrosion_allowance"],
    ovality: float = DEFAULTS["ovality"],
    temperature_derating: float = DEFAULTS["temperature_derating"],
    condition: str = DEFAULTS["condition"],
    strain_limit: float | None = DEFAULTS["strain_limit"],
) -> Propagation:
    """Propagation buckling of DNV-ST-F101 Sec.5 [5.4.5] along `state`'s pipe.

    A local buckle (from a dent, or excessive bending) in a pipe whose external overpressure exceeds the
    propagation pressure runs along it until the pressure drops or an arrestor stops it. The criterion,

        p_e − p_min ≤ p_pr/(γ_m γ_SC),   p_pr = 35 f_y α_fab (t₂/D)^2.5   (valid for 15 < D/t₂ < 45),

    is evaluated at every element midpoint; the utilisation is γ_m γ_SC (p_e − p_min)/p_pr.

    Parameters
    ----------
    state : State-like
        Provides ``positions`` (n + 1, 3) (m, frame e, e3 down), ``water_depth`` (m, or None), ``water_density``
        (kg/m³) and ``section`` (or ``sections`` and ``segment_of`` for a line of segments).
    grade, wall_thickness, safety_class, internal_pressure, fabrication, corrosion_allowance,
    temperature_derating, condition
        As for `dnv_st_f101` (the same defaults, `DEFAULTS`): the grade sets f_y, the fabrication α_fab, the
        condition and corrosion allowance t₂, the safety class γ_SC; p_min is the internal pressure.
    ovality, strain_limit
        Accepted so that one set of parameters serves every check; they do not enter this one.

    Returns
    -------
    Propagation

    Raises
    ------
    pipelay.InputError
        If an argument or a state attribute is missing, of the wrong type, shape or value.
    """
    options = _options(
        grade=grade,
        wall_thickness=wall_thickness,
        safety_class=safety_class,
        internal_pressure=internal_pressure,
        fabrication=fabrication,
        corrosion_allowance=corrosion_allowance,
        ovality=ovality,
        temperature_derating=temperature_derating,
        condition=condition,
        strain_limit=strain_limit,
    )
    positions = _state_array(state, "positions", (None, 3))
    n = positions.shape[0] - 1
    if n < 1:
        raise _input_error("state.positions", _Described("one node"), "at least two nodes", "is too short")
    water = _water(state, positions)
    p_e = water.external_pressure()
    p_i = np.zeros(n)
    p_pr = np.full(n, np.nan)
    gamma = GAMMA_M * GAMMA_SC[options.safety_class]
    notes = []
    basis = ""
    for section, prefix, elements in _steel_parts(state, n):
        steel = _steel(section, prefix, options)
        p_pr[elements] = (
            35.0 * steel.f_y * ALPHA_FAB[options.fabrication] * (steel.t2 / steel.outer_diameter) ** 2.5
        )
        p_i[elements] = _internal_pressure(section, prefix, water.part(elements), options.internal_pressure)
        d_over_t = steel.outer_diameter / steel.t2
        if not 15.0 < d_over_t < 45.0:
            notes.append(
                f"{prefix}: D/t2 = {d_over_t:.3g} is outside 15 < D/t2 < 45, the criterion's validity"
            )
        basis = basis or _basis("DNV-ST-F101 [5.4.5]", steel.grade, options, section, water)
    steel_elements = np.isfinite(p_pr)
    utilisation = np.zeros(n)
    utilisation[steel_elements] = np.clip(
        gamma * (p_e - p_i)[steel_elements] / p_pr[steel_elements], 0.0, None
    )
    return Propagation(
        utilisation=_frozen(utilisation),
        propagation_pressure=_frozen(p_pr),
        external_pressure=_frozen(p_e),
        internal_pressure=_frozen(p_i),
        gamma_m=GAMMA_M,
        gamma_sc=GAMMA_SC[options.safety_class],
        safety_class=options.safety_class,
        basis=basis,
        arrestors=_arrestor_advice(state, positions, water, utilisation, p_pr / gamma),
        notes=tuple(notes),
    )


def _steel_parts(state: Any, n: int) -> list[tuple[Any, str, NDArray[np.bool_]]]:
    """The steel sections of `state` with their names in errors and the elements (n,) each covers; cables
    are left out; an input error where there is no steel."""
    segment_of = _attribute(state, "segment_of", "state", required=False)
    sections = _attribute(state, "sections", "state", required=False)
    if segment_of is None or sections is None or len(sections) <= 1:
        return [(_attribute(state, "section", "state"), "state.section", np.ones(n, dtype=bool))]
    indices = np.asarray(segment_of)
    _check_segment_indices(indices, n, len(sections))
    parts = [
        (section, f"state.sections[{k}]", indices == k)
        for k, section in enumerate(sections)
        if not getattr(section, "is_cable", False) and np.any(indices == k)
    ]
    if not parts:
        raise _input_error(
            "state.sections", _Described(f"{len(sections)} cable segments"), "at least one steel pipe segment"
        )
    return parts


def _check_segment_indices(segment_of: NDArray[Any], n: int, count: int) -> None:
    """An input error unless `segment_of` holds (n,) indices of `count` segments."""
    if segment_of.shape != (n,) or np.any(segment_of < 0) or np.any(segment_of >= count):
        raise _input_error(
            "state.segment_of",
            _Described(f"an array of shape {segment_of.shape}"),
            f"({n},) segment indices in 0..{count - 1}",
        )


def _arrestor_advice(
    state: Any, positions: FloatArray, water: _Water, utilisation: FloatArray, design_pressure: FloatArray
) -> str | None:
    """Where the propagation criterion fails, in words: the stretch of pipe (arc length from end A along the
    reference, as `state.reference_arc_length`, else along the configuration), the depth beyond which it
    fails, and the advice; None where it nowhere fails."""
    failing = utilisation > 1.0
    if not np.any(failing):
        return None
    arc = _attribute(state, "reference_arc_length", "state", required=False)
    if arc is None or np.shape(arc) != (positions.shape[0],):
        arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(positions, axis=0), axis=1))])
    middle = 0.5 * (arc[:-1] + arc[1:])
    first, last = np.flatnonzero(failing)[[0, -1]]
    shallowest = float(np.min(water.below_surface[failing]))
    return (
        f"buckle arrestors needed from {middle[first]:.1f} m to {middle[last]:.1f} m from end A (water deeper "
        f"than {shallowest:.1f} m): there p_e − p_min exceeds p_pr/(γ_m γ_SC) = "
        f"{float(np.nanmin(design_pressure[failing])) / 1e6:.3g} MPa, so a local buckle started there would run "
        "along the pipe; arrestors along that stretch stop it (DNV-ST-F101 [5.4.5])"
    )


def describe_parameters(parameters: Mapping[str, Any] | None = None) -> str:
    """The parameters of the checks in one line, those not in `parameters` at their `DEFAULTS` (where no state
    is at hand to name its grade and pressures, as `Utilisation.basis` does), e.g. "DNV-ST-F101, the section's
    grade, safety class medium, seamless, installation, p_i of the contents"."""
    options = _options(**dict(parameters or {}))
    grade = options.grade or f"the section's grade (else {DEFAULT_GRADE})"
    inside = (
        "p_i of the contents"
        if options.internal_pressure is None
        else f"p_i {options.internal_pressure / 1e6:.4g} MPa given"
    )
    extra = [
        f"corrosion allowance {options.corrosion_allowance:g} m" * (options.corrosion_allowance > 0),
        f"ovality {options.ovality:g}" * (options.ovality != DEFAULTS["ovality"]),
        f"de-rating {options.temperature_derating / 1e6:g} MPa" * (options.temperature_derating > 0),
        "" if options.strain_limit is None else f"strain limit {options.strain_limit:g}",
    ]
    return ", ".join(
        [
            "DNV-ST-F101",
            grade,
            f"safety class {options.safety_class}",
            options.fabrication,
            options.condition,
            inside,
            *(part for part in extra if part),
        ]
    )


def _options(
    *,
    grade: str | None = DEFAULTS["grade"],
    wall_thickness: float | None = DEFAULTS["wall_thickness"],
    safety_class: str = DEFAULTS["safety_class"],
    internal_pressure: float | None = DEFAULTS["internal_pressure"],
    fabrication: str = DEFAULTS["fabrication"],
    corrosion_allowance: float = DEFAULTS["corrosion_allowance"],
    ovality: float = DEFAULTS["ovality"],
    temperature_derating: float = DEFAULTS["temperature_derating"],
    condition: str = DEFAULTS["condition"],
    strain_limit: float | None = DEFAULTS["strain_limit"],
) -> _Options:
    """The arguments of `dnv_st_f101` checked (the same keywords and defaults)."""
    return _Options(
        None if grade is None else _choice("grade", grade, list(GRADES), "is not a known grade"),
        wall_thickness,
        _choice("safety_class", safety_class, list(GAMMA_SC), "is not a safety class"),
        _choice("fabrication", fabrication, list(ALPHA_FAB), "is not a fabrication"),
        _choice("condition", condition, list(CONDITIONS), "is not a condition"),
        None if internal_pressure is None else _number("internal_pressure", internal_pressure, minimum=0.0),
        _number("corrosion_allowance", corrosion_allowance, minimum=0.0),
        _number("ovality", ovality, minimum=0.005, maximum=1.0, allowed="a fraction from 0.005 to 1"),
        _number("temperature_derating", temperature_derating, minimum=0.0),
        None if strain_limit is None else _number("strain_limit", strain_limit, positive=True),
    )


def _records_utilisation(
    section: Any,
    forces: FloatArray,
    strain: FloatArray,
    positions: FloatArray,
    sea: tuple[float, float] | None,
    parameters: Any,
) -> tuple[FloatArray, FloatArray]:
    """The load- and displacement-controlled utilisations (records, n) of the elements of one `section` at
    every record: `forces` (records, n, 6), `strain` (records, n), `positions` (records, n + 1, 3),
    `sea` (water depth, density) or None, `parameters` the keywords of `dnv_st_f101`. The same numbers as
    `dnv_st_f101` of each record (the same element-wise formulas), evaluated a block of records at a time."""
    count, n = forces.shape[:2]
    options = _options(**dict(parameters))
    if sea is not None:
        depth = _number("state.water_depth", sea[0], positive=True)
        density = _number("state.water_density", sea[1], positive=True)
    load = np.empty((count, n))
    displacement = np.empty((count, n))
    # A block of records at a time: a 3-hour storm's records are millions of element values, and the
    # formulas' temporaries for all of them at once would be gigabytes of fresh memory (its page faults cost
    # more than the arithmetic); a block's stay in cache. Element-wise formulas: the same numbers.
    block = max(1, RECORDS_BLOCK_ELEMENTS // n)
    for start in range(0, count, block):
        rows = slice(start, min(start + block, count))
        size = (rows.stop - rows.start) * n
        if sea is None:
            water = _Water(np.zeros(size), 0.0)
        else:
            water = _Water(_below_surface(positions[rows], depth).reshape(size), density)
        flat = forces[rows].reshape(size, 6)
        checked = _check_section(
            section, "state.section", flat, flat[:, 0], np.abs(strain[rows].reshape(size)), water, options
        )
        load[rows] = checked.load_controlled.reshape(-1, n)
        displacement[rows] = checked.displacement_controlled.reshape(-1, n)
    return load, displacement


@dataclass(frozen=True)
class _Options:
    """The checked arguments of `dnv_st_f101`, as the per-section checks take them."""

    grade: str | None
    wall_thickness: float | None
    safety_class: str
    fabrication: str
    condition: str
    internal_pressure: float | None
    corrosion_allowance: float
    ovality: float
    temperature_derating: float
    strain_limit: float | None


def _check_segments(
    sections: list[Any],
    segment_of: NDArray[Any],
    forces: FloatArray,
    tension: FloatArray,
    strain: FloatArray,
    water: _Water,
    options: _Options,
) -> Utilisation:
    """The checks of a line of segments: each steel segment with its own section, joined element by element."""
    n = forces.shape[0]
    _check_segment_indices(segment_of, n, len(sections))
    parts: list[Utilisation | None] = []
    for k, section in enumerate(sections):
        elements = segment_of == k
        if getattr(section, "is_cable", False) or not np.any(elements):
            parts.append(None)
            continue
        parts.append(
            _check_section(
                section,
                f"state.sections[{k}]",
                forces[elements],
                tension[elements],
                strain[elements],
                water.part(elements),
                options,
            )
        )
    checked = [(k, part) for k, part in enumerate(parts) if part is not None]
    if not checked:
        raise _input_error(
            "state.sections", _Described(f"{len(sections)} cable segments"), "at least one steel pipe segment"
        )
    moment = np.hypot(forces[:, 4], forces[:, 5])
    arrays = {
        "load_controlled": np.zeros(n),
        "displacement_controlled": np.zeros(n),
        "moment": moment,
        "effective_axial_force": tension,
        "wall_tension": tension.copy(),
        "external_pressure": water.external_pressure(),
        "internal_pressure": np.zeros(n),
        "strain": strain,
        "allowable_strain": np.full(n, np.inf),
        "alpha_p": np.zeros(n),
    }
    for k, part in checked:
        elements = segment_of == k
        for name in (
            "load_controlled",
            "displacement_controlled",
            "wall_tension",
            "allowable_strain",
            "alpha_p",
            "internal_pressure",
        ):
            arrays[name][elements] = getattr(part, name)
    governing_segment = max(checked, key=lambda item: float(np.max(item[1].load_controlled)))
    governing = governing_segment[1]
    notes = [f"segment {k}: {note}" for k, part in checked for note in part.notes]
    cables = [k for k, part in enumerate(parts) if part is None and np.any(segment_of == k)]
    if cables:
        notes.append(f"segments {cables} are cables: no steel wall, not checked (utilisation 0)")
    frozen = {name: _frozen(values) for name, values in arrays.items()}
    return replace(
        governing,
        load_controlled=frozen["load_controlled"],
        displacement_controlled=frozen["displacement_controlled"],
        moment=frozen["moment"],
        effective_axial_force=frozen["effective_axial_force"],
        wall_tension=frozen["wall_tension"],
        external_pressure=frozen["external_pressure"],
        strain=frozen["strain"],
        allowable_strain=frozen["allowable_strain"],
        alpha_p=frozen["alpha_p"],
        internal_pressure=frozen["internal_pressure"],
        notes=tuple(notes),
        segment_of=_frozen_indices(segment_of),
        segments=tuple(parts),
    )


def _frozen_indices(values: NDArray[Any]) -> NDArray[np.int64]:
    """A read-only int64 copy of `values`."""
    result = np.array(values, dtype=np.int64)
    result.setflags(write=False)
    return result


@dataclass(frozen=True)
class _Steel:
    """A steel section's wall and strength as the checks take them (SI units)."""

    grade: str
    outer_diameter: float
    wall_thickness: float
    t2: float
    smys: float
    smts: float
    f_y: float
    f_u: float
    youngs_modulus: float
    poisson_ratio: float


def _steel(section: Any, prefix: str, options: _Options) -> _Steel:
    """The wall and strength of `section` (named `prefix` in errors) under `options`: the grade given or the
    section's (X65 without one), the wall thickness given or the section's, t₂ (less the corrosion allowance
    in operation), SMYS/SMTS and the characteristic (de-rated, × α_U) f_y, f_u."""
    grade_key = options.grade
    if grade_key is None:
        section_grade = _attribute(section, "grade", required=False) or DEFAULT_GRADE
        grade_key = _choice(f"{prefix}.grade", section_grade, list(GRADES), "is not a known grade")
    diameter = _number(f"{prefix}.outer_diameter", _attribute(section, "outer_diameter"), positive=True)
    if options.wall_thickness is None:
        section_t = _attribute(section, "wall_thickness", prefix, required=False)
        if section_t is None:
            raise _input_error(
                "wall_thickness",
                None,
                f"a wall thickness > 0 in m, as this argument or as {prefix}.wall_thickness",
                f"is given neither as argument nor by {prefix}",
            )
        t = _number(f"{prefix}.wall_thickness", section_t, positive=True)
    else:
        t = _number("wall_thickness", options.wall_thickness, positive=True)
    if t >= diameter / 2:
        raise _input_error("wall_thickness", t, f"less than half the outer diameter ({diameter / 2!r} m)")
    youngs = _optional_number(section, "youngs_modulus", DEFAULT_YOUNGS_MODULUS, prefix, positive=True)
    poisson = _optional_number(
        section, "poisson_ratio", DEFAULT_POISSON_RATIO, prefix, minimum=0.0, maximum=0.5
    )
    t_corr = options.corrosion_allowance
    t2 = t - t_corr if options.condition == "operation" else t
    if t2 <= 0:
        raise _input_error("corrosion_allowance", t_corr, f"less than the wall thickness ({t!r} m)")
    smys, smts = GRADES[grade_key]
    f_temp = options.temperature_derating
    if f_temp >= smys:
        raise _input_error("temperature_derating", f_temp, f"less than the SMYS of {grade_key} ({smys!r} Pa)")
    return _Steel(
        grade=grade_key,
        outer_diameter=diameter,
        wall_thickness=t,
        t2=t2,
        smys=smys,
        smts=smts,
        f_y=_characteristic_strength(smys, f_temp, ALPHA_U),
        f_u=_characteristic_strength(smts, f_temp, ALPHA_U),
        youngs_modulus=youngs,
        poisson_ratio=poisson,
    )


def _check_section(
    section: Any,
    prefix: str,
    forces: FloatArray,
    tension: FloatArray,
    strain: FloatArray,
    water: _Water,
    options: _Options,
) -> Utilisation:
    """The checks of elements of one steel `section` (named `prefix` in errors) under their forces, at the
    depths below the surface of `water`."""
    safety, fab, cond, f0, limit = (
        options.safety_class,
        options.fabrication,
        options.condition,
        options.ovality,
        options.strain_limit,
    )
    n = forces.shape[0]
    steel = _steel(section, prefix, options)
    grade_key, diameter, t, t2 = steel.grade, steel.outer_diameter, steel.wall_thickness, steel.t2
    smys, smts, f_y, f_u = steel.smys, steel.smts, steel.f_y, steel.f_u
    youngs, poisson = steel.youngs_modulus, steel.poisson_ratio
    p_e = water.external_pressure()
    p_i = _internal_pressure(section, prefix, water, options.internal_pressure)

    gamma_sc = GAMMA_SC[safety]
    gamma_eps = GAMMA_EPSILON[safety]
    alpha_fab = ALPHA_FAB[fab]
    d_over_t = diameter / t2
    beta = _beta(d_over_t)
    alpha_c = (1.0 - beta) + beta * f_u / f_y
    m_p = _plastic_moment(f_y, diameter, t2)
    s_p = _plastic_axial_force(f_y, diameter, t2)
    p_b = _burst_pressure(f_y, f_u, diameter, t2)
    p_el = 2.0 * youngs * (t2 / diameter) ** 3 / (1.0 - poisson**2)
    p_p = f_y * alpha_fab * 2.0 * t2 / diameter
    p_c = _collapse_pressure(p_el, p_p, f0, diameter, t2)
    alpha_gw = _girth_weld_factor(d_over_t)

    # Load effects per element.
    moment = np.hypot(forces[:, 4], forces[:, 5])
    area_e = math.pi * diameter**2 / 4.0
    area_i = math.pi * (diameter - 2.0 * t) ** 2 / 4.0
    wall_tension = tension + p_i * area_i - p_e * area_e

    # Load-controlled condition.
    gamma = GAMMA_M * gamma_sc
    bending_axial = (gamma * moment / (alpha_c * m_p) + (gamma * tension / (alpha_c * s_p)) ** 2) ** 2
    internal = p_i > p_e
    overpressure_ratio = (p_i - p_e) / p_b
    alpha_p = np.where(
        overpressure_ratio < 2.0 / 3.0, 1.0 - beta, 1.0 - 3.0 * beta * (1.0 - overpressure_ratio)
    )
    pressure_term = np.where(
        internal,
        (alpha_p * (p_i - p_e) / (alpha_c * p_b)) ** 2,
        (gamma * (p_e - p_i) / p_c) ** 2,
    )
    load_controlled = bending_axial + pressure_term

    # Displacement-controlled condition.
    if limit is not None:
        allowable = np.full(n, limit)
    else:
        eps_c0 = _strain_resistance(t2, diameter, 0.0, p_b, ALPHA_H, alpha_gw)
        eps_internal = _strain_resistance(t2, diameter, p_i - p_e, p_b, ALPHA_H, alpha_gw) / gamma_eps
        reserve = np.clip(1.0 - gamma * (p_e - p_i) / p_c, 0.0, None)
        eps_external = eps_c0 / gamma_eps * reserve**1.25
        allowable = np.where(p_i >= p_e, eps_internal, eps_external)
    displacement_controlled = np.full(n, np.inf)
    np.divide(strain, allowable, out=displacement_controlled, where=allowable > 0)

    notes = _validity_notes(d_over_t, internal, np.abs(tension) / s_p)
    return Utilisation(
        load_controlled=_frozen(load_controlled),
        displacement_controlled=_frozen(displacement_controlled),
        moment=_frozen(moment),
        effective_axial_force=_frozen(tension),
        wall_tension=_frozen(wall_tension),
        external_pressure=_frozen(p_e),
        strain=_frozen(strain),
        allowable_strain=_frozen(allowable),
        alpha_p=_frozen(alpha_p),
        plastic_moment=m_p,
        plastic_axial_force=s_p,
        collapse_pressure=p_c,
        burst_pressure=p_b,
        smys=smys,
        smts=smts,
        f_y=f_y,
        f_u=f_u,
        outer_diameter=diameter,
        wall_thickness=t,
        t2=t2,
        internal_pressure=_frozen(p_i),
        gamma_m=GAMMA_M,
        gamma_sc=gamma_sc,
        gamma_epsilon=gamma_eps,
        alpha_c=alpha_c,
        alpha_u=ALPHA_U,
        alpha_fab=alpha_fab,
        alpha_h=ALPHA_H,
        alpha_gw=alpha_gw,
        beta=beta,
        grade=grade_key,
        safety_class=safety,
        fabrication=fab,
        condition=cond,
        basis=_basis("DNV-ST-F101", grade_key, options, section, water),
        notes=notes,
    )


# --- capacities ------------------------------------------------------------------------------------------


def _characteristic_strength(specified: float, derating: float, alpha_u: float) -> float:
    """Characteristic strength (SMYS or SMTS − de-rating) · α_U (Pa); Sec.5 [5.3.3.2] eqs. (5.4), (5.5)."""
    return (specified - derating) * alpha_u


def _plastic_moment(f_y: float, diameter: float, t: float) -> float:
    """Plastic moment capacity M_p = f_y (D − t)² t (N·m)."""
    return f_y * (diameter - t) ** 2 * t


def _plastic_axial_force(f_y: float, diameter: float, t: float) -> float:
    """Characteristic plastic axial force S_p = f_y π (D − t) t (N)."""
    return f_y * math.pi * (diameter - t) * t


def _burst_pressure(f_y: float, f_u: float, diameter: float, t: float) -> float:
    """Pressure containment resistance p_b = 2t/(D − t) · min(f_y, f_u/1.15) · 2/√3 (Pa)."""
    f_cb = min(f_y, f_u / 1.15)
    return 2.0 * t / (diameter - t) * f_cb * 2.0 / math.sqrt(3.0)


def _collapse_pressure(p_el: float, p_p: float, ovality: float, diameter: float, t: float) -> float:
    """Characteristic collapse pressure p_c (Pa): the smallest positive root of
    (p − p_el)(p² − p_p²) − p·p_el·p_p·O₀·D/t = 0.

    The cubic p³ + b p² + c p + d with b = −p_el, c = −(p_p² + p_el p_p O₀ D/t), d = p_el p_p² is positive at
    p = 0 and non-positive at p = min(p_el, p_p), and its roots multiply to −d < 0: it has one negative and
    two positive real roots, and p_c is the one in (0, min(p_el, p_p)]. The roots come from the
    trigonometric solution of the depressed cubic y³ + P y + Q = 0, p = y − b/3.
    """
    b = -p_el
    c = -(p_p**2 + p_el * p_p * ovality * diameter / t)
    d = p_el * p_p**2
    big_p = c - b * b / 3.0
    big_q = 2.0 * b**3 / 27.0 - b * c / 3.0 + d
    radius = 2.0 * math.sqrt(-big_p / 3.0)
    argument = 3.0 * big_q / (big_p * radius)
    theta = math.acos(max(-1.0, min(1.0, argument)))
    roots = [radius * math.cos((theta - 2.0 * math.pi * k) / 3.0) - b / 3.0 for k in range(3)]
    positive = [root for root in roots if root > 0.0]
    return min(positive)


def _beta(d_over_t: float) -> float:
    """Factor β of the flow stress parameter: 0.5 below D/t = 15, (60 − D/t)/90 up to 60, 0 above."""
    if d_over_t < 15.0:
        return 0.5
    if d_over_t <= 60.0:
        return (60.0 - d_over_t) / 90.0
    return 0.0


def _girth_weld_factor(d_over_t: float) -> float:
    """Girth weld factor α_gw: 1.0 for D/t ≤ 20, linear to 0.6 at D/t = 60, 0.6 beyond."""
    return float(np.interp(d_over_t, [20.0, 60.0], [1.0, 0.6]))


def _strain_resistance(
    t: float,
    diameter: float,
    pressure_difference: float | FloatArray,
    p_b: float,
    alpha_h: float,
    alpha_gw: float,
) -> Any:
    """Characteristic strain resistance ε_c(t, p_min − p_e)
    = 0.78 (t/D − 0.01)(1 + 5.75 (p_min − p_e)/p_b) α_h^−1.5 α_gw (dimensionless)."""
    return (
        0.78
        * (t / diameter - 0.01)
        * (1.0 + 5.75 * np.asarray(pressure_difference) / p_b)
        * alpha_h**-1.5
        * alpha_gw
    )


@dataclass(frozen=True)
class _Water:
    """The sea around elements: each element midpoint's depth below the surface (m, 0 above it and without a
    sea) and the water's density (kg/m³, 0 without a sea)."""

    below_surface: FloatArray
    density: float

    def external_pressure(self) -> FloatArray:
        """Hydrostatic pressure p_e = ρ_w g h at the element midpoints (Pa)."""
        pressure: FloatArray = self.density * GRAVITY * self.below_surface
        return pressure

    def part(self, elements: NDArray[Any]) -> _Water:
        """The same sea around the elements selected by `elements`."""
        return _Water(self.below_surface[elements], self.density)


def _water(state: Any, positions: FloatArray) -> _Water:
    """The sea around the elements of `state`, whose node positions are `positions` (frame e, e3 down)."""
    n = positions.shape[0] - 1
    water_depth = _attribute(state, "water_depth", "state", required=False)
    if water_depth is None:
        return _Water(np.zeros(n), 0.0)
    depth = _number("state.water_depth", water_depth, positive=True)
    density = _number("state.water_density", _attribute(state, "water_density"), positive=True)
    return _Water(_below_surface(positions, depth), density)


def _below_surface(positions: FloatArray, depth: float) -> FloatArray:
    """Each element midpoint's depth below the surface, max(depth + z_mid, 0) (m), of node positions
    (..., n + 1, 3) (frame e, e3 down): (..., n)."""
    z_mid = 0.5 * (positions[..., :-1, 2] + positions[..., 1:, 2])
    below: FloatArray = np.clip(depth + z_mid, 0.0, None)
    return below


def contents_pressure(contents_density: float, below_surface: FloatArray) -> FloatArray:
    """The internal pressure of a pipe's contents open to the sea surface, p_i = ρ_c g h (Pa), at depths h below
    the surface (m): a flooded pipe's water stands at sea level inside it, an empty pipe (ρ_c = 0) has none."""
    pressure: FloatArray = contents_density * GRAVITY * np.asarray(below_surface, dtype=np.float64)
    return pressure


def _internal_pressure(section: Any, prefix: str, water: _Water, given: float | None) -> FloatArray:
    """p_i at each element (Pa): `given` everywhere, or that of the section's contents (`contents_pressure`)."""
    if given is not None:
        return np.full(water.below_surface.shape, given)
    density = _optional_number(section, "contents_density", 0.0, prefix, minimum=0.0)
    return contents_pressure(density, water.below_surface)


def _basis(code: str, grade: str, options: _Options, section: Any, water: _Water) -> str:
    """What a check of `code` assumes, in one line: the grade, the safety class with γ_SC, the fabrication with
    α_fab, the condition and the pressures (`Utilisation.basis`, `Propagation.basis`)."""
    return (
        f"{code}, {grade}, safety class {options.safety_class} (γ_SC {GAMMA_SC[options.safety_class]:.2f}), "
        f"{options.fabrication} (α_fab {ALPHA_FAB[options.fabrication]:.2f}), {options.condition}, "
        f"{_pressure_basis(section, water, options.internal_pressure)}"
    )


def _pressure_basis(section: Any, water: _Water, given: float | None) -> str:
    """How p_i and p_e were taken, in words."""
    if given is not None:
        inside = f"p_i {given / 1e6:.4g} MPa given"
    else:
        density = _attribute(section, "contents_density", required=False) or 0.0
        inside = (
            f"p_i of the contents ({density:g} kg/m³, open to the surface)"
            if density > 0
            else "p_i 0 (empty)"
        )
    outside = f"p_e hydrostatic ({water.density:g} kg/m³)" if water.density > 0 else "p_e 0 (no sea)"
    return f"{inside}, {outside}"


def _validity_notes(d_over_t: float, internal: NDArray[np.bool_], axial_ratio: FloatArray) -> tuple[str, ...]:
    """Notes on where the state lies outside the stated validity of the criteria."""
    notes = []
    if d_over_t > 45.0:
        notes.append(f"D/t2 = {d_over_t:.3g} exceeds 45, the limit of the combined loading criteria")
    if d_over_t < 15.0:
        notes.append(f"D/t2 = {d_over_t:.3g} is below 15, outside the calibration range of the criteria")
    if np.any(internal & (axial_ratio >= 0.4)):
        notes.append("|S_Sd|/S_p >= 0.4 under internal overpressure, outside the stated validity")
    return tuple(notes)


# --- validation ------------------------------------------------------------------------------------------


class _Described:
    """A description shown as is (unquoted) in place of a value in an input error."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text


def _message(argument: str, value: object, allowed: str, problem: str = "is not allowed") -> str:
    """The text of an input error: `argument: value problem; allowed: allowed`."""
    shown = f'"{value}"' if isinstance(value, str) else repr(value)
    return f"{argument}: {shown} {problem}; allowed: {allowed}"


def _input_error(argument: str, value: object, allowed: str, problem: str = "is not allowed") -> Exception:
    """A `pipelay.InputError` naming the argument, its value and what is allowed."""
    from pipelay._core import InputError

    return InputError(_message(argument, value, allowed, problem))


def _choice(argument: str, value: object, options: list[str], problem: str) -> str:
    """`value` if it is one of `options`, else an input error listing them."""
    if not isinstance(value, str) or value not in options:
        raise _input_error(argument, value, ", ".join(options), problem)
    return value


def _number(
    argument: str,
    value: object,
    *,
    minimum: float | None = None,
    maximum: float | None = None,
    positive: bool = False,
    allowed: str | None = None,
) -> float:
    """`value` as a float if it is a finite real number within the bounds, else an input error."""
    if positive:
        bounds = "a finite number > 0"
    elif minimum is not None and maximum is not None:
        bounds = f"a finite number from {minimum:g} to {maximum:g}"
    elif minimum is not None:
        bounds = f"a finite number >= {minimum:g}"
    else:
        bounds = "a finite number"
    allowed = allowed or bounds
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _input_error(argument, value, allowed, "is not a number")
    number = float(value)
    if not math.isfinite(number):
        raise _input_error(argument, value, allowed, "is not finite")
    if positive and number <= 0.0:
        raise _input_error(argument, value, allowed, "is not positive")
    if minimum is not None and number < minimum:
        raise _input_error(argument, value, allowed, "is too small")
    if maximum is not None and number > maximum:
        raise _input_error(argument, value, allowed, "is too large")
    return number


def _attribute(owner: Any, name: str, prefix: str = "state.section", *, required: bool = True) -> Any:
    """`owner.name`; an input error if it is missing and `required`, else None."""
    if hasattr(owner, name):
        return getattr(owner, name)
    if required:
        raise _input_error(f"{prefix}.{name}", _Described("(absent)"), f"a {name!r} attribute", "is missing")
    return None


def _optional_number(
    section: Any,
    name: str,
    default: float,
    prefix: str,
    *,
    positive: bool = False,
    minimum: float | None = None,
    maximum: float | None = None,
) -> float:
    """The section's `name` as a float, or `default` where it is None or absent."""
    value = _attribute(section, name, required=False)
    if value is None:
        return default
    return _number(f"{prefix}.{name}", value, positive=positive, minimum=minimum, maximum=maximum)


def _state_array(state: Any, name: str, shape: tuple[int | None, ...]) -> FloatArray:
    """`state.name` as a finite float array of `shape` (None: any length), else an input error."""
    raw = _attribute(state, name, "state")
    described = "(" + ", ".join("n" if size is None else str(size) for size in shape) + ")"
    if len(shape) == 1:
        described = described[:-1] + ",)"
    try:
        array = np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError):
        raise _input_error(
            f"state.{name}", _Described(f"a {type(raw).__name__}"), f"a float array of shape {described}"
        ) from None
    if array.ndim != len(shape) or any(
        size is not None and size != actual for size, actual in zip(shape, array.shape, strict=True)
    ):
        raise _input_error(
            f"state.{name}", _Described(f"an array of shape {array.shape}"), f"shape {described}", "is wrong"
        )
    if not np.all(np.isfinite(array)):
        raise _input_error(f"state.{name}", _Described("NaN or infinite entries"), "finite numbers", "are")
    return array


def _frozen(values: Any) -> FloatArray:
    """A read-only float copy of `values`."""
    array = np.array(values, dtype=np.float64)
    array.flags.writeable = False
    return array
