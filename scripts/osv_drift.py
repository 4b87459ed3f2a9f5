#!/usr/bin/env python3
"""Mean (second-order) wave-drift coefficients of the built-in OSV with Capytaine (far-field method).

Usage: /tmp/capy/bin/python scripts/osv_drift.py [--out crates/pipelay/data/osv_drift.csv] [--nx 72 --nz 14]
       [--ntheta 360] [--roll-damping-ratio 0.15]   (needs capytaine>=3, numpy, xarray, scipy)

Writes the horizontal mean drift force and yaw moment per wave amplitude squared (N/m², N·m/m², body frame b,
about CO) of ``pl.Vessel.osv()`` for every (period, heading) of ``crates/pipelay/data/osv_raos.csv`` (read
from that table), sorted by period then heading. Heave, roll and pitch are written as 0: the far-field
method gives only the horizontal components.

Hull, mass, restoring, roll damping and frames are those of ``scripts/osv_raos.py`` (its ``Hull`` class and
engine parser are imported, not copied): the same analytic hull (default 72 × 14 panels per half, plus a
waterline lid), the engine's M_RB, the mesh's hydrostatic stiffness and linear roll damping 0.15 of
critical at the roll natural frequency; so the motions are those of the RAO table (printed check).

Method (Capytaine 3 has no QTF solver). Maruo (1960) / Newman (1967) far-field momentum and angular-momentum
balance in deep water, the total Kochin function of the body's outgoing waves being
    H(θ) = H_D(θ; β) + Σ_j ξ_j(β) H_R,j(θ),
H_D the diffraction (scattered-wave) Kochin function, H_R,j that of radiation problem j (unit displacement)
and ξ_j the complex RAO, Capytaine's convention: Re(· e^{−iωt}), frame x forward, y port, z up, incident
potential φ_0 = −(ig/ω) e^{kz} e^{ik(x cos β + y sin β)} (unit amplitude), Kochin function
    H(θ) = (1/4π) ∫ σ e^{kz} e^{−ik(x cos θ + y sin θ)} dS       (sources σ on hull and lid),
so that far away the body's waves are φ ~ −2πik H(θ) √(2/(πkR)) e^{i(kR − π/4)} e^{kz}. Per a² (a = 1), in
Capytaine's frame, β the wave direction, e_θ = (cos θ, sin θ):
    surge, sway (written; Maruo's formula):
        F = 2πρk² ∫ |H(θ)|² (e_β − e_θ) dθ + (k/ω) W e_β,      W = ½ω² B44 |ξ_4|²
    yaw (written; Newman's formula, moment about the vertical through CO):
        M_z = −(2πρω/k) Im H'(β) − 2πρk ∫ Im(H̄ H') dθ,        H' = dH/dθ (analytic, from the sources)
Derivation (deep water): the mean load is minus the mean outflow of momentum / angular momentum through a
far vertical cylinder. The body's waves carry away momentum (k/ω)·(their energy flux) in each direction θ,
which gives the −2πρk² ∫|H|² e_θ term; the incident × body-wave cross terms reduce, by stationary phase at
θ = β, to the interference power E_int = 2πρg Re H(β) times −(k/ω) e_β, i.e. −2πρω Re H(β) e_β; energy
conservation E_s + E_int + W = 0, with E_s = 2πρωk ∫|H|² dθ the power of the body's waves and W the power
absorbed by the added roll damping, turns that into Maruo's form above (which is ≥ 0 along e_β and → 0
quadratically in long waves). For yaw the cross terms of R v_θ v_R give −2πρ(g/ω) Im H'(β) and the body's
waves −2πρk ∫ Im(H̄H') dθ. These are the expressions of Capytaine's own ``far_field_mean_drift_force``
(its diagonal wave_direction_k = wave_direction_l, with the interference kept as −2πρω Re H(β) e_β), to which
the script compares ("direct" form). Printed checks: the energy balance residual, direct vs Maruo forms,
Capytaine's function, the motions against osv_raos.csv, and
  (a) long waves: drift → 0 (largest values at 30 s);
  (b) short waves (3 s): against the reflection limit below (head, bow/quarter, beam, following seas);
  (c) symmetry: sway(90°) = −sway(270°), surge < 0 at 180° and > 0 at 0° at every period, port/starboard mirror.
Run time: about 4 min on 2 cores at 72 × 14 panels, the table's 43 periods and 24 headings.

Frames. Capytaine (x fwd, y port, z up) to project b (x fwd, y starboard, z down): surge = F_x,
sway = −F_y, yaw = −M_z; Capytaine's wave_direction β = −heading. heading_deg as in the RAO table: the
direction the waves TRAVEL relative to the bow, from +x_b toward +y_b (0 = following, 90 = travelling to
starboard, 180 = head seas). So head seas push the vessel aft (surge < 0), beam seas at 90° to starboard
(sway > 0).

Short-wave check (Faltinsen 1990, Sea loads on ships and offshore structures, ch. 5): a wall-sided body in
short waves reflects fully on the illuminated waterline L1:
    F = ½ρg a² ∫_{L1} sin²α (−n) dl,   α = angle between the wave direction and the waterline tangent,
n the outward normal; evaluated on the mesh's waterline and compared at the shortest period.
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import capytaine as cpt
from capytaine.post_pro.rao import rao as capytaine_rao
from osv_raos import (  # the RAO script: same hull, engine data and frames
    BEAM,
    DOFS,
    L_PP,
    RHO,
    SIGN,
    G,
    Hull,
    P,
    centre_of_gravity,
    engine_matrices,
)

ROOT = Path(__file__).resolve().parent.parent
RAO_TABLE = ROOT / "crates" / "pipelay" / "data" / "osv_raos.csv"


def rao_grid(path: Path) -> tuple[np.ndarray, np.ndarray, dict]:
    """Periods and headings of the RAO table (and its complex RAOs, project frame, for the check)."""
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    head, rows = rows[0], rows[1:]
    col = {n: i for i, n in enumerate(head)}
    periods = sorted({float(r[col["period_s"]]) for r in rows})
    headings = sorted({float(r[col["heading_deg"]]) for r in rows})
    table = {}
    names = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    for r in rows:
        key = (float(r[col["period_s"]]), float(r[col["heading_deg"]]))
        table[key] = np.array(
            [float(r[col[f"{n}_amp"]]) * np.exp(-1j * float(r[col[f"{n}_phase"]])) for n in names]
        )
    return np.array(periods), np.array(headings), table


def kochin_matrices(mesh, k: float, theta: np.ndarray):
    """E, E' with H(θ) = σ · E(θ), H'(θ) = σ · E'(θ) for the sources σ on `mesh` (hull + lid)."""
    c = mesh.faces_centers
    wbar = np.outer(c[:, 0], np.cos(theta)) + np.outer(c[:, 1], np.sin(theta))
    dwbar = -np.outer(c[:, 0], np.sin(theta)) + np.outer(c[:, 1], np.cos(theta))
    e = (np.exp(k * c[:, 2]) * mesh.faces_areas / (4 * np.pi))[:, None] * np.exp(-1j * k * wbar)
    return e, -1j * k * dwbar * e


def waterline_short_wave(hull: Hull, heading_deg: float, n: int = 4000) -> np.ndarray:
    """Faltinsen's short-wave drift (surge, sway, yaw) per a², project frame, on the hull's waterline."""
    x = np.linspace(-L_PP / 2, L_PP / 2, n + 1)
    y = BEAM / 2 * hull.width(x)
    # closed polygon, counterclockwise seen from above in (x, y_starboard)... orientation fixed below
    px = np.concatenate([x, x[::-1][1:]])
    py = np.concatenate([y, -y[::-1][1:]])
    dx, dy = np.diff(px), np.diff(py)
    mx, my = 0.5 * (px[1:] + px[:-1]), 0.5 * (py[1:] + py[:-1])
    dl = np.hypot(dx, dy)
    ok = dl > 0
    dx, dy, mx, my, dl = dx[ok], dy[ok], mx[ok], my[ok], dl[ok]
    tx, ty = dx / dl, dy / dl
    nx, ny = ty, -tx  # candidate outward normal
    if np.sum(nx * mx + ny * my) < 0:
        nx, ny = -nx, -ny
    mu = np.radians(heading_deg)
    ex, ey = np.cos(mu), np.sin(mu)
    lit = ex * nx + ey * ny < 0
    sin2 = (ex * ty - ey * tx) ** 2
    fx = 0.5 * RHO * G * np.sum((sin2 * -nx * dl)[lit])
    fy = 0.5 * RHO * G * np.sum((sin2 * -ny * dl)[lit])
    mz = 0.5 * RHO * G * np.sum((sin2 * (mx * -ny - my * -nx) * dl)[lit])
    return np.array([fx, fy, mz])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "crates" / "pipelay" / "data" / "osv_drift.csv")
    parser.add_argument("--nx", type=int, default=72, help="panels along the length (default 72)")
    parser.add_argument("--nz", type=int, default=14, help="panels around each half-girth (default 14)")
    parser.add_argument("--lid-radius", type=float, default=1.7, help="lid panel radius, m (default 1.7)")
    parser.add_argument("--ntheta", type=int, default=360, help="Kochin angles over [0, 2π) (default 360)")
    parser.add_argument(
        "--roll-damping-ratio", type=float, default=0.15, help="as osv_raos.py (default 0.15)"
    )
    parser.add_argument(
        "--periods", type=str, default=None, help="comma list to override the table's periods (tests)"
    )
    args = parser.parse_args()

    t_start = time.perf_counter()
    periods, headings, rao_table = rao_grid(RAO_TABLE)
    if args.periods:
        periods = np.array(sorted(float(p) for p in args.periods.split(",")))
    if args.ntheta % 24:
        sys.exit("--ntheta must be a multiple of 24 so that every heading is on the Kochin grid")
    engine = engine_matrices()
    mass, r_g = centre_of_gravity(engine["M_RB"])
    hull = Hull(mass / RHO, lcb=r_g[0])
    mesh = hull.mesh(args.nx, args.nz)
    lid = mesh.generate_lid(z=0.0, faces_max_radius=args.lid_radius)
    body = cpt.FloatingBody(
        mesh=mesh,
        lid_mesh=lid,
        dofs=cpt.rigid_body_dofs(rotation_center=np.zeros(3)),
        center_of_mass=SIGN[:3] * r_g,
        mass=mass,
        name="osv",
    )
    print(
        f"mesh: {mesh.nb_faces} hull + {lid.nb_faces} lid panels ({args.nx} × {args.nz} per half);"
        f" {len(periods)} periods {periods.min():g}–{periods.max():g} s, {len(headings)} headings (from {RAO_TABLE.name})"
    )
    k_raw = (
        body.compute_hydrostatic_stiffness(rho=RHO, g=G).sel(influenced_dof=DOFS, radiating_dof=DOFS).values
    )
    keep = np.zeros((6, 6), dtype=bool)
    for i, j in [(2, 2), (3, 3), (4, 4), (2, 4), (4, 2)]:
        keep[i, j] = True
    k_capy = np.where(keep, k_raw, 0.0)  # as osv_raos.py
    m_capy = P @ engine["M_RB"] @ P

    theta = np.arange(args.ntheta) * 2 * np.pi / args.ntheta
    dtheta = 2 * np.pi / args.ntheta
    capy_dirs = np.mod(-np.radians(headings), 2 * np.pi)
    i_beta = np.rint(capy_dirs / dtheta).astype(int) % args.ntheta
    omegas = 2 * np.pi / periods

    solver = cpt.BEMSolver()
    results = []
    kochin = {}  # (omega index, problem key) -> (H, H')
    t_bem = time.perf_counter()
    for n, w in enumerate(omegas):
        problems = [
            cpt.RadiationProblem(body=body, omega=w, radiating_dof=d, rho=RHO, g=G, water_depth=np.inf)
            for d in DOFS
        ] + [
            cpt.DiffractionProblem(body=body, omega=w, wave_direction=b, rho=RHO, g=G, water_depth=np.inf)
            for b in capy_dirs
        ]
        res = solver.solve_all(problems, keep_details=True, progress_bar=False)
        e, de = kochin_matrices(body.mesh_including_lid, res[0].wavenumber, theta)
        sig = np.array([r.sources for r in res])
        hh, dh = sig @ e, sig @ de
        if n == 0:  # check against Capytaine's own Kochin function
            from capytaine.post_pro import compute_kochin

            ref = compute_kochin(res[-1], theta)
            print(
                f"  Kochin check vs capytaine.compute_kochin: max rel diff {np.max(np.abs(hh[-1] - ref)) / np.max(np.abs(ref)):.1e}"
            )
        for m, r in enumerate(res):
            kochin[(n, r.radiating_dof if m < 6 else round(float(r.wave_direction), 9))] = (hh[m], dh[m])
            r.sources = r.potential = r.pressure = None
        results += res
        print(f"  T = {periods[n]:5.2f} s done ({time.perf_counter() - t_bem:.0f} s)", flush=True)
    t_bem = time.perf_counter() - t_bem

    ds = cpt.assemble_dataset(results)
    ds["inertia_matrix"] = body.add_dofs_labels_to_matrix(m_capy)
    ds["hydrostatic_stiffness"] = body.add_dofs_labels_to_matrix(k_capy)
    ds = ds.sel(radiating_dof=DOFS, influenced_dof=DOFS)

    # Roll damping exactly as osv_raos.py: ratio of critical at the roll natural frequency (fixed point on A44).
    omega_sorted = ds["omega"].values
    a44 = ds["added_mass"].sel(radiating_dof="Roll", influenced_dof="Roll").values
    k44 = k_capy[3, 3]
    wr = np.sqrt(k44 / engine["M_RB"][3, 3])
    for _ in range(100):
        w_new = np.sqrt(k44 / (engine["M_RB"][3, 3] + np.interp(wr, omega_sorted, a44)))
        if abs(w_new - wr) < 1e-10:
            break
        wr = w_new
    b44 = 0.0
    dissipation = None
    if args.roll_damping_ratio > 0:
        b44 = (
            2
            * args.roll_damping_ratio
            * np.sqrt(k44 * (engine["M_RB"][3, 3] + np.interp(wr, omega_sorted, a44)))
        )
        d = np.zeros((6, 6))
        d[3, 3] = b44
        dissipation = body.add_dofs_labels_to_matrix(d)
        print(
            f"roll: T_n = {2 * np.pi / wr:.3f} s, added B44 = {b44:.4g} N·m·s/rad ({args.roll_damping_ratio:g} of critical)"
        )
    raos = capytaine_rao(ds, dissipation=dissipation).sel(radiating_dof=DOFS)

    # Drift, Capytaine frame, per a².
    nP, nH = len(periods), len(headings)
    drift = np.zeros((nP, nH, 3))  # Fx, Fy, Mz (Capytaine frame)
    maruo = np.zeros((nP, nH, 2))
    energy = np.zeros((nP, nH, 4))  # E_s, E_int, W, residual
    rao_check = 0.0
    for n, w in enumerate(omegas):
        k = w**2 / G
        for h, b in enumerate(capy_dirs):
            x = raos.sel(omega=w, wave_direction=b, method="nearest").values
            hd, dhd = kochin[(n, round(float(b), 9))]
            H = hd + sum(x[j] * kochin[(n, d)][0] for j, d in enumerate(DOFS))
            dH = dhd + sum(x[j] * kochin[(n, d)][1] for j, d in enumerate(DOFS))
            hb, dhb = H[i_beta[h]], dH[i_beta[h]]
            h2 = np.abs(H) ** 2
            drift[n, h, 0] = (
                -2 * np.pi * RHO * w * np.cos(b) * hb.real
                - 2 * np.pi * RHO * k**2 * np.sum(h2 * np.cos(theta)) * dtheta
            )
            drift[n, h, 1] = (
                -2 * np.pi * RHO * w * np.sin(b) * hb.real
                - 2 * np.pi * RHO * k**2 * np.sum(h2 * np.sin(theta)) * dtheta
            )
            drift[n, h, 2] = (
                -(2 * np.pi * RHO * w / k) * dhb.imag
                - 2 * np.pi * RHO * k * np.sum(np.imag(np.conj(H) * dH)) * dtheta
            )
            e_s = 2 * np.pi * RHO * w * k * np.sum(h2) * dtheta
            e_int = 2 * np.pi * RHO * G * hb.real
            wdis = 0.5 * w**2 * b44 * abs(x[3]) ** 2
            energy[n, h] = [e_s, e_int, wdis, e_s + e_int + wdis]
            maruo[n, h, 0] = 2 * np.pi * RHO * k**2 * np.sum(
                h2 * (np.cos(b) - np.cos(theta))
            ) * dtheta + k / w * wdis * np.cos(b)
            maruo[n, h, 1] = 2 * np.pi * RHO * k**2 * np.sum(
                h2 * (np.sin(b) - np.sin(theta))
            ) * dtheta + k / w * wdis * np.sin(b)
            key = (float(f"{periods[n]:.4g}"), float(headings[h]))
            if key in rao_table:
                rao_check = max(rao_check, float(np.max(np.abs(x * SIGN - rao_table[key]))))

    # To the project frame: surge = Fx, sway = −Fy, yaw = −Mz.
    proj = np.zeros((nP, nH, 6))
    proj[..., 0] = maruo[..., 0]
    proj[..., 1] = -maruo[..., 1]
    proj[..., 5] = -drift[..., 2]
    # Port/starboard symmetry makes sway and yaw vanish at 0° and 180°: write round-off there as 0.
    for h, mu in enumerate(headings):
        if mu % 180.0 == 0.0:
            proj[:, h, 1] = proj[:, h, 5] = 0.0

    header = [
        "Mean (second-order) wave-drift force and moment of the built-in OSV (pl.Vessel.osv(), Fossen's 83 m supply vessel, MSS osv.m), per wave amplitude squared",
        f"Produced by scripts/osv_drift.py with Capytaine {cpt.__version__}: far-field (Maruo 1960 / Newman 1967) momentum and angular-momentum balance, deep water, zero speed, rho = {RHO:g} kg/m3, g = {G:g} m/s2,",
        "  from the Kochin functions of the diffraction and radiation problems, H = H_D + sum_j xi_j H_R,j, xi_j the motions (same hull mesh, M_RB, restoring and 0.15-critical roll damping as osv_raos.csv; see the script's docstring):",
        "  surge, sway (Maruo): F = 2 pi rho k^2 int |H(t)|^2 (e_b - e_t) dt + (k/omega) W e_b, W = 0.5 omega^2 B44 |xi_4|^2 the power absorbed by the roll damping;",
        "  yaw (Newman): M_z = -(2 pi rho omega / k) Im H'(b) - 2 pi rho k int Im(conj(H) H') dt; Capytaine frame (x fwd, y port, z up), b = wave direction, e_t = (cos t, sin t); then mapped to b.",
        "  Checks printed by the script: energy balance, Capytaine's far_field_mean_drift_force, motions = osv_raos.csv, long-wave limit, short-wave reflection limit (beam seas sway = 1.00 of it at 3 s), symmetry.",
        f"Mesh: {mesh.nb_faces} hull panels ({args.nx} along, {args.nz} per half-girth, xOz symmetry) + {lid.nb_faces}-panel lid; Kochin functions on {args.ntheta} angles.",
        "Values: mean force/moment = value * a^2 for a regular wave of amplitude a (m): surge, sway N/m2; yaw N*m/m2 about CO (z_b down, positive bow to starboard).",
        "  heave, roll, pitch are 0: the far-field method gives the horizontal drift only (the vertical mean forces and the roll/pitch drift moments are not computed).",
        "  In irregular seas the mean load is sum_i 2 S(omega_i) d_omega value(T_i, heading) (Newman's approximation for the slow drift uses the same table).",
        "Frame: project body frame b (Fossen): x forward, y starboard, z down, origin CO = amidships on the waterline; yaw moment about CO.",
        "Heading: heading_deg = direction the waves TRAVEL relative to the bow, from +x_b toward +y_b, as in osv_raos.csv: 0 = following, 90 = travelling to starboard (from port), 180 = head seas;",
        "  so the drift pushes the vessel along the waves' travel: surge < 0 at 180, > 0 at 0; sway > 0 at 90, < 0 at 270.",
        "Grid: the periods and headings of osv_raos.csv, every combination, sorted by period then heading.",
    ]
    with open(args.out, "w") as f:
        f.writelines(f"# {line}\n" for line in header)
        f.write("period_s,heading_deg,surge,sway,heave,roll,pitch,yaw\n")
        for n in range(nP):
            for h in range(nH):
                v = proj[n, h]
                f.write(f"{periods[n]:.4g},{headings[h]:g}," + ",".join(f"{x:.6g}" for x in v) + "\n")
    print(f"wrote {args.out} ({nP * nH} rows); BEM + Kochin {t_bem:.0f} s")

    # ------------------------------------------------------------ checks
    def hi(mu):
        return int(np.argmin(np.abs(headings - mu)))

    q = 0.5 * RHO * G
    print(f"\nchecks (project frame; q = ½ρg = {q:.0f} N/m³)")
    print(f"  motions vs osv_raos.csv: max |ξ − table| = {rao_check:.2e} (m/m, rad/m)")
    e_ref = 0.5 * RHO * G * (G / (2 * omegas)) * L_PP  # incident wave power over the vessel's length, W/m²
    rel = np.abs(energy[..., 3]) / e_ref[:, None]
    print(
        "  energy balance |E_s + E_int + W| / (½ρg c_g L), max over headings, by period: "
        + ", ".join(f"{periods[n]:g} s {rel[n].max():.1e}" for n in range(0, nP, max(1, nP // 8)))
        + f"; max {rel.max():.1e}"
    )
    dm = np.abs(maruo[..., 0] - drift[..., 0]) + np.abs(maruo[..., 1] - drift[..., 1])
    scale = np.abs(drift[..., 0]).max() + np.abs(drift[..., 1]).max()
    print(
        f"  direct vs Maruo's energy form: max |ΔF| = {dm.max():.3g} N/m² ({dm.max() / scale:.1%} of the largest force);"
        f" following/head seas surge, direct vs Maruo: "
        + "; ".join(
            f"{periods[n]:g} s {drift[n, hi(0), 0]:.4g}/{maruo[n, hi(0), 0]:.4g}, {drift[n, hi(180), 0]:.4g}/{maruo[n, hi(180), 0]:.4g}"
            for n in range(0, nP, max(1, nP // 8))
        )
    )
    # Capytaine's own far-field function on a few cases (diagonal of its direction pairs).
    try:
        import xarray as xr
        from capytaine.post_pro import far_field_mean_drift_force

        sel_n = [0, nP // 2, nP - 1]
        sel_h = [hi(30), hi(90), hi(180)]
        th = np.concatenate([theta, [2 * np.pi]])
        kd = np.array(
            [
                [np.concatenate([kochin[(n, round(float(capy_dirs[h]), 9))][0]] * 1) for h in sel_h]
                for n in sel_n
            ]
        )
        kd = np.concatenate([kd, kd[..., :1]], axis=-1)
        kr = np.array([[kochin[(n, d)][0] for d in DOFS] for n in sel_n])
        kr = np.concatenate([kr, kr[..., :1]], axis=-1)
        w_sel = omegas[sel_n]
        dirs = capy_dirs[sel_h]
        if np.any(dirs == 0.0):  # capytaine wants the direction strictly inside the θ interval
            raise RuntimeError("direction on the θ border")
        sub = xr.Dataset(
            {
                "kochin_diffraction": (("omega", "wave_direction", "theta"), kd),
                "kochin_radiation": (("omega", "radiating_dof", "theta"), kr),
            },
            coords={"omega": w_sel, "wave_direction": dirs, "theta": th, "radiating_dof": DOFS},
        )
        sub["wavenumber"] = ("omega", w_sel**2 / G)
        sub["water_depth"] = np.inf
        sub["rho"] = RHO
        sub["g"] = G
        xs = raos.sel(omega=w_sel, wave_direction=dirs, method="nearest").assign_coords(
            omega=w_sel, wave_direction=dirs
        )
        ff = far_field_mean_drift_force(xs.transpose("omega", "wave_direction", "radiating_dof"), sub)
        worst = np.zeros(3)
        size = np.zeros(3)
        for a, n in enumerate(sel_n):
            for c, h in enumerate(sel_h):
                ref = np.array(
                    [
                        ff[v].values[a, c, c].real
                        for v in ("drift_force_surge", "drift_force_sway", "drift_force_yaw")
                    ]
                )
                worst = np.maximum(worst, np.abs(ref - drift[n, h]))
                size = np.maximum(size, np.abs(drift[n, h]))
        size[:2] = size[:2].max()
        worst = worst / size  # relative to the largest value of the component over the cases
        print(
            f"  vs capytaine.post_pro.far_field_mean_drift_force (3 periods × 30°/90°/180°): max rel diff surge {worst[0]:.1e},"
            f" sway {worst[1]:.1e}, yaw {worst[2]:.1e} (its dH/dθ is a finite difference, here analytic)"
        )
    except (ImportError, KeyError, ValueError, RuntimeError) as exc:  # the check is informative only
        print(f"  capytaine far_field_mean_drift_force comparison skipped: {exc}")

    n0, n1 = 0, nP - 1
    print(
        f"  (a) long waves, T = {periods[n1]:g} s: |surge| max {np.abs(proj[n1, :, 0]).max():.3g}, |sway| max"
        f" {np.abs(proj[n1, :, 1]).max():.3g} N/m², |yaw| max {np.abs(proj[n1, :, 5]).max():.3g} N·m/m²"
        f"  (vs q·L = {q * L_PP:.3g} N/m²)"
    )
    for mu in (180.0, 135.0, 90.0, 45.0, 0.0):
        sw = waterline_short_wave(hull, mu)
        h = hi(mu)
        print(
            f"  (b) T = {periods[n0]:g} s (kB = {omegas[n0] ** 2 / G * BEAM:.1f}), heading {mu:g}°: surge {proj[n0, h, 0]:.4g}, sway {proj[n0, h, 1]:.4g} N/m²,"
            f" yaw {proj[n0, h, 5]:.4g} N·m/m²; short-wave reflection limit surge {sw[0]:.4g}, sway {sw[1]:.4g}, yaw {sw[2]:.4g}"
        )
    sw90 = waterline_short_wave(hull, 90.0)
    print(
        f"      beam seas sway / (½ρg L) = {proj[n0, hi(90), 1] / (q * L_PP):.3f}; / reflection limit = {proj[n0, hi(90), 1] / sw90[1]:.3f}"
    )
    sw180 = waterline_short_wave(hull, 180.0)
    print(
        f"      head seas surge / (½ρg B) = {proj[n0, hi(180), 0] / (q * BEAM):.3f}; / reflection limit = {proj[n0, hi(180), 0] / sw180[0]:.3f}"
    )
    sym = np.max(np.abs(proj[:, hi(90), 1] + proj[:, hi(270), 1]))
    print(
        f"  (c) max |sway(90°) + sway(270°)| = {sym:.3g} N/m² (max |sway(90°)| = {np.abs(proj[:, hi(90), 1]).max():.4g});"
        f" surge at 180° all < 0: {bool(np.all(proj[:, hi(180), 0] < 0))} (max {proj[:, hi(180), 0].max():.3g});"
        f" surge at 0° all > 0: {bool(np.all(proj[:, hi(0), 0] > 0))} (min {proj[:, hi(0), 0].min():.3g})"
    )
    mirror = 0.0
    for h, mu in enumerate(headings):
        hm = hi((360.0 - mu) % 360.0)
        mirror = max(
            mirror, float(np.max(np.abs(proj[:, h] - proj[:, hm] * np.array([1, -1, 1, -1, 1, -1]))))
        )
    print(f"      port/starboard mirror: max |d(μ) − mirrored d(360° − μ)| = {mirror:.3g}")
    print(
        "\n  T [s] | surge 0°   surge 180° | sway 90°  sway 45°  sway 135° | yaw 45°    yaw 135°   [N/m², N·m/m²]"
    )
    for n in range(nP):
        print(
            f"  {periods[n]:5.2f} | {proj[n, hi(0), 0]:9.4g} {proj[n, hi(180), 0]:10.4g} | {proj[n, hi(90), 1]:9.4g}"
            f" {proj[n, hi(45), 1]:9.4g} {proj[n, hi(135), 1]:9.4g} | {proj[n, hi(45), 5]:10.4g} {proj[n, hi(135), 5]:10.4g}"
        )
    print(f"\ntotal run time {time.perf_counter() - t_start:.0f} s")


if __name__ == "__main__":
    main()
