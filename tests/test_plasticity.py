"""The pipe steel beyond yield: materials (elastic–perfectly plastic, Ramberg–Osgood, tables, grades) and a
pipe wall's moment–curvature integrated over its fibres, against the thin tube's closed forms, an independent
numerical integration of a Ramberg–Osgood wall, and Masing's rule on unloading.

The overlay model's own checks (its backbone, Masing's rule per fibre, a closed cycle's dissipation) are in the
engine (`rod::material`, `rod::fibre_section`)."""

from __future__ import annotations

import numpy as np
import pipelay as pl
import pytest

E, FY = 200e9, 400e6


def _thin_tube(material: pl.Material) -> tuple[pl.Section, float, float]:
    """A thin tube (D = 0.4 m, t = 2 mm) of `material`, its yield curvature and moment at the wall's middle as
    thin-tube theory takes them: κ_y = f_y/(E a), M_y = EI κ_y, a = (D − t)/2."""
    d, t = 0.4, 0.002
    section = pl.Section.pipe(d, t, material=material)
    inertia = np.pi / 64 * (d**4 - (d - 2 * t) ** 4)
    kappa_y = FY / (E * 0.5 * (d - t))
    return section, kappa_y, E * inertia * kappa_y


def test_a_thin_elastic_perfectly_plastic_tube_bends_as_the_closed_form() -> None:
    """M/M_y = 1.2647 at 5 κ_y (within 0.1 %); M tends to M_p = f_y (D − t)² t; unloading from 5 κ_y leaves
    3.7353 κ_y (within 0.1 %)."""
    section, kappa_y, moment_y = _thin_tube(pl.Material.elastic_perfectly_plastic(E, FY))
    up = np.linspace(0.0, 5.0 * kappa_y, 101)
    down = np.linspace(5.0 * kappa_y, 2.0 * kappa_y, 301)[1:]
    moments = section.moment_curvature(np.concatenate([up, down]))
    ratio = moments[100] / moment_y
    assert ratio == pytest.approx(1.2647, rel=1e-3)
    tail = moments[100:]
    curvatures = np.concatenate([up, down])[100:]
    residual = np.interp(0.0, tail[::-1], curvatures[::-1]) / kappa_y
    print(f"M/M_y at 5 κ_y {ratio:.5f}; residual curvature {residual:.5f} κ_y")
    assert residual == pytest.approx(3.7353, rel=1e-3)
    plastic = FY * (0.4 - 0.002) ** 2 * 0.002
    assert section.moment_curvature([0.0, 200.0 * kappa_y])[1] == pytest.approx(plastic, rel=1e-3)


def _ramberg_osgood_stress(strain: np.ndarray, e: float, sy: float, n: float) -> np.ndarray:
    """σ(ε) of ε = σ/E + (0.005 − σ_y/E)(σ/σ_y)ⁿ, by Newton's method from the elastic stress (vectorised)."""
    sign, target = np.sign(strain), np.abs(strain)
    stress = np.minimum(e * target, 2 * sy)
    alpha = 0.005 - sy / e
    for _ in range(200):
        f = stress / e + alpha * (stress / sy) ** n - target
        df = 1 / e + alpha * n / sy * (stress / sy) ** (n - 1)
        stress = np.clip(stress - f / df, 0.0, None)
    return sign * stress


def test_a_ramberg_osgood_wall_matches_an_independent_integration() -> None:
    """The moment of a 16-inch X65 wall (Ramberg–Osgood, σ_y 450 MPa, n 14) under monotonic bending up to 1 %
    outer-fibre strain, with and without 0.1 % axial strain, against the curve integrated on a fine grid
    (4000 angles, 8 Gauss radii) with the stress inverted from the curve itself: within 2e-3 of the moment."""
    d, t, e, sy, n = 0.4064, 0.0206, 207e9, 450e6, 14.0
    section = pl.Section.pipe(d, t, material=pl.Material.ramberg_osgood(e, sy, n))
    theta = (np.arange(4000) + 0.5) * 2 * np.pi / 4000
    nodes, weights = np.polynomial.legendre.leggauss(8)
    radii = 0.5 * (d - t) + 0.5 * t * nodes
    curvatures = np.linspace(0.0, 0.01 / (0.5 * d), 41)
    for axial in (0.0, 1e-3):
        computed = section.moment_curvature(curvatures, axial_strain=axial)
        worst = 0.0
        for kappa, moment in zip(curvatures[1:], computed[1:], strict=True):
            z = radii[:, None] * np.sin(theta)[None, :]
            stress = _ramberg_osgood_stress(axial + kappa * z, e, sy, n)
            area = (0.5 * t * weights * radii)[:, None] * (2 * np.pi / 4000)
            reference = np.sum(stress * z * area)
            worst = max(worst, abs(moment - reference) / abs(reference))
        print(f"axial strain {axial}: worst relative difference {worst:.2e}")
        assert worst < 2e-3


def test_unloading_follows_masings_rule_and_cycles_close() -> None:
    """From a reversal (κ_r, M_r) the moment is M_r − 2 M(Δκ/2) (the section's backbone doubled), and a
    second cycle between the same curvatures retraces the first."""
    section = pl.Section.pipe(0.6, 0.03, material=pl.Material.ramberg_osgood(207e9, 450e6, 14.0))
    kappa_r = 0.03
    backbone = section.moment_curvature(np.linspace(0.0, kappa_r, 301))
    deltas = np.linspace(0.0, 2 * kappa_r, 301)[1:]
    path = np.concatenate([np.linspace(0.0, kappa_r, 301), kappa_r - deltas])
    moments = section.moment_curvature(path)
    half = section.moment_curvature(0.5 * deltas)
    # `half` loads monotonically through Δκ/2, so its values are the backbone there.
    masing = backbone[-1] - 2 * half
    assert np.allclose(moments[301:], masing, rtol=0, atol=1e-9 * abs(backbone[-1]))
    cycle = np.concatenate([path, -kappa_r + deltas])
    twice = section.moment_curvature(np.concatenate([cycle, cycle[301:]]))
    assert np.allclose(twice[len(cycle) :], twice[301 : len(cycle)], rtol=0, atol=1e-9 * abs(backbone[-1]))


def test_bad_materials_are_refused() -> None:
    """A yield stress past E·0.5 %, a table that turns up, an unknown grade and a section without a wall."""
    with pytest.raises(pl.InputError, match="yield_stress"):
        pl.Material.ramberg_osgood(207e9, 2e9, 14.0)
    with pytest.raises(pl.InputError, match="stress"):
        pl.Material.table([1e-3, 2e-3], [200e6, 500e6])
    with pytest.raises(pl.InputError, match="grade"):
        pl.Material.grade("X99")
    with pytest.raises(pl.InputError, match="section"):
        pl.Section(EA=1e9, GA=1e8, GJ=1e6, EI=1e6, mass=10.0).moment_curvature([0.0, 0.01])
    x65 = pl.Material.grade("X65")
    assert x65.kind == "ramberg_osgood"
    strains = np.array([0.0, 0.005, 0.01, 0.0])
    assert x65.stress_strain(strains)[1] == pytest.approx(450e6, rel=2e-3)
    elastic = pl.Section.pipe(0.6, 0.03)
    inertia = np.pi / 64 * (0.6**4 - 0.54**4)
    assert elastic.moment_curvature([0.001])[0] == pytest.approx(207e9 * inertia * 0.001, rel=1e-12)


def test_a_cantilever_whose_wall_yields_reports_its_plastic_strain_and_residual_curvature() -> None:
    """A 10 m cantilever of the thin tube under an end moment of 1.2 M_y: statics bend it to the closed form's
    curvature (within 0.2 %); the state reports the largest plastic strain and the residual curvature κ − M/EI."""
    material = pl.Material.elastic_perfectly_plastic(E, FY)
    section, kappa_y, moment_y = _thin_tube(material)
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (10.0, 0.0, 0.0), 20, section)
    model = pl.Model(rod, gravity=0.0)
    model.clamp("A")
    model.point_load("B", moment=(0.0, 1.2 * moment_y, 0.0))
    state = model.static()
    moment = np.linalg.norm(state.section_forces[10, 3:])  # 1.2 M_y throughout
    assert moment == pytest.approx(1.2 * moment_y, rel=1e-6)
    curvature = state.residual_curvature[10] + 1.2 * kappa_y
    beta_ratio = _closed_form_curvature(1.2) * kappa_y
    print(f"curvature {curvature / kappa_y:.5f} κ_y, closed form {beta_ratio / kappa_y:.5f} κ_y")
    assert curvature == pytest.approx(beta_ratio, rel=2e-3)
    assert np.all(state.plastic_strain > 0.0)


def _closed_form_curvature(ratio: float) -> float:
    """φ = κ/κ_y of the thin tube at M/M_y = `ratio` (> 1), by bisection on (4/π)[φ(β/2 − sin 2β/4) + cos β]."""
    low, high = 1.0, 50.0
    for _ in range(200):
        phi = 0.5 * (low + high)
        beta = np.arcsin(1.0 / phi)
        value = 4.0 / np.pi * (phi * (0.5 * beta - 0.25 * np.sin(2 * beta)) + np.cos(beta))
        low, high = (phi, high) if value < ratio else (low, phi)
    return 0.5 * (low + high)


def _cycled(tmp_path: object = None) -> tuple[pl.Simulation, pl.Model]:
    """The thin tube's cantilever (no drag, no added mass, no weight) under an end moment 1.2 M_y sin(2πt/20 s)."""
    section = pl.Section.pipe(
        0.4, 0.002, material=pl.Material.elastic_perfectly_plastic(E, FY), drag=(0, 0), added_mass=(0, 0)
    )
    _, _, moment_y = _thin_tube(pl.Material.elastic_perfectly_plastic(E, FY))
    model = pl.Model(pl.Rod.straight((0.0, 0.0, 0.0), (10.0, 0.0, 0.0), 20, section), gravity=0.0)
    model.clamp("A")
    model.point_load("B", moment=(0.0, 1.2 * moment_y, 0.0), scale=lambda t: np.sin(2 * np.pi * t / 20.0))
    return model.simulation(model.rest(), dt=0.05), model


def test_a_run_bending_the_wall_back_and_forth_books_its_dissipation_exactly(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Cycled between ±1.2 M_y for two periods, slowly (its first mode is near 3 Hz): the energy ledger closes to
    1e-9 of the work supplied with the plastic dissipation booked; over the second cycle the area of the end's
    moment–rotation loop equals the dissipation within 1 %; a run resumed from a checkpoint at 25 s ends bit for
    bit where the whole run does."""
    simulation, model = _cycled()
    results = simulation.run(40.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - (results.supplied_work - results.dissipated)
    print(f"worst balance {np.abs(balance).max():.3e} J of {results.supplied_work[-1]:.3e} J supplied")
    assert np.abs(balance).max() < 1e-9 * results.supplied_work[-1]
    time = results.time
    second = time >= 20.0
    _, _, moment_y = _thin_tube(pl.Material.elastic_perfectly_plastic(E, FY))
    moment = 1.2 * moment_y * np.sin(2 * np.pi * time / 20.0)
    tip = np.array([_rotation_about_e2(r) for r in results.rotations[:, -1]])
    area = np.trapezoid(moment[second], tip[second])
    cycle = results.dissipated[-1] - np.interp(20.0, time, results.dissipated)
    print(f"loop area {area:.6e} J, dissipated over the cycle {cycle:.6e} J")
    assert cycle > 0.0 and area == pytest.approx(cycle, rel=1e-2)
    # All of it plastic: no drag, no damping; the energy dict carries it as plastic_dissipation.
    assert np.array_equal(results.energy["plastic_dissipation"], results.dissipated)
    _cycled()[0].run(40.0, progress=False, output=tmp_path / "cycled.nc")
    assert np.allclose(
        pl.load(tmp_path / "cycled.nc").energy["plastic_dissipation"], results.dissipated, rtol=0, atol=1e-9
    )
    part, _ = _cycled()
    part.run(25.0, progress=False)
    path = part.checkpoint(tmp_path / "part.npz")
    resumed = pl.resume(model, path)
    resumed.run(40.0, progress=False)
    assert np.array_equal(resumed.state.positions, simulation.state.positions)
    assert resumed.dissipated == simulation.dissipated


def _rotation_about_e2(rotation: np.ndarray) -> float:
    """The angle (rad) of a rotation matrix about e2 (the cantilever bends in the e1–e3 plane)."""
    return float(np.arctan2(rotation[0, 2], rotation[0, 0]))


def test_an_s_lay_whose_overbend_yields_reports_computed_strains_and_the_laid_pipes_residual_curvature() -> (
    None
):
    """`examples/s_lay_yielding.toml` (the S-lay example's pipe of X65 beyond yield, at a lower tension): the
    overbend strain is the one its shape gives, ε₀ + (D/2)|κ|, past the elastic estimate N/EA + (D/2)|M|/EI (the
    wall yields: its moment lags its curvature); the DNV-ST-F101 displacement-controlled check takes the state's
    strain; the laid pipe keeps a residual curvature from the overbend (from the history marched from the
    tensioner), the elastic pipe none; `pipelay static` prints it; and a run starts from it."""
    import subprocess
    import sys
    import tomllib
    from pathlib import Path

    from pipelay.scenario import load_scenario, parse_scenario

    example = Path(__file__).parent.parent / "examples" / "s_lay_yielding.toml"
    scenario = load_scenario(example)
    state = scenario.model.static()
    lay = state.lay_summary()
    forces = state.section_forces
    e = int(np.argmax(state.strain))
    ea = 207e9 * np.pi / 4 * (0.6**2 - 0.54**2)
    ei = 207e9 * np.pi / 64 * (0.6**4 - 0.54**4)
    elastic_estimate = forces[e, 0] / ea + 0.3 * np.hypot(forces[e, 4], forces[e, 5]) / ei
    print(f"overbend strain {lay['overbend_strain']:.5f}, elastic estimate {elastic_estimate:.5f}")
    assert lay["overbend_strain"] == pytest.approx(state.strain[e], rel=1e-12)
    assert lay["overbend_strain"] > 1.05 * elastic_estimate > 0.0
    assert state.plastic_strain.max() > 1e-4
    assert lay["residual_curvature"] > 1e-4
    # The displacement-controlled check's demand is the computed strain: its worst element is the strain's.
    checks = pl.checks.dnv_st_f101(state)
    assert int(np.argmax(checks.displacement_controlled)) == e
    elastic = tomllib.loads(example.read_text())
    del elastic["pipe"]["material"]
    assert np.isnan(parse_scenario(elastic, "elastic").model.static().lay_summary()["residual_curvature"])
    out = subprocess.run(
        [sys.executable, "-m", "pipelay", "static", str(example)], capture_output=True, text=True, check=True
    ).stdout
    assert f"lay: residual curvature {lay['residual_curvature']:12.4e} 1/m" in out
    results = scenario.model.simulation(state, dt=0.2).run(2.0, progress=False)
    energy = results.energy["total"]
    balance = energy[-1] - energy[0] - (results.supplied_work[-1] - results.dissipated[-1])
    assert abs(balance) < 1e-8 * abs(energy[0])
    assert np.all(np.isfinite(results.lay_summary()["residual_curvature"]))


def _thin_tube_backbone(kappa: float, kappa_y: float, moment_y: float) -> float:
    """The thin elastic–perfectly plastic tube's moment from rest at curvature `kappa` (odd in it)."""
    phi = abs(kappa) / kappa_y
    if phi <= 1.0:
        return moment_y * kappa / kappa_y
    beta = np.arcsin(1.0 / phi)
    ratio = 4.0 / np.pi * (phi * (0.5 * beta - 0.25 * np.sin(2 * beta)) + np.cos(beta))
    return float(np.sign(kappa) * moment_y * ratio)


def _reeled_closed_form(
    kappa_r: float, kappa_a: float, kappa_s: float, kappa_y: float, moment_y: float
) -> float:
    """The thin tube's residual curvature after reel (κ_r), unspooling (0), aligner (κ_a < κ_r) and
    straightener (κ_s), by Masing's rule with memory: each branch M = M_p ± 2 M(|κ − κ_p|/2) from its reversal
    point, a branch that closes a loop continuing the one the loop opened from; then released elastically."""

    def backbone(k: float) -> float:
        return _thin_tube_backbone(k, kappa_y, moment_y)

    m_r = backbone(kappa_r)
    m_0 = m_r - 2 * backbone(0.5 * kappa_r)
    m_a = m_0 + 2 * backbone(0.5 * kappa_a)
    if kappa_s >= 0.0:
        m_s = m_a - 2 * backbone(0.5 * (kappa_a - kappa_s))
    else:  # past the loop's start at κ = 0: on the branch down from the reel
        m_s = m_r - 2 * backbone(0.5 * (kappa_r - kappa_s))
    # Released: up from (κ_s, M_s) to zero moment, elastic while |M_s| < 2 M_y.
    assert abs(m_s) < 2 * moment_y
    return kappa_s - m_s / (moment_y / kappa_y)


def test_reeling_leaves_the_closed_form_residual_curvature_and_the_straightener_removes_it() -> None:
    """The thin tube reeled on an 8 m reel and bent over a 9 m aligner (of its centreline): its residual
    curvature, with and without a straightener, against Masing's rule with memory on the closed-form moment
    (within 1 %); `pl.design_straightener` against the closed form's setting (within 1 %), leaving the pipe
    straight; the accumulated plastic strain of its outermost fibre against the elastic–perfectly plastic
    fibre's (each stage's strain change less the yield strain from rest, twice it from a reversal)."""
    material = pl.Material.elastic_perfectly_plastic(E, FY)
    section, kappa_y, moment_y = _thin_tube(material)
    reel, aligner = 8.0, 9.0
    history = pl.ReelLay(reel, aligner).history(section)
    expected = _reeled_closed_form(1 / reel, 1 / aligner, 0.0, kappa_y, moment_y)
    print(f"residual {history['residual_curvature']:.6e} 1/m, closed form {expected:.6e} 1/m")
    assert history["residual_curvature"] == pytest.approx(expected, rel=1e-2)
    straightener = pl.design_straightener(section, reel, aligner)
    low, high = -2 / aligner, 1 / aligner
    for _ in range(100):
        middle = 0.5 * (low + high)
        low, high = (
            (middle, high)
            if _reeled_closed_form(1 / reel, 1 / aligner, middle, kappa_y, moment_y) < 0
            else (low, middle)
        )
    print(f"straightener {straightener.curvature:.6e} 1/m, closed form {0.5 * (low + high):.6e} 1/m")
    assert straightener.curvature == pytest.approx(0.5 * (low + high), rel=1e-2)
    straight = pl.ReelLay(reel, aligner, straightener).history(section)
    assert abs(straight["residual_curvature"]) < 1e-6 * kappa_y
    assert list(np.unique(straight["stage"])) == [0, 1, 2, 3, 4]
    # The outermost fibre (the quadrature's: the outer Gauss radius, the angle nearest π/2).
    t = 0.002
    radius = 0.5 * (0.4 - t) + 0.5 * t / np.sqrt(3)
    z = radius * np.sin(15.5 * 2 * np.pi / 64)
    path = z * np.array([0.0, 1 / reel, 0.0, 1 / aligner, straightener.curvature])
    yield_strain = FY / E
    changes = np.abs(np.diff(path))
    accumulated = changes[0] - yield_strain + np.sum(np.maximum(changes[1:] - 2 * yield_strain, 0.0))
    print(
        f"accumulated plastic strain {straight['accumulated_plastic_strain']:.6e}, the fibre's {accumulated:.6e}"
    )
    assert straight["accumulated_plastic_strain"] == pytest.approx(accumulated, rel=1e-9)


def test_the_reel_lay_example_prints_the_straightener_that_leaves_the_pipe_straight(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """`examples/reel_lay.py` runs, prints the designed straightener's curvature (the one
    `pl.design_straightener` gives) and a straightened residual curvature below 1e-9 1/m, and writes its figure."""
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).parent.parent / "examples" / "reel_lay.py"
    out = subprocess.run(
        [sys.executable, str(script), "--out", str(tmp_path)], capture_output=True, text=True, check=True
    ).stdout
    section = pl.Section.pipe(0.4064, 0.0206, grade="X65", material=pl.Material.grade("X65"))
    straightener = pl.design_straightener(section, 8.0, 9.0)
    assert f"straightener curvature              {straightener.curvature:12.4e} 1/m" in out
    line = next(row for row in out.splitlines() if row.startswith("residual curvature, straightened"))
    assert abs(float(line.split()[3])) < 1e-9
    assert (tmp_path / "reel_lay.png").stat().st_size > 10_000


def _reel_lay_scenario(straightener: float | str) -> pl.scenario.Scenario:
    """`examples/reel_lay.toml` with the straightener set to `straightener` (1/m, or "design")."""
    import tomllib
    from pathlib import Path

    from pipelay.scenario import parse_scenario

    example = Path(__file__).parent.parent / "examples" / "reel_lay.toml"
    data = tomllib.loads(example.read_text())
    data["vessel"]["lay"]["straightener"] = straightener
    return parse_scenario(data, "reel_lay")


def _reel_lay_section() -> pl.Section:
    """The pipe of `examples/reel_lay.toml`."""
    return pl.Section.pipe(0.4064, 0.0206, contents_density=0.0, material=pl.Material.grade("X65"))


def test_a_reel_lay_vessel_lays_the_pipe_in_the_state_its_reeling_left(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """`examples/reel_lay.toml` (16-inch X65 from an 8 m reel over a 9 m aligner, hung from a ramp 0.2 rad
    from the vertical in 500 m of water): with the straightener at 99 % of its design the laid pipe keeps the
    residual curvature the reeling leaves (`ReelLay.history`), within 2 % (the sagbend bends it back within
    its elastic range); with the designed one it lies within 5 % of that of straight (what is left, 3.6e-6 1/m,
    the sagbend's 0.125 % strain yields into the reeled wall's residual stresses; 6.9e-7 1/m in a pipe never
    reeled); `pipelay static` prints the reeling; and a run from the state books its energy exactly, its
    summary the laid pipe's residual curvature."""
    import subprocess
    import sys
    from pathlib import Path

    designed = _reel_lay_scenario("design")
    ramp = designed.model.reel_lay
    assert ramp is not None
    assert ramp.ramp_angle == pytest.approx(0.2, abs=1e-12)
    assert ramp.position == pytest.approx((-30.0, 0.0, -5.0))
    section = designed.model.rod.section
    setting = pl.design_straightener(section, 8.0, 9.0).curvature
    assert ramp.straightener.curvature == setting
    short = _reel_lay_scenario(0.99 * setting)
    entering = short.model.reel_lay.history(section)["residual_curvature"]  # type: ignore[union-attr]
    kept = short.model.static().lay_summary()["residual_curvature"]
    straight = designed.model.static().lay_summary()["residual_curvature"]
    print(f"entering {entering:.5e} 1/m, laid {kept:.5e} 1/m; straightened {straight:.3e} 1/m")
    assert abs(entering) > 1e-4
    assert kept == pytest.approx(abs(entering), rel=2e-2)
    assert straight < 5e-2 * abs(entering)
    example = Path(__file__).parent.parent / "examples" / "reel_lay.toml"
    out = subprocess.run(
        [sys.executable, "-m", "pipelay", "static", str(example)], capture_output=True, text=True, check=True
    ).stdout
    assert f"reel-lay: straightener   {setting:12.4e} 1/m" in out
    state = designed.model.static()
    results = designed.model.simulation(state, dt=0.2).run(2.0, progress=False)
    energy = results.energy["total"]
    balance = energy[-1] - energy[0] - (results.supplied_work[-1] - results.dissipated[-1])
    print(f"run: balance {balance:.3e} J of {energy[0]:.3e} J")
    assert abs(balance) < 1e-8 * abs(energy[0])
    # `pipelay run`'s summary reports the laid pipe's residual curvature over the run.
    from pipelay.cli import _run_summary

    residual = results.lay_summary()["residual_curvature"]
    summary = _run_summary(results.to_netcdf(tmp_path / "reel_lay.nc"))
    assert f"lay: residual curvature {np.min(residual):10.4g} … {np.max(residual):.4g} 1/m" in summary


def test_a_reel_lay_without_its_ramp_or_with_a_bad_one_is_refused() -> None:
    """A `pl.ReelLay` without `position` cannot hold the pipe; a ramp angle outside [0, π/2] is refused; the
    scenario names its key."""
    from pipelay.scenario import parse_scenario

    section = pl.Section.pipe(0.4064, 0.0206, material=pl.Material.grade("X65"))
    model = pl.Model(pl.Rod.straight((0, 0, 0), (600, 0, 0), 60, section), sea=pl.Sea(depth=300.0))
    with pytest.raises(pl.InputError, match="position"):
        model.attach_vessel("B", pl.Vessel.osv(), eta=(420, 0, -300, 0, 0, 0), lay=pl.ReelLay(8.0, 9.0))
    with pytest.raises(pl.InputError, match="ramp_angle"):
        pl.ReelLay(8.0, 9.0, position=(0, 0, 0), ramp_angle=2.0)
    data = _reel_lay_scenario("design").source
    data["vessel"]["lay"]["ramp_angle"] = -0.1
    with pytest.raises(pl.InputError, match=r"vessel\.lay\.ramp_angle"):
        parse_scenario(data, "bad ramp")
    data["vessel"]["lay"]["ramp_angle"] = 0.2
    data["vessel"]["lay"]["straightener"] = "none"
    with pytest.raises(pl.InputError, match=r"vessel\.lay\.straightener"):
        parse_scenario(data, "bad straightener")


def test_a_reel_lay_pays_out_reeled_pipe_and_restarts_from_statics_with_its_history() -> None:
    """`examples/reel_lay.toml` with the straightener at 99 % of its design, in stages: 40 s of pay-out at
    0.5 m/s (two new elements of reeled pipe at the ramp), 20 s to stop it, then a stage that restarts from
    statics. The new elements take the reeled wall's state: the line keeps the reeling's residual curvature
    within 5 % (every element but the two at the ramp's exit, where the lowered pipe bends 4× more than in
    the sagbend and the reeled wall yields again; pipe entering unyielded would keep none); the statics start from the run's plastic state; and the
    ledger stays exact through the splits (the growing element's stored energy the fibres' free energy) and
    the restart (its energy change booked as supplied work)."""
    scenario = _reel_lay_scenario(0.99 * pl.design_straightener(_reel_lay_section(), 8.0, 9.0).curvature)
    model = scenario.model
    entering = abs(model.reel_lay.history(model.rod.section)["residual_curvature"])  # type: ignore[union-attr]
    state = model.static()
    stages = pl.Stages(
        [
            pl.Stage("pay out", duration=40.0, pay_out=0.5, ramp=10.0),
            pl.Stage("stop", duration=20.0, pay_out=0.0, ramp=10.0),
            pl.Stage("settle", duration=2.0, statics=True),
        ]
    )
    simulation = model.simulation(state, dt=0.2, stages=stages)
    results = simulation.run(progress=False)
    after = simulation.state
    kept = after.residual_curvature
    assert kept is not None
    print(
        f"elements {len(state.positions) - 1} → {len(after.positions) - 1}; residual curvature "
        f"{kept[:-2].min() / entering:.5f} … {kept[:-2].max() / entering:.5f} of the entering {entering:.5e} 1/m"
    )
    assert len(after.positions) == len(state.positions) + 2
    assert np.all(np.abs(kept[:-2] / entering - 1) < 5e-2)
    energy = results.energy["total"]
    balance = energy - energy[0] - (results.supplied_work - results.dissipated)
    print(f"worst balance {np.abs(balance).max():.3e} J of {abs(energy[0]):.3e} J")
    assert np.abs(balance).max() < 1e-8 * abs(energy[0])
    assert results.energy["plastic_dissipation"][-1] > 0.0


def test_a_deepwater_s_lay_whose_overbend_yields_reports_its_strain_and_residual_curvature() -> None:
    """`examples/s_lay_deepwater.toml` (16-inch X65 in 1000 m of water over a 90 m stinger, n = 300): statics
    reach a designed lay (the pipe leaves a box before the tip, clear of it) whose overbend strain is past the
    steel's proportional limit and the elastic estimate N/EA + (D/2)|M|/EI; the laid pipe keeps a residual
    curvature and the overbend's plastic strain."""
    from pathlib import Path

    from pipelay.scenario import load_scenario

    example = Path(__file__).parent.parent / "examples" / "s_lay_deepwater.toml"
    state = load_scenario(example).model.static()
    lay = state.lay_summary()
    forces = state.section_forces
    e = int(np.argmax(state.strain))
    d, t = 0.4064, 0.0206
    ea = 207e9 * np.pi / 4 * (d**2 - (d - 2 * t) ** 2)
    ei = 207e9 * np.pi / 64 * (d**4 - (d - 2 * t) ** 4)
    elastic_estimate = forces[e, 0] / ea + 0.5 * d * np.hypot(forces[e, 4], forces[e, 5]) / ei
    print(
        f"departure {np.degrees(lay['departure_angle']):.2f}°, lift-off box {lay['liftoff_roller'] + 1}, tip "
        f"clearance {lay['tip_clearance']:.3f} m; overbend strain {lay['overbend_strain']:.5f} (elastic "
        f"estimate {elastic_estimate:.5f}); residual curvature {lay['residual_curvature']:.4e} 1/m"
    )
    assert 50.0 < np.degrees(lay["departure_angle"]) < 60.0
    assert lay["liftoff_roller"] + 1 < 16 and lay["tip_clearance"] > 0.3
    assert lay["overbend_strain"] == pytest.approx(state.strain[e], rel=1e-12)
    assert lay["overbend_strain"] > 1.05 * elastic_estimate > 0.0
    assert lay["residual_curvature"] > 1e-3
    assert state.plastic_strain[e] > 1e-4


def test_at_a_hand_over_the_wire_takes_the_yielding_walls_axial_force() -> None:
    """`examples/reel_lay.toml` (designed straightener) with an A&R winch: after 10 s of pay-out the winch takes
    the pipe over, and its wire takes on the top element's axial force as its reeled, yielding wall carries it
    (the fibres' resultant, the one the records show), exactly."""
    import tomllib
    from pathlib import Path

    from pipelay.scenario import parse_scenario

    example = Path(__file__).parent.parent / "examples" / "reel_lay.toml"
    data = tomllib.loads(example.read_text())
    data["vessel"]["winch"] = {
        "position": [-30.0 + 10.0 * np.sin(0.2), 0.0, -5.0 - 10.0 * np.cos(0.2)],  # 10 m up the ramp
        "tension_limit": 2e6,
        "element_length": 10.0,
        "wire": {"diameter": 0.08, "mass": 28.0, "EA": 5.5e8},
    }
    data["stages"] = [
        {"name": "lay", "duration": 10.0, "pay_out": 0.5},
        {"name": "hand-over", "duration": 4.0, "hold": "winch", "winch_speed": 0.0},
    ]
    del data["solver"]["t_end"]
    scenario = parse_scenario(data, "reel-lay hand-over")
    simulation = scenario.model.simulation(scenario.model.static(), dt=0.2, stages=scenario.stages)
    results = simulation.run(progress=False)
    k = int(np.flatnonzero(results.stage == 0)[-1])
    top = int(np.flatnonzero(np.isfinite(results.section_forces[k, :, 0]))[-1])
    tensioner = results.section_forces[k, top, 0]
    print(
        f"hand-over at {tensioner / 1e3:.3f} kN, the wire takes {simulation.hand_over_tension / 1e3:.3f} kN"
    )
    assert simulation.hand_over_tension == pytest.approx(tensioner, rel=1e-12)
