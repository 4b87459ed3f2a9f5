#!/usr/bin/env python3
"""First-order displacement RAOs of the built-in OSV (``pl.Vessel.osv()``) with Capytaine.

Fossen's 83 m offshore supply vessel (MSS ``osv.m``): its rigid-body mass matrix M_RB is read from the
engine (``crates/pipelay/src/vessel/rigid_body.rs``, ``Vessel::osv()``) so that the RAOs belong to the
simulated vessel; added mass, radiation damping and wave excitation come from Capytaine (linear
potential flow, zero speed, deep water) on a ship-like hull mesh of the OSV's main dimensions, and the
restoring from that mesh's hydrostatics (printed next to the engine's G).

Hull (analytic, port/starboard symmetric): half-breadth y(x, d) = B/2 · w(x) · (1 − (d/T)^q(x)) at depth d,
  w(x) = 1 − |2x/L|^p  (p = p_f forward, p_a aft),  q(x) = 1 + q0 exp(−α 2x/L),
with (p_f, p_a) fitted to C_w = 0.8 and LCF = −0.5 m, and (q0, α) to ∇ = m/ρ = 4855.5 m³ and LCB = x_G
= −4.5 m (so the vessel floats level with the engine's mass and CG): V-shaped sections forward (q ≈ 1),
box sections aft. A lid on the waterline removes irregular frequencies.

Frames. Capytaine: x forward, y port, z up, origin at CO. Project (Fossen, body frame b): x forward,
y starboard, z down, origin CO (amidships, on the waterline). The two differ by a half turn about x, a
proper rotation, so translations and rotations both map with P = diag(1, −1, −1): project DOF j =
s_j · Capytaine DOF j with s = (+1, −1, −1, +1, −1, −1) for (surge, sway, heave, roll, pitch, yaw), and
matrices map as P M P. Heave is positive down and pitch positive bow up, as in the engine.

Headings. heading_deg = β − ψ: the direction the waves travel, relative to the bow, measured from +x_b
toward +y_b (starboard), i.e. the engine's wave direction β (``Waves``: from e1 toward e2) minus the
vessel's yaw ψ. 0° = following seas, 90° = waves travelling to starboard (coming from port), 180° =
head seas, 270° = coming from starboard. Capytaine's wave_direction (from x toward its y = port) is −heading.

Phase. Capytaine's complex amplitudes are Re(X e^{−iωt}) and its incident elevation at CO is Re(a e^{−iωt})
= a cos(ωt). This script writes phase_j = −arg(X_j), so that for the wave elevation (up)
  ζ(x, y, t) = a cos(ωt − k(x cos μ + y sin μ)),   μ = heading, (x, y) in b from CO,
the motion is ξ_j(t) = |RAO_j| a cos(ωt + phase_j). For the engine's component
  η = a cos(k(x cos β + y sin β) − ωt + φ)  (earth frame)
and CO at (x_CO, y_CO): ξ_j(t) = |RAO_j| a cos(ωt − k(x_CO cos β + y_CO sin β) − φ + phase_j).

Usage: python scripts/osv_raos.py [--out crates/pipelay/data/osv_raos.csv] [--nx 72 --nz 14]  (needs capytaine>=3).
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr
from capytaine.post_pro.rao import rao as capytaine_rao

ROOT = Path(__file__).resolve().parent.parent
ENGINE_SOURCE = ROOT / "crates" / "pipelay" / "src" / "vessel" / "rigid_body.rs"

RHO = 1025.0
G = 9.81
L_PP, BEAM, DRAFT = 83.0, 18.0, 5.0
CW, LCF = 0.8, -0.5
DOFS = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]
NAMES = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
SIGN = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])  # project DOF = SIGN * Capytaine DOF
P = np.diag(SIGN)


# ---------------------------------------------------------------- engine data
def _engine_function_body() -> str:
    text = ENGINE_SOURCE.read_text()
    start = text.index("pub fn osv() -> Self {")
    return text[start : text.index("\n    }\n", start)]


def _numbers(chunk: str) -> np.ndarray:
    chunk = re.sub(r"//[^\n]*", "", chunk)
    return np.array([float(v) for v in re.findall(r"-?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?", chunk)])


def engine_matrices() -> dict[str, np.ndarray]:
    """M_RB, M_A, D and G of ``Vessel::osv()``, parsed from the engine's source (project frame, about CO)."""
    body = _engine_function_body()
    out = {}
    for key, var in (("M_RB", "m_rb"), ("M_A", "m_a"), ("G", "restoring")):
        m = re.search(rf"let {var} = Matrix6::from_row_slice\(&\[(.*?)\]\);", body, re.DOTALL)
        if m is None:
            sys.exit(f"could not find `{var}` in {ENGINE_SOURCE}")
        values = _numbers(m.group(1))
        if values.size != 36:
            sys.exit(f"`{var}` in {ENGINE_SOURCE}: expected 36 numbers, found {values.size}")
        out[key] = values.reshape(6, 6)
    m = re.search(r"let damping = Matrix6::from_diagonal\(&Vector6::new\((.*?)\)\);", body, re.DOTALL)
    if m is None:
        sys.exit(f"could not find `damping` in {ENGINE_SOURCE}")
    out["D"] = np.diag(_numbers(m.group(1)))
    return out


def centre_of_gravity(m_rb: np.ndarray) -> tuple[float, np.ndarray]:
    """Mass and r_g (project frame) from Fossen's M_RB = [[m I, −m S(r_g)], [m S(r_g), I_o]]."""
    mass = m_rb[0, 0]
    s = m_rb[3:, :3] / mass  # S(r_g)
    return mass, np.array([s[2, 1], s[0, 2], s[1, 0]])


# ---------------------------------------------------------------- hull
def _fit(fun, x0):
    from scipy.optimize import fsolve

    sol, _info, ier, msg = fsolve(fun, x0, full_output=True)
    if ier != 1:
        sys.exit(f"hull fit failed: {msg}")
    return sol


class Hull:
    """The analytic hull of the module docstring, fitted to the OSV's data (Capytaine frame, z up)."""

    def __init__(self, volume: float, lcb: float):
        xi = np.linspace(-1.0, 1.0, 40001)
        x = xi * L_PP / 2

        def w_of(p, s):
            return np.where(s >= 0.0, 1.0 - np.abs(s) ** p[0], 1.0 - np.abs(s) ** p[1])

        def waterplane(p):
            w = w_of(p, xi)
            area = BEAM * np.trapezoid(w, x)
            return [area / (L_PP * BEAM) - CW, BEAM * np.trapezoid(w * x, x) / area - LCF]

        self.p = _fit(waterplane, [4.0, 4.0])
        w = w_of(self.p, xi)

        def displacement(c):
            q = 1.0 + c[0] * np.exp(-c[1] * xi)
            section = q / (q + 1.0)  # sectional area coefficient of 1 − (d/T)^q
            vol = BEAM * DRAFT * np.trapezoid(w * section, x)
            return [vol / volume - 1.0, BEAM * DRAFT * np.trapezoid(w * section * x, x) / vol - lcb]

        self.q0, self.alpha = _fit(displacement, [5.0, 4.0])
        self._w_of = w_of

    def width(self, x):
        return self._w_of(self.p, 2.0 * np.asarray(x) / L_PP)

    def q(self, x):
        return 1.0 + self.q0 * np.exp(-self.alpha * 2.0 * np.asarray(x) / L_PP)

    def section(self, x: float, n: int) -> np.ndarray:
        """n + 1 points (y ≥ 0, z) of the section at x, waterline to keel, equally spaced in arc length."""
        y0 = BEAM / 2 * float(self.width(x))
        if y0 <= 1e-9:
            return np.column_stack([np.zeros(n + 1), -np.linspace(0.0, DRAFT, n + 1)])
        q = float(self.q(x))
        s = np.linspace(0.0, 1.0, 4001)
        depth = np.unique(np.concatenate([s, (1.0 - s) ** (1.0 / q)]))  # resolve the sides and the bottom
        y = y0 * (1.0 - depth**q)
        z = -DRAFT * depth
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(y), np.diff(z)))])
        target = np.linspace(0.0, arc[-1], n + 1)
        return np.column_stack([np.interp(target, arc, y), np.interp(target, arc, z)])

    def mesh(self, nx: int, nz: int) -> cpt.ReflectionSymmetricMesh:
        """Quadrilateral panels of the wetted hull: nx along the length, nz around each half-girth."""
        xs = np.linspace(-L_PP / 2, L_PP / 2, nx + 1)
        vertices = []
        for x in xs:
            yz = self.section(x, nz)
            vertices.append(np.column_stack([np.full(nz + 1, x), yz]))
        vertices = np.concatenate(vertices)
        # Triangles, not quads: Capytaine mirrors a face by reversing its vertices, which makes a non-planar
        # quad split along its other diagonal, so the two halves would not be exact mirror images (spurious
        # sway/roll/yaw in head seas). Each quad is cut along its shorter diagonal, unless that leaves a
        # triangle in the symmetry plane y = 0 (at the stem and stern); one that any cut leaves there is a
        # zero-thickness fin, which its mirror image cancels, and is dropped.
        on_plane = np.abs(vertices[:, 1]) < 1e-9
        faces = []
        for i in range(nx):
            for j in range(nz):
                a = i * (nz + 1) + j
                b = (i + 1) * (nz + 1) + j
                # quad (a, b, b + 1, a + 1): normal out of the hull (into the water) on the y > 0 side
                cuts = [[[a, b, b + 1], [a, b + 1, a + 1]], [[a, b, a + 1], [b, b + 1, a + 1]]]
                if np.linalg.norm(vertices[a] - vertices[b + 1]) > np.linalg.norm(
                    vertices[b] - vertices[a + 1]
                ):
                    cuts.reverse()
                for cut in cuts:
                    if not any(on_plane[t].all() for t in cut):
                        break
                faces += [t for t in cut if not on_plane[t].all()]
        half = cpt.Mesh(vertices, np.array(faces), name="osv_half")
        return cpt.ReflectionSymmetricMesh(half, plane="xOz", name="osv_hull")


# ---------------------------------------------------------------- main
def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "crates" / "pipelay" / "data" / "osv_raos.csv")
    parser.add_argument("--nx", type=int, default=72, help="panels along the length (default 72)")
    parser.add_argument("--nz", type=int, default=14, help="panels around each half-girth (default 14)")
    parser.add_argument("--lid-radius", type=float, default=1.7, help="lid panel radius, m (default 1.7)")
    parser.add_argument("--heading-step", type=float, default=15.0, help="deg, over [0, 360) (default 15)")
    parser.add_argument(
        "--roll-damping-ratio",
        type=float,
        default=0.15,
        help="extra linear roll damping, fraction of critical 2√(K44 (M44+A44)) at the roll natural "
        "frequency (default 0: potential damping only)",
    )
    args = parser.parse_args()

    t_start = time.perf_counter()
    engine = engine_matrices()
    mass, r_g = centre_of_gravity(engine["M_RB"])
    volume = mass / RHO
    hull = Hull(volume, lcb=r_g[0])
    print(f"engine: m = {mass:.1f} kg, r_g = {r_g} m (b frame), ∇ = m/ρ = {volume:.1f} m³")
    print(
        f"hull: p_f = {hull.p[0]:.4f}, p_a = {hull.p[1]:.4f}, q(x) = 1 + {hull.q0:.4f} exp(−{hull.alpha:.4f}·2x/L)"
        f" (q = {hull.q(L_PP / 2):.2f} at the bow, {hull.q(-L_PP / 2):.1f} at the stern)"
    )

    mesh = hull.mesh(args.nx, args.nz)
    lid = mesh.generate_lid(z=0.0, faces_max_radius=args.lid_radius)
    rotation_centre = np.zeros(3)  # CO
    body = cpt.FloatingBody(
        mesh=mesh,
        lid_mesh=lid,
        dofs=cpt.rigid_body_dofs(rotation_center=rotation_centre),
        center_of_mass=SIGN[:3] * r_g,
        mass=mass,
        name="osv",
    )
    print(
        f"mesh: {mesh.nb_faces} hull panels (triangles, 2 × 2 × {args.nx} × {args.nz}, xOz symmetry) + {lid.nb_faces} lid panels;"
        f" max panel radius {mesh.faces_radiuses.max():.2f} m (hull), {lid.faces_radiuses.max():.2f} m (lid)"
    )

    # Hydrostatics of the mesh against the engine's.
    hs = body.compute_hydrostatics(rho=RHO, g=G)
    k_raw = (
        body.compute_hydrostatic_stiffness(rho=RHO, g=G).sel(influenced_dof=DOFS, radiating_dof=DOFS).values
    )
    # Keep the heave/roll/pitch terms that survive port/starboard symmetry and equilibrium (CB and CG on one vertical):
    # drop the discretisation residues K34, K45 (odd in y) and K46, K56 (∝ x_B − x_G, y_B − y_G).
    keep = np.zeros((6, 6), dtype=bool)
    for i, j in [(2, 2), (3, 3), (4, 4), (2, 4), (4, 2)]:
        keep[i, j] = True
    k_capy = np.where(keep, k_raw, 0.0)
    k_proj = P @ k_capy @ P
    print(
        f"mesh hydrostatics: ∇ = {hs['disp_volume']:.1f} m³, A_wp = {hs['waterplane_area']:.1f} m²,"
        f" CB = {SIGN[:3] * np.asarray(hs['center_of_buoyancy'])} m (b frame),"
        f" x_F = {hs['waterplane_center'][0]:.3f} m, GM_T = {hs['transversal_metacentric_height']:.3f} m,"
        f" GM_L = {hs['longitudinal_metacentric_height']:.2f} m"
    )
    comparison = []
    for i, j in [(2, 2), (3, 3), (4, 4), (2, 4)]:
        comparison.append((f"G{i + 1}{j + 1}", k_proj[i, j], engine["G"][i, j]))
        print(
            f"  G{i + 1}{j + 1}: mesh {k_proj[i, j]:.6g}, engine {engine['G'][i, j]:.6g}"
            f" (mesh/engine = {k_proj[i, j] / engine['G'][i, j]:.3f})"
        )
    dropped = np.abs(np.where(keep, 0.0, k_raw))
    i, j = np.unravel_index(np.argmax(dropped), dropped.shape)
    print(
        f"  dropped residues: largest |K_{DOFS[i]},{DOFS[j]}| = {dropped[i, j]:.3g}"
        f" ({dropped[i, j] / k_raw[3, 3]:.2%} of K44)"
    )

    # BEM problems.
    periods = np.concatenate(
        [
            np.arange(3.0, 8.0, 0.5),
            np.arange(8.0, 13.0, 0.25),
            np.arange(13.0, 20.0, 1.0),
            np.arange(20.0, 30.1, 2.0),
        ]
    )
    periods = np.sort(periods)[::-1]
    omegas = 2 * np.pi / periods
    headings = np.arange(0.0, 360.0, args.heading_step)
    capy_directions = np.mod(-np.radians(headings), 2 * np.pi)
    test_matrix = xr.Dataset(
        coords={
            "omega": omegas,
            "wave_direction": capy_directions,
            "radiating_dof": DOFS,
            "water_depth": [np.inf],
            "rho": [RHO],
            "g": [G],
        }
    )
    print(
        f"BEM: {len(omegas)} periods {periods.min():g}–{periods.max():g} s, {len(headings)} headings;"
        f" solving {len(omegas) * (6 + len(headings))} problems ...",
        flush=True,
    )
    t_bem = time.perf_counter()
    solver = cpt.BEMSolver()
    ds = solver.fill_dataset(test_matrix, body, progress_bar=False)
    t_bem = time.perf_counter() - t_bem
    print(f"BEM done in {t_bem:.0f} s")

    m_capy = P @ engine["M_RB"] @ P
    ds["inertia_matrix"] = body.add_dofs_labels_to_matrix(m_capy)
    ds["hydrostatic_stiffness"] = body.add_dofs_labels_to_matrix(k_capy)
    ds = ds.sel(radiating_dof=DOFS, influenced_dof=DOFS)

    a = ds["added_mass"].sel(radiating_dof=DOFS, influenced_dof=DOFS).values  # (omega, i, j)
    omega_sorted = ds["omega"].values

    def natural(i: int, stiffness: float) -> float:
        """ω_n with ω² (M_ii + A_ii(ω)) = K_ii, by fixed point on the interpolated A_ii."""
        w = np.sqrt(stiffness / engine["M_RB"][i, i])
        for _ in range(100):
            aii = np.interp(w, omega_sorted, a[:, i, i])
            w_new = np.sqrt(stiffness / (engine["M_RB"][i, i] + aii))
            if abs(w_new - w) < 1e-10:
                break
            w = w_new
        return w

    w_n = {n: natural(i, k_proj[i, i]) for i, n in ((2, "heave"), (3, "roll"), (4, "pitch"))}
    dissipation = None
    if args.roll_damping_ratio > 0.0:
        wr = w_n["roll"]
        b44 = (
            2
            * args.roll_damping_ratio
            * np.sqrt(k_proj[3, 3] * (engine["M_RB"][3, 3] + np.interp(wr, omega_sorted, a[:, 3, 3])))
        )
        d = np.zeros((6, 6))
        d[3, 3] = b44
        dissipation = body.add_dofs_labels_to_matrix(d)
        print(f"extra roll damping B44 = {b44:.4g} N·m·s/rad ({args.roll_damping_ratio:g} of critical)")
    raos = capytaine_rao(
        ds, dissipation=dissipation
    )  # (omega, wave_direction, radiating_dof), Capytaine frame

    # To the project's frame and conventions.
    raos = raos.sel(radiating_dof=DOFS).transpose("omega", "wave_direction", "radiating_dof")
    values = raos.values * SIGN  # (omega, direction, dof)
    dir_index = {round(float(d), 9): n for n, d in enumerate(raos["wave_direction"].values)}
    order = [dir_index[round(float(d), 9)] for d in capy_directions]
    values = values[:, order, :]  # headings in the order of `headings`
    omega_out = raos["omega"].values
    idx = np.argsort(omega_out)[::-1]  # by increasing period
    omega_out, values = omega_out[idx], values[idx]
    period_out = 2 * np.pi / omega_out
    k_out = omega_out**2 / G
    amplitude = np.abs(values)
    phase = -np.angle(values)
    # Motions that port/starboard symmetry makes zero (sway, roll, yaw at 0° and 180°) come out at round-off
    # level with a meaningless phase: write them as exact zeros.
    negligible = amplitude < 1e-9 * amplitude.max(axis=(0, 1), keepdims=True)
    amplitude[negligible] = 0.0
    phase[negligible] = 0.0

    # Write.
    args.out.parent.mkdir(parents=True, exist_ok=True)
    header = [
        "First-order displacement RAOs of the built-in OSV (pl.Vessel.osv(), Fossen's 83 m supply vessel, MSS osv.m)",
        (
            f"Produced by scripts/osv_raos.py with Capytaine {cpt.__version__} (linear potential flow BEM, Delhommeau GF,"
            " zero forward speed, infinite depth, rho = 1025 kg/m3, g = 9.81 m/s2)."
        ),
        (
            f"Mesh: analytic ship-like hull L = {L_PP} m, B = {BEAM} m, T = {DRAFT} m, C_b = 0.65, C_w = {CW}, LCF = {LCF} m,"
            f" LCB = x_G = {r_g[0]} m; {mesh.nb_faces} triangular hull panels ({args.nx} along, {args.nz} per half-girth, xOz symmetry) + {lid.nb_faces}-panel waterline lid"
            " (irregular frequencies removed). See the script's docstring."
        ),
        (
            "Mass and inertia: the engine's M_RB (crates/pipelay/src/vessel/rigid_body.rs, Vessel::osv()) about CO;"
            " added mass, radiation damping and excitation: Capytaine; restoring: the mesh's hydrostatics"
        ),
        "  (mesh vs engine: " + ", ".join(f"{n} {mv:.4g} vs {ev:.4g}" for n, mv, ev in comparison) + ").",
        "Damping: "
        + (
            "potential (radiation) damping only. No viscous roll damping: the roll resonance (T ~ 10 s,"
            " and sway with it) is sharp and much overestimated, its peak value set by the period grid;"
            " add roll damping (script option --roll-damping-ratio) for use near it."
            if dissipation is None
            else f"radiation damping + linear roll damping {args.roll_damping_ratio:g} of critical at"
            f" the roll natural frequency."
        ),
        (
            "Frame: project body frame b (Fossen): x forward, y starboard, z down, origin CO = amidships on the waterline;"
            " motions about CO: surge, sway, heave (m, heave positive DOWN), roll, pitch, yaw (rad; roll starboard down,"
            " pitch bow up, yaw bow to starboard)."
        ),
        (
            "Heading: heading_deg = direction the waves TRAVEL relative to the bow, from +x_b toward +y_b: 0 = following,"
            " 90 = travelling to starboard (from port), 180 = head seas, 270 = from starboard;"
            " = engine wave direction beta (Waves, from e1 toward e2) minus vessel yaw psi."
        ),
        (
            "Units: *_amp per metre of wave amplitude: surge/sway/heave m/m, roll/pitch/yaw rad/m; *_phase rad;"
            " wavenumber_rad_m = omega^2/g (deep water)."
        ),
        (
            "Phase: for the wave elevation (up) zeta = a cos(omega t - k (x cos(heading) + y sin(heading))), (x, y) in b from"
            " CO, the motion is xi_j(t) = amp_j a cos(omega t + phase_j); so for the engine's component"
            " eta = a cos(k (x cos beta + y sin beta) - omega t + phi) (earth frame), xi_j = amp_j a cos(omega t"
            " - k (x_CO cos beta + y_CO sin beta) - phi + phase_j). Complex RAO_j = amp_j exp(-i phase_j) in Capytaine's"
            " exp(-i omega t) convention (= amp_j exp(+i phase_j) for exp(+i omega t))."
        ),
        (
            "Long-period limits: heave_amp -> 1 with heave_phase -> +-pi (z down); pitch and roll amp -> k |cos| and"
            " k |sin| of the heading (the vessel follows the wave slope)."
        ),
    ]
    columns = ["period_s", "omega_rad_s", "wavenumber_rad_m", "heading_deg"]
    for n in NAMES:
        columns += [f"{n}_amp", f"{n}_phase"]
    with open(args.out, "w") as f:
        f.writelines(f"# {line}\n" for line in header)
        f.write(",".join(columns) + "\n")
        for i in range(len(omega_out)):
            for h, heading in enumerate(headings):
                row = [f"{period_out[i]:.4g}", f"{omega_out[i]:.6f}", f"{k_out[i]:.6f}", f"{heading:g}"]
                for j in range(6):
                    row += [f"{amplitude[i, h, j]:.6g}", f"{phase[i, h, j]:.5f}"]
                f.write(",".join(row) + "\n")
    print(f"wrote {args.out} ({len(omega_out) * len(headings)} rows)")

    # Checks.
    def at(period, heading):
        i = int(np.argmin(np.abs(period_out - period)))
        h = int(np.argmin(np.abs(headings - heading)))
        return i, h

    print("\nchecks")
    i, h = at(30.0, 180.0)
    print(
        f"  T = {period_out[i]:g} s, head seas: |heave| = {amplitude[i, h, 2]:.4f} (phase {phase[i, h, 2]:+.3f} rad),"
        f" |pitch|/k = {amplitude[i, h, 4] / k_out[i]:.4f} (phase {phase[i, h, 4]:+.3f}), k = {k_out[i]:.5f} rad/m"
    )
    i, h = at(30.0, 90.0)
    print(
        f"  T = {period_out[i]:g} s, beam seas: |heave| = {amplitude[i, h, 2]:.4f}, |roll|/k = {amplitude[i, h, 3] / k_out[i]:.4f}"
        f" (phase {phase[i, h, 3]:+.3f}), |sway| = {amplitude[i, h, 1]:.4f}"
    )
    i, h = at(30.0, 0.0)
    print(
        f"  T = {period_out[i]:g} s, following: |heave| = {amplitude[i, h, 2]:.4f}, |pitch|/k = {amplitude[i, h, 4] / k_out[i]:.4f}"
        f" (phase {phase[i, h, 4]:+.3f})"
    )
    sym = 0.0
    for h, heading in enumerate(headings):
        mirror = np.mod(360.0 - heading, 360.0)
        hm = int(np.argmin(np.abs(headings - mirror)))
        if abs(headings[hm] - mirror) < 1e-9:
            sym = max(
                sym,
                float(np.max(np.abs(values[:, h, :] - values[:, hm, :] * np.array([1, -1, 1, -1, 1, -1])))),
            )
    print(f"  port/starboard symmetry: max |RAO(μ) − mirrored RAO(360° − μ)| = {sym:.2e}")
    for name, i in (("heave", 2), ("roll", 3), ("pitch", 4)):
        aii = np.interp(w_n[name], omega_sorted, a[:, i, i])
        t_engine = 2 * np.pi * np.sqrt((engine["M_RB"][i, i] + engine["M_A"][i, i]) / engine["G"][i, i])
        print(
            f"  {name} natural period 2π√((M + A(ω_n))/K) = {2 * np.pi / w_n[name]:.3f} s"
            f" (A = {aii:.4g}, K_mesh = {k_proj[i, i]:.4g}); engine (M_RB + M_A, G): {t_engine:.3f} s"
        )
    # Longer waves than the table's, for the limits only (not written).
    long_periods = np.array([60.0, 120.0])
    long = solver.fill_dataset(
        xr.Dataset(
            coords={
                "omega": 2 * np.pi / long_periods,
                "wave_direction": [np.pi / 2, np.pi],
                "radiating_dof": DOFS,
                "water_depth": [np.inf],
                "rho": [RHO],
                "g": [G],
            }
        ),
        body,
        progress_bar=False,
    )
    long["inertia_matrix"] = ds["inertia_matrix"]
    long["hydrostatic_stiffness"] = ds["hydrostatic_stiffness"]
    long_rao = capytaine_rao(long, dissipation=dissipation)
    for period in long_periods:
        w = 2 * np.pi / period
        k = w**2 / G
        beam = (
            long_rao.sel(omega=w, wave_direction=np.pi / 2, method="nearest").sel(radiating_dof=DOFS).values
            * SIGN
        )
        head = (
            long_rao.sel(omega=w, wave_direction=np.pi, method="nearest").sel(radiating_dof=DOFS).values
            * SIGN
        )
        print(
            f"  T = {period:g} s (extra): head |heave| = {abs(head[2]):.4f}, |pitch|/k = {abs(head[4]) / k:.4f};"
            f" beam |heave| = {abs(beam[2]):.4f}, |roll|/k = {abs(beam[3]) / k:.4f}"
        )
    # Heave dynamic amplification |K33 / (K33 − ω²(M33 + A33) − iω B33)| (excitation taken flat).
    b33 = ds["radiation_damping"].sel(influenced_dof="Heave", radiating_dof="Heave").values
    fine = np.linspace(omega_sorted.min(), omega_sorted.max(), 4001)
    daf = np.abs(
        k_proj[2, 2]
        / (
            k_proj[2, 2]
            - fine**2 * (engine["M_RB"][2, 2] + np.interp(fine, omega_sorted, a[:, 2, 2]))
            - 1j * fine * np.interp(fine, omega_sorted, b33)
        )
    )
    i = int(np.argmax(daf))
    print(
        f"  heave dynamic amplification peaks at T = {2 * np.pi / fine[i]:.2f} s (|DAF| = {daf[i]:.2f},"
        f" B33/(2√(K33(M33+A33))) = {np.interp(w_n['heave'], omega_sorted, b33) / (2 * np.sqrt(k_proj[2, 2] * (engine['M_RB'][2, 2] + np.interp(w_n['heave'], omega_sorted, a[:, 2, 2])))):.3f} at ω_n)"
    )

    def local_maxima(series):
        return [
            n
            for n in range(1, len(series) - 1)
            if series[n] > series[n - 1] and series[n] >= series[n + 1] and series[n] > 0.0
        ]

    for heading in (90.0, 180.0):
        h = int(np.argmin(np.abs(headings - heading)))
        text = []
        for name, j in (("heave", 2), ("roll", 3), ("pitch", 4)):
            peaks = local_maxima(amplitude[:, h, j])
            text.append(
                f"{name} "
                + (", ".join(f"{amplitude[n, h, j]:.4g} at {period_out[n]:g} s" for n in peaks) or "none")
            )
        print(f"  heading {heading:g}°, local maxima: " + "; ".join(text))

    print(
        "\n  T [s]   k [rad/m] | heave 90° roll 90° [rad/m] pitch 90° | heave 180° roll 180° pitch 180° [rad/m]"
    )
    h90 = int(np.argmin(np.abs(headings - 90.0)))
    h180 = int(np.argmin(np.abs(headings - 180.0)))
    for i in range(len(omega_out)):
        print(
            f"  {period_out[i]:5.2f}  {k_out[i]:.5f}   | {amplitude[i, h90, 2]:8.4f} {amplitude[i, h90, 3]:9.5f}"
            f" {amplitude[i, h90, 4]:10.5f} | {amplitude[i, h180, 2]:9.4f} {amplitude[i, h180, 3]:9.5f}"
            f" {amplitude[i, h180, 4]:10.5f}"
        )
    print(f"\ntotal run time {time.perf_counter() - t_start:.0f} s")


if __name__ == "__main__":
    main()
