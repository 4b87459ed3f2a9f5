"""Scenario files: a whole pipelay model, with its solver settings and outputs, in one TOML file.

`load_scenario(path)` reads a file and `parse_scenario(data)` an already parsed dict. Both check every key
before anything is built or solved and return a `Scenario` whose `model` is ready to solve:

```python
from pipelay.scenario import load_scenario

scenario = load_scenario("examples/jensen2009.toml")
state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
if scenario.t_end is not None:
    simulation = scenario.simulation(state)  # its dt, stages and high-frequency damping
    results = simulation.run(scenario.t_end, record_every=scenario.record_every)
```

`scenario.stages` is the file's `[[stages]]` as a `pl.Stages` (None without them; `scenario.t_end` is then the
end of the last stage unless `solver.t_end` says otherwise); a run resumed from a checkpoint takes them too,
`pl.resume(scenario.model, path, stages=scenario.stages)`.

Any mistake raises `pl.InputError` whose message starts with the key path, states the value and what is
allowed, and ends with the file, e.g. `pipe.outer_diameter: must be > 0 m, got -0.6 (in lay.toml)`. Unknown
keys and sections are rejected with the closest valid name suggested; a TOML syntax error names the file,
line and column. Entries of arrays of tables are numbered from 0 (`point_loads[1].force`).

The format is a set of pydantic models (`pipelay.scenario.models`, one per table and per kind of a table),
whose keys are the keyword arguments of the API calls the tables map onto; a key left out takes that call's
default. The models state each key once: what it takes, its unit, its default and its meaning. The
documentation's [Scenario reference](../scenario-reference.md) page (`docs/scenario-reference.md`) lists every
table and key with the conventions (units, frames, node numbering), generated from the models by
`pipelay.scenario.schema`'s `reference_tables()`; so is `json_schema()`, the format's JSON Schema, for editors
to complete and check scenario files (taplo / Even Better TOML: `#:schema scenario.schema.json` on the first
line). For a parameter sweep, `validate_overrides(data, {"sea.waves.hs": [1.0, 2.0]})` checks each dotted key
and value before any case runs, and `apply_overrides(data, {"sea.waves.hs": 2.0})` makes one case's document.

A results file written by `pipelay run` or a sweep keeps its scenario: `scenario_of_results(path)` gives it
back (`pipelay.scenario.provenance`; `mark_results` writes it).

The package's modules, each importing only those after it: `pipelay.scenario.provenance` (the scenario of a
results file), `pipelay.scenario.reading` (`load_scenario`,
`parse_scenario`, `Scenario`), `.overrides` (`validate_overrides`, `apply_overrides`), `.checking` (a document
checked against the models, pydantic's errors in the words above), `.schema` (`KEYS`, `reference_tables`,
`json_schema`: the format's shape and reference, read from the models), `.models` and `.models_vessel` (the
pydantic models), `.values` (what one key takes, and `api`, `About`: how the models document keys and tables).
It reaches the engine through `pipelay` and imports nothing of `pipelay.results` or `pipelay.analysis`.
"""

from pipelay.scenario.models import MAX_ELEMENTS
from pipelay.scenario.overrides import apply_overrides, validate_overrides
from pipelay.scenario.provenance import mark_results, scenario_of_results
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
    "mark_results",
    "parse_scenario",
    "scenario_of_results",
    "validate_overrides",
]
