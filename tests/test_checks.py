"""DNV-ST-F101 local-buckling checks (`pipelay.checks`) against values derived independently here.

The state is a duck-typed fake, so these tests need nothing of the compiled engine except `InputError`.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import math
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest


def _load_checks() -> ModuleType:
    """`pipelay.checks`, or the module loaded from its file when the package (engine) does not import."""
    try:
        import pipelay.checks as module
    except ImportError:
        path = Path(__file__).resolve().parents[1] / "python" / "pipelay" / "analysis" / "checks.py"
        spec = importlib.util.spec_from_file_location("pipelay_checks_standalone", path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module
        spec.loader.exec_module(module)
    return module


checks = _load_checks()

G = 9.81
RHO = 1025.0
D = 0.3239  # 12.75" line pipe
T = 0.0159
GAMMA_M = 1.15
GAMMA_SC_MEDIUM = 1.14


@pytest.fixture(autouse=True)
def _input_error_fallback(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where the engine cannot be imported, raise a plain ValueError with the module's message instead."""
    try:
        import pipelay._core  # noqa: F401
    except ImportError:
        monkeypatch.setattr(checks, "_input_error", lambda *args: ValueError(checks._message(*args)))


class FakeSection:
    def __init__(
        self,
        outer_diameter: float = D,
        wall_thickness: float | None = T,
        youngs_modulus: float | None = None,
        poisson_ratio: float | None = None,
    ) -> None:
        self.outer_diameter = outer_diameter
        self.wall_thickness = wall_thickness
        self.youngs_modulus = youngs_modulus
        self.poisson_ratio = poisson_ratio


class FakeState:
    """n elements along e1 at the midpoint depths `z` (frame e, e3 down), with the given loads."""

    def __init__(
        self,
        moment2: Any = 0.0,
        moment3: Any = 0.0,
        tension: Any = 0.0,
        z: Any = 0.0,
        strain: Any = 0.0,
        water_depth: float | None = None,
        section: FakeSection | None = None,
    ) -> None:
        arrays = np.broadcast_arrays(
            *(np.atleast_1d(np.asarray(v, dtype=float)) for v in (moment2, moment3, tension, z, strain))
        )
        m2, m3, s, z_mid, eps = (np.array(a) for a in arrays)
        n = m2.size
        self.section_forces = np.zeros((n, 6))
        self.section_forces[:, 0] = s
        self.section_forces[:, 3] = 123.0  # torsion: not part of the criteria
        self.section_forces[:, 4] = m2
        self.section_forces[:, 5] = m3
        self.tension = s
        # nodes at x = 0, 1, … with depths whose element midpoints are z_mid
        self.positions = np.zeros((n + 1, 3))
        self.positions[:, 0] = np.arange(n + 1)
        self.positions[:, 2] = _nodes_for_midpoints(z_mid)
        self.strain = eps
        self.water_depth = water_depth
        self.water_density = RHO
        self.section = section if section is not None else FakeSection()


def _nodes_for_midpoints(z_mid: np.ndarray) -> np.ndarray:
    """Node depths whose element midpoints are `z_mid` (first node chosen equal to the first midpoint)."""
    nodes = np.empty(z_mid.size + 1)
    nodes[0] = z_mid[0]
    for i, zm in enumerate(z_mid):
        nodes[i + 1] = 2.0 * zm - nodes[i]
    return nodes


def strengths(smys: float = 450e6, smts: float = 535e6, derating: float = 0.0) -> tuple[float, float]:
    return (smys - derating) * 0.96, (smts - derating) * 0.96


def alpha_c_expected(d_over_t: float, f_y: float, f_u: float) -> float:
    if d_over_t < 15:
        beta = 0.5
    elif d_over_t <= 60:
        beta = (60 - d_over_t) / 90
    else:
        beta = 0.0
    return (1 - beta) + beta * f_u / f_y


def collapse_by_roots(f_y: float, alpha_fab: float, ovality: float, d: float = D, t: float = T) -> float:
    p_el = 2 * 207e9 * (t / d) ** 3 / (1 - 0.3**2)
    p_p = f_y * alpha_fab * 2 * t / d
    # (p − p_el)(p² − p_p²) − p p_el p_p O D/t = p³ − p_el p² − (p_p² + p_el p_p O D/t) p + p_el p_p²
    roots = np.roots([1.0, -p_el, -(p_p**2 + p_el * p_p * ovality * d / t), p_el * p_p**2])
    real = roots[np.abs(roots.imag) < 1e-6 * np.abs(roots).max()].real
    return float(real[real > 0].min())


def test_grades_are_the_tabulated_smys_and_smts() -> None:
    assert checks.GRADES == {
        "X52": (360e6, 460e6),
        "X56": (390e6, 490e6),
        "X60": (415e6, 520e6),
        "X65": (450e6, 535e6),
        "X70": (485e6, 570e6),
        "X80": (555e6, 625e6),
    }


def test_plastic_capacities_and_strengths_by_hand() -> None:
    u = checks.dnv_st_f101(FakeState(), grade="X60", temperature_derating=30e6)
    f_y, f_u = strengths(415e6, 520e6, 30e6)
    assert (u.smys, u.smts) == (415e6, 520e6)
    assert u.f_y == pytest.approx(f_y, rel=1e-14)
    assert u.f_u == pytest.approx(f_u, rel=1e-14)
    assert u.plastic_moment == pytest.approx(f_y * (D - T) ** 2 * T, rel=1e-13)
    assert u.plastic_axial_force == pytest.approx(f_y * math.pi * (D - T) * T, rel=1e-13)
    f_cb = min(f_y, f_u / 1.15)
    assert u.burst_pressure == pytest.approx(2 * T / (D - T) * f_cb * 2 / math.sqrt(3), rel=1e-13)
    assert (u.gamma_m, u.gamma_sc, u.alpha_u, u.alpha_fab) == (1.15, 1.14, 0.96, 1.0)


def test_corrosion_allowance_is_deducted_in_operation_only() -> None:
    f_y, _ = strengths()
    installation = checks.dnv_st_f101(FakeState(), corrosion_allowance=3e-3)
    operation = checks.dnv_st_f101(FakeState(), corrosion_allowance=3e-3, condition="operation")
    assert installation.t2 == T
    assert operation.t2 == pytest.approx(T - 3e-3)
    t2 = T - 3e-3
    assert operation.plastic_moment == pytest.approx(f_y * (D - t2) ** 2 * t2, rel=1e-13)
    assert operation.plastic_moment < installation.plastic_moment


@pytest.mark.parametrize("thickness", [0.030, T, 0.007, 0.005])
def test_flow_stress_parameter_alpha_c(thickness: float) -> None:
    # D/t = 10.8 (β = 0.5), 20.4, 46.3 and 64.8 (β = 0)
    u = checks.dnv_st_f101(FakeState(), wall_thickness=thickness, grade="X70")
    f_y, f_u = strengths(485e6, 570e6)
    assert u.alpha_c == pytest.approx(alpha_c_expected(D / thickness, f_y, f_u), rel=1e-14)
    if D / thickness > 45:
        assert any("exceeds 45" in note for note in u.notes)
    elif D / thickness < 15:
        assert any("below 15" in note for note in u.notes)
    else:
        assert u.notes == ()


@pytest.mark.parametrize(
    ("fabrication", "alpha_fab", "ovality"),
    [("seamless", 1.0, 0.005), ("uoe", 0.85, 0.005), ("uo_tre", 0.93, 0.02), ("welded", 0.93, 0.03)],
)
def test_collapse_pressure_is_the_root_of_the_cubic(
    fabrication: str, alpha_fab: float, ovality: float
) -> None:
    u = checks.dnv_st_f101(FakeState(), fabrication=fabrication, ovality=ovality)
    f_y, _ = strengths()
    expected = collapse_by_roots(f_y, alpha_fab, ovality)
    assert u.alpha_fab == alpha_fab
    assert u.collapse_pressure == pytest.approx(expected, rel=1e-10)
    # below both the elastic and the plastic collapse pressure
    assert u.collapse_pressure < min(2 * 207e9 * (T / D) ** 3 / 0.91, f_y * alpha_fab * 2 * T / D)


def test_collapse_pressure_of_a_round_pipe_is_the_lesser_of_elastic_and_plastic() -> None:
    # O₀ = 0: the cubic factorises, p_c = min(p_el, p_p); a thin wall makes p_el govern
    p_el = 2 * 207e9 * (0.005 / D) ** 3 / (1 - 0.3**2)
    p_p = 432e6 * 2 * 0.005 / D
    assert checks._collapse_pressure(p_el, p_p, 0.0, D, 0.005) == pytest.approx(min(p_el, p_p), rel=1e-9)
    p_el = 2 * 207e9 * (T / D) ** 3 / (1 - 0.3**2)
    p_p = 432e6 * 2 * T / D
    assert checks._collapse_pressure(p_el, p_p, 0.0, D, T) == pytest.approx(min(p_el, p_p), rel=1e-9)


def test_youngs_modulus_and_poisson_ratio_come_from_the_section() -> None:
    section = FakeSection(youngs_modulus=200e9, poisson_ratio=0.28)
    u = checks.dnv_st_f101(FakeState(section=section), ovality=0.01)
    f_y, _ = strengths()
    p_el = 2 * 200e9 * (T / D) ** 3 / (1 - 0.28**2)
    p_p = f_y * 2 * T / D
    roots = np.roots([1.0, -p_el, -(p_p**2 + p_el * p_p * 0.01 * D / T), p_el * p_p**2])
    expected = min(r.real for r in roots if abs(r.imag) < 1e-3 and r.real > 0)
    assert u.collapse_pressure == pytest.approx(expected, rel=1e-10)


def test_pure_bending() -> None:
    # |M| = hypot(m2, m3): 3 and 4 make 5
    state = FakeState(moment2=[0.0, 3e4, 6e4], moment3=[1e5, 4e4, 8e4])
    u = checks.dnv_st_f101(state)
    f_y, f_u = strengths()
    m_p = f_y * (D - T) ** 2 * T
    alpha_c = alpha_c_expected(D / T, f_y, f_u)
    moment = np.array([1e5, 5e4, 1e5])
    np.testing.assert_allclose(u.moment, moment, rtol=1e-15)
    expected = (GAMMA_M * GAMMA_SC_MEDIUM * moment / (alpha_c * m_p)) ** 2
    np.testing.assert_allclose(u.load_controlled, expected, rtol=1e-13)


def test_pure_axial_force_tension_and_compression_alike() -> None:
    state = FakeState(tension=[1e6, -1e6, 2.5e6])
    u = checks.dnv_st_f101(state, safety_class="high")
    f_y, f_u = strengths()
    s_p = f_y * math.pi * (D - T) * T
    alpha_c = alpha_c_expected(D / T, f_y, f_u)
    expected = (GAMMA_M * 1.26 * np.array([1e6, 1e6, 2.5e6]) / (alpha_c * s_p)) ** 4
    np.testing.assert_allclose(u.load_controlled, expected, rtol=1e-13)
    assert u.load_controlled[0] == u.load_controlled[1]


def test_bending_and_axial_force_combine_inside_the_square() -> None:
    state = FakeState(moment3=2e5, tension=-8e5)
    u = checks.dnv_st_f101(state, safety_class="low")
    f_y, f_u = strengths()
    alpha_c = alpha_c_expected(D / T, f_y, f_u)
    g = GAMMA_M * 1.04
    m_term = g * 2e5 / (alpha_c * f_y * (D - T) ** 2 * T)
    s_term = (g * 8e5 / (alpha_c * f_y * math.pi * (D - T) * T)) ** 2
    assert u.load_controlled[0] == pytest.approx((m_term + s_term) ** 2, rel=1e-13)


def test_external_pressure_term_and_depths() -> None:
    # water depth 300 m: midpoints at the seabed end (z = 0), mid-water, at and above the surface
    z = [0.0, -120.0, -300.0, -310.0, 25.0]
    u = checks.dnv_st_f101(FakeState(z=z, water_depth=300.0))
    depth_below_surface = np.array([300.0, 180.0, 0.0, 0.0, 325.0])
    p_e = RHO * G * depth_below_surface
    np.testing.assert_allclose(u.external_pressure, p_e, rtol=1e-13)
    f_y, _ = strengths()
    p_c = collapse_by_roots(f_y, 1.0, 0.005)
    expected = (GAMMA_M * GAMMA_SC_MEDIUM * p_e / p_c) ** 2
    np.testing.assert_allclose(u.load_controlled, expected, rtol=1e-9)


def test_no_sea_means_no_external_pressure() -> None:
    u = checks.dnv_st_f101(FakeState(z=[0.0, -50.0], moment3=1e5))
    np.testing.assert_array_equal(u.external_pressure, 0.0)


def test_internal_pressure_reduces_the_external_overpressure_term() -> None:
    state = FakeState(z=[0.0], water_depth=500.0)
    p_e = RHO * G * 500.0
    u = checks.dnv_st_f101(state, internal_pressure=0.4 * p_e)
    f_y, _ = strengths()
    p_c = collapse_by_roots(f_y, 1.0, 0.005)
    assert u.load_controlled[0] == pytest.approx((GAMMA_M * GAMMA_SC_MEDIUM * 0.6 * p_e / p_c) ** 2, rel=1e-9)


@pytest.mark.parametrize("fraction", [0.3, 0.8])  # (p_i − p_e)/p_b on either side of 2/3
def test_internal_overpressure_form(fraction: float) -> None:
    f_y, f_u = strengths()
    p_b = 2 * T / (D - T) * min(f_y, f_u / 1.15) * 2 / math.sqrt(3)
    state = FakeState(z=[0.0], water_depth=100.0, moment3=1.5e5, tension=4e5)
    p_e = RHO * G * 100.0
    p_i = p_e + fraction * p_b
    u = checks.dnv_st_f101(state, internal_pressure=p_i)
    beta = (60 - D / T) / 90
    alpha_c = (1 - beta) + beta * f_u / f_y
    alpha_p = 1 - beta if fraction < 2 / 3 else 1 - 3 * beta * (1 - fraction)
    g = GAMMA_M * GAMMA_SC_MEDIUM
    bending = (
        g * 1.5e5 / (alpha_c * f_y * (D - T) ** 2 * T)
        + (g * 4e5 / (alpha_c * f_y * math.pi * (D - T) * T)) ** 2
    ) ** 2
    expected = bending + (alpha_p * fraction / alpha_c) ** 2
    assert u.alpha_p[0] == pytest.approx(alpha_p, rel=1e-13)
    assert u.load_controlled[0] == pytest.approx(expected, rel=1e-12)


def test_load_controlled_grows_with_the_moment() -> None:
    moments = np.linspace(0.0, 6e5, 25)
    state = FakeState(moment2=moments, tension=3e5, z=-200.0, water_depth=400.0)
    u = checks.dnv_st_f101(state)
    assert np.all(np.diff(u.load_controlled) > 0)
    assert u.worst_element("load_controlled") == 24
    assert u.max()["load_controlled"] == u.load_controlled[-1]


def test_effective_force_sign_and_wall_tension() -> None:
    # zero effective tension deep down: the wall is in compression −p_e A_e (plus the end cap of p_i)
    p_i = 2e6
    state = FakeState(z=[0.0, -1000.0], tension=[0.0, 5e5], water_depth=1000.0)
    u = checks.dnv_st_f101(state, internal_pressure=p_i)
    np.testing.assert_array_equal(u.effective_axial_force, [0.0, 5e5])
    area_e = math.pi * D**2 / 4
    area_i = math.pi * (D - 2 * T) ** 2 / 4
    p_e = RHO * G * 1000.0
    assert u.wall_tension[0] == pytest.approx(0.0 + p_i * area_i - p_e * area_e, rel=1e-13)
    assert u.wall_tension[0] < 0.0
    assert u.wall_tension[1] == pytest.approx(5e5 + p_i * area_i, rel=1e-13)  # at the surface: no p_e


def test_displacement_controlled_against_a_strain_limit() -> None:
    state = FakeState(strain=[0.001, -0.0025, 0.003], z=-100.0, water_depth=200.0)
    u = checks.dnv_st_f101(state, strain_limit=0.0025)
    np.testing.assert_allclose(u.displacement_controlled, [0.4, 1.0, 1.2], rtol=1e-14)
    np.testing.assert_array_equal(u.allowable_strain, 0.0025)
    assert u.worst_element("displacement_controlled") == 2
    assert u.max()["displacement_controlled"] == pytest.approx(1.2)


def test_displacement_controlled_strain_resistance_without_external_overpressure() -> None:
    p_i = 5e6
    u = checks.dnv_st_f101(FakeState(strain=[0.002, -0.004]), internal_pressure=p_i, safety_class="low")
    f_y, f_u = strengths()
    p_b = 2 * T / (D - T) * min(f_y, f_u / 1.15) * 2 / math.sqrt(3)
    alpha_gw = 1.0 - 0.4 * (D / T - 20) / 40  # girth weld factor between D/t = 20 and 60
    eps_c = 0.78 * (T / D - 0.01) * (1 + 5.75 * p_i / p_b) * 0.93**-1.5 * alpha_gw
    assert u.alpha_gw == pytest.approx(alpha_gw, rel=1e-14)
    np.testing.assert_allclose(u.allowable_strain, eps_c / 2.0, rtol=1e-13)
    np.testing.assert_allclose(
        u.displacement_controlled, np.array([0.002, 0.004]) / (eps_c / 2.0), rtol=1e-13
    )


def test_displacement_controlled_under_external_overpressure_reaches_unity_with_the_criterion() -> None:
    # the interaction (ε/(ε_c/γ_ε))^0.8 + (p_e − p_min)/(p_c/(γ_m γ_SC)) evaluated here independently
    strain = np.array([0.0005, 0.002, 0.004, 0.006, 0.01])
    state = FakeState(strain=strain, z=0.0, water_depth=1500.0)  # at the seabed end
    u = checks.dnv_st_f101(state, safety_class="high")
    f_y, _ = strengths()
    p_e = RHO * G * 1500.0
    p_c = collapse_by_roots(f_y, 1.0, 0.005)
    alpha_gw = 1.0 - 0.4 * (D / T - 20) / 40
    eps_c0 = 0.78 * (T / D - 0.01) * 0.93**-1.5 * alpha_gw
    lhs = (strain / (eps_c0 / 3.3)) ** 0.8 + p_e / (p_c / (GAMMA_M * 1.26))
    ratio = u.displacement_controlled
    # ε/ε_allow = r  ⇔  LHS = r^0.8 (1 − q) + q with q the pressure term
    q = p_e * GAMMA_M * 1.26 / p_c
    np.testing.assert_allclose(ratio**0.8 * (1 - q) + q, lhs, rtol=1e-12)
    assert np.all((ratio > 1) == (lhs > 1))
    assert (ratio > 1).any() and (ratio < 1).any()


def test_pressure_beyond_collapse_exhausts_the_strain_capacity() -> None:
    u = checks.dnv_st_f101(FakeState(strain=0.0001, z=0.0, water_depth=4000.0), wall_thickness=0.006)
    assert u.displacement_controlled[0] == math.inf
    assert u.load_controlled[0] > 1


def test_worst_element_over_both_checks() -> None:
    state = FakeState(moment3=[1e5, 2e5, 0.0], strain=[0.0, 0.0, 0.05])
    u = checks.dnv_st_f101(state)
    assert u.worst_element("load_controlled") == 1
    assert u.worst_element() == 2


def test_utilisation_is_immutable() -> None:
    u = checks.dnv_st_f101(FakeState(moment3=[1e5, 2e5]))
    with pytest.raises(dataclasses.FrozenInstanceError):
        u.plastic_moment = 1.0  # type: ignore[misc]
    with pytest.raises(ValueError):
        u.load_controlled[0] = 0.0


def test_safety_classes_set_the_factors() -> None:
    for safety_class, gamma_sc, gamma_eps in [("low", 1.04, 2.0), ("medium", 1.14, 2.5), ("high", 1.26, 3.3)]:
        u = checks.dnv_st_f101(FakeState(), safety_class=safety_class)
        assert (u.gamma_sc, u.gamma_epsilon) == (gamma_sc, gamma_eps)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"grade": "X99"}, r'grade: "X99" is not a known grade; allowed: X52, X56, X60, X65, X70, X80'),
        ({"safety_class": "normal"}, r'safety_class: "normal" .*allowed: low, medium, high'),
        ({"fabrication": "spiral"}, r'fabrication: "spiral" .*allowed: seamless, uoe, uo_tre, welded'),
        ({"condition": "testing"}, r'condition: "testing" .*allowed: installation, operation'),
        ({"internal_pressure": -1.0}, r"internal_pressure: -1.0 is too small"),
        ({"internal_pressure": math.nan}, r"internal_pressure: nan is not finite"),
        ({"corrosion_allowance": -1e-3}, r"corrosion_allowance: -0.001"),
        ({"corrosion_allowance": 0.02, "condition": "operation"}, r"corrosion_allowance: 0.02 .*less than"),
        ({"ovality": 0.001}, r"ovality: 0.001 is too small; allowed: a fraction from 0.005"),
        ({"temperature_derating": math.inf}, r"temperature_derating: inf is not finite"),
        ({"temperature_derating": 500e6}, r"temperature_derating: 500000000.0 .*SMYS"),
        ({"strain_limit": 0.0}, r"strain_limit: 0.0 is not positive"),
        ({"strain_limit": "0.3%"}, r'strain_limit: "0.3%" is not a number'),
        ({"wall_thickness": True}, r"wall_thickness: True is not a number"),
        ({"wall_thickness": 0.2}, r"wall_thickness: 0.2 .*half the outer diameter"),
    ],
)
def test_bad_arguments_are_named(kwargs: dict[str, Any], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        checks.dnv_st_f101(FakeState(), **kwargs)


def test_missing_wall_thickness() -> None:
    state = FakeState(section=FakeSection(wall_thickness=None))
    with pytest.raises(ValueError, match=r"wall_thickness: None is given neither"):
        checks.dnv_st_f101(state)
    assert checks.dnv_st_f101(state, wall_thickness=T).wall_thickness == T


def test_bad_state_is_named() -> None:
    state = FakeState(moment3=[1.0, 2.0])
    state.strain = np.array([0.0, np.nan])
    with pytest.raises(ValueError, match=r"state.strain: NaN or infinite entries"):
        checks.dnv_st_f101(state)
    state = FakeState(moment3=[1.0, 2.0])
    state.positions = state.positions[:2]
    with pytest.raises(
        ValueError, match=r"state.positions: an array of shape \(2, 3\) is wrong; allowed: shape \(3, 3\)"
    ):
        checks.dnv_st_f101(state)
    state = FakeState(water_depth=-5.0)
    with pytest.raises(ValueError, match=r"state.water_depth: -5.0 is not positive"):
        checks.dnv_st_f101(state)
    state = FakeState()
    del state.strain
    with pytest.raises(ValueError, match=r"state.strain: \(absent\) is missing"):
        checks.dnv_st_f101(state)


def test_errors_are_input_errors() -> None:
    pl = pytest.importorskip("pipelay")
    with pytest.raises(pl.InputError):
        checks.dnv_st_f101(FakeState(), grade="X99")
    u = checks.dnv_st_f101(FakeState())
    with pytest.raises(pl.InputError, match="check"):
        u.worst_element("both")  # type: ignore[arg-type]


class ContentsSection(FakeSection):
    """A section with contents of density `contents_density` (kg/m³)."""

    def __init__(self, contents_density: float) -> None:
        super().__init__()
        self.contents_density = contents_density


def test_a_flooded_pipe_has_its_contents_pressure_inside_and_no_overpressure() -> None:
    # flooded with sea water open to the surface: p_i = p_e at every depth, so no pressure term, and the
    # strain resistance of zero pressure difference (hand calculation, D/t = 20.4: α_gw 0.99)
    depths = np.array([50.0, 400.0, 800.0])
    state = FakeState(z=-depths, water_depth=1e3, moment3=2e5, strain=1e-3, section=ContentsSection(RHO))
    u = checks.dnv_st_f101(state)
    p_e = RHO * G * (1e3 - depths)
    np.testing.assert_allclose(u.internal_pressure, p_e, rtol=1e-14)
    np.testing.assert_allclose(u.external_pressure, p_e, rtol=1e-14)
    f_y, f_u = strengths()
    alpha_c = alpha_c_expected(D / T, f_y, f_u)
    bending = (GAMMA_M * GAMMA_SC_MEDIUM * 2e5 / (alpha_c * f_y * (D - T) ** 2 * T)) ** 2
    np.testing.assert_allclose(u.load_controlled, bending, rtol=1e-12)
    alpha_gw = 1.0 - 0.4 * (D / T - 20.0) / 40.0
    allowable = 0.78 * (T / D - 0.01) * 0.93**-1.5 * alpha_gw / 2.5
    np.testing.assert_allclose(u.allowable_strain, allowable, rtol=1e-12)
    assert "contents (1025 kg/m³" in u.basis and "safety class medium" in u.basis


def test_an_empty_pipe_has_no_internal_pressure() -> None:
    state = FakeState(z=[-200.0], water_depth=600.0, section=ContentsSection(0.0))
    u = checks.dnv_st_f101(state)
    f_y, _ = strengths()
    p_e = RHO * G * 400.0
    assert u.internal_pressure[0] == 0.0
    expected = (GAMMA_M * GAMMA_SC_MEDIUM * p_e / collapse_by_roots(f_y, 1.0, 0.005)) ** 2
    assert u.load_controlled[0] == pytest.approx(expected, rel=1e-12)
    assert "p_i 0 (empty)" in u.basis


def test_contents_heavier_than_sea_water_take_the_internal_overpressure_form() -> None:
    # brine of 1200 kg/m³: p_i − p_e = (1200 − 1025) g h > 0, small against p_b (α_p = 1 − β)
    state = FakeState(z=[-100.0], water_depth=900.0, section=ContentsSection(1200.0))
    u = checks.dnv_st_f101(state)
    f_y, f_u = strengths()
    p_b = 2 * T / (D - T) * min(f_y, f_u / 1.15) * 2 / math.sqrt(3)
    beta = (60 - D / T) / 90
    alpha_c = (1 - beta) + beta * f_u / f_y
    overpressure = (1200.0 - RHO) * G * 800.0
    assert u.internal_pressure[0] == pytest.approx(1200.0 * G * 800.0, rel=1e-14)
    assert u.load_controlled[0] == pytest.approx(
        ((1 - beta) * overpressure / (alpha_c * p_b)) ** 2, rel=1e-12
    )


def test_a_given_internal_pressure_replaces_the_contents() -> None:
    state = FakeState(z=[-100.0, -500.0], water_depth=900.0, section=ContentsSection(RHO))
    u = checks.dnv_st_f101(state, internal_pressure=2e6)
    np.testing.assert_array_equal(u.internal_pressure, 2e6)
    assert "p_i 2 MPa given" in u.basis


def test_the_defaults_live_in_one_place() -> None:
    import inspect

    for function in (checks.dnv_st_f101, checks.propagation_buckling):
        signature = inspect.signature(function)
        given = {name: p.default for name, p in signature.parameters.items() if name != "state"}
        assert given == checks.DEFAULTS


def test_propagation_buckling_by_hand() -> None:
    # D/t = 20.4 (inside 15 … 45); p_pr = 35 f_y α_fab (t/D)^2.5 ≈ 8.07 MPa, its design value / 1.311
    depths_below_surface = np.array([100.0, 500.0, 700.0, 900.0])
    state = FakeState(z=depths_below_surface - 1e3, water_depth=1e3)
    result = checks.propagation_buckling(state, fabrication="uoe")
    f_y, _ = strengths()
    p_pr = 35.0 * f_y * 0.85 * (T / D) ** 2.5
    p_e = RHO * G * depths_below_surface
    expected = GAMMA_M * GAMMA_SC_MEDIUM * p_e / p_pr
    np.testing.assert_allclose(result.propagation_pressure, p_pr, rtol=1e-14)
    np.testing.assert_allclose(result.utilisation, expected, rtol=1e-13)
    failing = expected > 1.0
    assert failing.tolist() == [False, False, True, True]
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(state.positions, axis=0), axis=1))])
    middle = 0.5 * (arc[:-1] + arc[1:])
    said = f"buckle arrestors needed from {middle[2]:.1f} m to {middle[3]:.1f} m from end A (water deeper than 700.0"
    assert result.arrestors is not None and said in result.arrestors
    assert result.worst_element() == 3 and result.max() == pytest.approx(expected[3], rel=1e-13)
    assert result.notes == ()


def test_propagation_buckling_of_a_flooded_pipe_is_nil() -> None:
    state = FakeState(z=[-10.0, -20.0], water_depth=2e3, section=ContentsSection(RHO))
    result = checks.propagation_buckling(state)
    np.testing.assert_array_equal(result.utilisation, 0.0)
    assert result.arrestors is None


def test_propagation_buckling_notes_a_thick_wall() -> None:
    state = FakeState(z=[0.0], water_depth=100.0, section=FakeSection(wall_thickness=0.03))
    assert "outside 15 < D/t2 < 45" in checks.propagation_buckling(state).notes[0]
