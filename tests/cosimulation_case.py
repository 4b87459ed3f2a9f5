"""The co-simulation tests' case: the J-lay of `examples/j_lay_dp.toml` with the PD of
`examples/cosimulation/dp_pd.py`, pipelay's runs of it, and the FMU runs, each in a process of its own.

pythonfmu's FMUs start Python inside the process that loads them; loaded into the tests' own Python they corrupt
its memory when freed (pythonfmu issues #228 and #229), so every FMU runs in a child process:
`python tests/cosimulation_case.py KIND FMU_FOLDER OUT.npz` writes its signals to OUT.npz.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tomllib
import warnings
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "j_lay_dp.toml"
CONTROLLER = ROOT / "examples" / "cosimulation" / "dp_pd.py"
SYSTEM = ROOT / "examples" / "cosimulation" / "OspSystemStructure.xml"
DATA = tomllib.loads(EXAMPLE.read_text())
KP, KD, REFERENCE = (np.array(DATA["controller"][key], dtype=float) for key in ("kp", "kd", "reference"))
POSE = ("x", "y", "z", "roll", "pitch", "yaw")
VELOCITY = ("u", "v", "w", "p", "q", "r")
CHI = ("X", "Y", "Z", "K", "M", "N")
INPUTS = {name: f"eta[{k}]" for k, name in enumerate(POSE)} | {
    name: f"nu[{k}]" for k, name in enumerate(VELOCITY)
}
OUTPUTS = {"tau_surge": "tau[0]", "tau_sway": "tau[1]", "tau_yaw": "tau[5]"}
PARAMETERS = {
    **{f"kp_{axis}": KP[dof] for axis, dof in (("surge", 0), ("sway", 1), ("yaw", 5))},
    **{f"kd_{axis}": KD[dof] for axis, dof in (("surge", 0), ("sway", 1), ("yaw", 5))},
    "x_ref": REFERENCE[0],
    "y_ref": REFERENCE[1],
    "yaw_ref": REFERENCE[5],
}
OBSERVER = {"noise": (0.5, 0.5, 0.005), "seed": 3}
DT = float(DATA["solver"]["dt"])
DURATION = 60.0
START = 0.05  # s: the controllers start in the first step, the vessel held by thrust in statics


def run(controller: object, duration: float = DURATION) -> object:
    """The example's J-lay with `controller` (a pl.PID) from its statics, recorded every step."""
    import pipelay as pl
    from pipelay.scenario import parse_scenario

    scenario = parse_scenario(DATA, origin=str(EXAMPLE), controller=controller)  # type: ignore[arg-type]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        return scenario.simulation().run(duration, progress=False)


def thrust_signal(times: np.ndarray) -> np.ndarray:
    """A commanded τ in surge, sway and yaw over `times` (N, N, N·m)."""
    return np.column_stack(
        [110e3 + 40e3 * np.sin(0.2 * times), 30e3 * np.sin(0.1 * times), 2e6 * np.sin(0.05 * times)]
    )


def pd(eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """The PD's command −Jᵀ(K_p η̃ + K_d J ν) in surge, sway and yaw (J(η) = diag(R(Θ), T(Θ)), zyx angles)."""
    (cf, sf), (ct, st), (cp, sp) = ((math.cos(a), math.sin(a)) for a in eta[3:6])
    rz = np.array([[cp, -sp, 0.0], [sp, cp, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cf, -sf], [0.0, sf, cf]])
    j = np.zeros((6, 6))
    j[:3, :3] = rz @ ry @ rx
    j[3:, 3:] = [[1.0, sf * st / ct, cf * st / ct], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]]
    error = eta - REFERENCE
    error[3:] = (error[3:] + math.pi) % (2.0 * math.pi) - math.pi
    tau = -j.T @ (KP * error + KD * (j @ nu))
    tau[2:5] = 0.0
    return tau


def vessel_motion(times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A prescribed vessel motion about the example's static pose `ETA0`: surge, sway and yaw oscillations (η (T, 6)
    in e, ν (T, 6) body frame, its exact rate)."""
    eta = np.tile(ETA0, (len(times), 1))
    eta[:, 0] += 2.0 * np.sin(0.2 * times)
    eta[:, 1] += 1.0 * np.sin(0.15 * times)
    eta[:, 5] += 0.02 * np.sin(0.1 * times)
    rate = np.column_stack(
        [0.4 * np.cos(0.2 * times), 0.15 * np.cos(0.15 * times), 0.002 * np.cos(0.1 * times)]
    )
    nu = np.zeros((len(times), 6))
    yaw = eta[:, 5]
    nu[:, 0] = np.cos(yaw) * rate[:, 0] + np.sin(yaw) * rate[:, 1]  # R(ψ)ᵀ ẋ (roll and pitch are zero)
    nu[:, 1] = -np.sin(yaw) * rate[:, 0] + np.cos(yaw) * rate[:, 1]
    nu[:, 5] = rate[:, 2]
    return eta, nu


ETA0 = np.array([878.005725, 0.0, -799.944773, 0.0, 0.0, 0.0])  # m, rad: near the example's static pose


def in_child(kind: str, folder: Path, out: Path) -> dict[str, np.ndarray]:
    """Runs `kind` with the FMUs in `folder` in a child process; its signals."""
    done = subprocess.run(
        [sys.executable, __file__, kind, str(folder), str(out)],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    if done.returncode != 0:
        raise AssertionError(f"the child run {kind} failed ({done.returncode}): {done.stderr[-3000:]}")
    with np.load(out) as signals:
        return dict(signals)


def _controller_fmu(folder: Path) -> dict[str, np.ndarray]:
    """The J-lay driven by the PD FMU through `pl.Controller.fmu`, with the allocation and the observer."""
    import pipelay as pl

    controller = pl.Controller.fmu(
        folder / "dp_pd.fmu",
        INPUTS,
        OUTPUTS,
        parameters=PARAMETERS,
        start=START,
        allocation="qp",
        observer=pl.Observer.passive(**OBSERVER),  # type: ignore[arg-type]
    )
    results = run(controller)
    return {"eta": results.eta, "tau": results.tau, "positions": results.positions}  # type: ignore[attr-defined]


def _simulate(
    fmpy: Any, fmu: Path, times: np.ndarray, inputs: list[str], values: np.ndarray, outputs: list[str]
) -> Any:
    """fmpy's run of `fmu` to DURATION at the step DT, its `inputs` given `values` (T, k) at `times`."""
    signal = np.zeros(len(times), dtype=[("time", float)] + [(name, float) for name in inputs])
    signal["time"] = times
    for k, name in enumerate(inputs):
        signal[name] = values[:, k]
    return fmpy.simulate_fmu(
        str(fmu), stop_time=DURATION, step_size=DT, output_interval=DT, input=signal, output=outputs
    )


def _plant_fmu(folder: Path) -> dict[str, np.ndarray]:
    """The plant FMU under fmpy, driven by the thrust signal sampled at its communication step."""
    import fmpy
    from pipelay.cosimulation.slave import PLANT_INPUTS

    times = np.arange(0.0, DURATION + DT / 2, DT)
    names = [f"eta_{n}" for n in POSE] + [f"chi_{n}" for n in CHI] + ["top_tension"]
    result = _simulate(
        fmpy, folder / "jlay.fmu", times, [s.name for s in PLANT_INPUTS], thrust_signal(times), names
    )
    return {
        "time": result["time"],
        "eta": np.column_stack([result[f"eta_{n}"] for n in POSE]),
        "chi": np.column_stack([result[f"chi_{n}"] for n in CHI]),
        "top_tension": result["top_tension"],
    }


def _pipe_fmu(folder: Path) -> dict[str, np.ndarray]:
    """The pipe FMU under fmpy, its hold point carried by the prescribed vessel motion sampled at its
    communication step."""
    import fmpy
    from pipelay.cosimulation.slave import PIPE_INPUTS

    times = np.arange(0.0, DURATION + DT / 2, DT)
    eta, nu = vessel_motion(times)
    names = [f"chi_{n}" for n in CHI] + ["energy", "supplied_work", "dissipated"]
    inputs = [s.name for s in PIPE_INPUTS]
    result = _simulate(fmpy, folder / "pipe.fmu", times, inputs, np.column_stack([eta, nu]), names)
    return {name: result[name] for name in ("time", *names)}


def _osp(folder: Path) -> dict[str, np.ndarray]:
    """The OSP system structure beside the FMUs run by libcosim: the plant's outputs at the end."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.ERROR)
    execution = CosimExecution.from_osp_config_file(str(folder / SYSTEM.name))
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    plant = execution.slave_index_from_instance_name("jlay")
    references = {v.name.decode(): v.reference for v in execution.slave_variables(plant)}
    if not execution.step(round(DURATION / DT)):
        raise RuntimeError("libcosim's step failed")
    return {name: np.array(observer.last_real_values(plant, [ref])[0]) for name, ref in references.items()}


if __name__ == "__main__":
    KIND, FOLDER, OUT = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    SIGNALS = {"controller": _controller_fmu, "plant": _plant_fmu, "pipe": _pipe_fmu, "osp": _osp}[KIND](
        FOLDER
    )
    np.savez(OUT, **SIGNALS)
    print(json.dumps(sorted(SIGNALS)))
