"""The lay-tension loop: an outer loop that moves the DP set-point along the route to hold the top tension."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pipelay as pl
import pytest

TARGET = 1.0e6


def _s_lay(x: float, tension: pl.TensionControl | None = None) -> pl.Model:
    """The S-lay example's pipe and stinger (140 elements, frictionless seabed) under PD control about x."""
    section = pl.Section.pipe(0.6, 0.03, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0))
    model = pl.Model(
        pl.Rod.straight((0, 0, 0), (700, 0, 0), 140, section),
        sea=pl.Sea(150.0, seabed=pl.Seabed(stiffness=1e5)),
    )
    model.pin("A")
    lay = pl.SLay(tensioner=(10, 0, -6.3), stinger=pl.Stinger(200.0, 100.0, 15, origin=(-40, 0, -6)))
    pid = pl.PID(
        kp=[2e5, 2e5, 0, 0, 0, 1e7],
        kd=[4e6, 4e6, 0, 0, 0, 1e8],
        reference=[x, 0, 0, 0, 0, 0],
        tension=tension,
    )
    model.attach_vessel("B", pl.Vessel.osv(), eta=[x, 0, -150, 0, 0, 0], controller=pid, lay=lay)
    return model


def test_tension_loop_settles_where_statics_put_the_vessel() -> None:
    """Starting 150 kN short of the target, the loop moves the set-point until the top tension is the target:
    the vessel comes to rest where the static lay-position search (Brent on statics, an independent path)
    puts it for that tension, to 1 cm; the energy never exceeds its start plus the supplied work."""
    static = pl.find_lay_position(_s_lay, "top_tension", TARGET, start=660.0)
    model = _s_lay(660.0, pl.TensionControl(TARGET, gain=3e-7, filter=20.0))
    state = model.static()
    assert state.lay_summary()["top_tension"] < 0.9 * TARGET
    results = model.simulation(state, dt=1.0).run(600.0, progress=False)
    tension = results.lay_summary()["top_tension"]
    late = results.time > 400.0
    print(
        f"vessel x {results.eta[-1, 0]:.4f} m (statics {static.state.eta[0]:.4f} m); "
        f"mean top tension over the last 200 s {tension[late].mean():.1f} N"
    )
    assert results.eta[-1, 0] == pytest.approx(static.state.eta[0], abs=0.01)
    assert tension[late].mean() == pytest.approx(TARGET, rel=3e-3)
    energy = results.energy["total"]
    scale = np.abs(energy).max()
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-6 * scale
    assert results.passivity_margin() <= 1e-9 * scale


def test_tension_loop_resumes_exactly(tmp_path: Path) -> None:
    """The loop's set-point and filtered tension are part of the checkpoint: 60 s, checkpoint, 60 s more equals
    120 s in one go, bit for bit."""
    model = _s_lay(660.0, pl.TensionControl(TARGET, gain=3e-7))
    state = model.static()
    whole = model.simulation(state, dt=1.0)
    whole.run(120.0, progress=False)
    first = model.simulation(state, dt=1.0)
    first.run(60.0, progress=False)
    first.checkpoint(tmp_path / "loop.npz")
    second = pl.resume(model, tmp_path / "loop.npz")
    second.run(120.0, progress=False)
    assert np.array_equal(second.state.positions, whole.state.positions)
    assert np.array_equal(second.state.eta, whole.state.eta)


@pytest.mark.parametrize(
    ("arguments", "name"),
    [({"gain": 0.0}, "gain"), ({"filter": -1.0}, "filter"), ({"rate_limit": 0.0}, "rate_limit")],
)
def test_bad_tension_loops_are_rejected(arguments: dict[str, float], name: str) -> None:
    """Gains, filter time constants and rate limits must be positive; the message names the argument."""
    values = {"gain": 1e-7, **arguments}
    with pytest.raises(pl.InputError, match=name):
        pl.TensionControl(TARGET, **values)
