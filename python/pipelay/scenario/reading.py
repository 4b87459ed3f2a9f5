"""Reading a scenario: a TOML file (`load_scenario`) or its parsed document (`parse_scenario`), checked, then
made into the API calls that build the model, returned as a `Scenario` with its solver settings and outputs.

Imports of pipelay: the package (`pl.Model`, `pl.Vessel`, ...: the engine's classes, looked up there when a
scenario is built), `pipelay.scenario.values`, `pipelay.scenario.models`, `pipelay.scenario.schema` and
`pipelay.scenario.checking`.
"""

from __future__ import annotations

import copy
import math
import os
import re
import tomllib
from collections.abc import Callable, Collection, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, cast

import pipelay as pl
from pipelay.scenario import models
from pipelay.scenario.checking import _check, _folder
from pipelay.scenario.schema import KEYS
from pipelay.scenario.values import End, join

__all__ = ["Scenario", "SmoothStart", "load_scenario", "parse_scenario"]

_PAY_OUT_RAMP = 60.0
"""Default `[pay_out]` ramp (s)."""


@dataclass
class Scenario:
    """A model ready to solve, its solver settings and outputs, as read from a scenario file.

    Attributes:
        model: the model with its supports, loads and vessel.
        dt: time step of the simulation (s).
        high_frequency_damping: ξ of `model.simulation(..., high_frequency_damping=)`; 0: energy conserving.
        t_end: end time of the simulation (s): `solver.t_end`, else the end of the stages; None: statics
            only.
        record_every: record every k-th time step.
        static_steps: initial number of load steps of the static solve; None: the engine's default.
        static_start: Newton's starting shape in statics: "auto", "reference" or "catenary".
        output: the `[output]` table: `plot_times` (list of s, or None when not given).
        checks: the `[checks]` table's keys given, the keyword arguments of `pl.checks.dnv_st_f101` and
            `pl.checks.propagation_buckling` for every utilisation shown ({} without one: their defaults).
        source: the parsed TOML as given (a copy), for provenance.
        stages: the `[[stages]]` as a `pl.Stages`, for `model.simulation(..., stages=)` and `pl.resume(...,
            stages=)`; None without stages.
        origin: where the scenario came from (a file's path, or the name given to `parse_scenario`).
        folder: the folder its relative file paths are relative to (absolute).
    """

    model: pl.Model
    dt: float
    t_end: float | None
    record_every: int
    static_steps: int | None
    static_start: Literal["auto", "reference", "catenary"]
    output: dict[str, Any]
    source: dict[str, Any]
    checks: dict[str, Any] = field(default_factory=dict)
    high_frequency_damping: float = 0.0
    stages: pl.Stages | None = None
    origin: str = "<dict>"
    folder: str | None = None

    def simulation(self, state: pl.State | None = None) -> pl.Simulation:
        """The scenario's simulation from `state` (default: the model's statics with the solver's settings):
        its time step, stages and high-frequency damping."""
        if state is None:
            state = self.model.static(steps=self.static_steps, start=self.static_start)
        return self.model.simulation(  # type: ignore[attr-defined, no-any-return]
            state=state,
            dt=self.dt,
            stages=self.stages,
            high_frequency_damping=self.high_frequency_damping,
        )


@dataclass(frozen=True)
class SmoothStart:
    """A speed that rises smoothly from 0 at `start_time` to `speed` over `ramp`: v(t) = speed · (3s² − 2s³),
    s = (t − start_time)/ramp clipped to [0, 1] (a step at start_time when ramp = 0); the `[pay_out]` speed.

    Attributes:
        speed: the final speed (m/s).
        start_time: when it starts rising (s).
        ramp: how long it takes to reach `speed` (s), ≥ 0.
    """

    speed: float
    start_time: float = 0.0
    ramp: float = _PAY_OUT_RAMP

    def __call__(self, t: float) -> float:
        """The speed at time t (s), m/s."""
        if self.ramp <= 0.0:
            return self.speed if t >= self.start_time else 0.0
        s = min(max((t - self.start_time) / self.ramp, 0.0), 1.0)
        return self.speed * s * s * (3.0 - 2.0 * s)

    def distance(self, t: float) -> float:
        """∫ v dt from start_time to t (m): the length paid out by time t."""
        if t <= self.start_time:
            return 0.0
        if self.ramp <= 0.0 or t >= self.start_time + self.ramp:
            return self.speed * (t - self.start_time - 0.5 * self.ramp)
        s = (t - self.start_time) / self.ramp
        return self.speed * self.ramp * (s**3 - 0.5 * s**4)


def _settings(file: models.ScenarioFile) -> dict[str, Any]:
    """The Scenario's solver settings and outputs."""
    solver = file.solver
    return {
        "dt": solver.dt,
        "high_frequency_damping": solver.high_frequency_damping,
        "t_end": file.run_end(),
        "record_every": solver.record_every,
        "static_steps": solver.static_steps,
        "static_start": solver.static_start,
        "output": {"plot_times": file.output.plot_times},
        "checks": file.checks.given(),
    }


# Building: the API calls of a checked document.


@contextmanager
def _engine(path: str, keys: Collection[str] = (), elsewhere: dict[str, str] | None = None) -> Iterator[None]:
    """Re-raise the engine's InputError with the key path in front (`path.key` if it names one of `keys`, the
    path `elsewhere[argument]` for arguments that belong to another table)."""
    try:
        yield
    except pl.InputError as error:
        message = str(error)
        argument, _, rest = message.partition(": ")
        if elsewhere and argument in elsewhere:
            raise pl.InputError(f"{elsewhere[argument]}: {rest}") from None
        if argument in keys:
            raise pl.InputError(f"{join(path, argument)}: {rest}") from None
        raise pl.InputError(f"{path}: {message}" if path else message) from None


_SEABED_SHAPE = {"bathymetry": "sea.seabed.bathymetry"}
_WINCH_ARGUMENTS = {
    "winch": "vessel.winch",
    "winch position": "vessel.winch.position",
    "winch.wire": "vessel.winch.wire",
    "wire": "vessel.winch.wire",
    "head_length": "vessel.winch.head.length",
    "head_diameter": "vessel.winch.head.diameter",
}
"""The engine's names, in `attach_vessel`'s errors, of what belongs to `[vessel.winch]`."""
_STINGER_ARGUMENTS = {
    "stinger radius": "vessel.lay.stinger.radius",
    "stinger length": "vessel.lay.stinger.length",
    "stinger origin": "vessel.lay.stinger.origin",
    "stinger angle": "vessel.lay.stinger.angle",
    "roller positions": "vessel.lay.stinger.positions",
    "roller axes": "vessel.lay.stinger.axes",
}
_CONTROLLER_ARGUMENTS = {
    "allocation": "controller.allocation",
    "observer": "controller.observer",
    "passivity": "controller.passivity",
}
"""The engine's names, in `attach_vessel`'s errors, of what belongs to `[controller]`."""
_HULL_TABLES: dict[str, Callable[..., Any]] = {
    "wind_coefficients": pl.HullCoefficients.read,
    "current_coefficients": pl.HullCoefficients.read,
    "drift_coefficients": pl.DriftCoefficients.read,
}
"""The readers of `[vessel]`'s hull tables, by key."""
_CURRENTS: dict[str, Callable[..., pl.Current]] = {
    "uniform": pl.Current.uniform,
    "linear": pl.Current.linear,
    "profile": pl.Current.profile,
}
_BATHYMETRIES: dict[str, Callable[..., pl.Bathymetry]] = {
    "flat": pl.Bathymetry.flat,
    "plane": pl.Bathymetry.plane,
    "grid": pl.Bathymetry.grid,
}
_WAVES: dict[str, Callable[..., pl.Waves]] = {"regular": pl.Waves.regular, "jonswap": pl.Waves.jonswap}


def _harmonic_drive(
    center: Any,
    period: float,
    amplitude: list[float] | None = None,
    phase: list[float] | None = None,
    ramp: float = 0.0,
) -> tuple[Callable[[float], list[float]], Callable[[float], list[float]]]:
    """Position and velocity of an end driven harmonically about `center` (m): x(t) = c + a r(t) sin(ωt + φ),
    ω = 2π/period, with the amplitude a ramped in by r(t) = 10s³ − 15s⁴ + 6s⁵, s = min(t/ramp, 1) (no jump in
    position, velocity or acceleration at t = 0)."""
    omega = 2.0 * math.pi / period
    a = amplitude if amplitude is not None else [0.0, 0.0, 0.0]
    phi = phase if phase is not None else [0.0, 0.0, 0.0]
    c = [float(v) for v in center]

    def ramp_of(t: float) -> tuple[float, float]:
        if ramp <= 0.0 or t >= ramp:
            return 1.0, 0.0
        x = max(t, 0.0) / ramp
        return 10 * x**3 - 15 * x**4 + 6 * x**5, (30 * x**2 - 60 * x**3 + 30 * x**4) / ramp

    def position(t: float) -> list[float]:
        r, _ = ramp_of(t)
        return [c[k] + a[k] * r * math.sin(omega * t + phi[k]) for k in range(3)]

    def velocity(t: float) -> list[float]:
        r, dr = ramp_of(t)
        return [
            a[k] * (dr * math.sin(omega * t + phi[k]) + r * omega * math.cos(omega * t + phi[k]))
            for k in range(3)
        ]

    return position, velocity


def _material(pipe: models.Pipe) -> pl.Material | None:
    """The steel's law of `[pipe.material]`, its Young's modulus the pipe's; None without one."""
    law = pipe.material
    if law is None:
        return None
    e = pipe.youngs_modulus if pipe.youngs_modulus is not None else 207e9
    if law.kind == "elastic_perfectly_plastic":
        return pl.Material.elastic_perfectly_plastic(e, law.yield_stress)
    if law.kind == "ramberg_osgood":
        return pl.Material.ramberg_osgood(e, law.yield_stress, law.n)
    return pl.Material.grade(law.grade, E=e) if law.n is None else pl.Material.grade(law.grade, law.n, E=e)


def _section(table: models.Pipe | models.Section | models.Cable, path: str, shown: str) -> pl.Section:
    """The cross-section of a `[pipe]`, `[section]` or `[cable]` table at `path` (in errors: `shown`)."""
    with _engine(shown, KEYS[path]):
        if isinstance(table, models.Pipe):
            layers = {
                "coatings": [pl.Coating(**layer.given()) for layer in table.coatings],
                "lining": None if table.lining is None else pl.Coating(**table.lining.given()),
            }
            section = pl.Section.pipe(
                **table.given("coatings", "lining", "material", "structural_damping"),
                **layers,
                material=_material(table),
            )
        elif isinstance(table, models.Cable):
            return pl.Section.cable(**table.given())
        else:
            section = pl.Section(**table.given("structural_damping"))
    if table.structural_damping is None:
        return section
    with _engine(f"{shown}.structural_damping", KEYS[f"{path}.structural_damping"]):
        return section.with_structural_damping(**table.structural_damping.given())


def _rod(file: models.ScenarioFile) -> pl.Rod:
    """The rod: a `[line]` of segments, or `[rod]` with its cross-section (`[pipe]` or `[section]`)."""
    if file.line is not None:
        segments = []
        for k, segment in enumerate(file.line.segments):
            kind = next(name for name in ("pipe", "section", "cable") if getattr(segment, name) is not None)
            section = _section(getattr(segment, kind), f"line.segments.{kind}", f"line.segments[{k}].{kind}")
            with _engine(f"line.segments[{k}]", KEYS["line.segments"]):
                segments.append(pl.Segment(segment.length, section, segment.elements))
        with _engine("line", KEYS["line"]):
            return pl.Rod.segments(file.line.start, file.line.direction, segments)
    table = "pipe" if file.pipe is not None else "section"
    section = _section(cast(models.Pipe | models.Section, getattr(file, table)), table, table)
    rod = cast(models.StraightRod | models.NodesRod, file.rod)
    with _engine("rod", KEYS["rod"]):
        if isinstance(rod, models.NodesRod):
            return pl.Rod(rod.nodes, section)
        return pl.Rod.straight(section=section, **rod.given())


def _seabed(seabed: models.Seabed) -> pl.Seabed:
    """`[sea.seabed]` and its bathymetry."""
    bathymetry = None
    if seabed.bathymetry is not None:
        with _engine("sea.seabed.bathymetry", KEYS["sea.seabed.bathymetry"]):
            bathymetry = _BATHYMETRIES[seabed.bathymetry.kind](**seabed.bathymetry.given())
    with _engine("sea.seabed", KEYS["sea.seabed"]):
        return pl.Seabed(**seabed.given("bathymetry"), bathymetry=bathymetry)


def _wind(wind: models.Wind) -> pl.Wind:
    """`[sea.wind]`; spectrum = "none" is a steady wind (`spectrum=None`)."""
    arguments: dict[str, Any] = wind.given("spectrum")
    if wind.spectrum is not None:
        arguments["spectrum"] = None if wind.spectrum == "none" else wind.spectrum
    with _engine("sea.wind", KEYS["sea.wind"]):
        return pl.Wind(**arguments)


def _sea(sea: models.Sea) -> pl.Sea:
    """`[sea]` with its current, seabed, waves and wind. The waves' `ramp` is passed only when the file gives
    it."""
    current = seabed = waves = wind = None
    if sea.current is not None:
        with _engine("sea.current", KEYS["sea.current"]):
            current = _CURRENTS[sea.current.kind](**sea.current.given())
    if sea.seabed is not None:
        seabed = _seabed(sea.seabed)
    if sea.waves is not None:
        with _engine("sea.waves", KEYS["sea.waves"]):
            waves = _WAVES[sea.waves.kind](**sea.waves.given())
    if sea.wind is not None:
        wind = _wind(sea.wind)
    with _engine("sea", KEYS["sea"], _SEABED_SHAPE):
        return pl.Sea(
            **sea.given("current", "seabed", "waves", "wind"),
            current=current,
            seabed=seabed,
            waves=waves,
            wind=wind,
        )


def _hold(model: pl.Model, supports: models.Supports) -> None:
    """Clamp, pin or drive the ends of `[supports]`."""
    ends: list[tuple[End, models.Clamp | models.Pin | models.Drive | None]] = [
        ("A", supports.A),
        ("B", supports.B),
    ]
    for end, support in ends:
        if support is None:
            continue
        with _engine(f"supports.{end}", KEYS[f"supports.{end}"]):
            if isinstance(support, models.Clamp):
                model.clamp(end, **support.given())
            elif isinstance(support, models.Pin):
                model.pin(end, **support.given())
            else:
                node = model.rod.nodes[0 if end == "A" else -1]
                center = node if support.position is None else support.position
                position, velocity = _harmonic_drive(center, **support.given("position"))
                model.drive(end, position, velocity=velocity)


def _lay(lay: models.SLay | models.JLay | models.ReelLay, pipe: pl.Section) -> pl.SLay | pl.JLay | pl.ReelLay:
    """The lay equipment of `[vessel.lay]` (and `[vessel.lay.stinger]`); a reel-lay's straightener set by
    design for the `pipe` at the hold point."""
    if isinstance(lay, models.JLay):
        with _engine("vessel.lay", KEYS["vessel.lay"]):
            return pl.JLay(**lay.given())
    if isinstance(lay, models.ReelLay):
        with _engine("vessel.lay", KEYS["vessel.lay"]):
            if lay.straightener == "design":
                straightener = pl.design_straightener(pipe, lay.reel_radius, lay.aligner_radius)
            else:
                straightener = pl.Straightener(cast(float, lay.straightener or 0.0))
            return pl.ReelLay(straightener=straightener, **lay.given("straightener"))
    stinger = None
    if lay.stinger is not None:
        with _engine("vessel.lay.stinger", KEYS["vessel.lay.stinger"], _STINGER_ARGUMENTS):
            if isinstance(lay.stinger, models.RollerStinger):
                stinger = pl.Stinger.from_rollers(**lay.stinger.given())
            else:
                arc = lay.stinger
                boxes = [arc.box] * arc.rollers if arc.box is not None else arc.boxes
                placed = (
                    None if boxes is None else [pl.RollerBox(**b.given(), kind=b.kind or "v") for b in boxes]
                )
                if arc.sections is None:
                    stinger = pl.Stinger(**arc.given("box", "boxes", "sections"), boxes=placed)
                else:
                    sections = [pl.StingerSection(**s.given()) for s in arc.sections]
                    fixed = arc.length - sum(s.length for s in arc.sections)
                    stinger = pl.Stinger.articulated(
                        sections,
                        **arc.given("box", "boxes", "sections", "length"),
                        fixed_length=max(fixed, 0.0),
                        boxes=placed,
                    )
    with _engine("vessel.lay", KEYS["vessel.lay"]):
        return pl.SLay(stinger=stinger, **lay.given("stinger"))


def _thrusters(thrusters: list[models.Thruster]) -> tuple[list[pl.Thruster], dict[str, str]]:
    """The thrusters of `[[vessel.thrusters]]`, and the key paths of the engine's names for their keys in
    `pl.Vessel`'s errors (`thrusters[1].position`)."""
    built, elsewhere = [], {}
    for k, thruster in enumerate(thrusters):
        with _engine(f"vessel.thrusters[{k}]", KEYS["vessel.thrusters"]):
            built.append(pl.Thruster(thruster.kind, **thruster.given()))
        elsewhere[f"thrusters[{k}]"] = f"vessel.thrusters[{k}]"
        for key in KEYS["vessel.thrusters"]:
            elsewhere[f"thrusters[{k}].{key}"] = f"vessel.thrusters[{k}].{key}"
    return built, elsewhere


def _vessel(vessel: models.ModelVessel | models.MatrixVessel) -> pl.Vessel:
    """The vessel of `[vessel]`, with the RAOs of `raos` if given (else the API's default); a vessel given by
    its matrices with its thrusters and hull tables."""
    tables: dict[str, Any] = {}
    if vessel.raos is not None:
        with _engine("vessel.raos", (), {"path": "vessel.raos", "raos": "vessel.raos"}):
            tables["raos"] = pl.Raos.read(vessel.raos)
    if isinstance(vessel, models.ModelVessel):
        with _engine("vessel", KEYS["vessel"]):
            return pl.Vessel.osv(**tables)
    for key, read in _HULL_TABLES.items():
        path = getattr(vessel, key)
        if path is not None:
            with _engine(f"vessel.{key}", (), {"path": f"vessel.{key}", key: f"vessel.{key}"}):
                tables[key] = read(path)
    thrusters, elsewhere = _thrusters(vessel.thrusters)
    if thrusters:
        tables["thrusters"] = thrusters
    given = vessel.given(
        "end", "eta", "angle", "raos", "hull_loads", "lay", "winch", "thrusters", *_HULL_TABLES
    )
    with _engine("vessel", KEYS["vessel"], elsewhere):
        return pl.Vessel(**given, **tables)


def _controller(controller: models.FixedController | models.RouteController) -> pl.PID:
    """The PID of `[controller]`, with its route, tension loop and observer."""
    arguments = controller.given("route", "tension", "observer")
    if isinstance(controller, models.RouteController):
        with _engine("controller.route", KEYS["controller.route"]):
            route = controller.route
            if route.waypoints is not None:
                arguments["reference"] = pl.Route.legs(**route.given())
            else:
                arguments["reference"] = pl.Route(**route.given())
    if controller.tension is not None:
        with _engine("controller.tension", KEYS["controller.tension"]):
            arguments["tension"] = pl.TensionControl(**controller.tension.given())
    if controller.observer is not None:
        with _engine("controller.observer", KEYS["controller.observer"]):
            arguments["observer"] = pl.Observer.passive(**controller.observer.given())
    with _engine("controller", KEYS["controller"]):
        return pl.PID(**arguments)


def _winch(winch: models.Winch) -> pl.Winch:
    """The A&R winch of `[vessel.winch]`, with its wire and head."""
    wire = None if winch.wire is None else _section(winch.wire, "vessel.winch.wire", "vessel.winch.wire")
    head = None
    body: dict[str, float] = {}
    if winch.head is not None:
        with _engine("vessel.winch.head", KEYS["vessel.winch.head"]):
            head = pl.Clump(**winch.head.given("length", "diameter"))
        body = {
            f"head_{key}": value for key, value in winch.head.given().items() if key in ("length", "diameter")
        }
    with _engine("vessel.winch", KEYS["vessel.winch"], _WINCH_ARGUMENTS):
        given = winch.given("position", "wire", "head")
        return pl.Winch(winch.position, wire=wire, head=head, **given, **body)


def _held_section(model: pl.Model, end: str) -> pl.Section:
    """The cross-section of the line's element at `end` ("A" or "B"): the pipe the vessel holds."""
    rod = model.rod
    return rod.sections[int(rod.segment_of[0 if end == "A" else -1])]


def _attach(model: pl.Model, file: models.ScenarioFile, controller: pl.PID | None = None) -> None:
    """Build the vessel, its lay equipment, winch, controller (`controller` in place of `[controller]`'s, if
    given) and environment; attach them (with the hull's loads if `hull_loads` says so)."""
    vessel = cast(models.ModelVessel | models.MatrixVessel, file.vessel)
    lay = None if vessel.lay is None else _lay(vessel.lay, _held_section(model, vessel.end))
    winch = None if vessel.winch is None else _winch(vessel.winch)
    body = _vessel(vessel)
    if controller is None and file.controller is not None:
        controller = _controller(file.controller)
    environment = []
    for i, force in enumerate(file.environment):
        with _engine(f"environment[{i}]", KEYS["environment"]):
            environment.append(pl.Force(**force.given()))
    hull_loads = {} if vessel.hull_loads is None else {"hull_loads": vessel.hull_loads}
    with _engine("vessel", KEYS["vessel"], _WINCH_ARGUMENTS | _CONTROLLER_ARGUMENTS):
        model.attach_vessel(
            vessel.end,
            body,
            eta=vessel.eta,
            angle=vessel.angle,
            controller=controller,
            environment=environment,
            lay=lay,
            winch=winch,
            **hull_loads,
        )


def _pay_out(pay_out: models.PayOut, controller: models.ControllerTable | None) -> SmoothStart:
    """The pay-out speed; speed = "route" is the route's speed, from the route's start time by default."""
    speed, start_time = pay_out.speed, pay_out.start_time
    if isinstance(speed, str):  # "route": the checks made sure there is one
        route = cast(models.RouteController, controller).route
        speed = route.speed or 0.0
        start_time = route.start_time if start_time is None else start_time
    ramp = _PAY_OUT_RAMP if pay_out.ramp is None else pay_out.ramp
    return SmoothStart(speed, start_time or 0.0, ramp)


def _stages(file: models.ScenarioFile) -> pl.Stages | None:
    """The `[[stages]]` as a pl.Stages (None for none); checked against the model when a simulation takes
    them."""
    if not file.stages:
        return None
    stages = []
    for k, stage in enumerate(file.stages):
        with _engine(f"stages[{k}]", KEYS["stages"]):
            stages.append(pl.Stage(stage.name, **stage.given("name")))
    with _engine("", ("stages",)):
        return pl.Stages(stages)


def _build(file: models.ScenarioFile, controller: pl.PID | None = None) -> pl.Model:
    """Make the API calls of a checked document (with `controller` in place of `[controller]`'s)."""
    rod = _rod(file)
    sea = None if file.sea is None else _sea(file.sea)
    gravity = file.gravity.acceleration if isinstance(file.gravity, models.Gravity) else file.gravity
    with _engine("", ("gravity",), _SEABED_SHAPE):
        model = pl.Model(rod, sea=sea, **({} if gravity is None else {"gravity": gravity}))
    if file.supports is not None:
        _hold(model, file.supports)
    for i, load in enumerate(file.point_loads):
        with _engine(f"point_loads[{i}]", KEYS["point_loads"]):
            model.point_load(**load.given())
    for i, attachment in enumerate(file.attachments):
        with _engine(f"attachments[{i}]", KEYS["attachments"]):
            model.attach(attachment.arc_length, pl.Clump(**attachment.given("arc_length")))
    if file.vessel is not None:
        _attach(model, file, controller)
    elif controller is not None:
        raise pl.InputError("controller: the scenario has no [vessel] for a controller to act on")
    if file.pay_out is not None:
        speed = _pay_out(file.pay_out, file.controller)
        with _engine("pay_out", KEYS["pay_out"]):
            model.pay_out(file.pay_out.end or "B", speed=speed)
    return model


def parse_scenario(
    data: dict[str, Any],
    origin: str = "<dict>",
    folder: str | os.PathLike[str] | None = None,
    *,
    controller: pl.PID | None = None,
) -> Scenario:
    """The scenario described by `data`, a parsed TOML document (its keys: the documentation's Scenario
    reference).

    Every key is checked before the model is built; nothing is solved (the engine checks the `[[stages]]`,
    `Scenario.stages`, against the model again when a simulation takes them). `origin` names the source in
    messages; file paths in it (`vessel.raos`, the hull tables) are relative to `folder` (default: the folder
    of `origin` if it is a file, else the current one). `controller` (a pl.PID, say `pl.PID.external` or
    `pl.Controller.fmu`) takes the place of `[controller]`'s. Raises pl.InputError whose message starts with the
    key path and ends with `(in origin)`.
    """
    relative_to = _folder(origin, folder)
    try:
        file = _check(data, relative_to)
        model = _build(file, controller)
        stages = _stages(file)
    except pl.InputError as error:
        raise pl.InputError(f"{error} (in {origin})") from None
    return Scenario(
        model=model,
        source=copy.deepcopy(data),
        stages=stages,
        origin=origin,
        folder=str(Path(relative_to).absolute()),
        **_settings(file),
    )


def _syntax_error(error: tomllib.TOMLDecodeError, text: str, origin: str) -> pl.InputError:
    """A TOML syntax error as an InputError naming the file, line and column."""
    message = str(error)
    found = re.fullmatch(r"(.*) \(at line (\d+), column (\d+)\)", message, flags=re.DOTALL)
    if found:
        reason, line, column = found.group(1), int(found.group(2)), int(found.group(3))
    else:
        reason = message.removesuffix(" (at end of document)")
        lines = text.split("\n")
        line, column = len(lines), len(lines[-1]) + 1
    return pl.InputError(f"{origin}, line {line}, column {column}: TOML syntax error: {reason}")


def load_scenario(path: str | os.PathLike[str]) -> Scenario:
    """The scenario in the TOML file at `path` (its keys: the documentation's Scenario reference); nothing is
    solved.

    Raises pl.InputError for a syntax error (naming the line and column) or any invalid key (naming the key
    path and the file); OSError if the file cannot be read.
    """
    origin = os.fspath(path)
    raw = Path(path).read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        line = raw.count(b"\n", 0, error.start) + 1
        raise pl.InputError(f"{origin}, line {line}: not UTF-8 text, as TOML must be") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise _syntax_error(error, text, origin) from None
    except RecursionError:
        raise pl.InputError(f"{origin}: arrays or tables nested too deeply") from None
    return parse_scenario(data, origin, Path(path).absolute().parent)
