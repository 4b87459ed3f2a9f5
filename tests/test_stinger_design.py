"""Stinger design (`pl.design_stinger`): the radius and roller heights for a target overbend strain and tip
clearance at a top tension, checked against the geometry of the arc, the thin-arc strain, and a scenario file
built from the design and solved on its own."""

from __future__ import annotations

import math

import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import parse_scenario

SECTION = pl.Section.pipe(0.6, 0.03)  # the S-lay example's empty 24-inch, 30 mm wall
DEPTH = 150.0
TENSION = 1.0e6
STRAIN = 0.0018
CLEARANCE = 0.3
CASES = {
    "24-inch in 150 m": ((0.6, 0.03), DEPTH, TENSION, STRAIN, CLEARANCE),
    "16-inch in 300 m": ((0.4064, 0.0159), 300.0, 6.0e5, 0.0020, 0.3),
}
"""Pipe (D, t), depth (m), top tension (N), overbend strain, tip clearance (m)."""


@pytest.fixture(scope="module", params=list(CASES))
def case(request: pytest.FixtureRequest) -> tuple[tuple[float, float], float, float, float, float]:
    return CASES[request.param]


@pytest.fixture(scope="module")
def design(case: tuple[tuple[float, float], float, float, float, float]) -> pl.StingerDesign:
    (diameter, wall), depth, tension, strain, clearance = case
    section = pl.Section.pipe(diameter, wall)
    return pl.design_stinger(section, depth, tension, overbend_strain=strain, tip_clearance=clearance)


def test_the_targets_are_met(design: pl.StingerDesign, case: tuple) -> None:
    _, _, tension, strain, clearance = case
    print(
        f"R = {design.radius:.2f} m, L = {design.length:.2f} m, {design.rollers} rollers, x = "
        f"{design.vessel_x:.2f} m, ε = {design.overbend_strain:.6f}, gap = {design.tip_clearance:.4f} m, "
        f"{design.solves} solves"
    )
    assert design.tip_clearance == pytest.approx(clearance, abs=0.01)
    assert design.overbend_strain == pytest.approx(strain, rel=0.01)
    assert design.top_tension == pytest.approx(tension, rel=1e-3)
    summary = design.state.lay_summary()
    assert summary["liftoff_roller"] < design.rollers - 1  # the pipe leaves before the tip, clear of it


def test_the_rollers_tops_lie_on_the_arc(design: pl.StingerDesign) -> None:
    # The arc starts level at the origin and bends down aft (body frame, z down): its centre is R below it.
    centre = np.asarray(design.origin) + np.array([0.0, 0.0, design.radius])
    distance = np.linalg.norm(design.roller_tops - centre, axis=1)
    np.testing.assert_allclose(distance, design.radius, atol=1e-3)
    along = design.radius * np.arctan2(
        design.origin[0] - design.roller_tops[:, 0], centre[2] - design.roller_tops[:, 2]
    )
    np.testing.assert_allclose(along, np.linspace(0.0, design.length, design.rollers), atol=1e-6)
    np.testing.assert_allclose(design.roller_heights, design.origin[2] - design.roller_tops[:, 2], rtol=0)
    assert np.all(np.diff(design.roller_heights) < 0.0)  # each lower than the last, aft


def test_the_radius_is_near_the_thin_arc_estimate(design: pl.StingerDesign, case: tuple) -> None:
    # over an arc the outer fibre strains (D/2)/(R + D/2) + T/EA: discrete rollers add a few percent
    (d, wall), _, tension, strain, _ = case
    thin = 0.5 * d / (strain - tension / pl.Section.pipe(d, wall).EA) - 0.5 * d
    assert design.radius == pytest.approx(thin, rel=0.05)
    assert design.radius > thin  # the rollers' peaks strain more than the smooth arc: a larger radius


def test_the_design_is_a_scenarios_stinger(design: pl.StingerDesign, case: tuple) -> None:
    """A scenario file with the design's [vessel.lay.stinger], its pipe and vessel position gives the same lay."""
    (diameter, wall), depth, *_ = case
    _same_lay_from_the_table(design, diameter, wall, depth)


def test_a_stinger_of_v_boxes_is_designed_to_its_targets() -> None:
    """With a V box (±30°) at every roller's place the design meets the targets as with lone rollers (the
    strain to 1 %, the tip clearance to 0.01 m: the pipe rests R(1/cos θ − 1) = 4.6 cm higher in a V, so the
    radius differs); its table holds the box, and a scenario built from it gives the same lay."""
    box = pl.RollerBox(kind="v", half_angle=math.radians(30.0))
    design = pl.design_stinger(
        SECTION, DEPTH, TENSION, overbend_strain=STRAIN, tip_clearance=CLEARANCE, box=box
    )
    print(f"V boxes: R {design.radius:.2f} m, L {design.length:.2f} m, {design.rollers} boxes")
    assert design.overbend_strain == pytest.approx(STRAIN, rel=0.01)
    assert design.tip_clearance == pytest.approx(CLEARANCE, abs=0.01)
    assert design.table()["box"]["half_angle"] == pytest.approx(math.radians(30.0))
    assert len(design.stinger.stations) == design.rollers and len(design.stinger) == 2 * design.rollers
    _same_lay_from_the_table(design, 0.6, 0.03, DEPTH)


def _same_lay_from_the_table(design: pl.StingerDesign, diameter: float, wall: float, depth: float) -> None:
    """The scenario of the design's pipe, vessel position and stinger table solves to the design's lay."""
    data = {
        "pipe": {"outer_diameter": diameter, "wall_thickness": wall},
        "rod": {
            "start": [0.0, 0.0, 0.0],
            "end": [design.pipe_length, 0.0, 0.0],
            "elements": round(design.pipe_length / 2.5),
        },
        "sea": {"depth": depth, "seabed": {"stiffness": 1e5, "friction": [0.5, 0.5], "mobilisation": 0.02}},
        "supports": {"A": {"kind": "pin"}},
        "vessel": {
            "end": "B",
            "model": "osv",
            "eta": [design.vessel_x, 0.0, -depth, 0.0, 0.0, 0.0],
            "lay": {"kind": "s-lay", "tensioner": list(design.tensioner), "stinger": design.table()},
        },
    }
    state = parse_scenario(data).model.static()
    summary = state.lay_summary()
    assert summary["tip_clearance"] == pytest.approx(design.tip_clearance, abs=1e-6)
    assert summary["overbend_strain"] == pytest.approx(design.overbend_strain, rel=1e-6)
    assert summary["top_tension"] == pytest.approx(design.top_tension, rel=1e-6)


@pytest.mark.parametrize(
    ("arguments", "named"),
    [
        ({"overbend_strain": 5e-5}, "overbend_strain"),  # below T/EA = 9e-5
        ({"tip_clearance": -0.1}, "tip_clearance"),
        ({"roller_spacing": math.nan}, "roller_spacing"),
        ({"origin": (0.0, 0.0)}, "origin"),
    ],
)
def test_bad_input_is_named(arguments: dict[str, object], named: str) -> None:
    with pytest.raises(pl.InputError, match=named):
        pl.design_stinger(SECTION, DEPTH, TENSION, **arguments)  # type: ignore[arg-type]
