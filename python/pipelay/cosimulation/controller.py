"""A controller FMU driving pipelay's vessel: `pl.Controller.fmu`.

The FMU (FMI 2.0 co-simulation) is run by fmpy in this process. Once per time step, at the step's start t,
pipelay sets the FMU's inputs from the pose η and velocity ν the sampled loop sees (the observer's estimate, if
there is one), calls `doStep(t, Δt)` and holds the outputs, the command τ, over the step: the controller answers
within the step, as pipelay's own sampled PID does. The command then goes through the allocation and the
thrusters, if asked for.
"""

from __future__ import annotations

import os
import re
import shutil
import weakref
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

import pipelay as pl

__all__ = ["Controller", "FmuLaw"]

_SIGNAL = re.compile(r"(eta|nu|tau)\[([0-5])\]")
_THRUST = (0, 1, 5)  # surge, sway, yaw: what a DP controller commands


def _signal(text: str, argument: str, kinds: tuple[str, ...]) -> tuple[str, int]:
    """("eta", 0) from "eta[0]"; an InputError naming `argument` unless it is one of `kinds`."""
    found = _SIGNAL.fullmatch(text) if isinstance(text, str) else None
    allowed = " or ".join(f'"{kind}[k]"' for kind in kinds)
    if found is None or found.group(1) not in kinds:
        raise pl.InputError(f"{argument}: {text!r} must be {allowed} (k = 0 … 5)")
    kind, index = found.group(1), int(found.group(2))
    if kind == "tau" and index not in _THRUST:
        raise pl.InputError(
            f"{argument}: {text!r} is not a DP command: tau[0] (surge, N), tau[1] (sway, N) or tau[5] (yaw, N·m)"
        )
    return kind, index


class FmuLaw:
    """The command law of a co-simulation FMU: `law(t, dt, eta, nu)` → τ (6,), for `pl.PID.external`.

    `inputs` maps the FMU's input variables to pipelay's signals ("eta[k]", "nu[k]"), `outputs` its output
    variables to the command's components ("tau[0]", "tau[1]", "tau[5]": surge, sway (N), yaw (N·m), body
    frame), `parameters` sets the FMU's parameters before it starts. The FMU is instantiated at the first call,
    at the run's time; `close()` (or garbage collection) frees it.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        inputs: Mapping[str, str],
        outputs: Mapping[str, str],
        parameters: Mapping[str, float] | None = None,
    ) -> None:
        import fmpy
        from fmpy.fmi2 import FMU2Slave

        path = Path(path)
        if not path.is_file():
            raise pl.InputError(f"path: {str(path)!r} is not a file (an FMU, .fmu)")
        try:
            description = fmpy.read_model_description(str(path))
        except Exception as error:  # noqa: BLE001 (fmpy raises what its zip and XML readers and checks do)
            raise pl.InputError(f"path: {str(path)!r} is not a readable FMU: {error}") from None
        if description.fmiVersion != "2.0" or description.coSimulation is None:
            raise pl.InputError(
                f"path: {str(path)!r} is an FMI {description.fmiVersion} FMU without co-simulation; an FMI 2.0 "
                "co-simulation FMU is needed"
            )
        variables = {v.name: v for v in description.modelVariables}

        def reference(name: str, argument: str, causalities: tuple[str, ...]) -> int:
            variable = variables.get(name)
            if variable is None or variable.causality not in causalities or variable.type != "Real":
                known = sorted(v.name for v in variables.values() if v.causality in causalities)
                raise pl.InputError(
                    f"{argument}: {name!r} is not a Real {'/'.join(causalities)} of the FMU (its: {known})"
                )
            return int(variable.valueReference)

        self.inputs = [
            (reference(name, "inputs", ("input",)), _signal(signal, f"inputs[{name!r}]", ("eta", "nu")))
            for name, signal in inputs.items()
        ]
        self.outputs = [
            (reference(name, "outputs", ("output",)), _signal(signal, f"outputs[{name!r}]", ("tau",))[1])
            for name, signal in outputs.items()
        ]
        if not self.outputs:
            raise pl.InputError("outputs: {} must map at least one FMU output to tau[0], tau[1] or tau[5]")
        self.parameters = [
            (reference(name, "parameters", ("parameter",)), float(value))
            for name, value in (parameters or {}).items()
        ]
        self._folder = fmpy.extract(str(path))
        self._fmu = FMU2Slave(
            guid=description.guid,
            unzipDirectory=self._folder,
            modelIdentifier=description.coSimulation.modelIdentifier,
            instanceName="controller",
        )
        self._started = False
        self._alive = [False]  # whether the FMU is instantiated, for the finalizer to free it
        self._finalizer = weakref.finalize(self, FmuLaw._free, self._fmu, self._folder, self._alive)

    @staticmethod
    def _free(fmu: Any, folder: str, alive: list[bool]) -> None:
        if alive[0]:
            fmu.terminate()
            fmu.freeInstance()
        shutil.rmtree(folder, ignore_errors=True)

    def __call__(
        self, t: float, dt: float, eta: npt.NDArray[np.float64], nu: npt.NDArray[np.float64]
    ) -> np.ndarray:
        """τ (6,) over the step from t to t + dt (s), from η (6,) and ν (6,) at t."""
        fmu = self._fmu
        if not self._started:
            fmu.instantiate()
            self._alive[0] = True
            fmu.setupExperiment(startTime=t)
            fmu.enterInitializationMode()
            if self.parameters:
                fmu.setReal([r for r, _ in self.parameters], [v for _, v in self.parameters])
            fmu.exitInitializationMode()
            self._started = True
        signals = {"eta": eta, "nu": nu}
        if self.inputs:
            fmu.setReal(
                [r for r, _ in self.inputs], [float(signals[kind][k]) for _, (kind, k) in self.inputs]
            )
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
        values = fmu.getReal([r for r, _ in self.outputs])
        tau = np.zeros(6)
        for (_, k), value in zip(self.outputs, values, strict=True):
            tau[k] = value
        return tau

    def close(self) -> None:
        """Terminates and frees the FMU and removes its extracted files."""
        self._finalizer()


class Controller:
    """Controllers from outside pipelay, as pipelay's sampled controller (`pl.PID.external`)."""

    @staticmethod
    def fmu(
        path: str | os.PathLike[str],
        inputs: Mapping[str, str],
        outputs: Mapping[str, str],
        *,
        parameters: Mapping[str, float] | None = None,
        start: float = 0.0,
        allocation: Literal["qp"] | None = None,
        observer: pl.Observer | None = None,
        thrust_limit: npt.ArrayLike | None = None,
        passivity: Literal["observe", "certify"] | None = None,
    ) -> pl.PID:
        """The controller FMU at `path` (FMI 2.0 co-simulation) as the vessel's controller.

        `inputs` maps its input variables to the pose and velocity the loop sees, `{"x": "eta[0]", "u": "nu[0]",
        ...}` (η = [x, y, z, φ, θ, ψ] in m and rad, ν body-frame velocities in m/s and rad/s); `outputs` its output
        variables to the command, `{"X": "tau[0]", "Y": "tau[1]", "N": "tau[5]"}` (body frame, N and N·m);
        `parameters` sets its parameters. Called once per time step from `start` (s), the FMU stepped by Δt with
        its inputs at the step's start and its outputs held over the step; with `allocation="qp"` the command
        goes to the thrusters, with `observer` the FMU sees the observer's estimate. Statics hold the vessel by
        the holding thrust. `passivity="certify"`: the time-domain passivity controller keeps the FMU's work on the
        vessel within zero, its storage as pipelay sees it (Thrusters › Energy and passivity); "observe" books it.
        Raises pl.InputError naming the argument for a variable the FMU does not have.
        """
        law = FmuLaw(path, inputs, outputs, parameters)
        return pl.PID.external(
            law,
            start=start,
            thrust_limit=thrust_limit,
            allocation=allocation,
            observer=observer,
            passivity=passivity,
        )
