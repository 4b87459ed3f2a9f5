"""Station keeping in scenario files: `[sea.wind]`, the vessel's `hull_loads`, `length`, `[[vessel.thrusters]]`
and hull tables, `controller.allocation` and `[controller.observer]` reach the API, bad values name their key,
and examples/j_lay_dp.toml holds station in wind, current and waves."""

from __future__ import annotations

import copy
import math
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import KEYS, json_schema, load_scenario, parse_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
OSV = pl.Vessel.osv()
# PID gains by pole placement on diag(M) (ω_n = 0.1, 0.1, 0.2 rad/s in surge, sway, yaw; ζ = 1).
OMEGA = np.array([0.1, 0.1, 0, 0, 0, 0.2])
KP = OMEGA**2 * np.diag(OSV.M)
KD = 2 * OMEGA * np.diag(OSV.M)
KI = 0.1 * OMEGA * KP
_TABLES = ("wind_coefficients", "current_coefficients", "drift_coefficients")

WIND_TABLE = """\
angle_deg,surge,sway,heave,roll,pitch,yaw
0,300,0,0,0,0,0
90,0,700,0,0,0,-2000
180,-250,0,0,0,0,0
270,0,-700,0,0,0,2000
"""
CURRENT_TABLE = """\
angle_deg,surge,sway,heave,roll,pitch,yaw
0,20,0,0,0,0,0
90,0,900,0,0,0,-500
180,-20,0,0,0,0,0
270,0,-900,0,0,0,500
"""
DRIFT_TABLE = """\
period_s,heading_deg,surge,sway,heave,roll,pitch,yaw
3,0,800,0,0,0,0,0
3,90,0,4000,0,0,0,100
3,180,-900,0,0,0,0,0
3,270,0,-4000,0,0,0,-100
30,0,10,0,0,0,0,0
30,90,0,50,0,0,0,1
30,180,-10,0,0,0,0,0
30,270,0,-50,0,0,0,-1
"""


def _toml(values: Any) -> str:
    """A vector or matrix as a TOML array, each float exactly (repr)."""
    array = np.asarray(values, dtype=float)
    if array.ndim == 1:
        return "[" + ", ".join(repr(float(x)) for x in array) + "]"
    return "[" + ", ".join(_toml(row) for row in array) + "]"


# A light 10 m rod hanging from CO of a vessel given by the OSV's matrices, with thrusters and tables of its
# own (every key away from its default), in wind, current and waves, under the observer-based PID.
SCENARIO = f"""
[section]
EA = 1e7
GA = 1e7
GJ = 1e4
EI = 1e4
mass = 30.0
outer_diameter = 0.1
drag = [1.2, 0.0]
rotational_damping = 1e3

[rod]
start = [10.0, 0.0, 10.0]
end = [10.0, 0.0, 0.0]
elements = 4

[sea]
depth = 100.0

[sea.current]
kind = "uniform"
velocity = [0.0, 0.3, 0.0]

[sea.waves]
kind = "jonswap"
hs = 1.5
tp = 8.0
direction = 2.5
seed = 2
components = 50

[sea.wind]
speed = 12.0
direction = 2.0
spectrum = "NPD"
seed = 3

[vessel]
end = "B"
eta = [10.0, 0.0, -100.0, 0.0, 0.0, 0.0]
angle = [0.0, {-math.pi / 2!r}, 0.0]
M = {_toml(OSV.M)}
D = {_toml(OSV.D)}
G = {_toml(OSV.G)}
M_RB = {_toml(OSV.M_RB)}
hull_loads = true
length = 80.0
wind_coefficients = "wind.csv"
current_coefficients = "current.csv"
drift_coefficients = "drift.csv"

[[vessel.thrusters]]
kind = "tunnel"
position = [30.0, 0.0]
max_thrust = 2e5
reverse_thrust = 1.5e5
thrust_rate = 5e4
time_constant = 0.5

[[vessel.thrusters]]
kind = "azimuth"
position = [-35.0, 7.0]
max_thrust = 4e5
thrust_rate = 2e4
azimuth_rate = 0.1
time_constant = 2.0

[[vessel.thrusters]]
kind = "azimuth"
position = [-35.0, -7.0]
max_thrust = 4e5
thrust_rate = 2e4
azimuth_rate = 0.1
time_constant = 2.0

[[vessel.thrusters]]
kind = "main"
position = [-38.0, 0.0]
max_thrust = 3e5
reverse_thrust = 2e5
time_constant = 1.5

[controller]
kp = {_toml(KP)}
kd = {_toml(KD)}
ki = {_toml(KI)}
reference = [10.5, 0.2, -100.0, 0.0, 0.0, 0.01]
allocation = "qp"

[controller.observer]
noise = [0.1, 0.1, 0.001]
seed = 4
wave_period = 7.5
"""


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    """A folder holding the scenario and its three hull tables."""
    (tmp_path / "wind.csv").write_text(WIND_TABLE)
    (tmp_path / "current.csv").write_text(CURRENT_TABLE)
    (tmp_path / "drift.csv").write_text(DRIFT_TABLE)
    (tmp_path / "dp.toml").write_text(SCENARIO, encoding="utf-8")
    return tmp_path


def _by_the_api(folder: Path) -> pl.Model:
    """SCENARIO's model, built with the Python API."""
    section = pl.Section(
        EA=1e7, GA=1e7, GJ=1e4, EI=1e4, mass=30.0, outer_diameter=0.1, drag=[1.2, 0.0], rotational_damping=1e3
    )
    sea = pl.Sea(
        100.0,
        current=pl.Current.uniform([0.0, 0.3, 0.0]),
        waves=pl.Waves.jonswap(1.5, 8.0, direction=2.5, seed=2, components=50),
        wind=pl.Wind(12.0, direction=2.0, spectrum="NPD", seed=3),
    )
    azimuth = {"thrust_rate": 2e4, "azimuth_rate": 0.1, "time_constant": 2.0}
    thrusters = [
        pl.Thruster("tunnel", (30.0, 0.0), 2e5, reverse_thrust=1.5e5, thrust_rate=5e4, time_constant=0.5),
        pl.Thruster("azimuth", (-35.0, 7.0), 4e5, **azimuth),
        pl.Thruster("azimuth", (-35.0, -7.0), 4e5, **azimuth),
        pl.Thruster("main", (-38.0, 0.0), 3e5, reverse_thrust=2e5, time_constant=1.5),
    ]
    vessel = pl.Vessel(
        OSV.M,
        OSV.D,
        OSV.G,
        M_RB=OSV.M_RB,
        length=80.0,
        thrusters=thrusters,
        wind_coefficients=pl.HullCoefficients.read(folder / "wind.csv"),
        current_coefficients=pl.HullCoefficients.read(folder / "current.csv"),
        drift_coefficients=pl.DriftCoefficients.read(folder / "drift.csv"),
    )
    controller = pl.PID(
        kp=KP,
        kd=KD,
        ki=KI,
        reference=[10.5, 0.2, -100.0, 0.0, 0.0, 0.01],
        allocation="qp",
        observer=pl.Observer.passive(noise=(0.1, 0.1, 0.001), seed=4, wave_period=7.5),
    )
    model = pl.Model(pl.Rod.straight((10.0, 0.0, 10.0), (10.0, 0.0, 0.0), 4, section), sea)
    model.attach_vessel(
        "B",
        vessel,
        eta=[10.0, 0.0, -100.0, 0.0, 0.0, 0.0],
        angle=[0.0, -math.pi / 2, 0.0],
        controller=controller,
        hull_loads=True,
    )
    return model


def _run(model: pl.Model, t_end: float = 20.0) -> pl.Results:
    return model.simulation(model.static(), dt=0.5).run(t_end, progress=False)


RECORDS = ("eta", "eta_low_frequency", "eta_estimate", "thrust", "azimuth", "tau_commanded", "tau", "chi")


def test_every_key_reaches_the_api(folder: Path) -> None:
    """A 20 s run of the scenario, its hull tables read from its folder, is the API's run of the same model
    record for record: every new key is passed as given (each is away from the API's default, so one left
    behind changes the run; `length`, which only bounds the thrusters' positions, shows in the error naming
    L/2 = 40 m below), and the run records the four thrusters and the observer's estimate."""
    scenario = load_scenario(folder / "dp.toml")
    results = _run(scenario.model)
    assert results.thrust is not None and results.thrust.shape == (41, 4)
    assert results.eta_estimate is not None
    twin = _run(_by_the_api(folder))
    for name in RECORDS:
        assert np.array_equal(getattr(results, name), getattr(twin, name)), name
    # The tunnel pushes athwartships, the main propeller ahead; the azimuth thrusters turn.
    assert results.azimuth is not None
    assert np.allclose(results.azimuth[:, 0], math.pi / 2) and np.allclose(results.azimuth[:, 3], 0.0)
    assert np.ptp(results.azimuth[:, 1]) > 0.01


def test_hull_loads_and_the_observer_change_the_run(folder: Path) -> None:
    """`hull_loads = false` leaves the wind, current and drift off the hull; without `[controller.observer]`
    there is no estimate and the PID sees the true pose; without `allocation` no thruster is recorded."""
    data = tomllib.loads(SCENARIO)
    base = _run(parse_scenario(data, "dp", folder).model)
    calm = copy.deepcopy(data)
    calm["vessel"]["hull_loads"] = False
    assert not np.array_equal(_run(parse_scenario(calm, "dp", folder).model).eta, base.eta)
    blind = copy.deepcopy(data)
    del blind["controller"]["observer"]
    seen = _run(parse_scenario(blind, "dp", folder).model)
    assert seen.eta_estimate is None and not np.array_equal(seen.eta, base.eta)
    direct = copy.deepcopy(data)
    del direct["controller"]["allocation"]
    assert _run(parse_scenario(direct, "dp", folder).model).thrust is None


def test_the_wind_is_the_tables(folder: Path) -> None:
    """`[sea.wind]` is `pl.Wind(speed, direction, spectrum, seed)`: its gusts are those of its seed, and
    `spectrum = "none"` is a steady wind."""
    data = tomllib.loads(SCENARIO)
    wind = parse_scenario(data, "dp", folder).model.sea.wind
    assert wind is not None and (wind.speed, wind.direction) == (12.0, 2.0)
    times = np.linspace(0.0, 600.0, 7)
    same = pl.Wind(12.0, direction=2.0, seed=3)
    assert [wind.speed_at(t) for t in times] == [same.speed_at(t) for t in times]
    assert [wind.speed_at(t) for t in times] != [pl.Wind(12.0, seed=0).speed_at(t) for t in times]
    data["sea"]["wind"] = {"speed": 8.0, "spectrum": "none"}
    steady = parse_scenario(data, "dp", folder).model.sea.wind
    assert steady is not None and steady.direction == 0.0
    assert {steady.speed_at(t) for t in times} == {8.0}


def test_the_osv_with_its_own_thrusters(folder: Path) -> None:
    """`model = "osv"` allocates to its own six thrusters and carries its own tables into `hull_loads`."""
    data = tomllib.loads(SCENARIO)
    vessel = data["vessel"]
    for key in ("M", "D", "G", "M_RB", "length", "thrusters", *_TABLES):
        del vessel[key]
    vessel["model"] = "osv"
    results = _run(parse_scenario(data, "dp", folder).model)
    assert results.thrust is not None and results.thrust.shape[1] == 6
    assert results.eta_estimate is not None


def edited(path: tuple[str | int, ...], value: object) -> dict[str, Any]:
    """SCENARIO with the value at `path` replaced (None: removed)."""
    data = tomllib.loads(SCENARIO)
    node = data
    for key in path[:-1]:
        node = node[key]
    if value is None:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return data


def _osv(*extra: str) -> dict[str, Any]:
    """SCENARIO with `model = "osv"` instead of the matrices, keeping the keys `extra` of the matrix vessel."""
    data = tomllib.loads(SCENARIO)
    for key in {"M", "D", "G", "M_RB", "length", "thrusters", *_TABLES} - set(extra):
        del data["vessel"][key]
    data["vessel"]["model"] = "osv"
    return data


THRUSTER = ("vessel", "thrusters", 0)


@pytest.mark.parametrize(
    ("data", "says"),
    [
        (
            edited((*THRUSTER, "max_thrust"), -1.0),
            r"vessel\.thrusters\[0\]\.max_thrust: must be > 0 N, got -1",
        ),
        (
            edited((*THRUSTER, "max_thrust"), None),
            r"vessel\.thrusters\[0\]\.max_thrust: missing required key",
        ),
        (edited((*THRUSTER, "kind"), "bow"), r'vessel\.thrusters\[0\]\.kind: must be "tunnel", "azimuth" or'),
        (edited((*THRUSTER, "max_trust"), 1.0), r"vessel\.thrusters\[0\]\.max_trust: unknown key; did you"),
        (
            edited((*THRUSTER, "azimuth_rate"), 0.1),
            r'vessel\.thrusters\[0\]\.azimuth_rate: only kind = "azimuth" turns',
        ),
        (
            edited(("vessel", "thrusters", 1, "reverse_thrust"), 1e5),
            r"vessel\.thrusters\[1\]\.reverse_thrust: an azimuth thruster turns",
        ),
        (
            edited(("vessel", "thrusters", 1, "position"), [1.0, 2.0, 3.0]),
            r"vessel\.thrusters\[1\]\.position: must be 2 numbers \[l_x, l_y\] \(m\), got 3",
        ),
        (
            edited(("vessel", "thrusters", 3, "position"), [-50.0, 0.0]),
            r"vessel\.thrusters\[3\]\.position: must lie on the hull: \|l_x\| ≤ L/2 = 40 m",
        ),
        (edited(("vessel", "thrusters"), {"kind": "main"}), r"vessel\.thrusters: must be an array of tables"),
        (edited(("vessel", "length"), None), r"vessel\.length: must be given with thrusters"),
        (edited(("vessel", "length"), 0.0), r"vessel\.length: must be > 0 m, got 0"),
        (edited(("vessel", "hull_loads"), "yes"), r"vessel\.hull_loads: must be true or false, got 'yes'"),
        (
            edited(("vessel", "wind_coefficients"), None),
            r"vessel\.wind_coefficients: must be given for the wind to act on the hull",
        ),
        (
            edited(("vessel", "wind_coefficients"), "none.csv"),
            r"vessel\.wind_coefficients: must be a table of hull coefficients \(CSV\) relative to the scenario",
        ),
        (
            edited(("vessel", "current_coefficients"), "drift.csv"),
            r'vessel\.current_coefficients: must have a column "angle_deg"',
        ),
        (
            edited(("vessel", "drift_coefficients"), "wind.csv"),
            r'vessel\.drift_coefficients: must have a column "period_s"',
        ),
        (
            _osv("thrusters"),
            r'vessel\.thrusters: conflicts with model = "osv": the OSV has its own thrusters',
        ),
        (_osv("length"), r'vessel\.length: conflicts with model = "osv": the OSV has its own thrusters and'),
        (
            _osv("drift_coefficients"),
            r'vessel\.drift_coefficients: conflicts with model = "osv": the OSV has',
        ),
        (edited(("sea", "wind", "speed"), -1.0), r"sea\.wind\.speed: must be >= 0 m/s, got -1"),
        (edited(("sea", "wind", "speed"), None), r"sea\.wind\.speed: missing required key"),
        (edited(("sea", "wind", "spectrum"), "jonswap"), r'sea\.wind\.spectrum: must be "NPD" or "none"'),
        (edited(("sea", "wind", "seed"), 1.5), r"sea\.wind\.seed: must be an integer >= 0, got 1\.5"),
        (edited(("controller", "allocation"), "lp"), r'controller\.allocation: must be "qp", got \'lp\''),
        (edited(("vessel", "thrusters"), None), r"controller\.allocation: needs a vessel with thrusters"),
        (
            edited(("controller", "observer", "noise"), [0.1, -0.1, 0.0]),
            r"controller\.observer\.noise\[1\]: must be >= 0 \(m, m, rad\), got -0\.1",
        ),
        (
            edited(("controller", "observer", "wave_period"), 0.0),
            r"controller\.observer\.wave_period: must be > 0 and <= 60 s, got 0",
        ),
        (edited(("controller", "observer", "gain"), 1.0), r"controller\.observer\.gain: unknown key"),
    ],
)
def test_bad_values_name_the_key(folder: Path, data: dict[str, Any], says: str) -> None:
    """A bad value of a new key raises InputError naming the key, what is wrong and the file."""
    with pytest.raises(pl.InputError, match=rf"^{says}.*\(in dp\)$"):
        parse_scenario(data, "dp", folder)


def _leaves(data: Any, path: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """The paths of every table, array and value under `data`."""
    if path:
        yield path
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        yield from _leaves(value, (*path, key))


NEW = (
    ("sea", "wind"),
    ("vessel", "thrusters"),
    ("vessel", "length"),
    ("vessel", "hull_loads"),
    *(("vessel", table) for table in _TABLES),
    ("controller", "allocation"),
    ("controller", "observer"),
)
BAD_VALUES: list[object] = ["abc", True, -1, 0, 2.5, math.nan, -math.inf, [], [1.0], [[1.0]], {}, {"x": 1}]


def test_no_other_exception_escapes(folder: Path) -> None:
    """Replacing or removing any value of the new keys gives a Scenario or an InputError naming a key."""
    base = tomllib.loads(SCENARIO)
    tried = 0
    for path in _leaves(base):
        if not any(path[: len(prefix)] == prefix for prefix in NEW):
            continue
        for value in [*BAD_VALUES, None]:
            tried += 1
            try:
                parse_scenario(edited(path, value), "dp", folder)
            except pl.InputError as error:
                message = str(error)
                assert message.split(".")[0].split(":")[0] in KEYS[""], message
                assert message.endswith("(in dp)"), message
    assert tried > 400


def test_the_schema_knows_the_new_keys() -> None:
    """The JSON Schema accepts the scenario and refuses, at the key, a turning tunnel and a wind without
    speed."""
    validator = jsonschema.Draft202012Validator(json_schema())
    assert not list(validator.iter_errors(tomllib.loads(SCENARIO)))
    turning = edited((*THRUSTER, "azimuth_rate"), 0.1)
    assert list(validator.iter_errors(turning))
    assert list(validator.iter_errors(edited(("sea", "wind", "speed"), None)))


# examples/j_lay_dp.toml


def test_j_lay_dp_example_holds_station() -> None:
    """The first 60 s of examples/j_lay_dp.toml: a J-lay in 15 m/s of gusting wind, a 0.5 m/s current and a
    2.5 m sea, the PID on the passive observer's estimate, its command allocated to the OSV's thrusters.

    The static solve balances the pipe's pull with K_p (the controller acts from t = 0), so the vessel starts
    χ_x/kp_x = 2.0 m aft of the reference at these gains; the integral (time constant 1/(0.1 ω) = 100 s) then
    takes it back. The low-frequency pose stays within 2.5 m of the reference (the estimate's error, up to
    0.4 m with 0.5 m of measurement noise, lets it drift aft a little more first) and is within half its
    starting distance by 60 s; every thruster stays within its capacity; E − E0 = supplied − dissipated to
    1e-8 of the work supplied; the estimate stays within 1 m (and 3σ_ψ in heading) of the low-frequency pose.
    """
    scenario = load_scenario(EXAMPLES / "j_lay_dp.toml")
    state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    results = scenario.model.simulation(state, dt=scenario.dt).run(
        60.0, record_every=scenario.record_every, progress=False
    )
    reference = np.array(scenario.source["controller"]["reference"])
    kp = np.array(scenario.source["controller"]["kp"])
    low = results.eta_low_frequency
    estimate = results.eta_estimate
    thrust = results.thrust
    assert low is not None and estimate is not None and thrust is not None and results.chi is not None
    offset = np.hypot(*(low[:, :2] - reference[:2]).T)
    start = results.chi[0, 0] / kp[0]
    error = np.hypot(*(estimate[:, :2] - low[:, :2]).T)
    energy = results.energy["total"]
    balance = energy - energy[0] - (results.supplied_work - results.dissipated)
    supplied = np.abs(results.supplied_work).max()
    capacity = np.array([t.max_thrust for t in OSV.thrusters])
    reverse = np.array([t.reverse_thrust for t in OSV.thrusters])
    print(
        f"starts {low[0, 0] - reference[0]:.3f} m (χ_x/kp_x {start:.3f} m); offset ≤ {offset.max():.3f} m, "
        f"{offset[-1]:.3f} m at 60 s; estimate within {error.max():.3f} m, "
        f"{np.abs(estimate[:, 5] - low[:, 5]).max():.4f} rad; thrust ≤ {(thrust / capacity).max():.3f} of "
        f"forward, ≥ {(thrust / reverse).min():.3f} of reverse; ledger {np.abs(balance).max():.2e} J of "
        f"{supplied:.3e} J supplied"
    )
    assert low[0, 0] - reference[0] == pytest.approx(start, rel=0.01)
    assert offset.max() < 2.5
    assert offset[-1] < 0.5 * offset[0]
    assert np.all(thrust <= capacity * (1 + 1e-9)) and np.all(thrust >= -reverse * (1 + 1e-9))
    assert supplied > 1e5
    assert np.abs(balance).max() < 1e-8 * supplied
    assert error.max() < 1.0
    assert np.abs(estimate[:, 5] - low[:, 5]).max() < 3 * 0.005
