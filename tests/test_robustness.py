"""The robustness campaign's fixed cases (issue 43): lay cases made by the campaign's generator (``lay_cases.py``
beside this file, shared with ``benches/robustness.py``), which statics must solve into a physical state whose
numbers agree with the generator's catenary design and with the physics of a current across the lay plane.

The cases: an S-lay (20" concrete-coated, 150 m) and a J-lay (16", 1000 m), each in a 0.6 m/s current toward 0°,
90° and 135° from the lay direction; the concrete-coated 16" S-lay in 120 m and the bare 6" S-lay in 227 m of the
issue, each at its design position and at positions around it. What is asserted of each state:

* `lay_cases.physical_problems` finds nothing (no pipe through the stinger, no roller overloaded, no compression at
  the hold point, no deflection against the current, ...);
* the top tension within 6 % of the design's catenary estimate w·(a + height of the hold point), and within 2 % of
  the tension at the touchdown plus w times the height from the touchdown to the hold point (the catenary's
  relation, exact for a cable with normal drag only on frictionless rollers; the pipe's bending moves it by its
  shear);
* the layback within 8 % of the design's; the touchdown on the seabed;
* S-lay: at least three rollers in contact, the departure within 5° of the design's;
* a current across the lay plane: the suspended pipe's largest sideways offset in the current's direction and
  0.5–2.5 times a taut-string estimate f·L²/(8·T̄) (f = ½ρ·C_d·D_h·|v|·v_y the drag across the plane, L the pipe's
  length from the touchdown to the hold point, T̄ the mean of the design's horizontal and top tensions), the
  touchdown moved in the current's direction too. (A dynamic relaxation of these cases, the current switched on in a
  run from the calm static state until the pipe stops, gives ratios of 1.3 to 1.8 and the touchdown 0.3–3.4 m
  downstream.)

The generator itself and the physical check are tested on their own at the end.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import types
import warnings
from collections import Counter

import lay_cases as lc
import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import parse_scenario

SLAY = lc.Choices(
    kind="s-lay", depth=150.0, nps=20, wall=0.0206, coating="concrete", concrete=0.05, element=8.0
)
"""20" × 20.6 mm X65 with 50 mm of concrete, empty, in 150 m: a shallow-water S-lay."""
JLAY = lc.Choices(
    kind="j-lay", depth=1000.0, nps=16, wall=0.0254, coating="3lpe", sagbend_strain=0.0008, element=10.0
)
"""16" × 25.4 mm X65 with 3LPE, empty, in 1000 m, the tower at the catenary's natural angle: a deep-water J-lay."""
ISSUE_16 = lc.Choices(kind="s-lay", depth=120.0, nps=16, wall=0.0159, coating="concrete", concrete=0.05)
"""The issue's concrete-coated 16" S-lay in 120 m (X65, 15.9 mm wall, 50 mm concrete), calm."""
ISSUE_6 = lc.Choices(kind="s-lay", depth=227.0, nps=6, wall=0.0071, coating="bare")
"""The issue's bare 6" S-lay in 227 m (X65, 7.1 mm wall), calm."""
CURRENT = 0.6
"""m/s, uniform."""


def solve(case: lc.LayCase, shift: float = 0.0) -> pl.State:
    """The static state of `case` with the vessel `shift` m along e1 from its design position."""
    document = copy.deepcopy(case.scenario)
    document["vessel"]["eta"][0] += shift
    scenario = parse_scenario(document)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        return scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)


def touchdown_tension(state: pl.State) -> tuple[float, float]:
    """The effective tension (N) of the element at the touchdown and that element's mean z (m)."""
    arcs = np.asarray(state.reference_arc_length)
    assert state.touchdown is not None
    element = int(np.searchsorted(arcs, state.touchdown.arc_length)) - 1
    return float(state.tension[element]), float(
        np.mean(np.asarray(state.positions)[element : element + 2, 2])
    )


def cross_offset_estimate(case: lc.LayCase) -> float:
    """Taut-string estimate (m) of the largest sideways offset under the current across the lay plane:
    f·L²/(8·T̄), f = ½ρ·C_d·D_h·|v|·v_y (N/m), L the pipe from the design's touchdown to the hold point (m), T̄ the
    mean of the design's horizontal and top tensions (N)."""
    c, d = case.choices, case.design
    drag = case.scenario["pipe"]["drag"][1]
    force = 0.5 * lc.RHO_WATER * drag * d["D_h"] * c.current * lc.current_cross(case)
    span = d["length"] - d["x_touchdown"]
    return abs(force) * span**2 / (8.0 * 0.5 * (d["H"] + d["top_tension"]))


def check_lay_state(state: pl.State, case: lc.LayCase) -> None:
    """The assertions of the module's docstring on a state of `case` at its design position."""
    d = case.design
    assert lc.physical_problems(state, case) == []
    summary = state.lay_summary()
    assert summary is not None
    top = summary["top_tension"]
    assert top == pytest.approx(d["top_tension"], rel=0.06)
    assert state.touchdown is not None
    t_touchdown, z_touchdown = touchdown_tension(state)
    z_hold = float(np.asarray(state.positions)[-1, 2])
    assert top == pytest.approx(t_touchdown + d["w"] * (z_touchdown - z_hold), rel=0.02)
    assert summary["layback"] == pytest.approx(d["layback"], rel=0.08)
    assert abs(state.touchdown.position[2]) <= d["D_h"]
    assert 0.0 < state.touchdown.arc_length < d["length"]
    if case.kind == "s-lay":
        reactions = np.asarray(state.roller_reactions)
        assert np.count_nonzero(reactions > 0.0) >= 3
        assert summary["departure_angle"] == pytest.approx(d["departure"], abs=math.radians(5.0))
    cross = lc.current_cross(case)
    if abs(cross) >= 0.1:
        offsets = np.asarray(state.positions)[:, 1]
        largest = float(offsets[int(np.argmax(np.abs(offsets)))])
        assert largest * cross > 0.0
        assert 0.5 <= abs(largest) / cross_offset_estimate(case) <= 2.5
        assert state.touchdown.position[1] * cross > 0.0


def currents(base: lc.Choices, name: str) -> list[object]:
    """`base` in the current toward 0° (in the lay plane), 90° and 135° (across it)."""
    cases: list[object] = []
    for heading in (0.0, 90.0, 135.0):
        choices = dataclasses.replace(base, current=CURRENT, current_heading_deg=heading)
        cases.append(pytest.param(choices, id=f"{name}-current-{heading:.0f}"))
    return cases


@pytest.mark.parametrize("choices", currents(SLAY, "s-lay") + currents(JLAY, "j-lay"))
def test_lay_in_a_current(choices: lc.Choices) -> None:
    """Statics of an S-lay and a J-lay in a current toward 0°, 90° and 135°: physical, and as designed."""
    case = lc.design(choices)
    check_lay_state(solve(case), case)


@pytest.mark.parametrize(
    ("choices", "shifts"),
    [
        pytest.param(ISSUE_16, (-2.0, -1.0, 0.0, 1.0, 2.0), id="16in-concrete-120m"),
        pytest.param(ISSUE_6, (-1.0, 0.0, 1.0), id="6in-bare-227m"),
    ],
)
def test_issue_cases_around_their_position(choices: lc.Choices, shifts: tuple[float, ...]) -> None:
    """The issue's calm S-lays at their design position (as designed) and 1–2 m either way (physical, the top
    tension rising as the vessel moves out)."""
    case = lc.design(choices)
    tensions = []
    for shift in shifts:
        state = solve(case, shift)
        assert lc.physical_problems(state, case) == [], f"at {shift:+g} m"
        if shift == 0.0:
            check_lay_state(state, case)
        tensions.append(state.lay_summary()["top_tension"])
    assert np.all(np.diff(tensions) > 0.0)


# The generator and the check.


def test_drawn_cases_are_sensible() -> None:
    """Fifty cases of seed 1: each redesigned from its choices gives the same case, breaks no rule, lies within
    the campaign's ranges and parses as a scenario; both lays, DP, waves and 500-element cases come up."""
    rejections: Counter[str] = Counter()
    cases = [lc.draw(1, index, rejections) for index in range(50)]
    for case in cases:
        again = lc.design(case.choices, case.index, case.seed)
        assert again.scenario == case.scenario
        d, c = case.design, case.choices
        assert lc.DT_RANGE[0] <= lc.NOMINAL_OD[c.nps] / c.wall <= lc.DT_RANGE[1]
        assert d["sagbend_strain"] <= lc.SAGBEND_STRAIN_MAX
        assert d["top_tension"] <= lc.TOP_TENSION_MAX
        assert d["specific_gravity"] >= lc.SPECIFIC_GRAVITY_MIN
        assert 0.0 <= c.current <= 1.2
        low, high = (30.0, 1000.0) if c.kind == "s-lay" else (300.0, 3000.0)
        assert low <= c.depth <= high
        if c.kind == "s-lay":
            assert lc.STINGER_LENGTH[0] <= d["stinger_length"] <= lc.STINGER_LENGTH[1] + 5.0
            assert d["overbend_strain"] <= lc.OVERBEND_FACTOR * lc.SMYS[c.grade] / lc.STEEL_E
            assert d["liftoff_arc"] < d["stinger_length"]
        else:
            assert abs(d["tower_angle"] - d["top_angle"]) <= math.radians(1.5) + 1e-12
        assert 0.0 < d["x_touchdown"] < d["x_vessel"] < d["length"] + 20.0
        parse_scenario(copy.deepcopy(case.scenario))
    kinds = Counter(case.kind for case in cases)
    assert kinds["s-lay"] > 15 and kinds["j-lay"] > 10
    assert any(case.choices.dp for case in cases) and any(case.choices.hs > 0 for case in cases)
    assert any(case.design["elements"] == 500 for case in cases)
    assert set(rejections) <= set(lc.RULES)


def test_catenary_helpers_agree() -> None:
    """The design's closed forms: the parameter for an angle gives that angle back; a catenary's arc and span
    satisfy s² = h² + 2ah and x = a·asinh(s/a); ∫T ds matches a quadrature."""
    h, angle = 180.0, math.radians(35.0)
    a = lc.parameter_for_angle(h, angle)
    assert math.acos(a / (a + h)) == pytest.approx(angle, rel=1e-12)
    span, arc = lc.catenary_span(a, h)
    assert span == pytest.approx(a * math.asinh(arc / a), rel=1e-12)
    x = np.linspace(0.0, span, 200_001)
    y = a * (np.cosh(x / a) - 1.0)
    integrand = 1000.0 * (a + y) * np.cosh(x / a)
    assert lc.catenary_tension_integral(a, h, 1000.0) == pytest.approx(
        np.sum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(x)), rel=1e-8
    )


def test_collapse_pressure_is_dnvs() -> None:
    """The collapse pressure satisfies DNV-ST-F101's cubic and lies below both the elastic and the plastic one."""
    od, wall, smys = 0.4064, 0.0206, 450e6
    p = lc.collapse_pressure(od, wall, smys, 0.85)
    elastic = 2.0 * lc.STEEL_E * (wall / od) ** 3 / (1.0 - 0.3**2)
    plastic = 2.0 * smys * 0.85 * wall / od
    assert 0.0 < p < min(elastic, plastic)
    assert (p - elastic) * (p**2 - plastic**2) == pytest.approx(
        p * elastic * plastic * 0.005 * od / wall, rel=1e-9
    )


def test_physical_check_flags_what_is_wrong() -> None:
    """The physical check on a physical state of the issue's 16" S-lay, then on copies made wrong: the pipe on the
    stinger lowered 2 m (through the rollers), a roller's reaction twenty-fold (overload), the top in compression,
    and a current across that the pipe bows against."""
    case = lc.design(ISSUE_16)
    state = solve(case)
    assert lc.physical_problems(state, case) == []

    def altered(**changes: object) -> types.SimpleNamespace:
        """A stand-in for the state with some of its numbers changed."""
        names = ("positions", "rotations", "tension", "eta", "roller_positions", "roller_reactions", "strain",
                 "reference_arc_length")  # fmt: skip
        fields: dict[str, object] = {name: np.array(getattr(state, name)) for name in names}
        summary = dict(state.lay_summary() or {}) | dict(changes.pop("summary", {}))  # type: ignore[call-overload]
        fields["lay_summary"] = lambda: summary
        return types.SimpleNamespace(**(fields | changes))

    positions = np.array(state.positions)
    positions[-30:, 2] += 2.0
    kinds = [kind for kind, _ in lc.physical_problems(altered(positions=positions), case)]  # type: ignore[arg-type]
    assert "through the rollers" in kinds
    reactions = np.array(state.roller_reactions)
    reactions[3] = 20.0 * np.max(reactions)
    kinds = [kind for kind, _ in lc.physical_problems(altered(roller_reactions=reactions), case)]  # type: ignore[arg-type]
    assert kinds == ["roller overload"]
    compressed = altered(summary={"top_tension": -1e4})
    assert "compression" in [kind for kind, _ in lc.physical_problems(compressed, case)]  # type: ignore[arg-type]
    across = lc.design(dataclasses.replace(ISSUE_16, current=0.8, current_heading_deg=90.0))
    bowed = np.array(state.positions)
    bowed[:, 1] = -5.0 * np.sin(np.pi * np.linspace(0.0, 1.0, len(bowed)))
    kinds = [kind for kind, _ in lc.physical_problems(altered(positions=bowed), across)]  # type: ignore[arg-type]
    assert kinds == ["against the current"]
