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

The format is a set of pydantic models (`pipelay.scenario.models`, one per table and per kind of a table),
whose keys are the keyword arguments of the API calls below. `json_schema()` is its JSON Schema, with the
descriptions, units and defaults of this reference, for editors to complete and check scenario files (taplo /
Even Better TOML: `#:schema scenario.schema.json` on the first line). For a parameter sweep,
`validate_overrides(data, {"sea.waves.hs": [1.0, 2.0]})` checks each dotted key and value before any case
runs, and `apply_overrides(data, {"sea.waves.hs": 2.0})` makes one case's document.

The package's modules, each importing only those after it: `pipelay.scenario.reading` (`load_scenario`,
`parse_scenario`, `Scenario`), `.overrides` (`validate_overrides`, `apply_overrides`), `.checking` (a document
checked against the models, pydantic's errors in the words above), `.schema` (`KEYS`, `json_schema`, which
reads this reference), `.models` and `.models_vessel` (the pydantic models), `.values` (what one key takes).
It reaches the engine through `pipelay` and imports nothing of `pipelay.results` or `pipelay.analysis`.

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

from pipelay.scenario.models import MAX_ELEMENTS
from pipelay.scenario.overrides import apply_overrides, validate_overrides
from pipelay.scenario.reading import Scenario, SmoothStart, load_scenario, parse_scenario
from pipelay.scenario.schema import KEYS, json_schema

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
