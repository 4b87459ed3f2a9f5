"""Coated and lined pipes (`pl.Coating`, `pl.Section.pipe(..., coatings=, lining=, grade=)`).

A coated pipe's steel wall is what the design checks see; its coatings add mass and set the outer surface
(the hydrodynamic diameter) that buoyancy, drag, added mass and contact act on. Checked against the hand
formulas, against a plain `pl.Section` with the coated pipe's mass and outer surface (the engine must see the
two alike), and through the DNV-ST-F101 check.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import load_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
G, RHO_W = 9.81, 1025.0
D, T = 0.6096, 0.0206  # 24-inch line pipe (m)
STEEL, PE, CONCRETE = 7850.0, 940.0, 3040.0  # kg/m³


def ring(inner: float, outer: float) -> float:
    return math.pi / 4.0 * (outer**2 - inner**2)


def concrete_pipe(**kwargs: object) -> pl.Section:
    """The 24-inch pipe with 3 mm of 3LPE and 60 mm of concrete, empty."""
    coatings = [pl.Coating(0.003, PE), pl.Coating(0.06, CONCRETE)]
    return pl.Section.pipe(D, T, coatings=coatings, drag=(0.0, 1.2), added_mass=(0.0, 1.0), **kwargs)


def test_submerged_weight_of_a_coated_pipe_is_the_hand_formula() -> None:
    section = concrete_pipe()
    d_pe, d_h = D + 0.006, D + 0.006 + 0.12
    mass = STEEL * ring(D - 2 * T, D) + PE * ring(D, d_pe) + CONCRETE * ring(d_pe, d_h)
    weight = (mass - RHO_W * math.pi / 4.0 * d_h**2) * G
    assert section.mass == pytest.approx(mass, rel=1e-12)
    assert section.submerged_weight == pytest.approx(weight, rel=1e-12)
    assert section.submerged_weight == pytest.approx(2513.15, abs=0.01)  # N/m: 256 kg/m submerged
    assert section.outer_diameter == D
    assert section.hydrodynamic_diameter == pytest.approx(d_h, rel=1e-15)
    assert section.displaced_area == pytest.approx(math.pi / 4.0 * d_h**2, rel=1e-15)
    # The coatings carry no stiffness: EA and EI are the steel's.
    bare = pl.Section.pipe(D, T)
    assert section.EA == bare.EA and section.EI == bare.EI and section.GJ == bare.GJ
    assert [(c.thickness, c.density) for c in section.coatings] == [(0.003, PE), (0.06, CONCRETE)]


def test_a_lining_holds_the_contents_in_its_bore() -> None:
    lined = pl.Section.pipe(D, T, contents_density=1025.0, lining=pl.Coating(0.005, 1100.0))
    bore = D - 2 * T - 0.01
    mass = STEEL * ring(D - 2 * T, D) + 1100.0 * ring(bore, D - 2 * T) + 1025.0 * math.pi / 4.0 * bore**2
    assert lined.mass == pytest.approx(mass, rel=1e-12)
    assert lined.hydrodynamic_diameter == D
    assert lined.lining is not None and lined.lining.thickness == 0.005


def hanging(section: pl.Section, current: float) -> pl.State:
    """500 m of pipe hanging from its top in 600 m of water, in a uniform current in e1."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (0.0, 0.0, -500.0), 50, section)
    sea = pl.Sea(600.0, current=pl.Current.uniform((current, 0.0, 0.0)))
    model = pl.Model(rod, sea=sea)
    model.pin("B")
    return model.static()


def plain_like(section: pl.Section, outer_diameter: float, displaced_area: float | None = None) -> pl.Section:
    """A plain `pl.Section` with `section`'s stiffness, mass, inertia and coefficients on `outer_diameter`."""
    return pl.Section(
        EA=section.EA,
        GA=section.GA,
        GJ=section.GJ,
        EI=section.EI,
        mass=section.mass,
        inertia=section.inertia,
        outer_diameter=outer_diameter,
        displaced_area=displaced_area,
        drag=section.drag,
        added_mass=section.added_mass,
    )


def test_the_engine_sees_a_coated_pipe_as_its_outer_surface() -> None:
    """The coated pipe hangs, drags and reacts exactly as a plain section with its mass, stiffness and outer
    surface: buoyancy, drag and contact all take the hydrodynamic diameter."""
    coated = concrete_pipe()
    plain = plain_like(coated, coated.hydrodynamic_diameter)
    a, b = hanging(coated, 0.5), hanging(plain, 0.5)
    np.testing.assert_allclose(a.positions, b.positions, rtol=0, atol=1e-9)
    np.testing.assert_allclose(a.reaction("B"), b.reaction("B"), rtol=1e-10)
    # In time too (added mass on the outer surface): released from statics into a current that turns.
    runs = []
    for section, state in ((coated, a), (plain, b)):
        rod = pl.Rod.straight((0.0, 0.0, 0.0), (0.0, 0.0, -500.0), 50, section)
        model = pl.Model(rod, sea=pl.Sea(600.0, current=pl.Current.uniform((0.0, 0.8, 0.0))))
        model.pin("B")
        runs.append(model.simulation(state=state, dt=0.5).run(10.0, progress=False).positions[-1])
    np.testing.assert_allclose(runs[0], runs[1], rtol=0, atol=1e-8)
    assert np.abs(runs[0] - a.positions).max() > 1.0
    # The top carries the submerged weight of the whole line (the current pushes it aside too).
    still = hanging(coated, 0.0)
    assert still.reaction("B")[2] == pytest.approx(coated.submerged_weight * 500.0, rel=1e-9)
    # Were the drag on the steel's diameter, the current would push the line less far aside.
    steel_surface = plain_like(coated, D, displaced_area=coated.displaced_area)
    assert abs(a.positions[0, 0]) > 1.1 * abs(hanging(steel_surface, 0.5).positions[0, 0])


def test_design_checks_see_the_steel_wall_and_the_sections_grade() -> None:
    state = hanging(concrete_pipe(grade="X70"), 0.5)
    coated = pl.checks.dnv_st_f101(state)
    assert np.array_equal(coated.load_controlled, pl.checks.dnv_st_f101(state, grade="X70").load_controlled)
    assert not np.array_equal(
        coated.load_controlled, pl.checks.dnv_st_f101(state, grade="X52").load_controlled
    )
    # The same forces on the bare steel section give the same utilisation: the coatings are not the wall.
    steel = SimpleNamespace(
        section_forces=state.section_forces,
        tension=state.tension,
        positions=state.positions,
        strain=state.strain,
        water_depth=state.water_depth,
        water_density=state.water_density,
        section=pl.Section.pipe(D, T, grade="X70"),
    )
    np.testing.assert_array_equal(coated.load_controlled, pl.checks.dnv_st_f101(steel).load_controlled)
    assert np.all(coated.load_controlled > 0.0)


@pytest.mark.parametrize(
    ("build", "named"),
    [
        (lambda: pl.Coating(0.0, CONCRETE), "thickness"),
        (lambda: pl.Coating(-0.06, CONCRETE), "thickness"),
        (lambda: pl.Coating(0.06, -1.0), "density"),
        (lambda: pl.Coating(0.06, CONCRETE, youngs_modulus=float("nan")), "youngs_modulus"),
        (lambda: pl.Section.pipe(D, T, grade="X99"), "grade"),
        (lambda: pl.Section.pipe(D, T, lining=pl.Coating(0.3, 1000.0)), "lining thickness"),
    ],
)
def test_bad_layers_and_grades_are_input_errors_naming_them(build: object, named: str) -> None:
    with pytest.raises(pl.InputError, match=f"^{named}"):
        build()  # type: ignore[operator]


def test_scenario_files_take_coatings_a_lining_and_a_grade(tmp_path: Path) -> None:
    text = (EXAMPLES / "s_lay_concrete.toml").read_text()
    scenario = load_scenario(EXAMPLES / "s_lay_concrete.toml")
    section = scenario.model.rod.section
    assert section.grade == "X65"
    assert section.submerged_weight == pytest.approx(concrete_pipe().submerged_weight, rel=1e-12)
    lined = text.replace(
        "[[pipe.coatings]]  # 3LPE",
        "[pipe.lining]\nthickness = 0.005\ndensity = 1100.0\n\n[[pipe.coatings]]  # 3LPE",
    )
    path = tmp_path / "lined.toml"
    path.write_text(lined)
    assert load_scenario(path).model.rod.section.lining.thickness == 0.005  # type: ignore[union-attr]
    for old, new, key in [
        ('grade = "X65"', 'grade = "X99"', "pipe.grade"),
        ("thickness = 0.003", "thickness = 0.0", "pipe.coatings[0].thickness"),
        ("density = 3040.0", "density = -3040.0", "pipe.coatings[1].density"),
    ]:
        path.write_text(text.replace(old, new, 1))
        with pytest.raises(pl.InputError, match=re.escape(key)):
            load_scenario(path)


def test_the_concrete_s_lay_example_solves_within_its_checks() -> None:
    """The example lays the heavy line at about 1.1 MN over its stinger, its steel within DNV-ST-F101 and
    below yield (no PhysicsWarning)."""
    scenario = load_scenario(EXAMPLES / "s_lay_concrete.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("error", pl.PhysicsWarning)
        state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    summary = state.lay_summary()
    assert summary is not None and 0.9e6 < summary["top_tension"] < 1.3e6
    assert 0.0 < summary["overbend_strain"] < 450e6 / 207e9
    check = pl.checks.dnv_st_f101(state, safety_class="low")
    assert check.grade == "X65"
    assert 0.1 < check.load_controlled.max() < 1.0 and check.displacement_controlled.max() < 1.0
