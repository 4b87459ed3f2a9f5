"""Stages of a lay and the A&R winch in scenario files: `[vessel.winch]` (with its wire and head) and
`[[stages]]` build the same `pl.Winch` and `pl.Stages` as the Python API, the run goes through them, the
length paid out is the integral of their ramped speeds, and a bad stage names `stages[k].key`."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.cli import main, start_simulation
from pipelay.scenario import Scenario, load_scenario

ANGLE = 0.2  # rad: the tower's lean from vertical
TOWER = (0.0, 0.0, -10.0)  # the tower exit, body frame (m)
UP = 5.0  # m: the winch's distance up the tower from its exit
WINCH = (TOWER[0] + UP * math.sin(ANGLE), 0.0, TOWER[2] - UP * math.cos(ANGLE))
DT = 0.5
EA_WIRE = 5.5e8

# A short J-lay in 150 m of water: 600 m of the 0.6 m × 25 mm pipe in 60 elements, the winch 5 m up the
# tower; 20 s of lay at 0.3 m/s, a 10 s hand-over to the winch, 20 s of lowering at 0.5 m/s.
STAGED = f"""\
title = "a short J-lay handed over to its A&R winch"

[pipe]
outer_diameter = 0.6
wall_thickness = 0.025
contents_density = 0.0
drag = [0.0, 1.0]
added_mass = [0.0, 1.0]

[rod]
start = [0.0, 0.0, 0.0]
end = [600.0, 0.0, 0.0]
elements = 60

[sea]
depth = 150.0

[sea.seabed]
stiffness = 1e5
friction = [0.5, 0.5]
mobilisation = 0.02

[supports.A]
kind = "pin"

[vessel]
end = "B"
model = "osv"
eta = [520.0, 0.0, -150.0, 0.0, 0.0, 0.0]

[vessel.lay]
kind = "j-lay"
position = {list(TOWER)}
angle = {ANGLE!r}

[vessel.winch]
position = {list(WINCH)}
tension_limit = 2e6
element_length = 10.0

[vessel.winch.wire]
diameter = 0.08
mass = 28.0
EA = 5.5e8
drag = [0.0, 1.2]
added_mass = [0.0, 1.0]

[vessel.winch.head]
mass = 5000.0
volume = 0.8
drag_area = 1.0
added_mass = 1.0

[controller]
kp = [2e5, 2e5, 0, 0, 0, 1e7]
kd = [4e6, 4e6, 0, 0, 0, 1e8]
reference = [520.0, 0.0, -150.0, 0.0, 0.0, 0.0]

[[stages]]
name = "lay"
duration = 20.0
pay_out = 0.3
route_speed = 0.3

[[stages]]
name = "hand-over"
duration = 10.0
hold = "winch"

[[stages]]
name = "lower"
duration = 20.0
winch_speed = 0.5

[solver]
dt = {DT}
"""


def write(tmp_path: Path, text: str = STAGED, name: str = "staged.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def by_hand(with_winch: bool = True) -> tuple[pl.Model, pl.Stages]:
    """The scenario's model and stages made with the Python API (`with_winch`: its winch too)."""
    pipe = pl.Section.pipe(0.6, 0.025, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0))
    seabed = pl.Seabed(stiffness=1e5, friction=(0.5, 0.5), mobilisation=0.02)
    model = pl.Model(pl.Rod.straight((0, 0, 0), (600, 0, 0), 60, pipe), sea=pl.Sea(150.0, seabed=seabed))
    model.pin("A")
    wire = pl.Section.cable(diameter=0.08, mass=28.0, EA=EA_WIRE, drag=(0.0, 1.2), added_mass=(0.0, 1.0))
    head = pl.Clump(5000.0, 0.8, 1.0, 1.0)
    winch = pl.Winch(WINCH, 2e6, wire=wire, element_length=10.0, head=head) if with_winch else None
    eta = [520.0, 0.0, -150.0, 0.0, 0.0, 0.0]
    pid = pl.PID(kp=[2e5, 2e5, 0, 0, 0, 1e7], kd=[4e6, 4e6, 0, 0, 0, 1e8], reference=eta)
    lay = pl.JLay(TOWER, ANGLE)
    model.attach_vessel("B", pl.Vessel.osv(), eta=eta, lay=lay, controller=pid, winch=winch)
    stages = pl.Stages(
        [
            pl.Stage("lay", 20.0, pay_out=0.3, route_speed=0.3),
            pl.Stage("hand-over", 10.0, hold="winch"),
            pl.Stage("lower", 20.0, winch_speed=0.5),
        ]
    )
    return model, stages


def travelled(legs: list[tuple[float, float, float]], t: float) -> float:
    """∫ v dt from 0 to t (m) of a speed in legs (start s, speed m/s, ramp s), each changing linearly from
    the speed before it (0 before the first) to its own over its ramp, and lasting until the next starts."""
    distance, before = 0.0, 0.0
    for k, (start, speed, ramp) in enumerate(legs):
        if t <= start:
            break
        end = legs[k + 1][0] if k + 1 < len(legs) else math.inf
        span = min(t, end) - start
        rising = min(ramp, span)
        reached = before + (speed - before) * rising / ramp if ramp > 0 else speed
        distance += 0.5 * (before + reached) * rising + speed * max(span - ramp, 0.0)
        before = reached
    return distance


# The pay-out speed of the stages, by their rules: each stage's change takes its ramp (10 s, the default, or
# the duration if shorter); the hand-over stops the tensioner's 0.3 m/s (the winch's brake holds once it has
# ramped to 0), and the winch then pays out at 0.5 m/s.
PAY_OUT = [(0.0, 0.3, 10.0), (20.0, 0.0, 10.0), (30.0, 0.5, 10.0)]
PAID = 0.3 * 10 / 2 + 0.3 * 10 + 0.3 * 10 / 2 + 0.5 * 10 / 2 + 0.5 * 10  # 13.5 m by t = 50 s


@pytest.fixture(scope="module")
def staged(tmp_path_factory: pytest.TempPathFactory) -> tuple[Scenario, pl.Simulation, pl.Results]:
    """The scenario read from its file and run through its stages, as `pipelay run` starts it."""
    scenario = load_scenario(write(tmp_path_factory.mktemp("staged")))
    simulation = start_simulation(scenario)
    return scenario, simulation, simulation.run(scenario.t_end, progress=False)


def test_the_file_builds_the_stages_of_the_python_api(
    staged: tuple[Scenario, pl.Simulation, pl.Results],
) -> None:
    """The file's stages are the API's: names, durations, starts; the run ends at the end of the stages (no
    solver.t_end), and the file's model and stages run exactly as the API's."""
    scenario, simulation, results = staged
    model, stages = by_hand()
    assert scenario.stages is not None
    assert scenario.stages.names == stages.names == ["lay", "hand-over", "lower"]
    assert scenario.stages.duration == stages.duration == 50.0
    assert scenario.t_end == 50.0 and simulation.stages_end == 50.0
    assert results.stage_names == ["lay", "hand-over", "lower"]
    np.testing.assert_array_equal(results.stage_starts, [0.0, 20.0, 30.0, 50.0])
    wire = scenario.model.rod.sections[1]  # attach_vessel adds the winch's wire to the line's sections
    assert wire.is_cable and (wire.EA, wire.mass, wire.drag, wire.damping) == (EA_WIRE, 28.0, (0.0, 1.2), 0.0)
    api = model.simulation(model.static(), dt=DT, stages=stages).run(progress=False)
    np.testing.assert_array_equal(api.time, results.time)
    np.testing.assert_array_equal(api.positions, results.positions)
    np.testing.assert_array_equal(api.length, results.length)


def test_the_run_goes_through_every_stage(staged: tuple[Scenario, pl.Simulation, pl.Results]) -> None:
    """A record per step to t = 50 s; each stage has duration/dt records (the first record opens stage 0);
    the hand-over puts the wire at the line's top and the vessel follows the route at the stages' speed."""
    _, simulation, results = staged
    assert results.time[-1] == pytest.approx(50.0, abs=1e-12) and len(results.time) == 101
    counts = np.bincount(results.stage)
    assert counts.tolist() == [1 + round(20.0 / DT), round(10.0 / DT), round(20.0 / DT)] == [41, 20, 40]
    assert simulation.hand_over_tension is not None and simulation.hand_over_tension > 0.0
    segment = results.segment
    before = int(np.flatnonzero(results.time == 20.0)[0])
    top = [int(np.flatnonzero(np.isfinite(row))[-1]) for row in segment[[before, -1]]]
    assert segment[before, top[0]] == 0 and segment[-1, top[1]] == 1  # pipe, then the wire (section 1)
    route = 520.0 + travelled([(0.0, 0.3, 10.0)], 50.0)  # 533.5 m: the DP reference at t = 50 s
    print(f"vessel x {results.eta[-1, 0]:.3f} m, reference {route:.3f} m")
    assert results.eta[-1, 0] == pytest.approx(route, abs=0.5)


def test_the_length_paid_out_is_the_integral_of_the_ramped_speeds(
    staged: tuple[Scenario, pl.Simulation, pl.Results],
) -> None:
    """At every record the line's unstretched length has grown by ∫ v dt of the stages' ramped speeds (4.5 m
    of pipe by the hand-over at 20 s, 13.5 m in all by 50 s), plus, from the hand-over on, the wire from the
    winch to the tower exit: 5 m stretched to the axial force it took on, unstretched 5/(1 + T/EA)."""
    _, simulation, results = staged
    tension = simulation.hand_over_tension
    assert tension is not None
    wire = UP / (1.0 + tension / EA_WIRE)
    assert travelled(PAY_OUT, 20.0) == pytest.approx(4.5, abs=1e-12)
    assert travelled(PAY_OUT, 50.0) == pytest.approx(PAID, abs=1e-12) and PAID == pytest.approx(13.5)
    expected = [travelled(PAY_OUT, t) + (wire if t > 20.0 else 0.0) for t in results.time]
    paid = results.length - results.length[0]
    print(
        f"paid out {paid[-1]:.9f} m, expected {expected[-1]:.9f} m (wire {wire:.9f} m, T = {tension:.1f} N)"
    )
    np.testing.assert_allclose(paid, expected, rtol=0.0, atol=1e-9)
    assert paid[-1] == pytest.approx(13.5 + wire, abs=1e-9)


def test_pipelay_run_and_resume_go_through_the_stages(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`pipelay check` lists the stages; `pipelay run` to 25 s (within the hand-over) with a checkpoint, then
    resumed to the end of the stages, ends where the uninterrupted run ends."""
    path = write(tmp_path)
    assert main(["check", str(path)]) == 0
    assert "through 3 stages (lay, hand-over, lower)" in capsys.readouterr().out
    whole, first, rest = tmp_path / "whole.nc", tmp_path / "first.nc", tmp_path / "rest.nc"
    assert main(["run", str(path), "-o", str(whole), "--no-progress"]) == 0
    cut = write(tmp_path, STAGED.replace("dt = 0.5", "dt = 0.5\nt_end = 25.0"), "cut.toml")
    state = tmp_path / "state.npz"
    assert main(["run", str(cut), "-o", str(first), "--no-progress", "--checkpoint", str(state)]) == 0
    assert main(["run", str(path), "-o", str(rest), "--no-progress", "--resume", str(state)]) == 0
    capsys.readouterr()
    ended, resumed = pl.load(whole), pl.load(rest)
    assert pl.load(first).time[-1] == pytest.approx(25.0) and resumed.time[-1] == pytest.approx(50.0)
    assert resumed.stage_names == ["lay", "hand-over", "lower"]
    np.testing.assert_array_equal(resumed.positions[-1], ended.positions[-1])
    assert resumed.length[-1] == ended.length[-1]


def edited(old: str, new: str) -> str:
    assert old in STAGED, old
    return STAGED.replace(old, new, 1)


WITHOUT_WINCH = STAGED[: STAGED.index("[vessel.winch]")] + STAGED[STAGED.index("[controller]") :]


@pytest.mark.parametrize(
    ("text", "key", "says"),
    [
        (edited("duration = 10.0\n", ""), "stages[1].duration", "missing required key"),
        (edited("winch_speed = 0.5", "winch_speed = 0.5\nspeed = 1.0"), "stages[2].speed", "did you mean"),
        (edited('hold = "winch"', 'hold = "crane"'), "stages[1].hold", '"tensioner" or "winch"'),
        (WITHOUT_WINCH.replace('hold = "winch"\n', ""), "stages[2].winch_speed", "[vessel.winch]"),
        (WITHOUT_WINCH, "stages[1].hold", "[vessel.winch]"),
        (
            edited("duration = 20.0\npay_out", "duration = 20.0\nramp = 30.0\npay_out"),
            "stages[0].ramp",
            "20 s",
        ),
        (edited("duration = 20.0\npay_out", "duration = 20.2\npay_out"), "stages[0].duration", "dt = 0.5"),
        (
            edited("winch_speed = 0.5", "winch_speed = 0.5\nwinch_tension = 5e5"),
            "stages[2].winch_tension",
            "give one of them",
        ),
        (edited("winch_speed = 0.5", "pay_out = 0.5"), "stages[2].pay_out", "winch_speed"),
        (edited("pay_out = 0.3", "winch_speed = 0.3"), "stages[0].winch_speed", "hand over first"),
        (edited("[controller]", "[pay_out]\nspeed = 0.3\n\n[controller]"), "stages[0].pay_out", "[pay_out]"),
        (edited("[vessel.winch.wire]", "[vessel.winch.cable]"), "vessel.winch.cable", "unknown section"),
        (edited("EA = 5.5e8", "EA = -5.5e8"), "vessel.winch.wire.EA", "> 0 N"),
        (edited("EA = 5.5e8", "EA = 5.5e8\ndamping = -1.0"), "vessel.winch.wire.damping", ">= 0 N·s"),
        (edited("mass = 5000.0", "mass = -5000.0"), "vessel.winch.head.mass", ">= 0 kg"),
        (
            edited(f"position = {list(WINCH)}", "position = [1.0, 0.0, -20.0]"),
            "vessel.winch.position",
            "ahead",
        ),
        (edited("tension_limit = 2e6", "tension_limit = 0.0"), "vessel.winch.tension_limit", "> 0 N"),
    ],
    ids=[
        "no duration",
        "unknown key",
        "crane",
        "winch_speed without a winch",
        "hold without a winch",
        "ramp beyond the stage",
        "part of a step",
        "speed and tension",
        "pay_out after the hand-over",
        "winch_speed before it",
        "two pay-outs",
        "wire misspelt",
        "wire EA",
        "wire damping",
        "head mass",
        "winch off the tower",
        "tension limit",
    ],
)
def test_bad_stages_and_winches_name_their_key(tmp_path: Path, text: str, key: str, says: str) -> None:
    """Each is an InputError that starts with the key path at fault and ends with the file."""
    path = write(tmp_path, text)
    with pytest.raises(pl.InputError) as caught:
        load_scenario(path)
    message = str(caught.value)
    assert message.startswith(f"{key}: "), message
    assert says in message and message.endswith(f"(in {path})"), message


def test_the_engine_refuses_the_same_stages_with_the_same_key() -> None:
    """Stages given to a model without a winch: the engine's own check names the same keys as the file's."""
    bare, _ = by_hand(with_winch=False)
    state = bare.static()
    with pytest.raises(pl.InputError, match=r"^stages\[0\]\.winch_speed"):
        bare.simulation(state, dt=DT, stages=pl.Stages([pl.Stage("lower", 10.0, winch_speed=0.5)]))
    with pytest.raises(pl.InputError, match=r"^stages\[1\]\.hold"):
        bare.simulation(
            state, dt=DT, stages=pl.Stages([pl.Stage("a", 1.0), pl.Stage("b", 1.0, hold="winch")])
        )


def test_t_end_defaults_to_the_end_of_the_stages(tmp_path: Path) -> None:
    """Without solver.t_end the run ends with the stages (50 s), plot times included; a t_end given is the
    run's end (the last stage's speeds carry on past the stages' end)."""
    assert load_scenario(write(tmp_path)).t_end == 50.0
    longer = edited("dt = 0.5", "dt = 0.5\nt_end = 80.0") + "\n[output]\nplot_times = [0.0, 80.0]\n"
    assert load_scenario(write(tmp_path, longer)).t_end == 80.0
    with pytest.raises(
        pl.InputError, match=r"^output\.plot_times\[1\]: must be <= the end of the \[\[stages\]\] = 50 s"
    ):
        load_scenario(write(tmp_path, STAGED + "\n[output]\nplot_times = [0.0, 60.0]\n"))


def test_the_wire_takes_the_cable_keys(tmp_path: Path) -> None:
    """[vessel.winch.wire] takes every key of pl.Section.cable, its axial damping among them."""
    scenario = load_scenario(write(tmp_path, edited("EA = 5.5e8", "EA = 5.5e8\ndamping = 2e5")))
    assert scenario.model.rod.sections[1].damping == 2e5
