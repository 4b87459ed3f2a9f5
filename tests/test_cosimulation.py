"""Co-simulation: pipelay as an FMU (`pipelay fmu`), a controller FMU as the vessel's controller
(`pl.Controller.fmu`), run by real masters: fmpy and DNV's libcosim (libcosimpy).

The system: the J-lay of `examples/j_lay_dp.toml` (the OSV in 800 m, a JONSWAP sea of 2.5 m, wind and a 0.5 m/s
current, thrust allocation). The controller FMU is `examples/cosimulation/dp_pd.py` built by pythonfmu: a PD on
the pose computed as pipelay's own PID computes it.

References: pipelay's in-process runs of the same loop (its own sampled PID; the same command law given as a
Python function), which the co-simulated runs must equal to 1e-9 of the signals' size; fmpy's validation of
the FMU; the scenario's current and wind, which the co-simulated loop must hold the vessel against.
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
import tomllib
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay.cosimulation.build import build_fmu
from pipelay.cosimulation.slave import PLANT_INPUTS, PLANT_OUTPUTS
from pipelay.scenario import parse_scenario

fmpy = pytest.importorskip("fmpy")
pythonfmu = pytest.importorskip("pythonfmu")

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "j_lay_dp.toml"
CONTROLLER = ROOT / "examples" / "cosimulation" / "dp_pd.py"
SYSTEM = ROOT / "examples" / "cosimulation" / "OspSystemStructure.xml"
DATA = tomllib.loads(EXAMPLE.read_text())
GAINS = DATA["controller"]
KP, KD, REFERENCE = (np.array(GAINS[key], dtype=float) for key in ("kp", "kd", "reference"))
POSE = ("x", "y", "z", "roll", "pitch", "yaw")
VELOCITY = ("u", "v", "w", "p", "q", "r")
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
DT = DATA["solver"]["dt"]
DURATION = 60.0


@pytest.fixture(scope="module")
def fmus(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The plant FMU of the example (`pipelay fmu`) and the PD controller FMU, side by side with the OSP system
    structure file that connects them."""
    folder = tmp_path_factory.mktemp("fmus")
    plant = build_fmu(EXAMPLE, folder / "jlay.fmu")
    from pythonfmu import FmuBuilder

    controller = Path(FmuBuilder.build_FMU(CONTROLLER, dest=folder))
    shutil.copy2(SYSTEM, folder / SYSTEM.name)
    return {"plant": plant, "controller": controller, "system": folder / SYSTEM.name}


def _jacobian(eta: np.ndarray) -> np.ndarray:
    """J(η) = diag(R(Θ), T(Θ)), zyx Euler angles."""
    (cf, sf), (ct, st), (cp, sp) = ((math.cos(a), math.sin(a)) for a in eta[3:6])
    rz = np.array([[cp, -sp, 0.0], [sp, cp, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cf, -sf], [0.0, sf, cf]])
    j = np.zeros((6, 6))
    j[:3, :3] = rz @ ry @ rx
    j[3:, 3:] = [[1.0, sf * st / ct, cf * st / ct], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]]
    return j


def _pd(eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """The PD's command, −Jᵀ(K_p η̃ + K_d J ν) in surge, sway and yaw."""
    error = eta - REFERENCE
    error[3:] = (error[3:] + math.pi) % (2.0 * math.pi) - math.pi
    j = _jacobian(eta)
    tau = -j.T @ (KP * error + KD * (j @ nu))
    tau[2:5] = 0.0
    return tau


def _run(controller: pl.PID, duration: float = DURATION) -> pl.Results:
    """The example's J-lay with `controller`, from its statics, recorded every step."""
    scenario = parse_scenario(DATA, origin=str(EXAMPLE), controller=controller)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        return scenario.simulation().run(duration, progress=False)


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(a).max())


def test_the_plant_fmu_passes_fmpys_validation_with_units_and_initial_unknowns(fmus: dict[str, Path]) -> None:
    """fmpy's validation finds nothing to complain of; every input and output has its unit; the outputs are
    the initial unknowns; the parameters are the numbers of the scenario's current, sea and wind, starting at
    the scenario's values (seeds and component counts left out)."""
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(fmus["plant"])) == []
    description = fmpy.read_model_description(str(fmus["plant"]))
    variables = {v.name: v for v in description.modelVariables}
    signals = (*PLANT_INPUTS, *PLANT_OUTPUTS)
    for signal in signals:
        assert variables[signal.name].unit == signal.unit
    assert {v.variable.name for v in description.initialUnknowns} == {s.name for s in PLANT_OUTPUTS}
    parameters = {v.name: float(v.start) for v in description.modelVariables if v.causality == "parameter"}
    assert parameters["sea.current.velocity[0]"] == 0.5
    assert parameters["sea.waves.hs"] == 2.5 and parameters["sea.wind.speed"] == 15.0
    assert not any(name.endswith(("seed", "components")) for name in parameters)
    assert variables["sea.waves.hs"].unit == "m" and variables["sea.current.velocity[0]"].unit == "m/s"


def test_a_controller_fmu_drives_the_j_lay_as_pipelays_own_sampled_pid(fmus: dict[str, Path]) -> None:
    """`pl.Controller.fmu` with the PD FMU, through the allocation and acting on the passive observer's
    estimate, equals pipelay's own sampled PD with the same gains and observer over 60 s of waves to 1e-9 of
    the signals (measured 1e-13: the FMU computes in its own order)."""
    observer = {"noise": (0.5, 0.5, 0.005), "seed": 3}
    own = _run(
        pl.PID(
            kp=KP,
            kd=KD,
            reference=REFERENCE,
            start=0.05,
            allocation="qp",
            observer=pl.Observer.passive(**observer),
        )
    )
    law = pl.Controller.fmu(
        fmus["controller"],
        INPUTS,
        OUTPUTS,
        parameters=PARAMETERS,
        start=0.05,
        allocation="qp",
        observer=pl.Observer.passive(**observer),
    )
    assert law.is_external
    driven = _run(law)
    assert own.eta is not None and driven.eta is not None and own.tau is not None and driven.tau is not None
    print(f"\nη {_relative(own.eta, driven.eta):.1e}, τ {_relative(own.tau, driven.tau):.1e}")
    assert _relative(own.eta, driven.eta) < 1e-9
    assert _relative(own.tau, driven.tau) < 1e-9
    assert _relative(own.positions, driven.positions) < 1e-9
    assert np.abs(own.eta[:, 1]).max() > 1e-3  # the loop did act: the vessel moved off and back


def _thrust_signal(times: np.ndarray) -> np.ndarray:
    """A commanded τ in surge, sway and yaw over `times` (N, N, N·m)."""
    return np.column_stack(
        [110e3 + 40e3 * np.sin(0.2 * times), 30e3 * np.sin(0.1 * times), 2e6 * np.sin(0.05 * times)]
    )


def test_the_plant_fmu_under_fmpy_equals_the_in_process_run(fmus: dict[str, Path]) -> None:
    """fmpy drives the plant FMU with a thrust history sampled at its communication step (0.1 s, the scenario's
    time step); pipelay's run with the same samples held over each step (`pl.PID.external`) gives the same pose,
    the pipe's force on the vessel and top tension to 1e-9 of their size (measured 0 to round-off)."""
    times = np.arange(0.0, DURATION + DT / 2, DT)
    samples = _thrust_signal(times)
    signal = np.zeros(len(times), dtype=[("time", float)] + [(s.name, float) for s in PLANT_INPUTS])
    signal["time"] = times
    for k, s in enumerate(PLANT_INPUTS):
        signal[s.name] = samples[:, k]
    names = (
        [f"eta_{n}" for n in POSE] + [f"chi_{n}" for n in ("X", "Y", "Z", "K", "M", "N")] + ["top_tension"]
    )
    co = fmpy.simulate_fmu(
        str(fmus["plant"]), stop_time=DURATION, step_size=DT, output_interval=DT, input=signal, output=names
    )

    def law(t: float, dt: float, eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
        k = round(t / DT)
        tau = np.zeros(6)
        tau[[0, 1, 5]] = samples[k]
        return tau

    own = _run(pl.PID.external(law, allocation="qp"))
    assert own.eta is not None and own.chi is not None
    eta = np.column_stack([co[f"eta_{n}"] for n in POSE])
    chi = np.column_stack([co[f"chi_{n}"] for n in ("X", "Y", "Z", "K", "M", "N")])
    assert np.allclose(co["time"], own.time, atol=1e-9)
    tension = own.lay_summary()["top_tension"]
    print(f"\nη {_relative(own.eta, eta):.1e}, χ {_relative(own.chi, chi):.1e}")
    assert _relative(own.eta, eta) < 1e-9
    assert _relative(own.chi, chi) < 1e-9
    assert _relative(tension, co["top_tension"]) < 1e-9


_OSP_RUN = """
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimObserver import CosimObserver

log_output_level(CosimLogLevel.ERROR)
execution = CosimExecution.from_osp_config_file(sys.argv[1])
observer = CosimObserver.create_last_value()
execution.add_observer(observer=observer)
plant = execution.slave_index_from_instance_name("jlay")
references = {v.name.decode(): v.reference for v in execution.slave_variables(plant)}
assert execution.step(int(sys.argv[2]))
print(json.dumps({name: observer.last_real_values(plant, [ref])[0] for name, ref in references.items()}))
"""


def _osp(system: Path, duration: float) -> dict[str, Any]:
    """The OSP system at `system` run by libcosim for `duration` (s), in a process of its own as DNV's `cosim`
    runs one (pythonfmu's FMUs of one name are loaded once per process): the plant's outputs at the end."""
    pytest.importorskip("libcosimpy")
    done = subprocess.run(
        [sys.executable, "-c", _OSP_RUN, str(system), str(round(duration / DT))],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return dict(json.loads(done.stdout.strip().splitlines()[-1]))


def test_an_osp_system_holds_station_and_equals_the_in_process_loop(fmus: dict[str, Path]) -> None:
    """libcosim runs `examples/cosimulation/OspSystemStructure.xml` (plant FMU + PD FMU, fixed step 0.1 s).
    Its master exchanges the signals at the communication points and steps both FMUs together, so the plant
    holds over each step the command the PD computed from the pose one step earlier, and nothing before its
    first answer: pipelay's run with that law (`pl.PID.external`) gives the same final pose, thrust and tension
    to 1e-9. The loop holds the vessel against the current, wind and waves: within 2 m of its set-point
    (measured 1.4 m; a PD leaves the mean load's offset), heading within 0.01 rad."""
    final = _osp(fmus["system"], DURATION)
    previous: list[np.ndarray] = []

    def delayed(t: float, dt: float, eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
        command = _pd(*previous[-1]) if previous else np.zeros(6)
        previous.append((eta.copy(), nu.copy()))
        return command

    own = _run(pl.PID.external(delayed, allocation="qp"))
    assert own.eta_low_frequency is not None and own.tau is not None
    eta = np.array([final[f"eta_lf_{n}"] for n in POSE])
    offset = math.hypot(eta[0] - REFERENCE[0], eta[1] - REFERENCE[1])
    print(
        f"\nOSP: offset {offset:.2f} m, heading {eta[5]:.4f} rad; η vs in-process {_relative(own.eta_low_frequency[-1], eta):.1e}"
    )
    assert _relative(own.eta_low_frequency[-1], eta) < 1e-9
    assert final["thrust_surge"] == pytest.approx(own.tau[-1, 0], rel=1e-9)
    assert final["top_tension"] == pytest.approx(own.lay_summary()["top_tension"][-1], rel=1e-9)
    assert offset < 2.0 and abs(eta[5]) < 0.01


def test_bad_controller_fmus_and_signals_name_their_argument(fmus: dict[str, Path], tmp_path: Path) -> None:
    """A variable the FMU lacks, a signal pipelay has not, a command in heave, a file that is no FMU: each an
    InputError naming the argument."""
    controller = fmus["controller"]
    with pytest.raises(pl.InputError, match=r"inputs: 'speed' is not a Real input"):
        pl.Controller.fmu(controller, {"speed": "nu[0]"}, OUTPUTS)
    with pytest.raises(pl.InputError, match=r"inputs\['x'\]: 'eta\[7\]' must be"):
        pl.Controller.fmu(controller, {"x": "eta[7]"}, OUTPUTS)
    with pytest.raises(pl.InputError, match=r"outputs\['tau_surge'\]: 'tau\[2\]' is not a DP command"):
        pl.Controller.fmu(controller, INPUTS, {"tau_surge": "tau[2]"})
    with pytest.raises(pl.InputError, match=r"parameters: 'kp' is not a Real parameter"):
        pl.Controller.fmu(controller, INPUTS, OUTPUTS, parameters={"kp": 1.0})
    (tmp_path / "not.fmu").write_text("no zip")
    with pytest.raises(pl.InputError, match=r"path: .* is not a readable FMU"):
        pl.Controller.fmu(tmp_path / "not.fmu", INPUTS, OUTPUTS)
    with pytest.raises(pl.InputError, match=r"parameters: \['sea.depthh'\] are not numbers"):
        build_fmu(EXAMPLE, tmp_path / "x.fmu", parameters=["sea.depthh"])


def test_a_law_that_fails_or_commands_nan_stops_the_run_naming_the_controller() -> None:
    """A command law that raises, or returns a non-finite τ, stops the run with an InputError naming
    `controller` and the time; nothing is propagated."""

    def failing(t: float, dt: float, eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
        raise RuntimeError("the DP computer is down")

    with pytest.raises(
        pl.InputError, match=r"controller: law\(0\) raised RuntimeError: the DP computer is down, got t = 0 s"
    ):
        _run(pl.PID.external(failing), duration=1.0)
    with pytest.raises(pl.InputError, match=r"controller.*must command finite thrust"):
        _run(pl.PID.external(lambda t, dt, eta, nu: np.full(6, np.nan)), duration=1.0)
