"""Seabed contact: energy through impacts, the ledger with friction and damping, sloping and gridded seabeds,
resuming with friction's state, and bad input.

Conventions (``shared/API.md``): SI units; frame e with e3 pointing down; the seabed is z = b(x, y); the normal
force per unit length is k·d·penetration of the centreline (MoorDyn's kBot convention).
"""

from __future__ import annotations

import math

import numpy as np
import pipelay as pl
import pytest

WATER = 1025.0


def flooded_pipe() -> pl.Section:
    """The 0.6 m × 15 mm steel pipe, flooded (submerged weight 1846 N/m)."""
    return pl.Section.pipe(0.6, 0.015, contents_density=WATER)


def dropped_rod(friction: float, damping: float) -> pl.Model:
    """A 20 m rod in vacuum (gravity only), 2–3 m above a flat seabed, free: it falls, hits and bounces."""
    section = pl.Section(EA=1e7, GA=1e7, GJ=1e4, EI=1e4, mass=50.0, inertia=(1, 0.5, 0.5), outer_diameter=0.3)
    rod = pl.Rod.straight((0, 0, -2.0), (20, 0, -3.0), 20, section)
    seabed = pl.Seabed(stiffness=2e5, damping=damping, friction=friction, mobilisation=0.01)
    return pl.Model(rod, sea=pl.Sea(100.0, density=0.0, seabed=seabed))


def test_frictionless_undamped_impacts_keep_the_energy() -> None:
    """A rod dropped on a frictionless, undamped seabed bounces: energy (kinetic + strain + gravity + contact)
    stays at its start to solver tolerance through every impact, and the contact did store energy."""
    model = dropped_rod(friction=0.0, damping=0.0)
    results = model.simulation(state=model.rest(), dt=0.002).run(3.0, progress=False)
    energy = results.energy["total"]
    assert np.max(results.energy["seabed"]) > 100.0  # the impacts compress the seabed
    assert np.max(np.abs(energy - energy[0])) < 1e-9 * energy[0]
    assert np.all(results.dissipated == 0.0) and np.all(results.supplied_work == 0.0)


@pytest.mark.parametrize(("friction", "damping"), [(0.5, 0.0), (0.5, 2e3), (0.0, 5e3)])
def test_friction_and_damping_close_the_ledger_every_step(friction: float, damping: float) -> None:
    """With friction and/or damping every step satisfies E_{n+1} − E_n = W − D with D ≥ 0, and the seabed
    takes energy out."""
    model = dropped_rod(friction, damping)
    results = model.simulation(state=model.rest(), dt=0.002).run(3.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.max(np.abs(balance)) < 1e-9 * energy[0]
    assert np.min(np.diff(results.dissipated)) >= 0.0
    assert results.dissipated[-1] > 1.0


def test_sloping_seabed_carries_the_normal_weight_at_the_analytic_penetration() -> None:
    """A pipe pinned at both ends along a frictionless plane seabed of slope θ sinks into it by
    w cos θ / (k d) (the contact force along the plane's normal), and the plane given as a grid is the same
    seabed."""
    section = flooded_pipe()
    slope = 0.1  # dz/dx: the seabed deepens along e1 (e3 down)
    k = 2e5
    start, end = np.array([0.0, 0.0, 0.0]), np.array([400.0, 0.0, 400.0 * slope])
    x, y = np.array([-50.0, 100.0, 300.0, 500.0]), np.array([-20.0, 20.0])
    grid = pl.Bathymetry.grid(x, y, np.outer(slope * x, np.ones_like(y)))
    states = []
    for bathymetry in (pl.Bathymetry.plane(0.0, (slope, 0.0)), grid):
        rod = pl.Rod.straight(start, end, 40, section)
        sea = pl.Sea(500.0, density=WATER, seabed=pl.Seabed(stiffness=k, bathymetry=bathymetry))
        model = pl.Model(rod, sea=sea)
        model.pin("A")
        model.pin("B")
        states.append(model.static())
    plane, gridded = states
    w = pl.Model(pl.Rod.straight(start, end, 1, section), sea=pl.Sea(500.0)).submerged_weight
    cos = 1.0 / math.sqrt(1.0 + slope**2)
    expected = w * cos / (k * section.outer_diameter)
    # Away from the pinned ends, whose bending boundary layer (4EI/kd)^¼ ≈ 9.5 m has decayed by e^-15 there.
    p = plane.positions[15:26]
    penetration = (p[:, 2] - slope * p[:, 0]) * cos
    assert np.max(np.abs(penetration / expected - 1.0)) < 1e-5
    normal = np.array([slope, 0.0, -1.0]) * cos
    force = plane.seabed_reaction[15:26]
    assert np.max(np.linalg.norm(np.cross(force, normal), axis=1)) < 1e-6 * np.max(
        np.linalg.norm(force, axis=1)
    )
    np.testing.assert_allclose(gridded.positions, plane.positions, rtol=0, atol=1e-9)
    assert plane.laid_length == pytest.approx(rod.length, rel=1e-12)
    assert plane.touchdown is not None and plane.touchdown.arc_length == pytest.approx(rod.length, rel=1e-12)


def test_wavy_grid_balances_forces_and_finds_the_touchdown() -> None:
    """A pipe hanging from a top point down onto a wavy gridded seabed: the forces on it balance (weight,
    seabed, support reactions) and the touchdown lies on the seabed surface."""
    section = flooded_pipe()
    x = np.linspace(-100.0, 1700.0, 37)
    y = np.array([-200.0, 0.0, 200.0])
    z = np.outer(3.0 * np.sin(x / 80.0) + 0.004 * x, np.ones_like(y))  # undulating along x, level across
    bathymetry = pl.Bathymetry.grid(x, y, z)
    a = np.array([0.0, 0.0, bathymetry.elevation(0.0, 0.0)])
    rod = pl.Rod.straight(a, a + [1600.0, 0.0, 0.0], 320, section)
    model = pl.Model(
        rod, sea=pl.Sea(800.0, density=WATER, seabed=pl.Seabed(stiffness=1e5, bathymetry=bathymetry))
    )
    model.pin("A")
    model.pin("B", position=(1200.0, 0.0, -780.0))
    state = model.static()
    w = model.submerged_weight
    total = (
        state.seabed_reaction.sum(axis=0)
        + np.array([0.0, 0.0, w * rod.length])
        - state.reaction("A")[:3]
        - state.reaction("B")[:3]
    )
    assert np.linalg.norm(total) < 1e-6 * w * rod.length
    touchdown = state.touchdown
    assert touchdown is not None and 300.0 < touchdown.arc_length < 600.0
    elevation = bathymetry.elevation(touchdown.position[0], touchdown.position[1])
    assert abs(touchdown.position[2] - elevation) < 1e-3


def test_resume_with_friction_is_bit_identical(tmp_path: object) -> None:
    """Friction's elastic slips are part of the state: a run checkpointed half-way and resumed gives the same
    numbers, bit for bit, as the uninterrupted run."""
    from pathlib import Path

    model = dropped_rod(friction=0.6, damping=1e3)
    state = model.rest()
    whole = model.simulation(state=state, dt=0.005).run(1.5, progress=False)
    first = model.simulation(state=state, dt=0.005)
    first.run(0.75, progress=False)
    path = Path(str(tmp_path)) / "friction.npz"
    first.checkpoint(path)
    rest = pl.resume(model, path).run(1.5, progress=False)
    np.testing.assert_array_equal(rest.positions[-1], whole.positions[-1])
    np.testing.assert_array_equal(rest.energy["seabed"][-1], whole.energy["seabed"][-1])
    np.testing.assert_array_equal(rest.reaction("A")[-1], whole.reaction("A")[-1])


@pytest.mark.parametrize(
    ("build", "argument"),
    [
        (lambda: pl.Seabed(stiffness=-1.0), "stiffness"),
        (lambda: pl.Seabed(stiffness=float("nan")), "stiffness"),
        (lambda: pl.Seabed(damping=-1.0), "damping"),
        (lambda: pl.Seabed(friction=-0.1), "friction"),
        (lambda: pl.Seabed(friction=(0.5, -1.0)), "friction"),
        (lambda: pl.Seabed(mobilisation=0.0), "mobilisation"),
        (lambda: pl.Seabed(mobilisation=-0.01), "mobilisation"),
        (lambda: pl.Bathymetry.grid([0.0, 1.0, 1.0], [0.0, 1.0], np.zeros((3, 2))), "x"),
        (lambda: pl.Bathymetry.grid([0.0, 1.0], [2.0, 1.0], np.zeros((2, 2))), "y"),
        (lambda: pl.Bathymetry.grid([0.0, 1.0], [0.0, 1.0], np.zeros((3, 2))), "z"),
        (lambda: pl.Bathymetry.grid([0.0, 1.0], [0.0, 1.0], [[0.0, float("nan")], [0.0, 0.0]]), "z"),
        (lambda: pl.Bathymetry.plane(0.0, (float("inf"), 0.0)), "gradient"),
        (lambda: pl.Sea(100.0, seabed=pl.Seabed(bathymetry=pl.Bathymetry.flat(-150.0))), "bathymetry"),
    ],
)
def test_bad_seabed_input_names_the_argument(build: object, argument: str) -> None:
    """Negative stiffness or friction, mobilisation ≤ 0, a grid that is not increasing, of the wrong shape or
    with NaN, a seabed above the surface: InputError naming the argument."""
    with pytest.raises(pl.InputError, match=f"^{argument}"):
        build()  # type: ignore[operator]


def test_plane_rising_above_the_surface_along_the_pipe_is_refused() -> None:
    """A sloping plane that is below the surface at A but above it under the pipe's far end."""
    seabed = pl.Seabed(bathymetry=pl.Bathymetry.plane(0.0, (-0.5, 0.0)))
    rod = pl.Rod.straight((0, 0, 0), (500, 0, 0), 10, flooded_pipe())
    with pytest.raises(pl.InputError, match="^bathymetry"):
        pl.Model(rod, sea=pl.Sea(100.0, seabed=seabed))


def test_heavy_seabed_damping_on_a_driven_line_converges() -> None:
    """MoorDyn's default seabed damping (cBot = 3e5 Pa·s/m, about 3.8 times critical for this wire rope) on the
    driven line of the MoorDyn comparison at n = 50, Δt = 0.05 s: every step converges (the damping grows
    smoothly with the penetration instead of switching on), and the seabed takes energy out."""
    import dataclasses

    from moordyn_seabed_case import SEABED_CASE, pipelay_model

    model = pipelay_model(50, dataclasses.replace(SEABED_CASE, cbot=3e5))
    results = model.simulation(dt=0.05).run(25.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.max(np.abs(balance)) < 1e-8 * np.max(np.abs(results.supplied_work))
    assert np.min(np.diff(results.dissipated)) >= 0.0
