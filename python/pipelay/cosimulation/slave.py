"""pipelay as an FMI 2.0 co-simulation slave (pythonfmu): the *plant*, pipe and vessel, driven by the thrust τ a
master's controller commands.

The FMU carries its scenario and `pipelay_fmu.json` (what `build_fmu` decided) in its resources; the slave
builds the model when the master leaves initialisation (with the parameters the master set, as overrides of the
scenario's keys), solves its statics and, at each `doStep(t, h)`, runs the simulation from t to t + h with the
inputs held. Its outputs are those of the state at the communication point.

The FMU runs where Python and pipelay are installed: pythonfmu's binary starts the host's Python and imports
this module.
"""

from __future__ import annotations

import json
import math
import tomllib
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real

__all__ = [
    "PIPE_INPUTS",
    "PIPE_OUTPUTS",
    "PLANT_INPUTS",
    "PLANT_OUTPUTS",
    "PipelayPipe",
    "PipelayPlant",
    "Signal",
]

SETTINGS = "pipelay_fmu.json"


@dataclass(frozen=True)
class Signal:
    """An FMU variable: its name, unit (FMI unit name) and what it is."""

    name: str
    unit: str
    description: str


PLANT_INPUTS = (
    Signal("tau_surge", "N", "commanded thrust in surge, body frame"),
    Signal("tau_sway", "N", "commanded thrust in sway, body frame (to starboard)"),
    Signal("tau_yaw", "N.m", "commanded thrust moment in yaw, body frame"),
)
_POSE = (("x", "m"), ("y", "m"), ("z", "m"), ("roll", "rad"), ("pitch", "rad"), ("yaw", "rad"))
_VELOCITY = (("u", "m/s"), ("v", "m/s"), ("w", "m/s"), ("p", "rad/s"), ("q", "rad/s"), ("r", "rad/s"))
_CHI = (("X", "N"), ("Y", "N"), ("Z", "N"), ("K", "N.m"), ("M", "N.m"), ("N", "N.m"))
# The lay summary's scalars, its keys, units and meanings (the documentation's Lay equipment › Lay tables).
LAY_OUTPUTS = (
    ("top_tension", "N", "the effective tension at the tensioner or tower"),
    ("departure_angle", "rad", "below the horizontal where the pipe leaves the equipment"),
    ("layback", "m", "horizontal distance from the hold point to the touchdown"),
    ("touchdown_arc_length", "m", "arc length from end A to the touchdown"),
    ("overbend_strain", "1", "the largest strain over the stinger (a fraction)"),
    ("sagbend_strain", "1", "the largest strain in the sagbend (a fraction)"),
    (
        "tip_clearance",
        "m",
        "the gap to the stinger's last roller (<= 0: the pipe rests on it; NaN: no stinger)",
    ),
)
PIPE_INPUTS = (
    *(Signal(f"eta_{n}", u, f"vessel pose η: {n} (CO in e, z down; zyx Euler angles)") for n, u in _POSE),
    *(Signal(f"nu_{n}", u, f"vessel velocity ν: {n} (body frame)") for n, u in _VELOCITY),
)
PIPE_OUTPUTS = (
    *(
        Signal(f"chi_{n}", u, f"the pipe's force and moment on the vessel: {n} (body frame, about CO)")
        for n, u in _CHI
    ),
    Signal("energy", "J", "the pipe's energy"),
    Signal("supplied_work", "J", "work supplied since the start (the hold point's motion, the sea)"),
    Signal("dissipated", "J", "energy dissipated since the start"),
)
PLANT_OUTPUTS = (
    *(
        Signal(f"eta_{n}", u, f"vessel pose η, its total motion (measured): {n} (CO in e, z down)")
        for n, u in _POSE
    ),
    *(
        Signal(f"eta_lf_{n}", u, f"vessel pose η, its low-frequency part (what DP controls): {n}")
        for n, u in _POSE
    ),
    *(Signal(f"nu_{n}", u, f"vessel velocity ν: {n} (body frame)") for n, u in _VELOCITY),
    *(
        Signal(f"chi_{n}", u, f"the pipe's force and moment on the vessel: {n} (body frame, about CO)")
        for n, u in _CHI
    ),
    *(Signal(name, unit, description) for name, unit, description in LAY_OUTPUTS),
    Signal("thrust_surge", "N", "thrust delivered in surge, body frame"),
    Signal("thrust_sway", "N", "thrust delivered in sway, body frame"),
    Signal("thrust_yaw", "N.m", "thrust moment delivered in yaw, body frame"),
    Signal("energy", "J", "the pipe–vessel system's energy"),
    Signal("supplied_work", "J", "work supplied since the start (thrust, environment)"),
    Signal("dissipated", "J", "energy dissipated since the start"),
)


def scalar_keys(data: dict[str, Any], tables: tuple[str, ...]) -> dict[str, float]:
    """The numbers under the dotted `tables` of a parsed scenario, by dotted key (arrays' entries as key[i])."""
    found: dict[str, float] = {}

    def walk(node: Any, key: str) -> None:
        if isinstance(node, bool):
            return
        if isinstance(node, int | float):
            found[key] = float(node)
        elif isinstance(node, dict):
            for name, value in node.items():
                walk(value, f"{key}.{name}")
        elif isinstance(node, list) and all(
            isinstance(v, int | float) and not isinstance(v, bool) for v in node
        ):
            for i, value in enumerate(node):
                found[f"{key}[{i}]"] = float(value)

    for table in tables:
        node: Any = data
        for part in table.split("."):
            node = node.get(part) if isinstance(node, dict) else None
        if node is not None:
            walk(node, table)
    return found


class ScenarioSlave(Fmi2Slave):
    """An FMU of a scenario: its settings and scenario from the resources, its variables by name."""

    author = "pipelay"
    inputs: tuple[Signal, ...] = ()
    outputs: tuple[Signal, ...] = ()

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        resources = Path(self.resources)
        settings = json.loads((resources / SETTINGS).read_text())
        self.scenario_path = resources / settings["scenario"]
        self.dt = float(settings["dt"])
        self.values: dict[str, float] = {}
        self.parameters: dict[str, float] = dict(settings["parameters"])
        self.simulation: Any = None
        for signal in self.inputs:
            self.values[signal.name] = 0.0
            self._register(signal.name, Fmi2Causality.input, Fmi2Variability.continuous, signal.description)
        for name in self.parameters:
            self.values[name] = self.parameters[name]
            self._register(name, Fmi2Causality.parameter, Fmi2Variability.fixed, f"scenario key {name}")
        for signal in self.outputs:
            self.values[signal.name] = 0.0
            self._register(signal.name, Fmi2Causality.output, Fmi2Variability.continuous, signal.description)

    def _register(self, name: str, causality: Fmi2Causality, variability: Fmi2Variability, text: str) -> None:
        def getter() -> float:
            return self.values[name]

        def setter(value: float) -> None:
            self.values[name] = float(value)

        self.register_variable(
            Real(
                name,
                causality=causality,
                variability=variability,
                description=text,
                getter=getter,
                setter=setter,
            ),
            nested=False,
        )

    def _scenario(self) -> dict[str, Any]:
        """The parsed scenario with the parameters the master set."""
        from pipelay.scenario.overrides import apply_overrides

        data = tomllib.loads(self.scenario_path.read_text())
        return apply_overrides(data, {name: self.values[name] for name in self.parameters})

    def do_step(self, current_time: float, step_size: float) -> bool:
        import pipelay as pl

        steps = max(1, round(step_size / self.dt))
        if not math.isclose(steps * self.dt, step_size, rel_tol=1e-9):
            self.log(f"the communication step {step_size} s is not a multiple of the time step {self.dt} s")
            return False
        self._hold(current_time)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", pl.PhysicsWarning)
                for _ in range(steps):
                    self.simulation.step()
        except (pl.ConvergenceError, pl.InputError) as error:
            self.log(str(error))
            return False
        self._read()
        return True

    def _hold(self, time: float) -> None:
        """Takes the inputs at the communication point `time` (s) for the step from it."""

    def _read(self) -> None:
        """Sets the outputs from the simulation's state."""
        raise NotImplementedError


class PipelayPlant(ScenarioSlave):
    """The pipe and the vessel of a scenario, driven by the thrust τ in surge, sway and yaw."""

    description = "pipelay plant: the pipe and the DP vessel of a scenario, driven by the commanded thrust"
    inputs = PLANT_INPUTS
    outputs = PLANT_OUTPUTS

    def _command(self, t: float, dt: float, eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
        """The external controller's law: the master's τ inputs, held over the step."""
        tau = np.zeros(6)
        tau[0], tau[1], tau[5] = (self.values[s.name] for s in PLANT_INPUTS)
        return tau

    def exit_initialization_mode(self) -> None:
        import pipelay as pl
        from pipelay.scenario import parse_scenario

        data = self._scenario()
        allocation = (data.get("controller") or {}).get("allocation")
        controller = pl.PID.external(self._command, allocation=allocation)
        scenario = parse_scenario(data, origin=str(self.scenario_path), controller=controller)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pl.PhysicsWarning)
            self.simulation = scenario.simulation()  # statics with the scenario's settings, its stages
        self._read()

    def _read(self) -> None:
        state = self.simulation.state
        values = self.values
        for (name, _), value in zip(_POSE, state.eta, strict=True):
            values[f"eta_{name}"] = float(value)
        for (name, _), value in zip(_POSE, self.simulation.eta_low_frequency, strict=True):
            values[f"eta_lf_{name}"] = float(value)
        for (name, _), value in zip(_VELOCITY, state.nu, strict=True):
            values[f"nu_{name}"] = float(value)
        for (name, _), value in zip(_CHI, state.chi, strict=True):
            values[f"chi_{name}"] = float(value)
        tau = state.tau
        values["thrust_surge"], values["thrust_sway"], values["thrust_yaw"] = (
            float(tau[k]) for k in (0, 1, 5)
        )
        read_lay_and_energy(values, state, self.simulation)


def read_lay_and_energy(values: dict[str, float], state: Any, simulation: Any) -> None:
    """The lay summary's scalars of `state` and the energy ledger of `simulation` into `values`."""
    summary = state.lay_summary() or {}
    for name, _, _ in LAY_OUTPUTS:
        value = summary.get(name)
        values[name] = float("nan") if value is None else float(value)
    read_ledger(values, simulation)


def read_ledger(values: dict[str, float], simulation: Any) -> None:
    """The energy, the supplied work and the dissipation of `simulation` (J) into `values`."""
    values["energy"] = float(simulation.energy)
    values["supplied_work"] = float(simulation.supplied_work)
    values["dissipated"] = float(simulation.dissipated)


class PipelayPipe(ScenarioSlave):
    """The pipe of a scenario alone, its hold point carried by the vessel motion the master gives
    (`pipelay.cosimulation.pipe.HeldPipe`)."""

    description = (
        "pipelay pipe: the pipe of a scenario, its hold point moved by the vessel's pose and velocity"
    )
    inputs = PIPE_INPUTS
    outputs = PIPE_OUTPUTS

    def exit_initialization_mode(self) -> None:
        from pipelay.cosimulation.pipe import HeldPipe

        self.pipe = HeldPipe(self._scenario(), self.scenario_path)
        if all(self.values[f"eta_{n}"] == 0.0 for n, _ in _POSE):
            # A pose the master never set: the statics', where the scenario holds the vessel.
            for (name, _), value in zip(_POSE, self.pipe.eta, strict=True):
                self.values[f"eta_{name}"] = float(value)
        self.simulation = self.pipe.simulation()
        self._read()

    def _hold(self, time: float) -> None:
        eta = np.array([self.values[f"eta_{n}"] for n, _ in _POSE])
        nu = np.array([self.values[f"nu_{n}"] for n, _ in _VELOCITY])
        self.pipe.hold(time, eta, nu)

    def _read(self) -> None:
        chi = self.pipe.chi(self.simulation.state, self.simulation.time)
        for (name, _), value in zip(_CHI, chi, strict=True):
            self.values[f"chi_{name}"] = float(value)
        read_ledger(self.values, self.simulation)
