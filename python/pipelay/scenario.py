"""Scenario files: a whole pipelay model, with its solver settings and outputs, in one TOML file.

`load_scenario(path)` reads a file and `parse_scenario(data)` an already parsed dict. Both check every key
before anything is built or solved and return a `Scenario` whose `model` is ready to solve:

```python
from pipelay.scenario import load_scenario

scenario = load_scenario("examples/jensen2009.toml")
state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
if scenario.t_end is not None:
    simulation = scenario.model.simulation(state=state, dt=scenario.dt)
    results = simulation.run(scenario.t_end, record_every=scenario.record_every)
```

Any mistake raises `pl.InputError` whose message starts with the key path, states the value and what is
allowed, and ends with the file, e.g. `pipe.outer_diameter: must be > 0 m, got -0.6 (in lay.toml)`. Unknown
keys and sections are rejected with the closest valid name suggested; a TOML syntax error names the file,
line and column. Entries of arrays of tables are numbered from 0 (`point_loads[1].force`).

The format is a set of pydantic models (`pipelay.scenario_models`, one per table and per kind of a table),
whose keys are the keyword arguments of the API calls below. `json_schema()` is its JSON Schema, with the
descriptions, units and defaults of this reference, for editors to complete and check scenario files (taplo /
Even Better TOML: `#:schema scenario.schema.json` on the first line). For a parameter sweep,
`validate_overrides(data, {"sea.waves.hs": [1.0, 2.0]})` checks each dotted key and value before any case
runs, and `apply_overrides(data, {"sea.waves.hs": 2.0})` makes one case's document.

## Scenario reference

Conventions are the Python API's: SI units; frame e with its origin at the seabed end, e1 along the lay
direction and **e3 pointing down**, so the sea surface is z = −depth; rod end "A" is node 0 (seabed end),
"B" is node n (top end). A vector is a TOML array (`[x, y, z]`), a matrix an array of rows. Every number
must be finite (TOML's `nan` and `inf` are rejected); integers are accepted where a number is asked for,
but not the reverse. Each section maps one to one onto the API call in its heading, whose default applies
to a key left out ("required" keys have none).

### Top level

| key           | unit | default | meaning                                                         |
|---------------|------|---------|-----------------------------------------------------------------|
| `title`       | —    | none    | a name for the scenario (text; kept in `Scenario.source`)       |
| `description` | —    | none    | free text (kept in `Scenario.source`)                           |
| `gravity`     | m/s² | 9.81    | acceleration of gravity along +e3, ≥ 0 (or a `[gravity]` table) |

### `[gravity]` — instead of the top-level `gravity` (`pl.Model(rod, sea, gravity)`)

| key            | unit | default  | meaning                                |
|----------------|------|----------|----------------------------------------|
| `acceleration` | m/s² | required | acceleration of gravity along +e3, ≥ 0 |

### `[pipe]` — `pl.Section.pipe`: a pipe from its geometry and material

Exactly one of `[pipe]` and `[section]`.

| key                | unit  | default  | meaning                                        |
|--------------------|-------|----------|------------------------------------------------|
| `outer_diameter`   | m     | required | outer diameter, > 0                            |
| `wall_thickness`   | m     | required | wall thickness, > 0 and ≤ outer_diameter / 2   |
| `density`          | kg/m³ | 7850     | density of the wall material, > 0              |
| `youngs_modulus`   | Pa    | 207e9    | Young's modulus, > 0                           |
| `poisson_ratio`    | —     | 0.3      | Poisson's ratio, in (−1, 0.5)                  |
| `contents_density` | kg/m³ | 0        | density of the contents (1025: flooded), ≥ 0   |
| `drag`             | —     | [0, 1]   | Morison drag coefficients [axial, normal], ≥ 0 |
| `added_mass`       | —     | [0, 1]   | added-mass coefficients [axial, normal], ≥ 0   |

### `[section]` — `pl.Section`: the cross-section's properties directly, instead of `[pipe]`

| key                  | unit    | default   | meaning                                              |
|----------------------|---------|-----------|------------------------------------------------------|
| `EA`                 | N       | required  | axial stiffness, > 0                                 |
| `GA`                 | N       | required  | shear stiffness, > 0: a number or [axis 2, axis 3]   |
| `GJ`                 | N·m²    | required  | torsional stiffness, > 0                             |
| `EI`                 | N·m²    | required  | bending stiffness, > 0: a number or [axis 2, axis 3] |
| `mass`               | kg/m    | required  | mass per unit length, contents included, > 0         |
| `inertia`            | kg·m    | [0, 0, 0] | rotational inertia per length [J1, J2, J3], ≥ 0      |
| `outer_diameter`     | m       | 0         | diameter that drag and added mass refer to, ≥ 0      |
| `displaced_area`     | m²      | π/4·d²    | buoyancy area per length (d: outer_diameter), ≥ 0    |
| `drag`               | —       | [0, 0]    | Morison drag coefficients [axial, normal], ≥ 0       |
| `added_mass`         | —       | [0, 0]    | added-mass coefficients [axial, normal], ≥ 0         |
| `rotational_damping` | N·m·s/m | 0         | a number or [t1, t2, t3], ≥ 0                        |

### `[rod]` — `pl.Rod.straight(start, end, elements)` or `pl.Rod(nodes)`: the stress-free reference

| key        | unit | default  | meaning                                                 |
|------------|------|----------|---------------------------------------------------------|
| `start`    | m    | required | first node (end A) [x, y, z] of a straight rod          |
| `end`      | m    | required | last node (end B) [x, y, z], distinct from `start`      |
| `elements` | —    | required | number of equal elements n, an integer in [1, 1000000]  |
| `nodes`    | m    | none     | instead of the three above: [[x, y, z], ...], ≥ 2 nodes |

### `[sea]` — `pl.Sea`; without it the pipe hangs in air (no buoyancy, drag or added mass)

| key       | unit  | default  | meaning                                     |
|-----------|-------|----------|---------------------------------------------|
| `depth`   | m     | required | water depth, > 0: the surface is z = −depth |
| `density` | kg/m³ | 1025     | water density, ≥ 0                          |

Its tables `[sea.current]`, `[sea.seabed]` and `[sea.waves]` follow.

### `[sea.current]` — `pl.Current.uniform`, `.linear` or `.profile`, chosen by `kind`

| key                | unit | default  | meaning                                                 |
|--------------------|------|----------|---------------------------------------------------------|
| `kind`             | —    | required | `"uniform"`, `"linear"` or `"profile"`                  |
| `velocity`         | m/s  | required | uniform: [vx, vy, vz] in e at every depth               |
| `surface_velocity` | m/s  | required | linear: [vx, vy, vz] at the surface, 0 at end A's depth |
| `depths`           | m    | required | profile: depths below the surface, increasing           |
| `velocities`       | m/s  | required | profile: one [vx, vy, vz] per depth, interpolated       |
| `start`            | s    | 0        | time the current starts                                 |

### `[sea.seabed]` — `pl.Seabed`: contact with the seabed (without it the pipe passes through the bottom)

| key            | unit   | default | meaning                                                                        |
|----------------|--------|---------|--------------------------------------------------------------------------------|
| `stiffness`    | Pa/m   | 1e5     | normal force per length = stiffness · d · penetration of the centreline, > 0   |
| `damping`      | Pa·s/m | 0       | normal damping (dynamics), ≥ 0                                                 |
| `friction`     | —      | 0       | Coulomb coefficient, a number or [axial, lateral], ≥ 0                          |
| `mobilisation` | m      | 0.01    | sliding distance at which friction reaches μN (pipe under its own weight), > 0 |

### `[sea.seabed.bathymetry]` — `pl.Bathymetry.flat`, `.plane` or `.grid`, chosen by `kind`; default flat z = 0

Elevations z are in frame e (e3 down: larger z is deeper); the seabed must lie below the surface z = −depth.

| key        | unit | default  | meaning                                                           |
|------------|------|----------|-------------------------------------------------------------------|
| `kind`     | —    | required | `"flat"`, `"plane"` or `"grid"`                                   |
| `z`        | m    | 0        | flat, plane: elevation at x = y = 0; grid: rows of len(y) numbers, one row per x |
| `gradient` | —    | [0, 0]   | plane: [dz/dx, dz/dy] (a positive value deepens along that axis)  |
| `x`        | m    | required | grid: strictly increasing x of the grid points                    |
| `y`        | m    | required | grid: strictly increasing y of the grid points                    |

### `[sea.waves]` — `pl.Waves.regular` or `.jonswap`, chosen by `kind`: linear (Airy) waves

They load the pipe (Morison drag and inertia in the waves' particle kinematics) and, through its RAOs, move
the vessel at wave frequency. Without `[sea.waves]` the sea is calm.

| key          | unit | default   | meaning                                                                               |
|--------------|------|-----------|---------------------------------------------------------------------------------------|
| `kind`       | —    | required  | `"regular"` or `"jonswap"`                                                            |
| `height`     | m    | required  | regular: crest-to-trough height, > 0                                                  |
| `period`     | s    | required  | regular: period, > 0                                                                  |
| `hs`         | m    | required  | jonswap: significant wave height, > 0                                                 |
| `tp`         | s    | required  | jonswap: peak period, > 0                                                             |
| `gamma`      | —    | 3.3       | jonswap: peak enhancement factor, ≥ 1                                                 |
| `spreading`  | —    | none      | jonswap: cos^2s spreading exponent s, > 0 and ≤ 1000; none: long-crested              |
| `seed`       | —    | 0         | jonswap: seed of the random phases (and directions), an integer ≥ 0                   |
| `components` | —    | 200       | jonswap: number of components, an integer in [1, 100000]                              |
| `direction`  | rad  | 0         | direction the waves travel toward, from e1 toward e2                                  |
| `ramp`       | s    | period/tp | time over which the waves grow smoothly from zero, ≥ 0 (regular: period, jonswap: tp) |

### `[supports.A]`, `[supports.B]` — `model.clamp`, `model.pin` or `model.drive` at that end

| key         | unit | default         | meaning                                                                 |
|-------------|------|-----------------|-------------------------------------------------------------------------|
| `kind`      | —    | required        | `"clamp"` (position and rotation held), `"pin"` or `"drive"`            |
| `position`  | m    | reference node  | where the end is held [x, y, z] (drive: the centre of its motion)       |
| `rotation`  | —    | reference frame | clamp only: R_t^e held, 3 rows of 3 numbers                             |
| `amplitude` | m    | [0, 0, 0]       | drive: x(t) = position + amplitude · r(t) · sin(2πt/period + phase)      |
| `period`    | s    | required        | drive: period of the motion, > 0                                        |
| `phase`     | rad  | [0, 0, 0]       | drive: phase of each component                                          |
| `ramp`      | s    | 0               | drive: the amplitude grows smoothly (C²) from 0 over this time, ≥ 0      |

### `[[point_loads]]` — `model.point_load`, one table per load of fixed direction in e

| key      | unit | default   | meaning                                                  |
|----------|------|-----------|----------------------------------------------------------|
| `node`   | —    | required  | index in [−(n+1), n] (negative: from the end) or "A"/"B" |
| `force`  | N    | [0, 0, 0] | force [fx, fy, fz] in e                                  |
| `moment` | N·m  | [0, 0, 0] | moment [mx, my, mz] in e                                 |

### `[vessel]` — `pl.Vessel.osv(raos)` or `pl.Vessel(M, D, G, ..., raos)`, then `model.attach_vessel`

Needs `[sea]`. Give `model` or the matrices (6×6, about CO, rows and columns surge … yaw).

| key                 | unit                  | default   | meaning                                         |
|---------------------|-----------------------|-----------|-------------------------------------------------|
| `end`               | —                     | required  | the end held, "A" or "B"; not in `[supports]`   |
| `model`             | —                     | none      | `"osv"`: the built-in offshore supply vessel    |
| `M`                 | kg, kg·m, kg·m²       | required  | M = M_RB + M_A, symmetric, positive definite    |
| `D`                 | kg/s, kg·m/s, kg·m²/s | required  | linear damping, positive semi-definite          |
| `G`                 | N/m, N, N·m/rad       | required  | restoring: heave, roll and pitch only           |
| `M_RB`              | kg, kg·m, kg·m²       | M         | rigid-body mass; M − M_RB is added mass         |
| `quadratic_damping` | kg/m, kg, kg·m²       | none      | D_q, positive semi-definite                     |
| `eta`               | m, rad                | required  | starting pose η = [x, y, z, φ, θ, ψ] in e (zyx) |
| `angle`             | rad                   | [0, 0, 0] | clamp angle β of the pipe on the vessel (zyx)   |
| `raos`              | —                     | see below | first-order motion RAOs: path of a CSV table     |

`raos` is the path (text) of a table of first-order displacement RAOs in pipelay's CSV format (`pl.Raos.read`:
columns period_s, heading_deg and <dof>_amp, <dof>_phase for surge … yaw), relative to the scenario file's
folder. Without it, `model = "osv"` moves with the built-in OSV's table, and a vessel given by its matrices has
no wave-frequency motion.

### `[vessel.lay]` — `pl.SLay` or `pl.JLay`: the pipe held by lay equipment instead of at CO

Positions in the vessel's body frame (forward, starboard, down; m from CO). Leave `vessel.angle` out.

| key                | unit | default  | meaning                                                            |
|--------------------|------|----------|--------------------------------------------------------------------|
| `kind`             | —    | required | `"s-lay"` (tensioner and stinger) or `"j-lay"` (tower)             |
| `tensioner`        | m    | required | s-lay: the tensioner [x, y, z]; the firing line is horizontal, +b1 |
| `roller_stiffness` | N/m  | 1e7      | s-lay: contact stiffness of every roller                           |
| `friction`         | —    | 0        | s-lay: roller friction; only 0 (free rollers) is modelled          |
| `position`         | m    | required | j-lay: the tower exit [x, y, z]                                    |
| `angle`            | rad  | 0        | j-lay: the tower's lean from vertical toward the bow, in [0, π/2]  |

### `[vessel.lay.stinger]` — `pl.Stinger`: the rollers of an s-lay

Either an arc (`radius`, `length`, `rollers`, …) or the rollers' top points (`positions`, `axes`).

| key             | unit | default   | meaning                                                         |
|-----------------|------|-----------|-----------------------------------------------------------------|
| `radius`        | m    | required  | arc: radius of the rollers' top line                            |
| `length`        | m    | required  | arc: its length (≤ π · radius)                                  |
| `rollers`       | —    | required  | arc: number of rollers spread evenly over it, 1 to 1000         |
| `origin`        | m    | [0, 0, 0] | arc: where it starts [x, y, z]; it runs aft and bends down      |
| `angle`         | rad  | 0         | arc: its slope below the horizontal at the origin               |
| `positions`     | m    | required  | rollers: top points, one row [x, y, z] per roller               |
| `axes`          | —    | b2        | rollers: axis directions, one row per roller                    |
| `roller_radius` | m    | 0.25      | radius of every roller                                          |

### `[controller]` — `pl.PID` on the vessel's η; needs `[vessel]`

Gains are 6 numbers (a diagonal matrix) or a 6×6 matrix.

| key              | unit                 | default  | meaning                                            |
|------------------|----------------------|----------|----------------------------------------------------|
| `kp`             | N/m, N·m/rad         | required | proportional gains                                 |
| `kd`             | N·s/m, N·m·s/rad     | required | derivative gains                                   |
| `ki`             | N/(m·s), N·m/(rad·s) | none     | integral gains; none: PD control                   |
| `reference`      | m, rad               | required | η_ref = [x, y, z, φ, θ, ψ]; or give `[controller.route]` |
| `start`          | s                    | 0        | time the controller takes over from holding thrust |
| `integral_limit` | m·s, rad·s           | none     | bound on ∫(η − η_ref) dt, 6 numbers > 0            |
| `thrust_limit`   | N, N, N·m            | none     | bound on thrust [surge, sway, yaw], > 0            |

### `[controller.route]` — `pl.Route`: a moving reference along a lay route, instead of `reference`

| key          | unit | default  | meaning                                         |
|--------------|------|----------|-------------------------------------------------|
| `start`      | m    | required | where the route starts, [x, y]                  |
| `heading`    | rad  | 0        | the route's direction and the vessel's heading  |
| `speed`      | m/s  | 0        | lay speed along the route                       |
| `start_time` | s    | 0        | when the reference starts moving                |

### `[controller.tension]` — `pl.TensionControl`: the lay-tension loop, `PID(tension=...)`

Moves the DP set-point along the reference's heading (the route's, or ψ of a fixed `reference`) at
−gain · (T_f − target) m/s, T_f the top tension low-passed with the `filter` time constant.

| key          | unit     | default  | meaning                                                 |
|--------------|----------|----------|---------------------------------------------------------|
| `target`     | N        | required | top tension to hold                                     |
| `gain`       | m/(s·N)  | required | set-point speed per newton of tension error, > 0        |
| `start`      | s        | 0        | time the loop starts                                    |
| `rate_limit` | m/s      | none     | bound on the set-point's speed, > 0                     |
| `filter`     | s        | 20       | time constant of the tension's low-pass filter, > 0     |

### `[pay_out]` — `model.pay_out(end, speed)`: pipe paid out (or in) through the tensioner or tower

The end must be the one `[vessel]` holds or a driven `[supports]` end. The speed rises smoothly from 0 at
`start_time` to `speed` over `ramp` seconds, v(t) = speed · (3s² − 2s³), s = (t − start_time)/ramp clipped
to [0, 1] (a sudden start sends an axial shock v·√(EA·m) through the pipe): the length paid out by t ≥
start_time + ramp is speed · (t − start_time − ramp/2). A route starts at full speed: a pay-out that starts
with it falls speed · ramp/2 behind the vessel, which lifts laid pipe off the seabed; starting it ramp/2
earlier (`start_time` = the route's − ramp/2) keeps the length paid out equal to the route's advance.

| key          | unit | default  | meaning                                                                           |
|--------------|------|----------|-----------------------------------------------------------------------------------|
| `end`        | —    | "B"      | the end the pipe is paid out at, "A" or "B"                                       |
| `speed`      | m/s  | required | of unstretched pipe (< 0 pays in), or `"route"`: the speed of `[controller.route]` |
| `start_time` | s    | 0        | when the pay-out starts; with speed = "route", the route's `start_time`           |
| `ramp`       | s    | 60       | time over which the speed rises to its value, ≥ 0 (0: at once)                   |

### `[[environment]]` — `pl.Force`, one table per force on the vessel; needs `[vessel]`

| key     | unit   | default  | meaning                                         |
|---------|--------|----------|-------------------------------------------------|
| `value` | N, N·m | required | force and moment [X, Y, Z, K, M, N], body frame |
| `start` | s      | 0        | time the force starts                           |

### `[solver]` — `model.static(steps, start)`, `model.simulation(dt)`, `simulation.run(t_end, record_every)`

| key            | unit | default | meaning                                                 |
|----------------|------|---------|---------------------------------------------------------|
| `static_steps` | —    | 1       | initial number of (adaptive) static load steps, ≥ 1     |
| `static_start` | —    | "auto"  | Newton's start: `"auto"`, `"reference"` or `"catenary"` |
| `dt`           | s    | 0.05    | time step, > 0                                          |
| `t_end`        | s    | none    | end of the time simulation, > 0; none: statics only     |
| `record_every` | —    | 1       | record every k-th time step, an integer ≥ 1             |

### `[output]` — for the figures; kept in `Scenario.output` for the program that runs the scenario

| key          | unit | default | meaning                                                                          |
|--------------|------|---------|----------------------------------------------------------------------------------|
| `plot_times` | s    | none    | times of the pipe shapes to plot, each in [0, t_end]; none: the plotter's choice |
"""

from __future__ import annotations

import copy
import itertools
import math
import os
import re
import tomllib
from collections.abc import Callable, Collection, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, cast

from pydantic import ValidationError

import pipelay as pl
from pipelay import scenario_models as models
from pipelay.scenario_models import KEYS, MAX_ELEMENTS, join, show, suggest

__all__ = [
    "KEYS",
    "MAX_ELEMENTS",
    "Scenario",
    "SmoothStart",
    "apply_overrides",
    "json_schema",
    "load_scenario",
    "parse_scenario",
    "validate_overrides",
]

_PAY_OUT_RAMP = 60.0
"""Default `[pay_out]` ramp (s)."""
_DRAFT = "https://json-schema.org/draft/2020-12/schema"


@dataclass
class Scenario:
    """A model ready to solve, its solver settings and outputs, as read from a scenario file.

    Attributes:
        model: the model with its supports, loads and vessel.
        dt: time step of the simulation (s).
        t_end: end time of the simulation (s); None: statics only.
        record_every: record every k-th time step.
        static_steps: initial number of load steps of the static solve; None: the engine's default.
        static_start: Newton's starting shape in statics: "auto", "reference" or "catenary".
        output: the `[output]` table: `plot_times` (list of s, or None when not given).
        source: the parsed TOML as given (a copy), for provenance.
    """

    model: pl.Model
    dt: float
    t_end: float | None
    record_every: int
    static_steps: int | None
    static_start: Literal["auto", "reference", "catenary"]
    output: dict[str, Any]
    source: dict[str, Any]


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


# Checking: the pydantic models, their errors as InputError.


def _folder(origin: str, folder: str | os.PathLike[str] | None) -> Path:
    """The folder file paths in a scenario are relative to: `folder`, else the origin's if it is a file, else
    the current one."""
    if folder is not None:
        return Path(folder)
    return Path(origin).absolute().parent if Path(origin).is_file() else Path.cwd()


def _errors(data: object, folder: Path) -> list[str]:
    """The messages `key.path: what is wrong` of a document, the one to report first; [] if it is valid."""
    try:
        models.ScenarioFile.model_validate(data, context={"folder": folder})
    except ValidationError as error:
        return models.explain(error)
    return []


def _check(data: object, folder: Path) -> models.ScenarioFile:
    """The checked document; raises InputError `key.path: message` (without the origin)."""
    try:
        return models.ScenarioFile.model_validate(data, context={"folder": folder})
    except ValidationError as error:
        raise pl.InputError(models.explain(error)[0]) from None


def _settings(file: models.ScenarioFile) -> dict[str, Any]:
    """The Scenario's solver settings and outputs."""
    solver = file.solver
    return {
        "dt": solver.dt,
        "t_end": solver.t_end,
        "record_every": solver.record_every,
        "static_steps": solver.static_steps,
        "static_start": solver.static_start,
        "output": {"plot_times": file.output.plot_times},
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
_STINGER_ARGUMENTS = {
    "stinger radius": "vessel.lay.stinger.radius",
    "stinger length": "vessel.lay.stinger.length",
    "stinger origin": "vessel.lay.stinger.origin",
    "stinger angle": "vessel.lay.stinger.angle",
    "roller positions": "vessel.lay.stinger.positions",
    "roller axes": "vessel.lay.stinger.axes",
}
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


def _rod(file: models.ScenarioFile) -> pl.Rod:
    """The cross-section (`[pipe]` or `[section]`) and the rod."""
    if file.pipe is not None:
        with _engine("pipe", KEYS["pipe"]):
            section = pl.Section.pipe(**file.pipe.given())
    else:
        with _engine("section", KEYS["section"]):
            section = pl.Section(**cast(models.Section, file.section).given())
    with _engine("rod", KEYS["rod"]):
        if isinstance(file.rod, models.NodesRod):
            return pl.Rod(file.rod.nodes, section)
        return pl.Rod.straight(section=section, **file.rod.given())


def _seabed(seabed: models.Seabed) -> pl.Seabed:
    """`[sea.seabed]` and its bathymetry."""
    bathymetry = None
    if seabed.bathymetry is not None:
        with _engine("sea.seabed.bathymetry", KEYS["sea.seabed.bathymetry"]):
            bathymetry = _BATHYMETRIES[seabed.bathymetry.kind](**seabed.bathymetry.given())
    with _engine("sea.seabed", KEYS["sea.seabed"]):
        return pl.Seabed(**seabed.given("bathymetry"), bathymetry=bathymetry)


def _sea(sea: models.Sea) -> pl.Sea:
    """`[sea]` with its current, seabed and waves. The waves' `ramp` is passed only when the file gives it."""
    current = seabed = waves = None
    if sea.current is not None:
        with _engine("sea.current", KEYS["sea.current"]):
            current = _CURRENTS[sea.current.kind](**sea.current.given())
    if sea.seabed is not None:
        seabed = _seabed(sea.seabed)
    if sea.waves is not None:
        with _engine("sea.waves", KEYS["sea.waves"]):
            waves = _WAVES[sea.waves.kind](**sea.waves.given())
    with _engine("sea", KEYS["sea"], _SEABED_SHAPE):
        return pl.Sea(**sea.given("current", "seabed", "waves"), current=current, seabed=seabed, waves=waves)


def _hold(model: pl.Model, supports: models.Supports) -> None:
    """Clamp, pin or drive the ends of `[supports]`."""
    ends: list[tuple[models.End, models.Clamp | models.Pin | models.Drive | None]] = [
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


def _lay(lay: models.SLay | models.JLay) -> pl.SLay | pl.JLay:
    """The lay equipment of `[vessel.lay]` (and `[vessel.lay.stinger]`)."""
    if isinstance(lay, models.JLay):
        with _engine("vessel.lay", KEYS["vessel.lay"]):
            return pl.JLay(**lay.given())
    stinger = None
    if lay.stinger is not None:
        with _engine("vessel.lay.stinger", KEYS["vessel.lay.stinger"], _STINGER_ARGUMENTS):
            if isinstance(lay.stinger, models.RollerStinger):
                stinger = pl.Stinger.from_rollers(**lay.stinger.given())
            else:
                stinger = pl.Stinger(**lay.stinger.given())
    with _engine("vessel.lay", KEYS["vessel.lay"]):
        return pl.SLay(stinger=stinger, **lay.given("stinger"))


def _vessel(vessel: models.ModelVessel | models.MatrixVessel) -> pl.Vessel:
    """The vessel of `[vessel]`, with the RAOs of `raos` if given (else the API's default)."""
    raos: dict[str, Any] = {}
    if vessel.raos is not None:
        with _engine("vessel.raos", (), {"path": "vessel.raos", "raos": "vessel.raos"}):
            raos["raos"] = pl.Raos.read(vessel.raos)
    with _engine("vessel", KEYS["vessel"]):
        if isinstance(vessel, models.ModelVessel):
            return pl.Vessel.osv(**raos)
        return pl.Vessel(**vessel.given("end", "eta", "angle", "raos", "lay"), **raos)


def _controller(controller: models.FixedController | models.RouteController) -> pl.PID:
    """The PID of `[controller]`, with its route and tension loop."""
    arguments = controller.given("route", "tension")
    if isinstance(controller, models.RouteController):
        with _engine("controller.route", KEYS["controller.route"]):
            arguments["reference"] = pl.Route(**controller.route.given())
    if controller.tension is not None:
        with _engine("controller.tension", KEYS["controller.tension"]):
            arguments["tension"] = pl.TensionControl(**controller.tension.given())
    with _engine("controller", KEYS["controller"]):
        return pl.PID(**arguments)


def _attach(model: pl.Model, file: models.ScenarioFile) -> None:
    """Build the vessel, its lay equipment, controller and environment; attach them."""
    vessel = cast(models.ModelVessel | models.MatrixVessel, file.vessel)
    lay = None if vessel.lay is None else _lay(vessel.lay)
    body = _vessel(vessel)
    controller = None if file.controller is None else _controller(file.controller)
    environment = []
    for i, force in enumerate(file.environment):
        with _engine(f"environment[{i}]", KEYS["environment"]):
            environment.append(pl.Force(**force.given()))
    with _engine("vessel", KEYS["vessel"]):
        model.attach_vessel(
            vessel.end,
            body,
            eta=vessel.eta,
            angle=vessel.angle,
            controller=controller,
            environment=environment,
            lay=lay,
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


def _build(file: models.ScenarioFile) -> pl.Model:
    """Make the API calls of a checked document."""
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
    if file.vessel is not None:
        _attach(model, file)
    if file.pay_out is not None:
        speed = _pay_out(file.pay_out, file.controller)
        with _engine("pay_out", KEYS["pay_out"]):
            model.pay_out(file.pay_out.end or "B", speed=speed)
    return model


def parse_scenario(
    data: dict[str, Any], origin: str = "<dict>", folder: str | os.PathLike[str] | None = None
) -> Scenario:
    """The scenario described by `data`, a parsed TOML document (see the module's reference).

    Every key is checked before the model is built; nothing is solved. `origin` names the source in messages;
    file paths in it (`vessel.raos`) are relative to `folder` (default: the folder of `origin` if it is a file,
    else the current one). Raises pl.InputError whose message starts with the key path and ends with
    `(in origin)`.
    """
    try:
        file = _check(data, _folder(origin, folder))
        model = _build(file)
    except pl.InputError as error:
        raise pl.InputError(f"{error} (in {origin})") from None
    return Scenario(model=model, source=copy.deepcopy(data), **_settings(file))


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
    """The scenario in the TOML file at `path` (see the module's reference); nothing is solved.

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


# Sweeps: dotted keys.

_NAME = re.compile(r"([A-Za-z_]\w*)((?:\[\d+\])*)")


def _dotted(key: str) -> list[str | int]:
    """`sea.waves.hs` as ["sea", "waves", "hs"], `point_loads[0].force` as ["point_loads", 0, "force"]."""
    parts: list[str | int] = []
    for name in key.split("."):
        found = _NAME.fullmatch(name)
        if found is None:
            raise pl.InputError(f"{key}: not a dotted key (key names joined by '.', entries as name[i])")
        parts.append(found.group(1))
        parts.extend(int(index) for index in re.findall(r"\d+", found.group(2)))
    return parts


def _check_key(key: str) -> None:
    """A dotted key names a key of the format."""
    table = ""
    for name in (part for part in _dotted(key) if isinstance(part, str)):
        if table not in KEYS:
            raise pl.InputError(f"{key}: {table} is a value, not a table")
        if name not in KEYS[table]:
            raise pl.InputError(
                f"{key}: {join(table, name)} is not a key of the format{suggest(name, KEYS[table])}"
            )
        table = join(table, name)


def _child(node: object, part: str | int, key: str) -> Any:
    """The table or entry `part` of `node` on the way to `key` (a missing table is created)."""
    if isinstance(part, str) and isinstance(node, dict):
        return node.setdefault(part, {})
    if isinstance(part, int) and isinstance(node, list) and -len(node) <= part < len(node):
        return node[part]
    raise pl.InputError(f"{key}: no table or entry {part!r} on the way in the scenario, got {show(node)}")


def apply_overrides(data: dict[str, Any], case: dict[str, Any]) -> dict[str, Any]:
    """A deep copy of the parsed document `data` with each dotted key of `case` (`"sea.waves.hs"`,
    `"point_loads[0].force"`) set to its value, creating missing tables; `data` is left as it is.

    Raises pl.InputError naming the key if its way goes through a value or a missing entry of an array.
    """
    result = copy.deepcopy(data)
    for key, value in case.items():
        *way, last = _dotted(key)
        node: Any = result
        for part in way:
            node = _child(node, part, key)
        if isinstance(last, int):
            _child(node, last, key)  # the entry must exist
        elif not isinstance(node, dict):
            raise pl.InputError(f"{key}: no table to set {last!r} in, got {show(node)}")
        node[last] = copy.deepcopy(value)
    return result


def _check_case(data: dict[str, Any], case: dict[str, Any], folder: Path) -> None:
    """`data` with the case's keys set is a valid document: an error about one of its keys first, an error
    elsewhere said to come from the case's values."""
    messages = _errors(apply_overrides(data, case), folder)
    prefixes = tuple(f"{key}{end}" for key in case for end in (":", ".", "["))
    about = [message for message in messages if message.startswith(prefixes)]
    if about:
        raise pl.InputError(about[0])
    if messages:
        values = ", ".join(f"{key} = {show(value)}" for key, value in case.items())
        raise pl.InputError(f"{values}: {messages[0]}")


def validate_overrides(
    data: dict[str, Any],
    overrides: dict[str, list[Any]],
    origin: str = "<sweep>",
    folder: str | os.PathLike[str] | None = None,
) -> None:
    """Check a parameter sweep before any case runs: each dotted key of `overrides` (`"sea.waves.hs"`,
    `"controller.kp"`, `"point_loads[0].force"`) names a key of the format, and every case (one value of each
    key), put in the parsed document `data` (itself valid), makes a valid document: keys that depend on each
    other (`solver.t_end` and `output.plot_times`) are judged together.

    Only the keys are checked, nothing is built (the engine's own checks, e.g. a matrix's symmetry, come when
    a case runs). `folder` is as for `parse_scenario`. Raises pl.InputError naming the dotted key, the bad
    value and what is allowed, ending with `(in origin)`.
    """
    where = _folder(origin, folder)
    try:
        for key, values in overrides.items():
            _check_key(key)
            if not isinstance(values, list) or not values:
                raise pl.InputError(f"{key}: must be a non-empty list of values, got {show(values)}")
        _check(data, where)
        for values in itertools.product(*overrides.values()):
            _check_case(data, dict(zip(overrides, values, strict=True)), where)
    except pl.InputError as error:
        raise pl.InputError(f"{error} (in {origin})") from None


# The JSON Schema, documented from the reference above.


def _reference(doc: str) -> dict[str, tuple[str, dict[str, list[str]]]]:
    """The reference tables of `doc`: for each table path, its heading's description and its rows by key
    ([unit, default, meaning])."""
    tables = {}
    for block in re.split(r"^### ", doc, flags=re.MULTILINE)[1:]:
        heading, _, body = block.partition("\n")
        names, _, about = heading.partition(" — ")
        rows = {}
        for line in body.splitlines():
            if line.startswith("| `"):
                key, *cells = (cell.strip() for cell in line.strip("|").split("|"))
                rows[key.strip("`")] = cells
        for path in re.findall(r"`\[\[?([\w.]+)\]\]?`", names) or [""]:
            tables[path] = (about, rows)
    return tables


def _toml(text: str) -> object:
    """The TOML value `text` spells (a default of the reference), or None."""
    try:
        return tomllib.loads(f"value = {text}")["value"]
    except tomllib.TOMLDecodeError:
        return None


def _heading(reference: dict[str, Any], path: str) -> str:
    """The description of the table at `path`: its heading's, or that of its first table (`[supports.A]`)."""
    inside = (about for table, (about, _) in reference.items() if table.startswith(f"{path}."))
    return reference[path][0] if path in reference else next(inside, "")


def _document(definition: dict[str, Any], path: str, reference: dict[str, Any]) -> None:
    """Describe a table's schema and its properties from the reference: meaning, unit and default."""
    about, rows = reference.get(path, ("", {}))
    if about:
        definition["description"] = about
    for key, schema in definition.get("properties", {}).items():
        schema.pop("title", None)  # pydantic's "Outer Diameter": the description says more
        if key not in rows:  # a table: its heading's description; its keys have the defaults
            schema.pop("default", None)
            schema["description"] = _heading(reference, join(path, key))
            continue
        unit, default, meaning = rows[key]
        given = "required" if key in definition.get("required", ()) else f"default {default}"
        schema["description"] = f"{meaning} ({'' if unit == '—' else unit + '; '}{given})"
        value = _toml(default)
        if given != "required" and value is not None:
            schema["default"] = value


def _without_null(schema: Any) -> Any:
    """The schema without pydantic's `null` (an absent key, which TOML cannot write): no `{"type": "null"}`
    branches, no `"default": null`."""
    if isinstance(schema, list):
        return [_without_null(item) for item in schema]
    if not isinstance(schema, dict):
        return schema
    result = {key: _without_null(value) for key, value in schema.items() if (key, value) != ("default", None)}
    branches = [branch for branch in result.pop("anyOf", []) if branch != {"type": "null"}]
    if len(branches) == 1:
        result.update(branches[0])
    elif branches:
        result["anyOf"] = branches
    return result


def json_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of scenario files, from the format's pydantic models, with the meaning,
    unit and default of each key from this module's reference, for editors to complete and check scenario
    files (e.g. taplo / Even Better TOML).

    It checks what a schema can: key names, types, bounds, vector and matrix shapes, the keys of each kind.
    The rules across keys (exactly one of [pipe] and [section], a vessel needs a sea, ...) and finiteness are
    left to `load_scenario`.
    """
    schema = models.ScenarioFile.model_json_schema()
    reference = _reference(__doc__ or "")
    paths = {table.__name__: path for table, path in models.TABLES.items()}
    for name, definition in [("ScenarioFile", schema), *schema.get("$defs", {}).items()]:
        _document(definition, paths[name], reference)
    schema["title"] = "pipelay scenario"
    schema["description"] = (__doc__ or "").split("\n", 1)[0]
    return {"$schema": _DRAFT, **_without_null(schema)}
