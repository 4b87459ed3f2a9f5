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

### `[vessel]` — `pl.Vessel.osv()` or `pl.Vessel(M, D, G, ...)`, then `model.attach_vessel`

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
import difflib
import math
import operator
import os
import re
import reprlib
import tomllib
from collections.abc import Callable, Collection, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, NoReturn, cast

import pipelay as pl

__all__ = ["KEYS", "MAX_ELEMENTS", "Scenario", "SmoothStart", "load_scenario", "parse_scenario"]

MAX_ELEMENTS = 1_000_000
"""Largest number of elements a scenario's `[rod]` may ask for."""
_INT64 = 2**63 - 1  # the largest count the engine takes

_End = Literal["A", "B"]
_ETA = "[x, y, z, φ, θ, ψ]"
_POSITIVE = ((">", 0.0),)
_NON_NEGATIVE = ((">=", 0.0),)
_COMPARE: dict[str, Callable[[float, float], bool]] = {
    ">": operator.gt,
    ">=": operator.ge,
    "<": operator.lt,
    "<=": operator.le,
}
_SHOW = reprlib.Repr()
_SHOW.maxlist = _SHOW.maxdict = 8
_SHOW.maxstring = _SHOW.maxother = 60


def _show(value: object) -> str:
    """A short rendering of a value for messages, in TOML spelling where it differs from Python's."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return "a table"
    return _SHOW.repr(value)


def _fail(path: str, message: str) -> NoReturn:
    """Raise the InputError `path: message`."""
    raise pl.InputError(f"{path}: {message}")


def _paren(unit: str) -> str:
    """` (unit)`, or nothing for a dimensionless quantity."""
    return f" ({unit})" if unit else ""


def _either(options: tuple[str, ...]) -> str:
    """`"a", "b" or "c"`."""
    quoted = [f'"{option}"' for option in options]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]


def _suggest(name: str, allowed: tuple[str, ...]) -> str:
    """`; did you mean 'x'?` for the closest allowed name (case-insensitive), else the allowed names."""
    lowered = {option.lower(): option for option in allowed}
    close = difflib.get_close_matches(name.lower(), list(lowered), n=1, cutoff=0.6)
    if close:
        return f"; did you mean '{lowered[close[0]]}'?"
    return f"; allowed: {', '.join(allowed)}"


def _join(path: str, key: str) -> str:
    """The key path of `key` inside the table at `path` ("" for the top level)."""
    return f"{path}.{key}" if path else key


# Checks: each describes what it allows and turns a TOML value into what the API takes, or fails.


class _Check:
    """How one value is read: `describe()` says what is allowed, calling it checks and converts."""

    def describe(self) -> str:
        """What is allowed, with units, e.g. `a number > 0 (m)`."""
        raise NotImplementedError

    def __call__(self, value: object, path: str) -> Any:
        """The value converted for the API; raises InputError naming `path` if it is not allowed."""
        raise NotImplementedError


@dataclass(frozen=True)
class _Number(_Check):
    """A finite number in `unit`, within `bounds` ((operator, limit) pairs)."""

    unit: str
    bounds: tuple[tuple[str, float], ...] = ()

    def limits(self) -> str:
        """The bounds as text, e.g. `> -1 and < 0.5`."""
        return " and ".join(f"{op} {limit:g}" for op, limit in self.bounds)

    def describe(self) -> str:
        """What is allowed."""
        bounds = f" {self.limits()}" if self.bounds else ""
        return f"a number{bounds}{_paren(self.unit)}"

    def __call__(self, value: object, path: str) -> float:
        """The value as a float."""
        if isinstance(value, bool) or not isinstance(value, int | float):
            _fail(path, f"must be a number{_paren(self.unit)}, got {_show(value)}")
        try:
            number = float(value)
        except OverflowError:  # an integer beyond the largest float
            number = math.inf
        if not math.isfinite(number):
            _fail(path, f"must be a finite number{_paren(self.unit)}, got {_show(value)}")
        if not all(_COMPARE[op](number, limit) for op, limit in self.bounds):
            unit = _paren(self.unit) if "," in self.unit else f" {self.unit}".rstrip()
            _fail(path, f"must be {self.limits()}{unit}, got {_show(value)}")
        return number


@dataclass(frozen=True)
class _Integer(_Check):
    """An integer in [low, high] (no upper limit when high is None)."""

    low: int
    high: int | None = None

    def describe(self) -> str:
        """What is allowed."""
        return (
            f"an integer >= {self.low}" if self.high is None else f"an integer in [{self.low}, {self.high}]"
        )

    def __call__(self, value: object, path: str) -> int:
        """The value as an int."""
        if isinstance(value, bool) or not isinstance(value, int):
            _fail(path, f"must be {self.describe()}, got {_show(value)}")
        if value < self.low or (self.high is not None and value > self.high):
            _fail(path, f"must be {self.describe()}, got {value}")
        if value > _INT64:
            _fail(path, f"must be {self.describe()} and <= {_INT64} (64 bits), got {value}")
        return value


@dataclass(frozen=True)
class _Text(_Check):
    """Any text."""

    def describe(self) -> str:
        """What is allowed."""
        return "text (a quoted string)"

    def __call__(self, value: object, path: str) -> str:
        """The value as a str."""
        if not isinstance(value, str):
            _fail(path, f"must be {self.describe()}, got {_show(value)}")
        return value


@dataclass(frozen=True)
class _Choice(_Check):
    """One of a few words."""

    options: tuple[str, ...]

    def describe(self) -> str:
        """What is allowed."""
        return _either(self.options)

    def __call__(self, value: object, path: str) -> str:
        """The word."""
        if not isinstance(value, str):
            _fail(path, f"must be {self.describe()}, got {_show(value)}")
        if value not in self.options:
            close = difflib.get_close_matches(value, self.options, n=1, cutoff=0.6)
            hint = f'; did you mean "{close[0]}"?' if close else ""
            _fail(path, f"must be {self.describe()}, got {_show(value)}{hint}")
        return value


def _some(at_least: int) -> str:
    """`a list of at least n` (or `a non-empty list of` for n = 1), for lists of any length."""
    return "a non-empty list of" if at_least == 1 else f"a list of at least {at_least}"


def _items(value: object, path: str, expected: str, count: int | None, at_least: int = 0) -> list[Any]:
    """`value` as a list of `count` items (or at least `at_least` when count is None)."""
    if not isinstance(value, list | tuple):
        _fail(path, f"must be {expected}, got {_show(value)}")
    if (count is not None and len(value) != count) or len(value) < at_least:
        _fail(path, f"must be {expected}, got {len(value)}: {_show(value)}")
    return list(value)


@dataclass(frozen=True)
class _Vector(_Check):
    """`count` numbers (`labels` names them), each within `bounds`; count None: any number of them."""

    count: int | None
    unit: str
    labels: str = ""
    bounds: tuple[tuple[str, float], ...] = ()
    at_least: int = 0

    def describe(self) -> str:
        """What is allowed."""
        bounds = " " + _Number(self.unit, self.bounds).limits() if self.bounds else ""
        labels = f" {self.labels}" if self.labels else ""
        if self.count is None:
            return f"{_some(self.at_least)} numbers{bounds}{_paren(self.unit)}"
        return f"{self.count} numbers{labels}{bounds}{_paren(self.unit)}"

    def __call__(self, value: object, path: str) -> list[float]:
        """The numbers as floats."""
        items = _items(value, path, self.describe(), self.count, self.at_least)
        number = _Number(self.unit, self.bounds)
        return [number(item, f"{path}[{i}]") for i, item in enumerate(items)]


@dataclass(frozen=True)
class _Matrix(_Check):
    """Rows of `cols` numbers: exactly `rows` rows, or (rows None) at least `at_least`."""

    rows: int | None
    cols: int
    unit: str
    labels: str = ""
    at_least: int = 0

    def describe(self) -> str:
        """What is allowed."""
        row = f"{self.cols} numbers {self.labels}".rstrip()
        if self.rows is None:
            return f"{_some(self.at_least)} rows of {row}{_paren(self.unit)}"
        return f"a {self.rows}×{self.cols} matrix, {self.rows} rows of {row}{_paren(self.unit)}"

    def __call__(self, value: object, path: str) -> list[list[float]]:
        """The rows as lists of floats."""
        rows = _items(value, path, self.describe(), self.rows, self.at_least)
        row = _Vector(self.cols, self.unit, self.labels)
        return [row(item, f"{path}[{i}]") for i, item in enumerate(rows)]


@dataclass(frozen=True)
class _NumberOrVector(_Check):
    """One number, or `count` numbers (`labels`), each within `bounds`."""

    count: int
    unit: str
    labels: str
    bounds: tuple[tuple[str, float], ...]

    def describe(self) -> str:
        """What is allowed."""
        vector = _Vector(self.count, self.unit, self.labels, self.bounds).describe()
        return f"a number or {vector}"

    def __call__(self, value: object, path: str) -> float | list[float]:
        """The float or the list of floats."""
        if isinstance(value, list | tuple):
            return _Vector(self.count, self.unit, self.labels, self.bounds)(value, path)
        if isinstance(value, bool) or not isinstance(value, int | float):
            _fail(path, f"must be {self.describe()}, got {_show(value)}")
        return _Number(self.unit, self.bounds)(value, path)


@dataclass(frozen=True)
class _NumberOrWord(_Check):
    """A finite number in `unit`, or one of a few words."""

    unit: str
    options: tuple[str, ...]

    def describe(self) -> str:
        """What is allowed."""
        return f"a number{_paren(self.unit)} or {_either(self.options)}"

    def __call__(self, value: object, path: str) -> float | str:
        """The float, or the word."""
        if isinstance(value, str):
            if value not in self.options:
                _fail(path, f"must be {self.describe()}, got {_show(value)}")
            return value
        if isinstance(value, bool) or not isinstance(value, int | float):
            _fail(path, f"must be {self.describe()}, got {_show(value)}")
        return _Number(self.unit)(value, path)


@dataclass(frozen=True)
class _Gains(_Check):
    """Controller gains: 6 numbers (a diagonal matrix) or a 6×6 matrix."""

    unit: str

    def describe(self) -> str:
        """What is allowed."""
        return f"6 numbers (the diagonal) or a 6×6 matrix{_paren(self.unit)}"

    def __call__(self, value: object, path: str) -> list[float] | list[list[float]]:
        """The gains as a list or a list of rows."""
        items = _items(value, path, self.describe(), 6)
        rows = [isinstance(item, list | tuple) for item in items]
        if all(rows):
            return _Matrix(6, 6, self.unit)(items, path)
        if any(rows):
            _fail(path, f"must be {self.describe()}, got a mix of numbers and rows: {_show(value)}")
        return _Vector(6, self.unit)(items, path)


@dataclass(frozen=True)
class _Node(_Check):
    """A node: an integer index (its range is checked against the rod) or "A" / "B"."""

    def describe(self) -> str:
        """What is allowed."""
        return 'a node index (an integer; negative counts from the end) or "A" / "B"'

    def __call__(self, value: object, path: str) -> int | str:
        """The index or the end's name."""
        if isinstance(value, str):
            return _Choice(("A", "B"))(value, path)
        if isinstance(value, bool) or not isinstance(value, int):
            _fail(path, f"must be {self.describe()}, got {_show(value)}")
        return value


# The sections: every key and how it is read. KEYS, derived from them, lists every table's keys.

_XYZ = "[x, y, z]"
_VELOCITY = "[vx, vy, vz]"
_PAIR = "[axial, normal]"
_AXES = "[axis 2, axis 3]"
_PIPE: dict[str, _Check] = {
    "outer_diameter": _Number("m", _POSITIVE),
    "wall_thickness": _Number("m", _POSITIVE),
    "density": _Number("kg/m³", _POSITIVE),
    "youngs_modulus": _Number("Pa", _POSITIVE),
    "poisson_ratio": _Number("", ((">", -1.0), ("<", 0.5))),
    "contents_density": _Number("kg/m³", _NON_NEGATIVE),
    "drag": _Vector(2, "", _PAIR, _NON_NEGATIVE),
    "added_mass": _Vector(2, "", _PAIR, _NON_NEGATIVE),
}
_SECTION: dict[str, _Check] = {
    "EA": _Number("N", _POSITIVE),
    "GA": _NumberOrVector(2, "N", _AXES, _POSITIVE),
    "GJ": _Number("N·m²", _POSITIVE),
    "EI": _NumberOrVector(2, "N·m²", _AXES, _POSITIVE),
    "mass": _Number("kg/m", _POSITIVE),
    "inertia": _Vector(3, "kg·m", "[J1, J2, J3]", _NON_NEGATIVE),
    "outer_diameter": _Number("m", _NON_NEGATIVE),
    "displaced_area": _Number("m²", _NON_NEGATIVE),
    "drag": _Vector(2, "", _PAIR, _NON_NEGATIVE),
    "added_mass": _Vector(2, "", _PAIR, _NON_NEGATIVE),
    "rotational_damping": _NumberOrVector(3, "N·m·s/m", "[t1, t2, t3]", _NON_NEGATIVE),
}
_ROD: dict[str, _Check] = {
    "start": _Vector(3, "m", _XYZ),
    "end": _Vector(3, "m", _XYZ),
    "elements": _Integer(1, MAX_ELEMENTS),
    "nodes": _Matrix(None, 3, "m", _XYZ, at_least=2),
}
_SEA: dict[str, _Check] = {"depth": _Number("m", _POSITIVE), "density": _Number("kg/m³", _NON_NEGATIVE)}
_CURRENT: dict[str, _Check] = {
    "kind": _Choice(("uniform", "linear", "profile")),
    "velocity": _Vector(3, "m/s", _VELOCITY),
    "surface_velocity": _Vector(3, "m/s", _VELOCITY),
    "depths": _Vector(None, "m", at_least=1),
    "velocities": _Matrix(None, 3, "m/s", _VELOCITY, at_least=1),
    "start": _Number("s"),
}
_SEABED: dict[str, _Check] = {
    "stiffness": _Number("Pa/m", _POSITIVE),
    "damping": _Number("Pa·s/m", _NON_NEGATIVE),
    "friction": _NumberOrVector(2, "", _PAIR.replace("normal", "lateral"), _NON_NEGATIVE),
    "mobilisation": _Number("m", _POSITIVE),
}
_BATHYMETRY: dict[str, _Check] = {
    "kind": _Choice(("flat", "plane", "grid")),
    "z": _Number("m"),
    "gradient": _Vector(2, "", "[dz/dx, dz/dy]"),
    "x": _Vector(None, "m", at_least=2),
    "y": _Vector(None, "m", at_least=2),
}
_DRIVE_KEYS = ("amplitude", "period", "phase", "ramp")
_BATHYMETRY_KINDS = {"flat": ("z",), "plane": ("z", "gradient"), "grid": ("x", "y", "z")}
_CURRENT_KINDS = {
    "uniform": ("velocity",),
    "linear": ("surface_velocity",),
    "profile": ("depths", "velocities"),
}
_SUPPORT: dict[str, _Check] = {
    "kind": _Choice(("clamp", "pin", "drive")),
    "position": _Vector(3, "m", _XYZ),
    "rotation": _Matrix(3, 3, ""),
    "amplitude": _Vector(3, "m", _XYZ),
    "period": _Number("s", _POSITIVE),
    "phase": _Vector(3, "rad", _XYZ),
    "ramp": _Number("s", _NON_NEGATIVE),
}
_POINT_LOAD: dict[str, _Check] = {
    "node": _Node(),
    "force": _Vector(3, "N", "[fx, fy, fz]"),
    "moment": _Vector(3, "N·m", "[mx, my, mz]"),
}
_MATRICES = ("M", "D", "G", "M_RB", "quadratic_damping")
_VESSEL: dict[str, _Check] = {
    "end": _Choice(("A", "B")),
    "model": _Choice(("osv",)),
    "M": _Matrix(6, 6, "kg, kg·m, kg·m²"),
    "D": _Matrix(6, 6, "kg/s, kg·m/s, kg·m²/s"),
    "G": _Matrix(6, 6, "N/m, N, N·m/rad"),
    "M_RB": _Matrix(6, 6, "kg, kg·m, kg·m²"),
    "quadratic_damping": _Matrix(6, 6, "kg/m, kg, kg·m²"),
    "eta": _Vector(6, "m, rad", _ETA),
    "angle": _Vector(3, "rad", "[φ, θ, ψ]"),
}
_LAY: dict[str, _Check] = {
    "kind": _Choice(("s-lay", "j-lay")),
    "tensioner": _Vector(3, "m", _XYZ),
    "roller_stiffness": _Number("N/m", _POSITIVE),
    "friction": _Number("", _NON_NEGATIVE),
    "position": _Vector(3, "m", _XYZ),
    "angle": _Number("rad"),
}
_LAY_KINDS = {
    "s-lay": ("tensioner", "roller_stiffness", "friction", "stinger"),
    "j-lay": ("position", "angle"),
}
_STINGER: dict[str, _Check] = {
    "radius": _Number("m", _POSITIVE),
    "length": _Number("m", _POSITIVE),
    "rollers": _Integer(1, 1000),
    "origin": _Vector(3, "m", _XYZ),
    "angle": _Number("rad"),
    "positions": _Matrix(None, 3, "m", _XYZ, at_least=1),
    "axes": _Matrix(None, 3, "", _XYZ, at_least=1),
    "roller_radius": _Number("m", _POSITIVE),
}
_CONTROLLER: dict[str, _Check] = {
    "kp": _Gains("N/m, N·m/rad"),
    "kd": _Gains("N·s/m, N·m·s/rad"),
    "ki": _Gains("N/(m·s), N·m/(rad·s)"),
    "reference": _Vector(6, "m, rad", _ETA),
    "start": _Number("s"),
    "integral_limit": _Vector(6, "m·s, rad·s", _ETA, _POSITIVE),
    "thrust_limit": _Vector(3, "N, N, N·m", "[surge, sway, yaw]", _POSITIVE),
}
_ROUTE: dict[str, _Check] = {
    "start": _Vector(2, "m", "[x, y]"),
    "heading": _Number("rad"),
    "speed": _Number("m/s"),
    "start_time": _Number("s"),
}
_TENSION: dict[str, _Check] = {
    "target": _Number("N"),
    "gain": _Number("m/(s·N)", _POSITIVE),
    "start": _Number("s"),
    "rate_limit": _Number("m/s", _POSITIVE),
    "filter": _Number("s", _POSITIVE),
}
_PAY_OUT: dict[str, _Check] = {
    "end": _Choice(("A", "B")),
    "speed": _NumberOrWord("m/s", ("route",)),
    "start_time": _Number("s"),
    "ramp": _Number("s", _NON_NEGATIVE),
}
_PAY_OUT_RAMP = 60.0
_ENVIRONMENT: dict[str, _Check] = {
    "value": _Vector(6, "N, N·m", "[X, Y, Z, K, M, N]"),
    "start": _Number("s"),
}
_SOLVER: dict[str, _Check] = {
    "static_steps": _Integer(1),
    "static_start": _Choice(("auto", "reference", "catenary")),
    "dt": _Number("s", _POSITIVE),
    "t_end": _Number("s", _POSITIVE),
    "record_every": _Integer(1),
}
_OUTPUT: dict[str, _Check] = {
    "plot_times": _Vector(None, "s", bounds=_NON_NEGATIVE, at_least=1),
}
_GRAVITY = _Number("m/s²", _NON_NEGATIVE)
_TOP: dict[str, _Check] = {"title": _Text(), "description": _Text()}
_SECTIONS: tuple[str, ...] = ("gravity", "pipe", "section", "rod", "sea", "supports", "point_loads", "vessel")
_SECTIONS += ("controller", "pay_out", "environment", "solver", "output")

KEYS: dict[str, tuple[str, ...]] = {
    "": (*_TOP, *_SECTIONS),
    "gravity": ("acceleration",),
    "pipe": tuple(_PIPE),
    "section": tuple(_SECTION),
    "rod": tuple(_ROD),
    "sea": (*_SEA, "current", "seabed"),
    "sea.current": tuple(_CURRENT),
    "sea.seabed": (*_SEABED, "bathymetry"),
    "sea.seabed.bathymetry": tuple(_BATHYMETRY),
    "supports": ("A", "B"),
    "supports.A": tuple(_SUPPORT),
    "supports.B": tuple(_SUPPORT),
    "point_loads": tuple(_POINT_LOAD),
    "vessel": (*_VESSEL, "lay"),
    "vessel.lay": (*_LAY, "stinger"),
    "vessel.lay.stinger": tuple(_STINGER),
    "controller": (*_CONTROLLER, "route", "tension"),
    "controller.route": tuple(_ROUTE),
    "controller.tension": tuple(_TENSION),
    "pay_out": tuple(_PAY_OUT),
    "environment": tuple(_ENVIRONMENT),
    "solver": tuple(_SOLVER),
    "output": tuple(_OUTPUT),
}
"""Every table's keys ("" is the top level; an array of tables lists the keys of one entry)."""


class _Table:
    """One TOML table: its key path and values. Unknown keys are rejected when it is opened."""

    def __init__(self, value: object, path: str, keys: tuple[str, ...]) -> None:
        """Open `value` as the table at `path` whose keys are `keys`."""
        if not isinstance(value, dict):
            _fail(path, f"must be a table [{path}], got {_show(value)}")
        for key, item in value.items():
            if key not in keys:
                tables = isinstance(item, list) and bool(item) and all(isinstance(i, dict) for i in item)
                what = "section" if isinstance(item, dict) or tables else "key"
                _fail(_join(path, str(key) or '""'), f"unknown {what}{_suggest(str(key), keys)}")
        self.values: dict[str, Any] = value
        self.path = path

    def read(self, checks: dict[str, _Check], required: tuple[str, ...] = ()) -> dict[str, Any]:
        """The checked values of the keys of `checks` that are present; `required` ones must be."""
        for key in required:
            if key not in self.values:
                _fail(_join(self.path, key), f"missing required key; must be {checks[key].describe()}")
        return {
            key: check(self.values[key], _join(self.path, key))
            for key, check in checks.items()
            if key in self.values
        }


def _tables(value: object, path: str) -> list[object]:
    """The entries of the array of tables `[[path]]`."""
    if not isinstance(value, list):
        _fail(path, f"must be an array of tables [[{path}]], got {_show(value)}")
    for i, item in enumerate(value):
        if not isinstance(item, dict):
            _fail(f"{path}[{i}]", f"must be a table (an entry of [[{path}]]), got {_show(item)}")
    return value


@dataclass
class _Plan:
    """The checked arguments of every API call that builds the model, before any is made."""

    section: tuple[str, dict[str, Any]]
    rod: dict[str, Any]
    sea: dict[str, Any] | None
    current: tuple[str, dict[str, Any]] | None
    seabed: tuple[dict[str, Any], tuple[str, dict[str, Any]] | None] | None
    model: dict[str, Any]
    supports: dict[_End, tuple[str, dict[str, Any]]]
    point_loads: list[dict[str, Any]]
    vessel: dict[str, Any] | None
    controller: dict[str, Any] | None
    environment: list[dict[str, Any]]
    pay_out: dict[str, Any] | None = None


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


def _read_section(top: _Table) -> tuple[str, dict[str, Any]]:
    """`[pipe]` or `[section]`: which, and the arguments of pl.Section.pipe or pl.Section."""
    if "pipe" in top.values and "section" in top.values:
        _fail("section", "conflicts with [pipe]: give exactly one of [pipe] and [section]")
    if "section" in top.values:
        table = _Table(top.values["section"], "section", KEYS["section"])
        return "section", table.read(_SECTION, required=("EA", "GA", "GJ", "EI", "mass"))
    if "pipe" not in top.values:
        _fail("pipe", "missing required section; give [pipe] (pl.Section.pipe) or [section] (pl.Section)")
    pipe = _Table(top.values["pipe"], "pipe", KEYS["pipe"]).read(
        _PIPE, required=("outer_diameter", "wall_thickness")
    )
    half = pipe["outer_diameter"] / 2.0
    if pipe["wall_thickness"] > half:
        _fail(
            "pipe.wall_thickness",
            f"must be <= outer_diameter / 2 = {half:g} m, got {pipe['wall_thickness']:g}",
        )
    return "pipe", pipe


def _read_rod(top: _Table) -> tuple[dict[str, Any], int]:
    """`[rod]`: the arguments of pl.Rod.straight or pl.Rod, and the number of elements."""
    if "rod" not in top.values:
        _fail("rod", "missing required section; give start, end and elements (or nodes)")
    table = _Table(top.values["rod"], "rod", KEYS["rod"])
    straight = ("start", "end", "elements")
    if "nodes" in table.values:
        for key in straight:
            if key in table.values:
                _fail(f"rod.{key}", "conflicts with rod.nodes; give either nodes or start, end and elements")
        rod = table.read(_ROD)
        return rod, len(rod["nodes"]) - 1
    rod = table.read(_ROD, required=straight)
    return rod, rod["elements"]


def _read_bathymetry(value: object) -> tuple[str, dict[str, Any]]:
    """`[sea.seabed.bathymetry]`: its kind and the arguments of pl.Bathymetry.flat, .plane or .grid."""
    path = "sea.seabed.bathymetry"
    table = _Table(value, path, KEYS[path])
    kind = table.read({"kind": _BATHYMETRY["kind"]}, required=("kind",))["kind"]
    keys = _BATHYMETRY_KINDS[kind]
    for key in table.values:
        if key not in (*keys, "kind"):
            _fail(f"{path}.{key}", f'not a key of kind = "{kind}", which takes {", ".join(keys)}')
    if kind != "grid":
        return kind, table.read({key: _BATHYMETRY[key] for key in keys})
    arguments = table.read({"x": _BATHYMETRY["x"], "y": _BATHYMETRY["y"]}, required=("x", "y"))
    if "z" not in table.values:
        _fail(f"{path}.z", "missing required key; must be rows of numbers, one row of len(y) per x (m)")
    rows = _Matrix(len(arguments["x"]), len(arguments["y"]), "m", "(one per y)")
    arguments["z"] = rows(table.values["z"], f"{path}.z")
    return kind, arguments


def _read_seabed(value: object) -> tuple[dict[str, Any], tuple[str, dict[str, Any]] | None]:
    """`[sea.seabed]`: the arguments of pl.Seabed, and the kind and arguments of its bathymetry."""
    table = _Table(value, "sea.seabed", KEYS["sea.seabed"])
    seabed = table.read(_SEABED)
    bathymetry = _read_bathymetry(table.values["bathymetry"]) if "bathymetry" in table.values else None
    return seabed, bathymetry


def _read_sea(
    top: _Table,
) -> tuple[
    dict[str, Any] | None,
    tuple[str, dict[str, Any]] | None,
    tuple[dict[str, Any], tuple[str, dict[str, Any]] | None] | None,
]:
    """`[sea]`, `[sea.current]` and `[sea.seabed]`: the arguments of pl.Sea, the kind and arguments of the
    current, and those of the seabed."""
    if "sea" not in top.values:
        return None, None, None
    table = _Table(top.values["sea"], "sea", KEYS["sea"])
    sea = table.read(_SEA, required=("depth",))
    seabed = _read_seabed(table.values["seabed"]) if "seabed" in table.values else None
    if "current" not in table.values:
        return sea, None, seabed
    current = _Table(table.values["current"], "sea.current", KEYS["sea.current"])
    kind = current.read({"kind": _CURRENT["kind"]}, required=("kind",))["kind"]
    keys = (*_CURRENT_KINDS[kind], "start")
    for key in current.values:
        if key not in (*keys, "kind"):
            _fail(f"sea.current.{key}", f'not a key of kind = "{kind}", which takes {", ".join(keys)}')
    arguments = current.read({key: _CURRENT[key] for key in keys}, required=_CURRENT_KINDS[kind])
    if kind == "profile" and len(arguments["velocities"]) != len(arguments["depths"]):
        count = len(arguments["depths"])
        _fail(
            "sea.current.velocities",
            f"must have one row {_VELOCITY} (m/s) per depth ({count}), got {len(arguments['velocities'])}",
        )
    return sea, (kind, arguments), seabed


def _read_supports(top: _Table) -> dict[_End, tuple[str, dict[str, Any]]]:
    """`[supports.A]`, `[supports.B]`: each end's kind and the arguments of model.clamp or model.pin."""
    if "supports" not in top.values:
        return {}
    value = top.values["supports"]
    if not isinstance(value, dict):
        _fail("supports", f"must be a table with [supports.A] and/or [supports.B], got {_show(value)}")
    supports: dict[_End, tuple[str, dict[str, Any]]] = {}
    for end, table in value.items():
        if end not in ("A", "B"):
            _fail(f"supports.{end}", 'unknown end; must be "A" (node 0, seabed end) or "B" (node n, top end)')
        arguments = _Table(table, f"supports.{end}", KEYS[f"supports.{end}"]).read(
            _SUPPORT, required=("kind",)
        )
        kind = arguments.pop("kind")
        if kind != "clamp" and "rotation" in arguments:
            _fail(
                f"supports.{end}.rotation", f'only kind = "clamp" holds a rotation; a {kind} leaves it free'
            )
        motion = [key for key in _DRIVE_KEYS if key in arguments]
        if kind != "drive" and motion:
            _fail(
                f"supports.{end}.{motion[0]}", f'only kind = "drive" moves its end; a {kind} holds it still'
            )
        if kind == "drive" and "period" not in arguments:
            _fail(f"supports.{end}.period", 'missing required key for kind = "drive"; a number > 0 (s)')
        supports[cast(_End, end)] = (kind, arguments)
    return supports


def _read_point_loads(top: _Table, elements: int) -> list[dict[str, Any]]:
    """`[[point_loads]]`: the arguments of each model.point_load."""
    loads = []
    for i, entry in enumerate(_tables(top.values.get("point_loads", []), "point_loads")):
        path = f"point_loads[{i}]"
        load = _Table(entry, path, KEYS["point_loads"]).read(_POINT_LOAD, required=("node",))
        node = load["node"]
        if isinstance(node, int) and not -(elements + 1) <= node <= elements:
            _fail(
                f"{path}.node",
                f"must be a node index in [{-(elements + 1)}, {elements}] (n = {elements}), got {node}",
            )
        loads.append(load)
    return loads


def _read_vessel(top: _Table, sea: object, supports: Collection[str]) -> dict[str, Any] | None:
    """`[vessel]`: the arguments of pl.Vessel (or `model`) and of model.attach_vessel."""
    if "vessel" not in top.values:
        for section in ("controller", "environment"):
            if section in top.values:
                _fail(section, "needs a [vessel] to act on")
        return None
    table = _Table(top.values["vessel"], "vessel", KEYS["vessel"])
    if "model" in table.values:
        for key in _MATRICES:
            if key in table.values:
                _fail(
                    f"vessel.{key}", "conflicts with vessel.model; give either model or the matrices M, D, G"
                )
        vessel = table.read(_VESSEL, required=("end", "eta"))
    elif any(key in table.values for key in _MATRICES):
        vessel = table.read(_VESSEL, required=("end", "M", "D", "G", "eta"))
    else:
        _fail("vessel.model", 'missing; give model = "osv" or the matrices M, D and G (6×6)')
    if sea is None:
        _fail("vessel", "needs a [sea] to float in")
    if vessel["end"] in supports:
        end = vessel["end"]
        _fail(
            "vessel.end", f'end "{end}" also has [supports.{end}]; an end is held by a support or the vessel'
        )
    if "lay" in table.values:
        if "angle" in vessel:
            _fail("vessel.angle", "conflicts with [vessel.lay]: the tensioner or tower sets the pipe's angle")
        vessel["lay"] = _read_lay(table.values["lay"])
    return vessel


def _read_lay(value: object) -> tuple[str, dict[str, Any], dict[str, Any] | None]:
    """`[vessel.lay]` and `[vessel.lay.stinger]`: the kind, the arguments of pl.SLay or pl.JLay, and those of
    pl.Stinger (or of Stinger.from_rollers when `positions` is given)."""
    table = _Table(value, "vessel.lay", KEYS["vessel.lay"])
    kind = table.read({"kind": _LAY["kind"]}, required=("kind",))["kind"]
    keys = _LAY_KINDS[kind]
    for key in table.values:
        if key not in (*keys, "kind"):
            _fail(f"vessel.lay.{key}", f'not a key of kind = "{kind}", which takes {", ".join(keys)}')
    required = ("tensioner",) if kind == "s-lay" else ("position",)
    arguments = table.read({key: _LAY[key] for key in keys if key in _LAY}, required=required)
    if "stinger" not in table.values:
        return kind, arguments, None
    stinger = _Table(table.values["stinger"], "vessel.lay.stinger", KEYS["vessel.lay.stinger"])
    if "positions" in stinger.values:
        for key in ("radius", "length", "rollers", "origin", "angle"):
            if key in stinger.values:
                _fail(
                    f"vessel.lay.stinger.{key}",
                    "conflicts with positions: give an arc or the rollers' points",
                )
        rollers = stinger.read(_STINGER, required=("positions",))
        if "axes" in rollers and len(rollers["axes"]) != len(rollers["positions"]):
            _fail(
                "vessel.lay.stinger.axes",
                f"must have one row per roller ({len(rollers['positions'])}), got {len(rollers['axes'])}",
            )
        return kind, arguments, rollers
    if "axes" in stinger.values:
        _fail("vessel.lay.stinger.axes", "belongs to positions (rollers given point by point)")
    return kind, arguments, stinger.read(_STINGER, required=("radius", "length", "rollers"))


def _read_solver(top: _Table) -> dict[str, Any]:
    """`[solver]`, with the defaults filled in."""
    settings = {"dt": 0.05, "t_end": None, "record_every": 1, "static_steps": None, "static_start": "auto"}
    if "solver" in top.values:
        settings.update(_Table(top.values["solver"], "solver", KEYS["solver"]).read(_SOLVER))
    return settings


def _read_output(top: _Table, t_end: float | None) -> dict[str, Any]:
    """`[output]`, with the defaults filled in."""
    output: dict[str, Any] = {"plot_times": None}
    if "output" in top.values:
        output.update(_Table(top.values["output"], "output", KEYS["output"]).read(_OUTPUT))
    limit = "0 s: statics only (no solver.t_end)" if t_end is None else f"<= solver.t_end = {t_end:g} s"
    for i, time in enumerate(output["plot_times"] or ()):
        if time > (t_end or 0.0):
            _fail(f"output.plot_times[{i}]", f"must be {limit}, got {time:g}")
    return output


def _read_pay_out(top: _Table, controller: dict[str, Any] | None) -> dict[str, Any] | None:
    """`[pay_out]`: the end, and the speed, start time and ramp of the smoothly started pay-out (speed =
    "route" replaced by the route's speed, and the start time defaulting to the route's)."""
    if "pay_out" not in top.values:
        return None
    table = _Table(top.values["pay_out"], "pay_out", KEYS["pay_out"])
    pay_out = {"end": "B", "start_time": 0.0, "ramp": _PAY_OUT_RAMP}
    given = table.read(_PAY_OUT, required=("speed",))
    if given["speed"] == "route":
        route = (controller or {}).get("route")
        if route is None:
            _fail("pay_out.speed", '"route" needs a [controller.route] to take the speed from; there is none')
        given["speed"] = route.get("speed", 0.0)
        given.setdefault("start_time", route.get("start_time", 0.0))
    pay_out.update(given)
    return pay_out


def _read(data: object) -> tuple[_Plan, dict[str, Any]]:
    """Check every key of a parsed scenario: the plan of API calls, and the solver and output settings."""
    if not isinstance(data, dict):
        _fail("scenario", f"must be a table of sections (a dict), got {_show(data)}")
    top = _Table(data, "", KEYS[""])
    top.read(_TOP)
    model: dict[str, Any] = {}
    if "gravity" in top.values:
        gravity = top.values["gravity"]
        if isinstance(gravity, dict):
            table = _Table(gravity, "gravity", KEYS["gravity"])
            model["gravity"] = table.read({"acceleration": _GRAVITY}, required=("acceleration",))[
                "acceleration"
            ]
        else:
            model["gravity"] = _GRAVITY(gravity, "gravity")
    section = _read_section(top)
    rod, elements = _read_rod(top)
    sea, current, seabed = _read_sea(top)
    supports = _read_supports(top)
    point_loads = _read_point_loads(top, elements)
    vessel = _read_vessel(top, sea, supports)
    if not supports and vessel is None:
        _fail("supports", "missing; hold the rod with [supports.A], [supports.B] or a [vessel]")
    controller = None
    if "controller" in top.values:
        table = _Table(top.values["controller"], "controller", KEYS["controller"])
        if "route" in table.values:
            if "reference" in table.values:
                _fail("controller.reference", "conflicts with [controller.route]: give one of them")
            controller = table.read(_CONTROLLER, required=("kp", "kd"))
            route = _Table(table.values["route"], "controller.route", KEYS["controller.route"])
            controller["route"] = route.read(_ROUTE, required=("start",))
        else:
            controller = table.read(_CONTROLLER, required=("kp", "kd", "reference"))
        if "tension" in table.values:
            tension = _Table(table.values["tension"], "controller.tension", KEYS["controller.tension"])
            controller["tension"] = tension.read(_TENSION, required=("target", "gain"))
    pay_out = _read_pay_out(top, controller)
    environment = [
        _Table(entry, f"environment[{i}]", KEYS["environment"]).read(_ENVIRONMENT, required=("value",))
        for i, entry in enumerate(_tables(top.values.get("environment", []), "environment"))
    ]
    settings = _read_solver(top)
    settings["output"] = _read_output(top, settings["t_end"])
    plan = _Plan(
        section,
        rod,
        sea,
        current,
        seabed,
        model,
        supports,
        point_loads,
        vessel,
        controller,
        environment,
        pay_out,
    )
    return plan, settings


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
            raise pl.InputError(f"{_join(path, argument)}: {rest}") from None
        raise pl.InputError(f"{path}: {message}" if path else message) from None


_SEABED_SHAPE = {"bathymetry": "sea.seabed.bathymetry"}


def _harmonic_drive(
    center: Any,
    period: float,
    amplitude: list[float] | None = None,
    phase: list[float] | None = None,
    ramp: float = 0.0,
    **_: Any,
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


def _build(plan: _Plan) -> pl.Model:
    """Make the API calls of a checked plan."""
    kind, arguments = plan.section
    with _engine(kind, KEYS[kind]):
        section = pl.Section.pipe(**arguments) if kind == "pipe" else pl.Section(**arguments)
    with _engine("rod", KEYS["rod"]):
        if "nodes" in plan.rod:
            rod = pl.Rod(plan.rod["nodes"], section)
        else:
            rod = pl.Rod.straight(section=section, **plan.rod)
    sea = None
    if plan.sea is not None:
        current = None
        if plan.current is not None:
            kind, arguments = plan.current
            factories: dict[str, Callable[..., pl.Current]] = {
                "uniform": pl.Current.uniform,
                "linear": pl.Current.linear,
                "profile": pl.Current.profile,
            }
            with _engine("sea.current", KEYS["sea.current"]):
                current = factories[kind](**arguments)
        seabed = None
        if plan.seabed is not None:
            arguments, shape = plan.seabed
            bathymetry = None
            if shape is not None:
                kind, shape_arguments = shape
                factories_b: dict[str, Callable[..., pl.Bathymetry]] = {
                    "flat": pl.Bathymetry.flat,
                    "plane": pl.Bathymetry.plane,
                    "grid": pl.Bathymetry.grid,
                }
                with _engine("sea.seabed.bathymetry", KEYS["sea.seabed.bathymetry"]):
                    bathymetry = factories_b[kind](**shape_arguments)
            with _engine("sea.seabed", KEYS["sea.seabed"]):
                seabed = pl.Seabed(**arguments, bathymetry=bathymetry)
        with _engine("sea", KEYS["sea"], _SEABED_SHAPE):
            sea = pl.Sea(**plan.sea, current=current, seabed=seabed)
    with _engine("", ("gravity",), _SEABED_SHAPE):
        model = pl.Model(rod, sea=sea, **plan.model)
    for end, (kind, arguments) in plan.supports.items():
        with _engine(f"supports.{end}", KEYS[f"supports.{end}"]):
            if kind == "clamp":
                model.clamp(end, **arguments)
            elif kind == "pin":
                model.pin(end, **arguments)
            else:
                node = rod.nodes[0 if end == "A" else -1]
                position, velocity = _harmonic_drive(arguments.get("position", node), **arguments)
                model.drive(end, position, velocity=velocity)
    for i, load in enumerate(plan.point_loads):
        with _engine(f"point_loads[{i}]", KEYS["point_loads"]):
            model.point_load(**load)
    if plan.vessel is not None:
        _attach(model, plan.vessel, plan)
    if plan.pay_out is not None:
        arguments = dict(plan.pay_out)
        end = arguments.pop("end")
        with _engine("pay_out", KEYS["pay_out"]):
            model.pay_out(end, speed=SmoothStart(**arguments))
    return model


def _attach(model: pl.Model, vessel_arguments: dict[str, Any], plan: _Plan) -> None:
    """Build the vessel (from its checked arguments), the plan's controller and environment; attach them."""
    arguments = dict(vessel_arguments)
    end, eta = arguments.pop("end"), arguments.pop("eta")
    angle = arguments.pop("angle", None)
    lay = _lay(arguments.pop("lay")) if "lay" in arguments else None
    with _engine("vessel", KEYS["vessel"]):
        vessel = pl.Vessel.osv() if arguments.pop("model", None) == "osv" else pl.Vessel(**arguments)
    controller = None
    if plan.controller is not None:
        arguments = dict(plan.controller)
        if "route" in arguments:
            with _engine("controller.route", KEYS["controller.route"]):
                arguments["reference"] = pl.Route(**arguments.pop("route"))
        if "tension" in arguments:
            with _engine("controller.tension", KEYS["controller.tension"]):
                arguments["tension"] = pl.TensionControl(**arguments.pop("tension"))
        with _engine("controller", KEYS["controller"]):
            controller = pl.PID(**arguments)
    environment = []
    for i, force in enumerate(plan.environment):
        with _engine(f"environment[{i}]", KEYS["environment"]):
            environment.append(pl.Force(**force))
    with _engine("vessel", KEYS["vessel"]):
        model.attach_vessel(
            end, vessel, eta=eta, angle=angle, controller=controller, environment=environment, lay=lay
        )


def _lay(plan: tuple[str, dict[str, Any], dict[str, Any] | None]) -> pl.SLay | pl.JLay:
    """The lay equipment of a checked `[vessel.lay]`."""
    kind, arguments, stinger_arguments = plan
    if kind == "j-lay":
        with _engine("vessel.lay", KEYS["vessel.lay"]):
            return pl.JLay(**arguments)
    stinger = None
    if stinger_arguments is not None:
        with _engine(
            "vessel.lay.stinger",
            KEYS["vessel.lay.stinger"],
            {
                "stinger radius": "vessel.lay.stinger.radius",
                "stinger length": "vessel.lay.stinger.length",
                "stinger origin": "vessel.lay.stinger.origin",
                "stinger angle": "vessel.lay.stinger.angle",
                "roller positions": "vessel.lay.stinger.positions",
                "roller axes": "vessel.lay.stinger.axes",
            },
        ):
            if "positions" in stinger_arguments:
                stinger = pl.Stinger.from_rollers(**stinger_arguments)
            else:
                stinger = pl.Stinger(**stinger_arguments)
    with _engine("vessel.lay", KEYS["vessel.lay"]):
        return pl.SLay(stinger=stinger, **arguments)


def parse_scenario(data: dict[str, Any], origin: str = "<dict>") -> Scenario:
    """The scenario described by `data`, a parsed TOML document (see the module's reference).

    Every key is checked before the model is built; nothing is solved. `origin` names the source in messages.
    Raises pl.InputError whose message starts with the key path and ends with `(in origin)`.
    """
    try:
        plan, settings = _read(data)
        model = _build(plan)
    except pl.InputError as error:
        raise pl.InputError(f"{error} (in {origin})") from None
    return Scenario(model=model, source=copy.deepcopy(data), **settings)


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
    return parse_scenario(data, origin)
