"""The sampled DP loop's passivity certificate: the time-domain passivity observer and controller (Hannaford and
Ryu) on the port between the controller (with its allocation, thrusters and observer) and the vessel.

The system: the J-lay of `examples/j_lay_dp.toml` in its JONSWAP sea of 2.5 m, wind and current, the PID through
the thrust allocation acting on the passive observer's estimate, 300 s at Δt = 0.1 s.

References: the energy ledger (E − E₀ = W − D exact), from which the loop's certificate follows wherever the
controller's work stays within its storage; the same run without the observer (which must not change it).
"""

from __future__ import annotations

import tomllib
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import parse_scenario

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "j_lay_dp.toml"
DURATION = 300.0


def _scenario(passivity: str | None, sampled: bool = True, **changes: Any) -> Any:
    data = tomllib.loads(EXAMPLE.read_text())
    if not sampled:  # the implicit PID, without gusts: a run that resumes bit for bit
        del data["controller"]["observer"], data["controller"]["allocation"], data["sea"]["wind"]
    if passivity is not None:
        data["controller"]["passivity"] = passivity
    data["controller"].update(changes)
    return parse_scenario(data, origin=str(EXAMPLE))


def _run(passivity: str | None, duration: float = DURATION, **changes: Any) -> pl.Results:
    scenario = _scenario(passivity, **changes)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        return scenario.simulation().run(duration, progress=False, record_every=10)


@pytest.fixture(scope="module")
def runs() -> dict[str, pl.Results]:
    return {kind: _run(None if kind == "none" else kind) for kind in ("none", "observe", "certify")}


def _offset(results: pl.Results) -> np.ndarray:
    eta = results.eta_low_frequency
    assert eta is not None
    return np.hypot(eta[:, 0] - 880.0, eta[:, 1])


def test_the_observer_alone_changes_nothing_and_books_the_controllers_work(
    runs: dict[str, pl.Results],
) -> None:
    """With `passivity="observe"` the run is the run without it, bit for bit; its reserve starts at the PID's
    storage at the start, ½η̃ᵀK_pη̃ with η̃ the static offset the pipe's pull leaves (measured 111 kJ), and
    moves by the controller's work: the uncertified loop gives the vessel more than it held (measured: its
    reserve down to −43 kJ)."""
    plain, observed = runs["none"], runs["observe"]
    assert np.array_equal(plain.eta, observed.eta)
    assert plain.passivity_reserve is None and observed.passivity_reserve is not None
    reserve = observed.passivity_reserve
    data = tomllib.loads(EXAMPLE.read_text())
    kp, reference = np.array(data["controller"]["kp"]), np.array(data["controller"]["reference"])
    eta = observed.eta_low_frequency
    assert eta is not None
    storage = 0.5 * np.sum(kp * (eta[0] - reference) ** 2)
    assert reserve[0] == pytest.approx(storage, rel=1e-9)
    assert reserve.min() < 0.0
    assert observed.passivity_steps is not None and observed.passivity_steps[-1] == 0
    print(f"\nuncertified loop: reserve {reserve.min() / 1e3:.1f} … {reserve.max() / 1e3:.1f} kJ")


def test_the_certified_loop_stays_within_its_storage_with_the_ledger_exact(
    runs: dict[str, pl.Results],
) -> None:
    """Certified, the controller never gives the vessel more than it held: its reserve ≥ 0 at every record (to
    1e-9 of the energy moved) and the loop's margin max(E − E₀ − W_env − R₀) ≤ 0; the plant's ledger stays exact.
    The passivity controller acts where the sampled loop (lagging thrusters, an estimate a step old) would give
    back more than it took."""
    certified, observed = runs["certify"], runs["observe"]
    reserve = certified.passivity_reserve
    steps, dissipated = certified.passivity_steps, certified.passivity_withheld
    assert reserve is not None and steps is not None and dissipated is not None
    scale = np.abs(certified.supplied_work).max()
    energy = certified.energy["total"]
    plant = certified.passivity_margin()
    closed = certified.passivity_margin(loop=True)
    total_steps = round(DURATION / 0.1)
    print(
        f"\ncertified: reserve ≥ {reserve.min():.3e} J; loop margin {closed:.3e} J, plant margin {plant:.3e} J of "
        f"{np.abs(energy).max():.2e} J; the passivity controller acted in {steps[-1]:.0f} of {total_steps} steps, "
        f"withholding {dissipated[-1] / 1e3:.1f} kJ; uncertified reserve down to "
        f"{observed.passivity_reserve.min() / 1e3:.1f} kJ"  # type: ignore[union-attr]
    )
    assert reserve.min() >= -1e-9 * scale
    assert closed <= 1e-9 * np.abs(energy).max()
    assert plant <= 1e-9 * np.abs(energy).max()
    balance = energy - energy[0] - certified.supplied_work + certified.dissipated
    assert np.abs(balance).max() < 1e-9 * np.abs(energy).max()
    with pytest.raises(pl.InputError, match=r"loop: .*passivity"):
        runs["none"].passivity_margin(loop=True)


def test_certification_changes_station_keeping_little(runs: dict[str, pl.Results]) -> None:
    """What the passivity controller's damping costs: the largest offset from the set-point and the mean thrust
    against the uncertified loop's, within 20 % each (stated in the DP page)."""
    certified, observed = runs["certify"], runs["observe"]
    assert certified.tau is not None and observed.tau is not None
    offsets = (_offset(observed).max(), _offset(certified).max())
    thrust = (np.abs(observed.tau[:, 0]).mean(), np.abs(certified.tau[:, 0]).mean())
    print(
        f"\nlargest offset {offsets[0]:.2f} m uncertified, {offsets[1]:.2f} m certified; mean surge thrust "
        f"{thrust[0] / 1e3:.1f} kN, {thrust[1] / 1e3:.1f} kN"
    )
    assert offsets[1] == pytest.approx(offsets[0], rel=0.2)
    assert thrust[1] == pytest.approx(thrust[0], rel=0.2)


def test_a_certified_run_resumes_bit_for_bit_and_its_file_keeps_the_reserve(tmp_path: Path) -> None:
    """The observer's ledger is in checkpoints (the resumed run equals the uninterrupted one: the implicit PID,
    without gusts, for a sampled loop restarts its observer and thrusters at a resume) and in results files."""
    scenario = _scenario("certify", sampled=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        whole = scenario.simulation().run(40.0, progress=False)
        first = scenario.simulation()
        first.run(20.0, progress=False)
        path = first.checkpoint(tmp_path / "half.ckpt")
        resumed = pl.resume(scenario.model, path).run(40.0, progress=False)
    assert whole.passivity_reserve is not None and resumed.passivity_reserve is not None
    assert np.array_equal(whole.passivity_reserve[-1:], resumed.passivity_reserve[-1:])
    assert np.array_equal(whole.eta[-1], resumed.eta[-1])
    loaded = pl.load(whole.to_netcdf(tmp_path / "run.nc"))
    assert np.array_equal(loaded.passivity_reserve, whole.passivity_reserve)
    assert loaded.passivity_margin(loop=True) == whole.passivity_margin(loop=True)


def test_bad_passivity_settings_name_their_key() -> None:
    """A mode that does not exist, or an observer about a moving reference, is an InputError naming the key."""
    with pytest.raises(pl.InputError, match=r"passivity.*\"certify\""):
        pl.PID(kp=np.ones(6), kd=np.ones(6), reference=np.zeros(6), passivity="always")
    route = pl.Route((0.0, 0.0), heading=0.0, speed=1.0)
    with pytest.raises(pl.InputError, match=r"passivity.*fixed reference"):
        pl.PID(kp=np.ones(6), kd=np.ones(6), reference=route, passivity="certify")
    with pytest.raises(pl.InputError, match=r"controller.passivity"):
        _scenario("sometimes")
