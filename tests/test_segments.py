"""Lines of segments (`pl.Segment`, `pl.Rod.segments`) and the cable element (`pl.Section.cable`).

A line is a chain of segments, each with its own section and element count, continuous at the joints. Checked:
a vertical two-segment line against statics by hand (the tension at each element's midpoint is the submerged
weight hanging below it, so its slope along the line jumps at the joint from one segment's weight to the
other's), a cable hanging a pipe, the energy ledger of a driven pipe-and-wire line in a current, DNV-ST-F101 on
a two-grade line against each part checked alone, and bad input.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import load_scenario

HEAVY = pl.Section.pipe(0.3239, 0.0254, grade="X70")  # 12-inch heavy wall
STANDARD = pl.Section.pipe(0.3239, 0.0127, grade="X65", coatings=[pl.Coating(0.05, 3040.0)])
WIRE = pl.Section.cable(diameter=0.08, mass=28.0, EA=5.5e8)  # an 80 mm A&R wire rope
G, RHO_W = 9.81, 1025.0


def hanging(segments: list[pl.Segment]) -> tuple[pl.Model, pl.State]:
    """The line hanging from a pin at end B (the top, z = 0), end A free below, in still water."""
    length = sum(s.length for s in segments)
    rod = pl.Rod.segments(start=(0.0, 0.0, length), direction=(0.0, 0.0, -1.0), segments=segments)
    model = pl.Model(rod, sea=pl.Sea(depth=2.0 * length))
    model.pin("B")
    return model, model.static()


def weight_below(segments: list[pl.Segment], arc: np.ndarray) -> np.ndarray:
    """Submerged weight of the line between end A and arc length `arc` from A (N)."""
    bounds = np.cumsum([0.0] + [s.length for s in segments])
    total = np.zeros_like(arc)
    for segment, start, end in zip(segments, bounds[:-1], bounds[1:], strict=True):
        total += segment.section.submerged_weight * np.clip(arc - start, 0.0, end - start)
    return total


@pytest.mark.parametrize(
    "segments",
    [
        [pl.Segment(300.0, HEAVY, 30), pl.Segment(200.0, STANDARD, 25)],
        [pl.Segment(300.0, HEAVY, 30), pl.Segment(200.0, WIRE, 40)],
    ],
    ids=["heavy-wall below standard pipe", "pipe on a wire rope"],
)
def test_a_vertical_line_carries_the_weight_below_each_point(segments: list[pl.Segment]) -> None:
    """Tension at each element midpoint = the submerged weight below it (Σ w_i L_i at the top); the slope
    dT/ds is w of the segment, jumping at the joint. Measured when written: within 2e-9 of the top tension."""
    model, state = hanging(segments)
    rod = model.rod
    np.testing.assert_array_equal(rod.segment_of, np.repeat([0, 1], [s.elements for s in segments]))
    arc = state.reference_arc_length
    middle = 0.5 * (arc[:-1] + arc[1:])
    expected = weight_below(segments, middle)
    top = weight_below(segments, np.array([rod.length]))[0]
    assert np.max(np.abs(state.tension - expected)) < 1e-8 * top
    assert state.reaction("B")[2] == pytest.approx(top, rel=1e-9)
    slope = np.diff(state.tension) / np.diff(middle)
    joint = segments[0].elements  # the first element of segment 1
    w0, w1 = (s.section.submerged_weight for s in segments)
    np.testing.assert_allclose(slope[: joint - 1], w0, rtol=1e-6)
    np.testing.assert_allclose(slope[joint:], w1, rtol=1e-6)
    # Across the joint the slope is the two weights' mean over the two half-elements.
    h0, h1 = segments[0].length / segments[0].elements, segments[1].length / segments[1].elements
    assert slope[joint - 1] == pytest.approx((w0 * h0 + w1 * h1) / (h0 + h1), rel=1e-6)
    # The line hangs straight and stretches by ∫ T/EA.
    assert np.max(np.abs(state.positions[:, :2])) < 1e-9
    stretch = np.sum(state.tension / np.array([rod.sections[k].EA for k in rod.segment_of]) * np.diff(arc))
    assert state.positions[0, 2] - state.positions[-1, 2] == pytest.approx(rod.length + stretch, rel=1e-9)


def test_a_cable_carries_tension_only_and_pins_the_pipe_below_it() -> None:
    """The wire's section forces are its tension alone, and it holds the pipe below it as a pin: the pipe turns
    freely at the joint (its end's axis leaves the wire's direction) while the line's force passes along the
    wire."""
    segments = [pl.Segment(300.0, HEAVY, 30), pl.Segment(200.0, WIRE, 40)]
    rod = pl.Rod.segments(start=(0.0, 0.0, 500.0), direction=(0.0, 0.0, -1.0), segments=segments)
    model = pl.Model(rod, sea=pl.Sea(depth=1000.0, current=pl.Current.uniform((0.6, 0.0, 0.0))))
    model.pin("B")
    state = model.static()
    forces = state.section_forces
    assert np.all(forces[30:, 1:] == 0.0) and np.all(forces[30:, 0] > 0.0)
    # The current pushes the line aside.
    assert state.positions[0, 0] > 10.0
    # At the joint (node 30) the force the wire passes is along its first chord: horizontal over vertical
    # force of the wire's lowest element is its chord's slope.
    chord = state.positions[31] - state.positions[30]
    below = weight_below(segments, np.array([300.0]))[0]
    drag = state.reaction("B")[0]  # the current's total push, carried to the pin
    assert drag > 0.0
    wire_drag = 0.5 * RHO_W * 1.2 * 0.08 * 0.6**2  # per metre of (nearly vertical) wire
    horizontal_at_joint = drag - wire_drag * 200.0
    assert chord[0] / chord[2] == pytest.approx(horizontal_at_joint / below, rel=0.02)
    assert WIRE.is_cable and not HEAVY.is_cable
    assert WIRE.displaced_area == pytest.approx(math.pi / 4.0 * 0.08**2, rel=1e-15)
    assert WIRE.submerged_weight == pytest.approx((28.0 - RHO_W * WIRE.displaced_area) * G, rel=1e-12)


def test_the_energy_ledger_closes_every_step_with_a_pipe_on_a_wire() -> None:
    """A pipe hung on a wire rope, its top driven in surge in a current: every step's change of stored energy
    equals the work supplied less the work dissipated (the drag), to round-off, with the wire's added mass
    isotropic and by direction (axial 0, normal 1: it then acts along each wire element's chord, balanced by
    a discrete gradient). Measured when written: the largest step imbalance 3.7e-7 J isotropic and 5.5e-7 J by
    direction, of a stored energy 1.1e8 J (it was 0.046 J with the axial coefficient held at each node's axis
    of the step's start)."""
    wire = pl.Section.cable(diameter=0.08, mass=28.0, EA=5.5e8, added_mass=(1.0, 1.0))
    assert ledger_imbalance(wire) < 1e-13 * 1.1e8
    assert ledger_imbalance(WIRE) < 1e-13 * 1.1e8


def ledger_imbalance(wire: pl.Section) -> float:
    """The largest step imbalance of the ledger of the driven pipe on `wire` (J)."""
    segments = [pl.Segment(300.0, HEAVY, 30), pl.Segment(200.0, wire, 40)]
    rod = pl.Rod.segments(start=(0.0, 0.0, 500.0), direction=(0.0, 0.0, -1.0), segments=segments)
    model = pl.Model(rod, sea=pl.Sea(depth=1000.0, current=pl.Current.uniform((0.4, 0.0, 0.0))))
    model.drive("B", lambda t: (3.0 * math.sin(0.5 * t) * min(t / 10.0, 1.0) ** 3, 0.0, 0.0))
    results = model.simulation(model.static(), dt=0.1).run(30.0, progress=False)
    energy = results.energy["total"]
    imbalance = np.diff(energy) - (np.diff(results.supplied_work) - np.diff(results.dissipated))
    assert results.dissipated[-1] > 1e3
    assert np.all(results.tension[:, 30:] >= 0.0)
    return float(np.max(np.abs(imbalance)))


def test_dnv_of_a_two_grade_line_is_the_check_of_each_part_alone() -> None:
    """Each element is checked with its own segment's steel wall and grade, as if its part were the whole line."""
    segments = [pl.Segment(300.0, HEAVY, 30), pl.Segment(200.0, STANDARD, 20), pl.Segment(100.0, WIRE, 10)]
    rod = pl.Rod.segments(start=(0.0, 0.0, 0.0), direction=(1.0, 0.0, 0.0), segments=segments)
    model = pl.Model(rod, sea=pl.Sea(depth=400.0))
    model.pin("A", (0.0, 0.0, 0.0))
    model.pin("B", (500.0, 0.0, -300.0))
    state = model.static()
    whole = pl.checks.dnv_st_f101(state)
    np.testing.assert_array_equal(whole.segment_of, state.segment_of)
    for k, elements in enumerate([slice(0, 30), slice(30, 50)]):
        nodes = slice(elements.start, elements.stop + 1)
        part = SimpleNamespace(
            section_forces=state.section_forces[elements],
            tension=state.tension[elements],
            positions=state.positions[nodes],
            strain=state.strain[elements],
            water_depth=state.water_depth,
            water_density=state.water_density,
            section=state.sections[k],
        )
        alone = pl.checks.dnv_st_f101(part)
        np.testing.assert_array_equal(whole.load_controlled[elements], alone.load_controlled)
        np.testing.assert_array_equal(whole.displacement_controlled[elements], alone.displacement_controlled)
        assert whole.segments[k] is not None and whole.segments[k].grade == ["X70", "X65"][k]
    assert whole.segments[2] is None
    assert np.all(whole.load_controlled[50:] == 0.0)
    assert any("cables" in note for note in whole.notes)
    # The scalars are the governing segment's.
    governing = int(whole.segment_of[np.argmax(whole.load_controlled)])
    assert whole.grade == whole.segments[governing].grade


@pytest.mark.parametrize(
    ("build", "named"),
    [
        (lambda: pl.Segment(0.0, HEAVY, 10), "length"),
        (lambda: pl.Segment(-5.0, HEAVY, 10), "length"),
        (lambda: pl.Segment(10.0, HEAVY, 0), "elements"),
        (lambda: pl.Rod.segments((0, 0, 0), (1, 0, 0), []), "segments"),
        (lambda: pl.Rod.segments((0, 0, 0), (0, 0, 0), [pl.Segment(1.0, HEAVY, 1)]), "direction"),
        (lambda: pl.Section.cable(diameter=0.0, mass=28.0, EA=5.5e8), "diameter"),
        (lambda: pl.Section.cable(diameter=0.08, mass=-1.0, EA=5.5e8), "mass"),
        (lambda: pl.Section.cable(diameter=0.08, mass=28.0, EA=math.nan), "EA"),
    ],
)
def test_bad_segments_are_input_errors_naming_them(build: object, named: str) -> None:
    with pytest.raises(pl.InputError, match=named):
        build()  # type: ignore[operator]


LINE_FILE = """
[line]
start = [0.0, 0.0, 500.0]
direction = [0.0, 0.0, -1.0]
length = 500.0
[[line.segments]]
length = 300.0
elements = 30
[line.segments.pipe]
outer_diameter = 0.3239
wall_thickness = 0.0254
grade = "X70"
[[line.segments]]
length = 200.0
elements = 40
[line.segments.cable]
diameter = 0.08
mass = 28.0
EA = 5.5e8
[sea]
depth = 1000.0
[supports.B]
kind = "pin"
"""


def test_scenario_files_take_a_line_of_segments(tmp_path: Path) -> None:
    """`[line]` with `[[line.segments]]` builds the same line as `pl.Rod.segments`."""
    path = tmp_path / "line.toml"
    path.write_text(LINE_FILE)
    scenario = load_scenario(path)
    rod = scenario.model.rod
    assert rod.elements == 70 and rod.length == pytest.approx(500.0, rel=1e-15)
    assert rod.sections[0].grade == "X70" and rod.sections[1].is_cable
    assert rod.sections[1].EA == 5.5e8 and rod.sections[1].drag == (0.0, 1.2)
    _, by_hand = hanging([pl.Segment(300.0, HEAVY, 30), pl.Segment(200.0, WIRE, 40)])
    np.testing.assert_array_equal(scenario.model.static().tension, by_hand.tension)


@pytest.mark.parametrize(
    ("change", "named"),
    [
        (("length = 500.0", "length = 450.0"), "line.length"),
        (("[line.segments.cable]", "[line.segments.section]"), "line.segments"),
        (("mass = 28.0", "mass = -28.0"), "line.segments[1].cable.mass"),
        (("elements = 40", "elements = 0"), "line.segments[1].elements"),
        (("[sea]", "[rod]\nstart = [0, 0, 0]\nend = [1, 0, 0]\nelements = 1\n[sea]"), "rod"),
    ],
)
def test_bad_lines_in_scenario_files_name_their_key(
    tmp_path: Path, change: tuple[str, str], named: str
) -> None:
    path = tmp_path / "line.toml"
    path.write_text(LINE_FILE.replace(*change, 1))
    with pytest.raises(pl.InputError, match=re.escape(named)):
        load_scenario(path)


PAID = pl.Section.pipe(0.3, 0.02, drag=(0.1, 1.0), added_mass=(0.0, 1.0))
PAID_HEAVY = pl.Section.pipe(0.3, 0.03, drag=(0.1, 1.0), added_mass=(0.0, 1.0))
PAID_WIRE = pl.Section.cable(0.08, 28.0, 5.5e8, added_mass=(1.0, 1.0))


def _pulse(t: float, speed: float = 0.5, duration: float = 30.0, ramp: float = 10.0) -> float:
    """`speed` (m/s) for `duration` s with smooth ramps: pays out speed·duration = 15 m."""

    def smooth(t: float) -> float:
        s = min(max(t / ramp, 0.0), 1.0)
        return s * s * (3.0 - 2.0 * s)

    return speed * (smooth(t) - smooth(t - duration))


def _paying() -> pl.Model:
    """100 m of pipe hanging in 300 m of water from a tensioner (a drive at the origin) at end B, paying out
    15 m: 5 m of heavy-wall pipe, then the A&R wire."""
    model = pl.Model(pl.Rod.straight((0, 0, 100.0), (0, 0, 0), 20, PAID), sea=pl.Sea(300.0))
    model.drive("B", position=lambda t: np.zeros(3))
    model.pay_out("B", speed=_pulse, feed=[(5.0, PAID_HEAVY), (100.0, PAID_WIRE)])
    return model


@pytest.fixture(scope="module")
def paid_through_joints() -> tuple[pl.Simulation, pl.Results]:
    model = _paying()
    simulation = model.simulation(model.static(), dt=0.05)
    return simulation, simulation.run(90.0, progress=False)


def test_pay_out_through_segment_joints_keeps_the_ledger(
    paid_through_joints: tuple[pl.Simulation, pl.Results],
) -> None:
    """Paying out through two joints (pipe → heavy wall → wire): the new elements take the fed sections, the
    ledger closes (E − E0 = supplied − dissipated, pay-out's energy in the supplied work) and the line settles to
    the statics of the same line built whole. An element that changes section keeps its axial force (its
    unstretched length set for the new stiffness), so the joints pass without ringing. Measured when written:
    balance at most 1.2e-7 J of 4.3e6 J; the settled top tension within 2.1e-6 of the statics' and swinging by 0.14 %
    (rms; 6.8 % when a changed element kept its strain instead); 2.0 Newton iterations a step."""
    simulation, results = paid_through_joints
    state = simulation.state
    np.testing.assert_array_equal(state.segment_of, [0] * 20 + [1] + [2] * 2)
    assert [s.is_cable for s in state.sections] == [False, False, True]
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-10 * np.abs(energy).max()
    assert results.pay_out_energy[-1] != 0.0
    whole = pl.Model(
        pl.Rod.segments(
            (0, 0, 115.0),
            (0, 0, -1.0),
            [pl.Segment(100.0, PAID, 20), pl.Segment(5.0, PAID_HEAVY, 1), pl.Segment(10.0, PAID_WIRE, 2)],
        ),
        sea=pl.Sea(300.0),
    )
    whole.pin("B", (0.0, 0.0, 0.0))
    expected = np.linalg.norm(whole.static().reaction("B")[:3])
    late = results.time > 70.0
    top = np.linalg.norm(results.reaction("B")[late, :3], axis=1)
    assert top.mean() == pytest.approx(expected, rel=2e-5)
    assert top.std() < 5e-3 * expected
    assert np.mean(results.iterations[1:]) < 2.5
    # The record keeps each element's segment; the rows of the shorter meshes end in NaN.
    np.testing.assert_array_equal(results.segment[-1], state.segment_of)
    np.testing.assert_array_equal(results.segment[0], [0] * 20 + [np.nan] * 3)


def test_segments_survive_netcdf_and_checkpoints(
    tmp_path: Path, paid_through_joints: tuple[pl.Simulation, pl.Results]
) -> None:
    """The segment record round-trips through netCDF; a run resumed from a checkpoint taken after the first
    joint passed continues bit for bit."""
    _, results = paid_through_joints
    back = pl.load(results.to_netcdf(tmp_path / "paid.nc"))
    np.testing.assert_array_equal(back.segment, results.segment)
    model = _paying()
    part = model.simulation(model.static(), dt=0.05)
    part.run(30.0, progress=False)
    assert 1 in part.state.segment_of
    resumed = pl.resume(_paying(), part.checkpoint(tmp_path / "paid.npz"))
    resumed.run(90.0, progress=False)
    simulation, _ = paid_through_joints
    assert np.array_equal(resumed.state.positions, simulation.state.positions)
    np.testing.assert_array_equal(resumed.state.segment_of, simulation.state.segment_of)


def test_a_feed_needs_a_pay_out_and_parts_of_positive_length() -> None:
    model = pl.Model(pl.Rod.straight((0, 0, 100.0), (0, 0, 0), 20, PAID), sea=pl.Sea(300.0))
    model.drive("B", position=lambda t: np.zeros(3))
    with pytest.raises(pl.InputError, match=r"feed\[1\] length"):
        model.pay_out("B", speed=0.5, feed=[(5.0, PAID_HEAVY), (0.0, PAID_WIRE)])


def test_a_cable_in_water_keeps_its_energy_with_added_mass_by_direction() -> None:
    """A 300 m wire in water (no gravity, no drag: nothing supplied or dissipated once released), pulled apart
    and sideways for 2 s, then 1100 steps in free flight with added mass 0 along and 1 across it: the energy
    (its axial added mass acting along each element's chord) is constant to round-off and the linear momentum
    too. The chord forces of the discrete gradient are not moment-free, so the angular momentum drifts
    slightly. Measured when written: energy 4.4e-11, linear momentum 3.7e-14, angular momentum 8.0e-5."""
    axis = np.array([0.6, 0.0, 0.8])
    section = pl.Section.cable(0.08, 28.0, 5.5e8, drag=(0.0, 0.0), added_mass=(0.0, 1.0))
    rod = pl.Rod.straight((0.0, 0.0, 0.0), tuple(300.0 * axis), 30, section)
    model = pl.Model(rod, sea=pl.Sea(5000.0), gravity=0.0)
    side, out = np.array([0.0, 1.0, 0.0]), np.cross(axis, [0.0, 1.0, 0.0])

    def loads_on(t: float) -> float:
        return 1.0 if t < 2.0 else 0.0

    model.point_load("B", force=tuple(1e6 * axis + 5e4 * side + 2e4 * out), scale=loads_on)
    model.point_load("A", force=tuple(-1e6 * axis - 2.5e4 * side), scale=loads_on)
    simulation = model.simulation(state=model.rest(), dt=0.05)
    simulation.run(3.0, progress=False)
    energy = simulation.state.energy()["total"]
    linear = np.array(simulation.linear_momentum())
    angular = np.array(simulation.angular_momentum())
    results = simulation.run(58.0, progress=False, record_every=10)
    assert np.max(np.abs(results.energy["total"] - energy)) < 1e-9 * energy
    assert np.linalg.norm(np.array(simulation.linear_momentum()) - linear) < 1e-12 * np.linalg.norm(linear)
    assert np.linalg.norm(np.array(simulation.angular_momentum()) - angular) < 1e-3 * np.linalg.norm(angular)
    assert results.supplied_work[-1] == 0.0 and results.dissipated[-1] == 0.0


def test_a_wire_paid_out_from_its_end_keeps_the_ledger_and_settles() -> None:
    """100 m of pipe hanging on 50 m of wire, the wire paid out 15 m at its top (a winch: a drive at the
    origin). The ledger closes, the line settles to the statics of the same line with 65 m of wire, and the
    energy pay-out brings in is the winch's work −∫T v dt; Newton takes two iterations a step, as for a pipe.
    Measured when written: balance 3.1e-8 J of 7.9e6 J; top tension within 2.2e-6 of the statics'; pay-out
    energy within 6e-6 of the winch's work; 2.0 iterations a step (7.9 when both levels' strains were taken
    at the growing length, which slackened the growing element's start)."""
    wire = pl.Section.cable(0.08, 28.0, 5.5e8)

    def line(wire_length: float, elements: int) -> pl.Rod:
        segments = [pl.Segment(100.0, PAID, 20), pl.Segment(wire_length, wire, elements)]
        return pl.Rod.segments((0.0, 0.0, 100.0 + wire_length), (0.0, 0.0, -1.0), segments)

    model = pl.Model(line(50.0, 10), sea=pl.Sea(400.0))
    model.drive("B", position=lambda t: np.zeros(3))
    model.pay_out("B", speed=_pulse)
    results = model.simulation(model.static(), dt=0.05).run(90.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-12 * np.abs(energy).max()
    assert results.length[-1] == pytest.approx(165.0, abs=1e-9)
    assert np.nanmax(results.segment[-1]) == 1.0 and np.sum(results.segment[-1] == 1.0) == 13
    assert np.mean(results.iterations[1:]) < 2.5
    longer = pl.Model(line(65.0, 13), sea=pl.Sea(400.0))
    longer.pin("B", (0.0, 0.0, 0.0))
    expected = np.linalg.norm(longer.static().reaction("B")[:3])
    top = np.linalg.norm(results.reaction("B")[:, :3], axis=1)
    assert top[results.time > 70.0].mean() == pytest.approx(expected, rel=2e-5)
    speed = np.array([_pulse(t) for t in 0.5 * (results.time[1:] + results.time[:-1])])
    winch_work = -np.sum(top[1:] * speed * np.diff(results.time))
    assert results.pay_out_energy[-1] == pytest.approx(winch_work, rel=5e-5)


def test_a_wire_swept_across_the_seabed_feels_the_lateral_friction() -> None:
    """A 100 m wire lying on the seabed along e1, pinned at A, its end B driven round A at 0.01 rad/s until it
    lies along e2: it then slides sideways, so the seabed's friction is its lateral coefficient (1.0), not the
    axial one (0.2), and the force B needs to turn it is about μ_l w L/2 (the wire bows under the friction it
    drags, having no bending stiffness, which lowers it a little). A cable node has no rotation of its own, so
    the friction's directions follow its chords. Measured when written: 10 591 N against μ_l w L/2 = 11 207 N
    (2 205 N, the axial friction, when the directions stayed with the nodes' reference frames); ledger balance
    1.4e-7 J."""
    wire = pl.Section.cable(0.08, 28.0, 5.5e8, drag=(0.0, 0.0), added_mass=(0.0, 0.0))
    length = 100.0
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (length, 0.0, 0.0), 20, wire)
    model = pl.Model(rod, sea=pl.Sea(100.0, seabed=pl.Seabed(stiffness=1e6, friction=(0.2, 1.0))))
    model.pin("A", (0.0, 0.0, 0.0))
    omega, ramp = 0.01, 20.0

    def angle(t: float) -> float:
        """Turned by ω(t − ramp/2) after a smooth start over `ramp` s (rad)."""
        s = min(t / ramp, 1.0)
        return omega * (t - ramp / 2.0) if t > ramp else omega * ramp * s**3 * (1.0 - s / 2.0)

    model.drive("B", lambda t: (length * math.cos(angle(t)), length * math.sin(angle(t)), 0.0))
    results = model.simulation(model.static(), dt=0.1).run(180.0, progress=False)
    turned = np.array([angle(t) for t in results.time])
    force = results.reaction("B")[:, :3]
    # The force B's drive applies across the line, against the friction (the rod's on B is its opposite).
    across = force[:, 0] * np.sin(turned) - force[:, 1] * np.cos(turned)
    late = results.time > 150.0
    lateral = 1.0 * wire.submerged_weight * length / 2.0
    assert math.degrees(turned[-1]) > 90.0
    assert across[late].mean() == pytest.approx(lateral, rel=0.1)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-10 * results.dissipated[-1]
