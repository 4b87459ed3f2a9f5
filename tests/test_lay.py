"""Lay equipment through the Python API: S-lay over stinger rollers and J-lay from a tower.

References: the classic overbend strain d_o/(2R) + T/EA on a densely rollered stinger; the roller contact
law F = k·max(0, r_r + d_o/2 − d) with d recomputed here from the node positions and the vessel pose; the
force balance of the vessel (pipe force = tensioner force + roller forces); the J-lay tower geometry; the
first integral T + w z + M²/(2EI) = const of the weighted elastica; the discrete energy ledger
E(t) − E(0) = W(t) − D(t) and the thrust work ∫ τ·ν dt; the DNV-ST-F101 criteria of ``pl.checks``.

Frame e: origin at end A, e1 along the lay, e3 down, sea surface at z = −depth. Body frame b: forward,
starboard, down; R(Θ) = Rz(ψ) Ry(θ) Rx(φ) maps b to e.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cache
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from numpy.typing import NDArray
from scipy.optimize import minimize_scalar

FloatArray = NDArray[np.float64]

DIAMETER = 0.6
SECTION = pl.Section.pipe(
    outer_diameter=DIAMETER,
    wall_thickness=0.03,
    contents_density=0.0,
    drag=(0.0, 1.0),
    added_mass=(0.0, 1.0),
)
DEPTH = 150.0
TENSIONER = (10.0, 0.0, -6.3)
STINGER_ORIGIN = np.array([-40.0, 0.0, -6.0])
ROLLER_RADIUS = 0.25
ROLLER_STIFFNESS = 1e7


def _rotation(eta: FloatArray) -> FloatArray:
    """Fossen's R(Θ) = Rz(ψ) Ry(θ) Rx(φ) (body → e) of a pose η = [x, y, z, φ, θ, ψ]."""
    phi, theta, psi = eta[3:6]
    cf, sf = math.cos(phi), math.sin(phi)
    ct, st = math.cos(theta), math.sin(theta)
    cp, sp = math.cos(psi), math.sin(psi)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cf, -sf], [0.0, sf, cf]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    rz = np.array([[cp, -sp, 0.0], [sp, cp, 0.0], [0.0, 0.0, 1.0]])
    return rz @ ry @ rx


def _midway(r0: FloatArray, r1: FloatArray) -> FloatArray:
    """The rotation halfway from r0 to r1 (geodesic on SO(3)): r0·exp(½ log(r0ᵀ r1)), by Rodrigues."""
    q = r0.T @ r1
    angle = math.acos(max(-1.0, min(1.0, 0.5 * (np.trace(q) - 1.0))))
    if angle < 1e-12:
        return r0
    axis = np.array([q[2, 1] - q[1, 2], q[0, 2] - q[2, 0], q[1, 0] - q[0, 1]]) / (2.0 * math.sin(angle))
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    half = 0.5 * angle
    return r0 @ (np.eye(3) + math.sin(half) * k + (1.0 - math.cos(half)) * k @ k)


def _to_body(state: pl.State, points: FloatArray) -> FloatArray:
    """Points (…, 3) in e expressed in the vessel's body frame, relative to CO."""
    eta = state.eta
    assert eta is not None
    return (points - eta[:3]) @ _rotation(eta)


def _stinger(radius: float = 100.0, length: float = 80.0, rollers: int = 12) -> pl.Stinger:
    """A stinger arc from 40 m aft of CO, 6 m above the waterline, starting horizontal."""
    return pl.Stinger(
        radius, length, rollers, origin=tuple(STINGER_ORIGIN), angle=0.0, roller_radius=ROLLER_RADIUS
    )


def _arc_centre(radius: float) -> FloatArray:
    """Centre of a stinger arc starting horizontal at STINGER_ORIGIN and bending down (body frame)."""
    return STINGER_ORIGIN + np.array([0.0, 0.0, radius])


def _s_lay(
    x: float,
    *,
    seabed: bool = True,
    stinger: pl.Stinger | None = None,
    elements: int = 280,
    length: float = 700.0,
    environment: list[pl.Force] | None = None,
) -> pl.Model:
    """The 24-inch pipe from A = (0, 0, 0) laid by an OSV at x with a tensioner and a stinger."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (length, 0.0, 0.0), elements, SECTION)
    sea = pl.Sea(DEPTH, seabed=pl.Seabed(stiffness=1e5)) if seabed else pl.Sea(DEPTH)
    model = pl.Model(rod, sea)
    model.pin("A")
    lay = pl.SLay(
        tensioner=TENSIONER,
        stinger=stinger if stinger is not None else _stinger(),
        friction=0.0,
        roller_stiffness=ROLLER_STIFFNESS,
    )
    model.attach_vessel(
        "B", pl.Vessel.osv(), eta=[x, 0.0, -DEPTH, 0.0, 0.0, 0.0], lay=lay, environment=environment
    )
    return model


@cache
def _s_lay_state(x: float, seabed: bool) -> pl.State:
    """Static S-lay state (280 elements, 80 m stinger of 12 rollers), cached across tests."""
    return _s_lay(x, seabed=seabed).static()


def _catmull_rom(points: FloatArray) -> Callable[[int, float], FloatArray]:
    """The centreline through `points` (N, k) as the Catmull–Rom spline the roller contact uses: on element
    e, r(ξ) = ½[(−ξ³ + 2ξ² − ξ) p_{e−1} + (3ξ³ − 5ξ² + 2) p_e + (−3ξ³ + 4ξ² + ξ) p_{e+1} + (ξ³ − ξ²) p_{e+2}],
    the missing node at an end mirrored (p_{−1} = 2p_0 − p_1)."""
    padded = np.vstack([2.0 * points[0] - points[1], points, 2.0 * points[-1] - points[-2]])

    def at(e: int, xi: float) -> FloatArray:
        x2, x3 = xi * xi, xi * xi * xi
        w = 0.5 * np.array([-x3 + 2 * x2 - xi, 3 * x3 - 5 * x2 + 2, -3 * x3 + 4 * x2 + xi, x3 - x2])
        return w @ padded[e : e + 4]

    return at


def _roller_contacts(state: pl.State, stinger: pl.Stinger, radius: float) -> tuple[FloatArray, FloatArray]:
    """For each roller of an arc stinger: the distance d (m) from its axis (along b2) to the pipe's centreline
    in the body x–z plane, the Catmull–Rom spline through the nodes (minimised by scipy over the elements
    next to the nearest chord), and the unit direction (body frame) from the axis to the nearest point."""
    tops = stinger.positions
    normals = (tops - _arc_centre(radius)) / radius
    axes = tops - ROLLER_RADIUS * normals
    nodes = _to_body(state, state.positions)[:, [0, 2]]
    distances, directions = [], []
    for centre in axes[:, [0, 2]]:
        p = nodes - centre
        chord = p[1:] - p[:-1]
        s = np.clip(-np.sum(p[:-1] * chord, axis=1) / np.sum(chord * chord, axis=1), 0.0, 1.0)
        foot = p[:-1] + s[:, None] * chord
        nearest = int(np.argmin(np.hypot(foot[:, 0], foot[:, 1])))
        spline = _catmull_rom(p)
        best = (math.inf, np.zeros(2))
        for e in range(max(nearest - 1, 0), min(nearest + 2, len(chord))):
            found = minimize_scalar(
                lambda xi, e=e, spline=spline: float(np.linalg.norm(spline(e, xi))),
                bounds=(0.0, 1.0),
                method="bounded",
                options={"xatol": 1e-12},
            )
            if found.fun < best[0]:
                best = (found.fun, spline(e, found.x))
        distances.append(best[0])
        directions.append([best[1][0] / best[0], 0.0, best[1][1] / best[0]])
    return np.array(distances), np.array(directions)


# --- 1. overbend strain ----------------------------------------------------------------------------------


def test_overbend_strain_on_a_dense_stinger_is_the_classic_estimate() -> None:
    """A 100 m stinger arc of 60 m with 31 rollers (2 m spacing) and 0.875 m elements, vessel at x = 640 m: the
    pipe rests on the rollers from 12 m to the tip. Over the middle of the arc (15–45 m) the centreline lies
    at R + d_o/2 from the arc's centre (the arc is the rollers' top line, so the roller radius does not enter;
    to 1 cm: roller overlap F/k ≈ 1 mm and the sag of the pipe between rollers, s²/(8R) = 5 mm), and the
    strain averages d_o/(2(R + d_o/2)) + N1/EA to 1 % (the curvature ripples between the discrete rollers —
    ±5 % element to element — but averages over whole spans; measured −0.1 %). The largest strain there is
    not below the estimate."""
    radius, length, rollers = 100.0, 60.0, 31
    stinger = _stinger(radius, length, rollers)
    state = _s_lay(640.0, stinger=stinger, elements=800).static()
    reactions = state.roller_reactions
    assert reactions is not None and reactions.shape == (rollers,)
    # The rollers over the middle of the arc all carry the pipe.
    roller_arc = np.linspace(0.0, length, rollers)
    middle_rollers = (roller_arc >= 15.0) & (roller_arc <= 45.0)
    assert np.all(reactions[middle_rollers] > 0.0), reactions

    middles = 0.5 * (state.positions[1:] + state.positions[:-1])
    relative = _to_body(state, middles) - _arc_centre(radius)
    arc = radius * np.arctan2(-relative[:, 0], -relative[:, 2])  # slope below horizontal × R
    on_arc = (arc > 15.0) & (arc < 45.0) & (relative[:, 0] < 0.0)
    assert 30 <= np.count_nonzero(on_arc) <= 40
    centreline_radius = radius + DIAMETER / 2.0
    offset = np.hypot(relative[on_arc, 0], relative[on_arc, 2]) - centreline_radius
    assert np.max(np.abs(offset)) < 0.01, offset

    strain = state.strain[on_arc]
    estimate = DIAMETER / (2.0 * centreline_radius) + state.section_forces[on_arc, 0] / SECTION.EA
    print(
        f"\noverbend: mean strain {strain.mean():.6f}, estimate {estimate.mean():.6f} "
        f"({strain.mean() / estimate.mean() - 1:+.2%}), max {strain.max():.6f}, "
        f"centreline offset {offset.min() * 1e3:.1f}..{offset.max() * 1e3:.1f} mm"
    )
    assert strain.mean() == pytest.approx(estimate.mean(), rel=0.01)
    assert strain.max() >= estimate.mean()
    # The lay summary's overbend strain is at least this (it covers the whole overbend).
    summary = state.lay_summary()
    assert summary is not None
    assert summary["overbend_strain"] >= strain.max()


# --- 2. rollers push only ------------------------------------------------------------------------------


@pytest.mark.parametrize(("x", "seabed"), [(620.0, True), (660.0, True), (580.0, False)])
def test_rollers_push_only_with_the_contact_law(x: float, seabed: bool) -> None:
    """Roller reactions against the contact law recomputed from the geometry: d = distance from the roller's
    axis to the pipe's centreline, the Catmull–Rom spline through state.positions (in the vessel's frame from
    its pose η), overlap
    δ = r_r + d_o/2 − d, F = k·max(δ, 0) to 1e-6 of the largest reaction (Newton's tolerance; measured
    ≤ 4e-7 N). So unloaded rollers do not touch the pipe (δ ≤ 0), rollers past the lift-off roller carry
    nothing, the contact energy is Σ F²/(2k), and the pipe's force on the vessel is the tensioner's force
    plus the rollers' (the tensioner's from the top element's section force at its midpoint, turned by the
    midpoint's rotation, plus the weight of the half element above it; to 1e-5 of the force, measured
    ≤ 2e-6)."""
    state = _s_lay_state(x, seabed)
    stinger = _stinger()
    radius = 100.0
    eta = state.eta
    assert eta is not None
    # The stinger's roller tops lie on its arc, and the pipe is held at the tensioner on the vessel.
    assert np.allclose(np.linalg.norm(stinger.positions - _arc_centre(radius), axis=1), radius, atol=1e-9)
    np.testing.assert_allclose(state.positions[-1], eta[:3] + _rotation(eta) @ TENSIONER, atol=1e-8)

    forces = state.roller_reactions
    assert forces is not None and forces.shape == (len(stinger),)
    assert np.all(forces >= 0.0)
    distance, direction = _roller_contacts(state, stinger, radius)
    overlap = ROLLER_RADIUS + DIAMETER / 2.0 - distance
    np.testing.assert_allclose(
        forces, ROLLER_STIFFNESS * np.maximum(overlap, 0.0), rtol=0, atol=1e-6 * forces.max()
    )
    loaded = forces > 0.0
    assert np.count_nonzero(loaded) >= 3
    assert np.all(overlap[~loaded] <= 1e-9)
    print(
        f"\nx = {x}: reactions {np.round(forces / 1e3, 1)} kN; overlaps of loaded rollers "
        f"{np.round(overlap[loaded] * 1e3, 2)} mm; gaps of the others {np.round(-overlap[~loaded] * 1e3, 1)} mm"
    )

    summary = state.lay_summary()
    assert summary is not None
    liftoff = summary["liftoff_roller"]
    assert liftoff == int(np.flatnonzero(loaded)[-1])
    assert np.all(forces[liftoff + 1 :] == 0.0) and forces[liftoff] > 0.0
    assert state.energy()["rollers"] == pytest.approx(np.sum(forces**2) / (2.0 * ROLLER_STIFFNESS), rel=1e-9)

    # The vessel: the pipe's force on it (reaction at B) = the tensioner's + the rollers' (reacting the
    # rollers' push on the pipe). The tensioner holds the half element above the top element's midpoint.
    rollers_on_pipe = _rotation(eta) @ np.sum(forces[:, None] * direction, axis=0)
    element = 700.0 / 280
    weight = _s_lay(x, seabed=seabed).submerged_weight * element / 2.0
    upper_on_lower = _midway(state.rotations[-2], state.rotations[-1]) @ state.section_forces[-1, :3]
    tensioner_on_vessel = -upper_on_lower + np.array([0.0, 0.0, weight])
    on_vessel = state.reaction("B")[:3]
    balance = on_vessel - (tensioner_on_vessel - rollers_on_pipe)
    print(f"vessel balance residual {balance} N of {np.linalg.norm(on_vessel):.0f} N")
    assert np.linalg.norm(balance) < 1e-5 * np.linalg.norm(on_vessel)
    assert np.linalg.norm(rollers_on_pipe) > 0.1 * np.linalg.norm(state.reaction("B")[:3])


@pytest.mark.parametrize("x", [620.0, 640.0, 660.0])
def test_tip_clearance_is_the_gap_at_the_last_roller(x: float) -> None:
    """The lay summary's tip clearance is the gap between the pipe's surface and the stinger's last roller: the
    distance from the roller's axis to the pipe's centreline spline (recomputed here from the positions and
    the vessel pose), less the roller's radius and the pipe's half diameter, to 1e-9 m; in contact (≤ 0) it
    is minus the overlap F/k."""
    state = _s_lay_state(x, True)
    distances, _ = _roller_contacts(state, _stinger(), 100.0)
    expected = distances[-1] - ROLLER_RADIUS - DIAMETER / 2
    summary = state.lay_summary()
    assert summary is not None and state.roller_reactions is not None
    print(f"\nx = {x}: tip clearance {summary['tip_clearance']:.6f} m (geometry {expected:.6f} m)")
    assert summary["tip_clearance"] == pytest.approx(expected, abs=1e-9)
    if summary["tip_clearance"] <= 0.0:
        assert -summary["tip_clearance"] == pytest.approx(
            state.roller_reactions[-1] / ROLLER_STIFFNESS, abs=1e-9
        )
    else:
        assert state.roller_reactions[-1] == 0.0


# --- 3. J-lay ------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def j_lay() -> tuple[pl.Model, pl.State]:
    """J-lay from a tower leaning 0.2 rad, exit 20 m aft of CO and 30 m above the waterline, 150 m of water,
    700 m of pipe on a seabed, vessel at x = 620 m."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (700.0, 0.0, 0.0), 280, SECTION)
    model = pl.Model(rod, pl.Sea(DEPTH, seabed=pl.Seabed(stiffness=1e5)))
    model.pin("A")
    lay = pl.JLay(position=(-20.0, 0.0, -30.0), angle=0.2)
    model.attach_vessel("B", pl.Vessel.osv(), eta=[620.0, 0.0, -DEPTH, 0.0, 0.0, 0.0], lay=lay)
    return model, model.static()


def test_j_lay_holds_the_pipe_at_the_tower(j_lay: tuple[pl.Model, pl.State]) -> None:
    """The pipe's end is at CO + R(η)·position (1e-6 m), its tangent in the body frame is the tower's
    (sin α, 0, −cos α) (1e-9), and the departure angle is π/2 − α turned by the vessel's pitch θ (the tower is
    fixed to the hull; 1e-9 rad). No rollers: no reactions, no lift-off roller."""
    _, state = j_lay
    eta = state.eta
    assert eta is not None
    alpha = 0.2
    rotation = _rotation(eta)
    np.testing.assert_allclose(state.positions[-1], eta[:3] + rotation @ [-20.0, 0.0, -30.0], atol=1e-6)
    tangent = rotation.T @ state.rotations[-1][:, 0]
    np.testing.assert_allclose(tangent, [math.sin(alpha), 0.0, -math.cos(alpha)], atol=1e-9)
    summary = state.lay_summary()
    assert summary is not None
    print(
        f"\nJ-lay: departure {summary['departure_angle']:.6f} rad, pitch {eta[4]:.2e} rad, summary {summary}"
    )
    assert abs(eta[4]) > 1e-4  # the pipe pitches the vessel: the test sees the difference
    assert summary["departure_angle"] == pytest.approx(math.pi / 2 - alpha + eta[4], abs=1e-9)
    assert state.roller_reactions is None
    assert summary["liftoff_roller"] is None
    assert summary["liftoff_arc_length"] == pytest.approx(700.0)
    td = state.touchdown
    assert td is not None
    assert summary["touchdown_arc_length"] == pytest.approx(td.arc_length, rel=1e-12)
    assert summary["layback"] == pytest.approx(np.hypot(*(state.positions[-1] - td.position)[:2]), rel=1e-9)


def test_j_lay_tension_follows_the_elastica_first_integral(j_lay: tuple[pl.Model, pl.State]) -> None:
    """Between touchdown and tower the pipe carries only its submerged weight w, so the weighted elastica's
    first integral H = T + w z + M²/(2EI) is constant along it (T effective tension, z down). Checked at the
    element midpoints from the first one clear of the seabed to the top element: spread of H ≤ 1e-4·T_top (the
    stretch T/EA ≈ 3e-5 and shear are left out of the integral; measured 2e-5). The classic
    T_top − w(z_td − z_top) = T_td without the M² term is off by 0.4 % here but by 9 % with the vessel at
    610 m: the tower clamps the pipe, so M² at the top is not small; T + w z alone varies > 10× more."""
    model, state = j_lay
    w = model.submerged_weight
    ei = SECTION.EI[0]
    middles = 0.5 * (state.positions[1:] + state.positions[:-1])
    forces = state.section_forces
    tension = forces[:, 0]
    moment2 = forces[:, 4] ** 2 + forces[:, 5] ** 2
    first_integral = tension + w * middles[:, 2] + moment2 / (2.0 * ei)
    seabed = state.seabed_reaction
    assert seabed is not None
    clear = int(np.flatnonzero(np.linalg.norm(seabed, axis=1) > 0.0).max()) + 1  # first element clear
    top = tension[-1]
    summary = state.lay_summary()
    assert summary is not None
    assert summary["top_tension"] == pytest.approx(top, rel=1e-12)
    spread = np.ptp(first_integral[clear:]) / top
    td = state.touchdown
    assert td is not None
    element = 700.0 / 280
    assert clear * element == pytest.approx(td.arc_length, abs=2 * element)
    classic = (top - w * (td.position[2] - middles[-1, 2])) / tension[clear] - 1.0
    print(
        f"\nJ-lay: T_top {top:.0f} N, T_td {tension[clear]:.0f} N, spread of H {spread:.1e}, classic {classic:+.2%}"
    )
    assert spread < 1e-4
    # Without the M² term the relation is only approximate, and the M² term is what closes it.
    no_bending = tension + w * middles[:, 2]
    assert np.ptp(no_bending[clear:]) / top > 10 * spread


# --- 4. and 5. dynamics, results and files -------------------------------------------------------------


SURGE_FORCE = 2e5


@pytest.fixture(scope="module")
def s_lay_run() -> tuple[pl.State, pl.Results]:
    """S-lay at x = 660 m with drag, pushed forward by a constant 200 kN surge force from t = 0 (statics
    holds the vessel with thrust, which the dynamics keeps); 10 s at Δt = 0.2 s."""
    model = _s_lay(660.0, environment=[pl.Force([SURGE_FORCE, 0, 0, 0, 0, 0], start=0.0)])
    state = model.static()
    results = model.simulation(state, dt=0.2).run(10.0, progress=False)
    return state, results


def test_energy_ledger_closes_with_rollers(s_lay_run: tuple[pl.State, pl.Results]) -> None:
    """E(t) − E(0) = W(t) − D(t) at every record to 1e-9 of the energy scale (the energy–momentum step with the
    rollers' discrete gradient is exact up to Newton's tolerance; measured 3e-14). W is the trapezoidal
    integral of (τ + F_env)·ν over the records (the midpoint rule of the step; to 1e-9), D ≥ 0 grows (drag), the
    rollers' energy is Σ F²/(2k) at every record, and the push moves the vessel and changes the roller
    reactions by more than 5 % of the largest."""
    _, results = s_lay_run
    energy = results.energy
    total = energy["total"]
    parts = sum(v for k, v in energy.items() if k != "total")
    scale = np.max(np.abs(total))
    np.testing.assert_allclose(parts, total, rtol=0, atol=1e-12 * scale)
    ledger = total - total[0] - (results.supplied_work - results.dissipated)
    print(
        f"\nledger {np.max(np.abs(ledger)):.2e} J of {scale:.2e} J; W {results.supplied_work[-1]:.4e} J, "
        f"D {results.dissipated[-1]:.4e} J"
    )
    assert np.max(np.abs(ledger)) <= 1e-9 * scale
    assert np.all(np.diff(results.dissipated) >= 0.0) and results.dissipated[-1] > 0.0

    tau, nu = results.tau, results.nu
    assert tau is not None and nu is not None
    power = np.sum((tau + np.array([SURGE_FORCE, 0, 0, 0, 0, 0])) * nu, axis=1)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(results.time))])
    np.testing.assert_allclose(work, results.supplied_work, rtol=0, atol=1e-9 * np.max(np.abs(work)))

    reactions = results.roller_reactions
    assert reactions is not None
    assert np.all(reactions >= 0.0)
    np.testing.assert_allclose(
        np.sum(reactions**2, axis=1) / (2.0 * ROLLER_STIFFNESS), energy["rollers"], rtol=1e-9, atol=1e-6
    )
    change = np.max(np.ptp(reactions, axis=0))
    eta = results.eta
    assert eta is not None
    print(f"vessel surge {eta[-1, 0] - eta[0, 0]:.3f} m, largest roller change {change:.0f} N")
    assert eta[-1, 0] - eta[0, 0] > 0.5
    assert change > 0.05 * np.max(reactions)


def test_results_carry_rollers_and_lay_summary(
    s_lay_run: tuple[pl.State, pl.Results], tmp_path: Path
) -> None:
    """Results: roller reactions (T, k) and the lay summary's (T,) arrays start from the static state (1e-9
    relative; the first record is the state itself), and a netCDF round trip (pl.load) restores both exactly."""
    state, results = s_lay_run
    count = len(results)
    reactions = results.roller_reactions
    assert reactions is not None and state.roller_reactions is not None
    assert reactions.shape == (count, 12)
    np.testing.assert_allclose(reactions[0], state.roller_reactions, rtol=1e-9, atol=1e-6)
    summary = results.lay_summary()
    static = state.lay_summary()
    assert summary is not None and static is not None
    assert set(summary) == set(static)
    for key, values in summary.items():
        assert values.shape == (count,), key
        first = static[key]
        expected = math.nan if first is None else float(first)
        assert values[0] == pytest.approx(expected, rel=1e-9, nan_ok=True), key
    assert summary["top_tension"][0] == pytest.approx(state.tension[-1], rel=1e-9)
    assert np.ptp(summary["top_tension"]) > 0.0

    back = pl.load(results.to_netcdf(tmp_path / "r.nc"))
    assert back.roller_reactions is not None
    np.testing.assert_array_equal(back.roller_reactions, reactions)
    loaded = back.lay_summary()
    assert loaded is not None and set(loaded) == set(summary)
    for key, values in summary.items():
        np.testing.assert_array_equal(loaded[key], values, err_msg=key)


# --- 6. bad input --------------------------------------------------------------------------------------


def _attach_with_angle() -> None:
    model = pl.Model(pl.Rod.straight((0, 0, 0), (700, 0, 0), 28, SECTION), pl.Sea(DEPTH))
    model.pin("A")
    model.attach_vessel(
        "B",
        pl.Vessel.osv(),
        eta=[620.0, 0, -DEPTH, 0, 0, 0],
        angle=(0.0, 0.1, 0.0),
        lay=pl.SLay(tensioner=TENSIONER, stinger=_stinger()),
    )


@pytest.mark.parametrize(
    ("build", "argument"),
    [
        (lambda: pl.SLay(tensioner=TENSIONER, stinger=_stinger(), friction=-0.1), "friction"),
        (lambda: pl.Stinger(100.0, 80.0, 0), "rollers"),
        (lambda: pl.Stinger(10.0, 80.0, 5), "stinger length"),
        (lambda: pl.JLay((0.0, 0.0, 0.0), angle=2.0), "angle"),
        (lambda: pl.JLay((0.0, 0.0, 0.0), angle=-0.1), "angle"),
        (lambda: pl.Stinger.from_rollers([[0.0, 0.0, 0.0]], axes=[[0.0, 0.0, 1.0]]), "roller axes"),
        (lambda: pl.SLay(tensioner=TENSIONER, stinger=_stinger(), roller_stiffness=0.0), "roller_stiffness"),
        (_attach_with_angle, "angle"),
    ],
)
def test_bad_lay_input_names_the_argument(build: Callable[[], object], argument: str) -> None:
    """Bad lay input raises pl.InputError (a ValueError) whose message starts with the argument's name."""
    with pytest.raises(pl.InputError) as error:
        build()
    assert isinstance(error.value, ValueError)
    assert str(error.value).startswith(argument + ":"), str(error.value)


# --- 7. DNV check --------------------------------------------------------------------------------------


def test_dnv_check_on_an_s_lay() -> None:
    """pl.checks.dnv_st_f101 on S-lay states (X65, safety class low): finite (n,) arrays; the largest
    displacement-controlled utilisation sits at the largest strain (within 2 elements; the allowable strain
    only falls with depth); above the waterline p_e = 0, the allowable strain is one constant and the
    load-controlled utilisation is exactly (γ M/(α_c M_p) + (γ S/(α_c S_p))²)² with M = |(M2, M3)| and
    S = N1 from the state (1e-12); and the vessel at 620 m, with the larger moment over the stinger tip, has the
    larger load-controlled utilisation than at 660 m."""
    largest = {}
    for x in (620.0, 660.0):
        state = _s_lay_state(x, True)
        n = len(state.strain)
        check = pl.checks.dnv_st_f101(state, grade="X65", safety_class="low")
        load, displacement = check.load_controlled, check.displacement_controlled
        assert load.shape == (n,) and displacement.shape == (n,)
        assert np.all(np.isfinite(load)) and np.all(np.isfinite(displacement))
        assert abs(int(np.argmax(displacement)) - int(np.argmax(state.strain))) <= 2

        middles = 0.5 * (state.positions[1:] + state.positions[:-1])
        dry = middles[:, 2] < -DEPTH
        assert 20 < np.count_nonzero(dry) < 60
        assert np.all(check.external_pressure[dry] == 0.0)
        allowable = check.allowable_strain
        np.testing.assert_allclose(allowable[dry], allowable[dry][0], rtol=1e-12)
        wet = np.flatnonzero(~dry)
        by_depth = wet[np.argsort(middles[wet, 2])]
        assert np.all(np.diff(allowable[by_depth]) <= 1e-15)

        moment = np.hypot(state.section_forces[:, 4], state.section_forces[:, 5])
        np.testing.assert_allclose(check.moment, moment, rtol=1e-12)
        gamma = check.gamma_m * check.gamma_sc
        axial = (gamma * state.tension / (check.alpha_c * check.plastic_axial_force)) ** 2
        expected = (gamma * moment / (check.alpha_c * check.plastic_moment) + axial) ** 2
        np.testing.assert_allclose(load[dry], expected[dry], rtol=1e-12)
        largest[x] = (moment.max(), load.max())
        print(
            f"\nx = {x}: max strain {state.strain.max():.5f} at {np.argmax(state.strain)}, max DC "
            f"{displacement.max():.3f} at {np.argmax(displacement)}, max LC {load.max():.3f} at {np.argmax(load)}, "
            f"max moment {moment.max():.3e} N·m"
        )
    assert largest[620.0][0] > largest[660.0][0]
    assert largest[620.0][1] > largest[660.0][1]
