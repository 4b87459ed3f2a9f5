"""Co-simulation: pipelay as an FMU (`pipelay fmu`), a controller FMU as the vessel's controller
(`pl.Controller.fmu`), run by real masters: fmpy and DNV's libcosim (libcosimpy).

The system: the J-lay of `examples/j_lay_dp.toml` (the OSV in 800 m, a JONSWAP sea of 2.5 m, wind and a 0.5 m/s
current, thrust allocation). The controller FMU is `examples/cosimulation/dp_pd.py` built by pythonfmu: a PD on
the pose computed as pipelay's own PID computes it. Every FMU runs in a child process
(`tests/cosimulation_case.py` says why).

References: pipelay's in-process runs of the same loop (its own sampled PID; the same command law given as a
Python function), which the co-simulated runs must equal to 1e-9 of the signals' size; fmpy's validation of
the FMU; the scenario's current and wind, which the co-simulated loop must hold the vessel against.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from cosimulation_case import (
    CONTROLLER,
    DT,
    DURATION,
    EXAMPLE,
    INPUTS,
    KD,
    KP,
    OBSERVER,
    OUTPUTS,
    POSE,
    REFERENCE,
    START,
    SYSTEM,
    in_child,
    pd,
    run,
    thrust_signal,
)
from pipelay.cosimulation.build import build_fmu
from pipelay.cosimulation.slave import PLANT_INPUTS, PLANT_OUTPUTS

fmpy = pytest.importorskip("fmpy")
pythonfmu = pytest.importorskip("pythonfmu")


@pytest.fixture(scope="module")
def fmus(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The folder with the plant FMU of the example (`pipelay fmu`), the PD controller FMU and the OSP system
    structure file that connects them."""
    folder = tmp_path_factory.mktemp("fmus")
    build_fmu(EXAMPLE, folder / "jlay.fmu")
    build_fmu(EXAMPLE, folder / "pipe.fmu", kind="pipe")
    from pythonfmu import FmuBuilder

    FmuBuilder.build_FMU(CONTROLLER, dest=folder)
    shutil.copy2(SYSTEM, folder / SYSTEM.name)
    return folder


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(a).max())


def test_the_plant_fmu_passes_fmpys_validation_with_units_and_initial_unknowns(fmus: Path) -> None:
    """fmpy's validation finds nothing to complain of; every input and output has its unit; the outputs are
    the initial unknowns; the parameters are the numbers of the scenario's current, sea and wind, starting at
    the scenario's values (seeds and component counts left out)."""
    from fmpy.validation import validate_fmu

    plant = str(fmus / "jlay.fmu")
    assert validate_fmu(plant) == []
    description = fmpy.read_model_description(plant)
    variables = {v.name: v for v in description.modelVariables}
    for signal in (*PLANT_INPUTS, *PLANT_OUTPUTS):
        assert variables[signal.name].unit == signal.unit
    assert {v.variable.name for v in description.initialUnknowns} == {s.name for s in PLANT_OUTPUTS}
    parameters = {v.name: float(v.start) for v in description.modelVariables if v.causality == "parameter"}
    assert parameters["sea.current.velocity[0]"] == 0.5
    assert parameters["sea.waves.hs"] == 2.5 and parameters["sea.wind.speed"] == 15.0
    assert not any(name.endswith(("seed", "components")) for name in parameters)
    assert variables["sea.waves.hs"].unit == "m" and variables["sea.current.velocity[0]"].unit == "m/s"
    assert description.defaultExperiment.stepSize == str(DT)


def test_a_controller_fmu_drives_the_j_lay_as_pipelays_own_sampled_pid(fmus: Path, tmp_path: Path) -> None:
    """`pl.Controller.fmu` with the PD FMU, through the allocation and acting on the passive observer's
    estimate, equals pipelay's own sampled PD with the same gains and observer over 60 s of waves to 1e-9 of
    the signals (measured 4e-16 and 2e-12: the FMU computes in its own order)."""
    own = run(
        pl.PID(
            kp=KP,
            kd=KD,
            reference=REFERENCE,
            start=START,
            allocation="qp",
            observer=pl.Observer.passive(**OBSERVER),  # type: ignore[arg-type]
        )
    )
    driven = in_child("controller", fmus, tmp_path / "controller.npz")
    assert own.eta is not None and own.tau is not None
    print(f"\nη {_relative(own.eta, driven['eta']):.1e}, τ {_relative(own.tau, driven['tau']):.1e}")
    assert _relative(own.eta, driven["eta"]) < 1e-9
    assert _relative(own.tau, driven["tau"]) < 1e-9
    assert _relative(own.positions, driven["positions"]) < 1e-9
    assert np.abs(own.eta[:, 1]).max() > 1e-3  # the loop did act: the vessel moved off and back


def test_the_plant_fmu_under_fmpy_equals_the_in_process_run(fmus: Path, tmp_path: Path) -> None:
    """fmpy drives the plant FMU with a thrust history sampled at its communication step (0.1 s, the scenario's
    time step); pipelay's run with the same samples held over each step (`pl.PID.external`) gives the same pose,
    the pipe's force on the vessel and top tension to 1e-9 of their size (measured 0: the same arithmetic)."""
    co = in_child("plant", fmus, tmp_path / "plant.npz")
    samples = thrust_signal(np.arange(0.0, DURATION + DT / 2, DT))

    def law(t: float, dt: float, eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
        tau = np.zeros(6)
        tau[[0, 1, 5]] = samples[round(t / DT)]
        return tau

    own = run(pl.PID.external(law, allocation="qp"))
    assert own.eta is not None and own.chi is not None
    assert np.allclose(co["time"], own.time, atol=1e-9)
    print(f"\nη {_relative(own.eta, co['eta']):.1e}, χ {_relative(own.chi, co['chi']):.1e}")
    assert _relative(own.eta, co["eta"]) < 1e-9
    assert _relative(own.chi, co["chi"]) < 1e-9
    assert _relative(own.lay_summary()["top_tension"], co["top_tension"]) < 1e-9


def test_the_pipe_fmu_carried_by_a_vessel_motion_equals_the_pipe_driven_in_process(
    fmus: Path, tmp_path: Path
) -> None:
    """The pipe FMU (`--kind pipe`) under fmpy, its hold point carried by a prescribed vessel motion (surge ±2 m,
    sway ±1 m, yaw ±0.02 rad) given at each 0.1 s, gives the pipe's force and moment on the vessel as pipelay's
    own run of the pipe driven by that motion (`HeldPipe`, the same samples held over each step) to 1e-9 (measured
    0), and its energy ledger closes. At t = 0 it is the plant's χ of the same statics to 1e-9 (measured 3e-11):
    the pipe alone, held where the vessel holds it, is in the same equilibrium."""
    import tomllib

    from cosimulation_case import CHI, vessel_motion
    from pipelay.cosimulation.pipe import HeldPipe
    from pipelay.scenario import parse_scenario

    co = in_child("pipe", fmus, tmp_path / "pipe.npz")
    data = tomllib.loads(EXAMPLE.read_text())
    held = HeldPipe(data, EXAMPLE)
    times = np.arange(0.0, DURATION + DT / 2, DT)
    eta, nu = vessel_motion(times)
    simulation = held.simulation()
    chi = [held.chi(simulation.state, 0.0)]
    energy = [simulation.energy]
    for k in range(len(times) - 1):
        held.hold(times[k], eta[k], nu[k])
        simulation.step()
        chi.append(held.chi(simulation.state, simulation.time))
        energy.append(simulation.energy)
    chi_own = np.array(chi)
    chi_co = np.column_stack([co[f"chi_{n}"] for n in CHI])
    print(f"\nχ {_relative(chi_own, chi_co):.1e}; χ swings {np.ptp(chi_own[:, 0]) / 1e3:.0f} kN in surge")
    assert _relative(chi_own, chi_co) < 1e-9
    assert _relative(np.array(energy), co["energy"]) < 1e-9
    balance = co["energy"] - co["energy"][0] - co["supplied_work"] + co["dissipated"]
    print(f"balance {np.abs(balance).max():.1e} J of {np.abs(co['energy']).max():.1e} J")
    assert np.abs(balance).max() < 1e-9 * np.abs(co["energy"]).max()
    plant = parse_scenario(data, origin=str(EXAMPLE)).model.static()
    assert plant.chi is not None
    assert _relative(np.asarray(plant.chi), chi_co[0]) < 1e-9


def test_an_osp_system_holds_station_and_equals_the_in_process_loop(fmus: Path, tmp_path: Path) -> None:
    """libcosim runs `examples/cosimulation/OspSystemStructure.xml` (plant FMU + PD FMU, fixed step 0.1 s, the
    PD seeing the low-frequency pose). Its master exchanges the signals at the communication points and steps
    both FMUs together, so the plant holds over each step the command the PD computed from the pose one step
    earlier, and nothing before its first answer: pipelay's run with that law (`pl.PID.external`) gives the
    same final pose, thrust and tension to 1e-9 (measured 0). The loop holds the vessel against the current,
    wind and waves: within 2 m of its set-point (measured 1.35 m; a PD leaves the mean load's offset), heading
    within 0.01 rad."""
    pytest.importorskip("libcosimpy")
    final = in_child("osp", fmus, tmp_path / "osp.npz")
    previous: list[tuple[np.ndarray, np.ndarray]] = []

    def delayed(t: float, dt: float, eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
        command = pd(*previous[-1]) if previous else np.zeros(6)
        previous.append((eta.copy(), nu.copy()))
        return command

    own = run(pl.PID.external(delayed, allocation="qp"))
    assert own.eta_low_frequency is not None and own.tau is not None
    eta = np.array([float(final[f"eta_lf_{n}"]) for n in POSE])
    offset = math.hypot(eta[0] - REFERENCE[0], eta[1] - REFERENCE[1])
    difference = _relative(own.eta_low_frequency[-1], eta)
    print(f"\nOSP: offset {offset:.2f} m, heading {eta[5]:.4f} rad; η vs in-process {difference:.1e}")
    assert difference < 1e-9
    assert float(final["thrust_surge"]) == pytest.approx(own.tau[-1, 0], rel=1e-9)
    assert float(final["top_tension"]) == pytest.approx(own.lay_summary()["top_tension"][-1], rel=1e-9)
    assert offset < 2.0 and abs(eta[5]) < 0.01


def test_bad_controller_fmus_and_signals_name_their_argument(fmus: Path, tmp_path: Path) -> None:
    """A variable the FMU lacks, a signal pipelay has not, a command in heave, a file that is no FMU, a
    parameter the scenario has not: each an InputError naming the argument (checked before the FMU's binary is
    loaded)."""
    controller = fmus / "dp_pd.fmu"
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
        pl.InputError, match=r"controller: law\(0\) raised RuntimeError: the DP computer is down"
    ):
        run(pl.PID.external(failing), duration=1.0)
    with pytest.raises(pl.InputError, match=r"controller.*must command finite thrust"):
        run(pl.PID.external(lambda t, dt, eta, nu: np.full(6, np.nan)), duration=1.0)
