"""The articulated stinger: hinged sections under the S-lay example's pipe. Statics balance the moments about
each free hinge (computed here from the state's roller reactions and the sections' weights, independently of
the engine's residual); a run with the sections moving in a current keeps the energy ledger exact, records
the hinge angles in its results and files, and resumes from a checkpoint bit for bit; bad input is refused.

The closed-form angle of one section under its own weight (k φ = W a cos(α + φ), to 1e-6), the tangents and
the ledger in vacuum are tested in the engine (`crates/pipelay/tests/articulated_stinger.rs`)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.plots.replay import prepare
from pipelay.scenario import parse_scenario

EXAMPLE = Path(__file__).parent.parent / "examples" / "s_lay_articulated.toml"


def _example(**changes: object) -> dict:
    """The articulated example's document, each section's keys updated by `changes`."""
    data = tomllib.loads(EXAMPLE.read_text())
    for section in data["vessel"]["lay"]["stinger"]["sections"]:
        section.update(changes)
    return data


def _turn(angle: float) -> np.ndarray:
    """Rotation by `angle` about b2 (positive: aft end down, b1 → −b3)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _placed(point: np.ndarray, hinges: np.ndarray, angles: np.ndarray, section: int) -> np.ndarray:
    """A point of section `section` (body frame, at zero angles) where the hinge angles put it: turned about
    each hinge from the last to the first."""
    for i in range(section, -1, -1):
        point = hinges[i] + _turn(angles[i]) @ (point - hinges[i])
    return point


def _body_rotation(eta: np.ndarray) -> np.ndarray:
    """R_b^e of the vessel's Euler angles (φ, θ, ψ), zyx."""
    phi, theta, psi = eta[3:]
    rx = np.array([[1, 0, 0], [0, np.cos(phi), -np.sin(phi)], [0, np.sin(phi), np.cos(phi)]])
    ry = np.array([[np.cos(theta), 0, np.sin(theta)], [0, 1, 0], [-np.sin(theta), 0, np.cos(theta)]])
    rz = np.array([[np.cos(psi), -np.sin(psi), 0], [np.sin(psi), np.cos(psi), 0], [0, 0, 1]])
    return rz @ ry @ rx


def test_free_hinges_balance_the_moments_of_the_pipe_and_the_sections() -> None:
    """In still water, about each free hinge (axis b2) the moments of the sections' weight less buoyancy (at
    their chords' middles) and of the rollers' forces on the stinger (along lines through the rollers' axes)
    of the sections beyond it add up to zero, to 1e-6 of their size; the sections float between their limits
    with the pipe on them."""
    data = _example(hinge_stiffness=0.0)
    state = parse_scenario(data, "free hinges").model.static()
    arc = data["vessel"]["lay"]["stinger"]
    sections = [pl.StingerSection(**s) for s in arc["sections"]]
    fixed = arc["length"] - sum(s.length for s in sections)
    stinger = pl.Stinger.articulated(
        sections, arc["radius"], arc["rollers"], fixed_length=fixed, origin=arc["origin"]
    )
    angles = state.hinge_angles
    hinges = stinger.hinges
    assert len(angles) == 2 and np.all(np.abs(angles) < 0.29), angles
    # The arc: 200 m radius from (−40, 0, −6), its centre below the origin; rollers 0.25 m in radius.
    centre = np.array([-40.0, 0.0, 194.0])
    tops = stinger.positions
    axes_points = tops - 0.25 * (tops - centre) / 200.0
    on = np.array(stinger.roller_sections)
    forces = state.roller_reaction_vectors  # on the pipe, body frame
    assert np.count_nonzero(np.linalg.norm(forces[on >= 0], axis=1)) >= 4
    gravity = _body_rotation(state.eta).T @ np.array([0.0, 0.0, 9.81])
    ends = np.vstack([hinges[1:], [tops[-1]]])
    for j in range(2):
        hinge = _placed(hinges[j], hinges, angles, j - 1) if j > 0 else hinges[0]
        moments = []
        for i in range(j, 2):
            data = stinger.sections[i]
            middle = _placed(0.5 * (hinges[i] + ends[i]), hinges, angles, i)
            weight = data.mass * gravity - data.buoyancy * gravity / 9.81
            moments.append(np.cross(middle - hinge, weight)[1])
        for k in np.flatnonzero(on >= j):
            point = _placed(axes_points[k], hinges, angles, on[k])
            moments.append(np.cross(point - hinge, -forces[k])[1])
        total, size = sum(moments), sum(abs(m) for m in moments)
        print(f"hinge {j}: angle {angles[j]:.5f} rad, moment {total:.3e} of {size:.3e} N·m")
        assert abs(total) < 1e-6 * size


def test_a_run_in_a_current_moves_the_sections_and_keeps_the_ledger(tmp_path: Path) -> None:
    """The example in a current starting at 2 s: the sections swing (drag on them and on the pipe), the hinge
    angles are recorded over time and in the results file (written whole or streamed), the ledger closes to 1e-8 of the stored energy,
    and a run resumed from a checkpoint at 3 s ends bit for bit where the whole run does."""
    data = _example()
    data["sea"]["current"] = {"kind": "uniform", "velocity": [0.8, 0.3, 0.0], "start": 2.0}
    scenario = parse_scenario(data, "current from 2 s")
    whole = scenario.model.simulation(dt=0.2)
    results = whole.run(6.0, progress=False)
    angles = results.hinge_angles
    assert angles is not None and angles.shape == (len(results.time), 2)
    assert np.ptp(angles[:, 1]) > 1e-4, np.ptp(angles, axis=0)
    energy = results.energy["total"]
    balance = energy[-1] - energy[0] - (results.supplied_work[-1] - results.dissipated[-1])
    print(f"hinge angles swing by {np.ptp(angles, axis=0)} rad; balance {balance:.3e} J of {energy[0]:.3e} J")
    assert abs(balance) < 1e-8 * abs(energy[0]), balance
    assert np.any(results.energy["stinger"] != results.energy["stinger"][0])
    loaded = pl.load(results.to_netcdf(tmp_path / "run.nc"))
    assert np.array_equal(loaded.hinge_angles, angles)
    assert np.array_equal(loaded.energy["stinger"], results.energy["stinger"])
    # A run streamed to its file records the same angles.
    streamed = parse_scenario(data, "current from 2 s").model.simulation(dt=0.2)
    streamed.run(6.0, progress=False, output=tmp_path / "streamed.nc")
    assert np.array_equal(pl.load(tmp_path / "streamed.nc").hinge_angles, angles)
    part = parse_scenario(data, "current from 2 s").model.simulation(dt=0.2)
    part.run(3.0, progress=False)
    checkpoint = part.checkpoint(tmp_path / "part.npz")
    resumed = pl.resume(parse_scenario(data, "current from 2 s").model, checkpoint)
    resumed.run(6.0, progress=False)
    assert np.array_equal(resumed.state.hinge_angles, whole.state.hinge_angles)
    assert np.array_equal(resumed.state.positions, whole.state.positions)


def test_bad_sections_are_refused_naming_the_key() -> None:
    """Hinge limits that do not hold 0, a negative mass, too many sections, and sections longer than the
    arc are refused with the argument or key named."""
    with pytest.raises(pl.InputError, match="hinge_limits"):
        pl.StingerSection(20.0, 1e4, 1e5, hinge_limits=(0.1, 0.3))
    with pytest.raises(pl.InputError, match="mass"):
        pl.StingerSection(20.0, -1.0, 1e5)
    section = pl.StingerSection(5.0, 1e4, 1e5)
    with pytest.raises(pl.InputError, match="sections"):
        pl.Stinger.articulated([section] * 11, 200.0, 15)
    stinger = pl.Stinger.articulated([section] * 2, 200.0, 5, fixed_length=10.0)
    assert stinger.roller_sections == [-1, -1, -1, 0, 1] and len(stinger.sections) == 2
    data = _example(length=80.0)
    with pytest.raises(pl.InputError, match="vessel.lay.stinger.sections"):
        parse_scenario(data, "too long")


def test_the_replay_turns_the_sections_with_their_hinge_angles() -> None:
    """The replay draws the articulated stinger's sections and rollers where each frame's hinge angles put
    them: a section's end lies at its length's chord from its hinge, and the rollers move with the sections."""
    data = _example()
    data["sea"]["current"] = {"kind": "uniform", "velocity": [1.5, 0.0, 0.0], "start": 0.0}
    scenario = parse_scenario(data, "current along")
    simulation = scenario.model.simulation(dt=0.2)
    results = simulation.run(2.0, progress=False)
    scene = prepare(results, scenario.model, "tension", 5)
    assert scene.equipment is not None and scene.equipment[0] == "rollers and hinged sections"
    first, last = scene.equipment[1][0], scene.equipment[1][-1]
    lines = last[15:].reshape(2, 3, 3)
    assert np.all(np.isnan(lines[:, 2]))
    chord = 2 * 200.0 * np.sin(30.0 / 400.0)
    assert np.allclose(np.linalg.norm(lines[:, 1] - lines[:, 0], axis=1), chord, rtol=1e-9)
    # The sections' last end sits where the state's section lines put it (plot coordinates flip z).
    end = simulation.state.section_lines[-1, 1] * np.array([1.0, 1.0, -1.0])
    assert np.allclose(lines[-1, 1], end, atol=1e-6)
    assert np.linalg.norm(last[:15] - first[:15]) > 0.0


def test_pipelay_static_prints_the_hinge_angles() -> None:
    """`pipelay static` on the example prints each section's hinge angle, as the state gives it."""
    import subprocess
    import sys

    out = subprocess.run(
        [sys.executable, "-m", "pipelay", "static", str(EXAMPLE)], capture_output=True, text=True, check=True
    ).stdout
    state = parse_scenario(_example(), "example").model.static()
    expected = ", ".join(f"{np.degrees(a):.2f}°" for a in state.hinge_angles)
    assert f"lay: hinge angles        {expected}" in out


def test_in_waves_the_sections_move_with_the_vessel_and_the_ledger_closes() -> None:
    """In a JONSWAP sea (Hs 2.5 m, Tp 9 s, 30° off the bow) the vessel's wave-frequency motion swings the
    sections and the waves' particle velocity drags on them; over 30 s the ledger closes to 1e-8 of the largest
    stored energy, and the hinges stay within their limits (±0.3 rad, the limit springs' give aside)."""
    data = _example()
    data["sea"]["waves"] = {
        "kind": "jonswap", "hs": 2.5, "tp": 9.0, "gamma": 3.3, "direction": 0.5235987755982988,
        "seed": 1, "components": 100, "ramp": 10.0,
    }  # fmt: skip
    results = parse_scenario(data, "waves").model.simulation(dt=0.2).run(30.0, progress=False)
    angles = results.hinge_angles
    energy = results.energy["total"]
    balance = energy - energy[0] - (results.supplied_work - results.dissipated)
    print(f"hinge swings {np.ptp(angles, axis=0)} rad; worst balance {np.abs(balance).max():.3e} J")
    assert np.all(np.ptp(angles, axis=0) > 0.01)
    assert np.abs(balance).max() < 1e-8 * np.abs(energy).max()
    assert np.all(np.abs(angles) < 0.31)
