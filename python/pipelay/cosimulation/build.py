"""`pipelay fmu`: a scenario as an FMI 2.0 co-simulation FMU (the plant: pipe and vessel, driven by τ).

The FMU is built by pythonfmu: its binary starts the host's Python, which must have pipelay installed, and
runs `pipelay.cosimulation.slave`. The scenario, the files it names and the FMU's settings go into its
resources. pythonfmu writes no units and no initial unknowns; they are added to `modelDescription.xml` here.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import tempfile
import zipfile
from pathlib import Path
from typing import Any
from xml.etree import ElementTree

import pipelay as pl

__all__ = ["DEFAULT_PARAMETER_TABLES", "build_fmu"]

DEFAULT_PARAMETER_TABLES = ("sea.current", "sea.waves", "sea.wind")
"""The tables whose numbers become the FMU's parameters by default: the current and the sea."""
_NOT_PARAMETERS = re.compile(r".*\.(seed|components)$")  # integers that select, not physical values
_BASE_UNITS = {
    "m": {"m": "1"},
    "rad": {"rad": "1"},
    "N": {"kg": "1", "m": "1", "s": "-2"},
    "N.m": {"kg": "1", "m": "2", "s": "-2"},
    "m/s": {"m": "1", "s": "-1"},
    "rad/s": {"rad": "1", "s": "-1"},
    "J": {"kg": "1", "m": "2", "s": "-2"},
    "s": {"s": "1"},
    "1": {},
}


def _referenced_files(data: Any, folder: Path) -> set[str]:
    """The relative paths, among the scenario's strings, of files in `folder` (RAO and hull tables, say)."""
    found: set[str] = set()
    if isinstance(data, dict):
        for value in data.values():
            found |= _referenced_files(value, folder)
    elif isinstance(data, list):
        for value in data:
            found |= _referenced_files(value, folder)
    elif (
        isinstance(data, str)
        and not os.path.isabs(data)
        and ".." not in Path(data).parts
        and (folder / data).is_file()
    ):
        found.add(data)
    return found


def _unit_of(name: str, key_units: dict[str, str]) -> str | None:
    from pipelay.cosimulation.slave import PIPE_INPUTS, PIPE_OUTPUTS, PLANT_INPUTS, PLANT_OUTPUTS

    for signal in (*PLANT_INPUTS, *PLANT_OUTPUTS, *PIPE_INPUTS, *PIPE_OUTPUTS):
        if signal.name == name:
            return signal.unit
    return key_units.get(name)


def _parameter_unit(key: str) -> str | None:
    """The unit of a scenario key that is a parameter: from the scenario reference's units, where known."""
    last = re.sub(r"\[\d+\]$", "", key.rsplit(".", 1)[-1])
    return {
        "velocity": "m/s",
        "speed": "m/s",
        "direction": "rad",
        "hs": "m",
        "height": "m",
        "amplitude": "m",
        "tp": "s",
        "period": "s",
        "ramp": "s",
        "depth": "m",
    }.get(last)


def _finish_model_description(text: str, dt: float, key_units: dict[str, str]) -> str:
    """pythonfmu's modelDescription.xml with units, the outputs as initial unknowns and the default step (the
    FMI 2.0 schema's order: CoSimulation, UnitDefinitions, …, DefaultExperiment, ModelVariables)."""
    root = ElementTree.fromstring(text)
    used = set()
    for variable in root.iter("ScalarVariable"):
        unit = _unit_of(variable.get("name", ""), key_units)
        real = variable.find("Real")
        if unit is not None and real is not None:
            real.set("unit", unit)
            used.add(unit)
    definitions = ElementTree.Element("UnitDefinitions")
    for unit in sorted(used):
        node = ElementTree.SubElement(definitions, "Unit", name=unit)
        ElementTree.SubElement(node, "BaseUnit", _BASE_UNITS[unit])
    children = list(root)
    root.insert(children.index(root.find("CoSimulation")) + 1, definitions)
    if root.find("DefaultExperiment") is None:
        experiment = ElementTree.Element("DefaultExperiment", startTime="0", stepSize=repr(dt))
        root.insert(list(root).index(root.find("ModelVariables")), experiment)
    structure = root.find("ModelStructure")
    outputs = None if structure is None else structure.find("Outputs")
    if structure is not None and outputs is not None and structure.find("InitialUnknowns") is None:
        initial = ElementTree.SubElement(structure, "InitialUnknowns")
        for unknown in outputs:
            ElementTree.SubElement(initial, "Unknown", index=unknown.get("index", ""))
    ElementTree.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ElementTree.tostring(root, encoding="unicode")


def build_fmu(
    scenario: str | os.PathLike[str],
    output: str | os.PathLike[str],
    *,
    kind: str = "plant",
    parameters: list[str] | None = None,
) -> Path:
    """Builds the FMU of the scenario file `scenario` at `output` (.fmu) and returns its path.

    `kind="pipe"`: the pipe alone, its hold point carried by the vessel's pose η and velocity ν (inputs, as the
    plant's outputs of those names), the pipe's force and moment on the vessel χ out, with the energy and the
    supplied work; for a scenario whose vessel has no stinger (`pipelay.cosimulation.pipe.HeldPipe`).
    `kind="plant"`, the pipe and the vessel. Inputs: the thrust τ in surge, sway (N) and yaw (N·m), body frame, held over each communication step (through
    the thrusters' allocation if the scenario's `[controller]` has `allocation = "qp"`). Outputs: η, ν, the pipe's
    force and moment on the vessel χ, the delivered thrust, the lay summary's scalars, the energy and the supplied
    work. Parameters: the dotted scenario keys `parameters` (numbers in the scenario), by default every number
    of `sea.current`, `sea.waves` and `sea.wind`. The communication step must be a multiple of the scenario's
    `solver.dt`. Raises pl.InputError for a scenario without a vessel or a parameter it does not have.
    """
    from pythonfmu import FmuBuilder

    from pipelay.cosimulation.slave import SETTINGS, scalar_keys
    from pipelay.scenario import load_scenario

    source = Path(scenario)
    loaded = load_scenario(source)  # checked now, not in the master
    data = loaded.source  # the parsed document, as the file has it
    if kind not in ("plant", "pipe"):
        raise pl.InputError(f'kind: {kind!r} must be "plant" (pipe and vessel) or "pipe" (the pipe alone)')
    if "vessel" not in data:
        raise pl.InputError(
            f"scenario: {str(source)!r} has no [vessel]: the {kind} FMU needs a vessel's hold point"
        )
    if kind == "pipe":
        from pipelay.cosimulation.pipe import HeldPipe

        HeldPipe(data, source)  # checked now, not in the master
    if parameters is None:
        numbers = scalar_keys(data, DEFAULT_PARAMETER_TABLES)
        chosen = {key: value for key, value in numbers.items() if not _NOT_PARAMETERS.match(key)}
    else:
        every = scalar_keys(data, tuple(data))
        missing = [key for key in parameters if key not in every]
        if missing:
            raise pl.InputError(
                f"parameters: {missing} are not numbers of the scenario {str(source)!r} (a parameter starts at the "
                "scenario's value)"
            )
        chosen = {key: every[key] for key in parameters}
    output = Path(output)
    if output.suffix != ".fmu":
        raise pl.InputError(f"output: {str(output)!r} must end in .fmu")
    identifier = re.sub(r"\W", "_", output.stem)
    if not identifier or identifier[0].isdigit():
        identifier = f"pipelay_{identifier}"
    folder = source.absolute().parent
    base = {"plant": "PipelayPlant", "pipe": "PipelayPipe"}[kind]
    with tempfile.TemporaryDirectory(prefix="pipelay_fmu_") as temporary:
        work = Path(temporary)
        script = work / f"{identifier}.py"
        script.write_text(
            f"from pipelay.cosimulation.slave import {base}\n\n\n"
            f"class {identifier}({base}):\n"
            f'    """pipelay {kind} of {source.name}."""\n'
        )
        resources = work / "resources"
        resources.mkdir()
        shutil.copy2(source, resources / "scenario.toml")
        tops = set()
        for relative in _referenced_files(data, folder):
            top = Path(relative).parts[0]
            tops.add(top)
            target = resources / relative
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(folder / relative, target)
        (resources / SETTINGS).write_text(
            json.dumps({"scenario": "scenario.toml", "dt": loaded.dt, "parameters": chosen}, indent=1)
        )
        project = [resources / name for name in ("scenario.toml", SETTINGS, *sorted(tops))]
        built = Path(FmuBuilder.build_FMU(script, dest=work / f"{identifier}.fmu", project_files=project))
        key_units = {key: unit for key in chosen if (unit := _parameter_unit(key)) is not None}
        output.parent.mkdir(parents=True, exist_ok=True)
        with (
            zipfile.ZipFile(built) as original,
            zipfile.ZipFile(output, "w", zipfile.ZIP_DEFLATED) as finished,
        ):
            for item in original.infolist():
                content = original.read(item.filename)
                if item.filename == "modelDescription.xml":
                    content = _finish_model_description(content.decode(), loaded.dt, key_units).encode()
                finished.writestr(item, content)
    return output
