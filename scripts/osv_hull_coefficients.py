#!/usr/bin/env python3
"""Wind and current load coefficients of the built-in OSV (``pl.Vessel.osv()``, Fossen's 83 m MSS ``osv.m``).

Usage: python3 scripts/osv_hull_coefficients.py [--out-dir crates/pipelay/data]   (numpy only;
       e.g. /work/main/.venv/bin/python if the system python has no numpy)

Writes ``osv_wind.csv`` and ``osv_current.csv``: columns angle_deg, surge, sway, heave, roll, pitch, yaw for
angle_deg = 0, 10, ..., 350. Each value is a dimensional coefficient (m² for forces, m³ for moments) such that
the load in the body frame, about CO, is

    F_j = ½ ρ V_r² · value_j(γ),

V_r the relative speed, γ the relative angle, ρ the fluid's density (air for wind, sea water for current),
which the engine supplies: the tables do not contain ρ.

Conventions (as ``osv_raos.csv``): body frame b, x forward, y starboard, z down, origin CO amidships on the
waterline; roll positive starboard down, yaw positive bow to starboard. angle_deg γ is the direction the flow
TRAVELS relative to the bow, from +x_b toward +y_b: 0 = from astern travelling forward, 90 = travelling to
starboard (coming from port), 180 = head-on. So a 90° wind gives sway > 0, a 180° wind surge < 0.

Wind: Blendermann (1994), "Parameter identification of wind loads on ships", J. Wind Eng. Ind. Aerodyn. 51,
339-351, as coded in Fossen's MSS toolbox ``LIBRARY/environment/blendermann94.m`` (Fossen 2021, Handbook of
Marine Craft Hydrodynamics and Motion Control, 2nd ed., §10.1), its data row 11 "Offshore supply vessel":
CD_t = 0.90, CD_l,AF(0) = 0.55 (head wind), CD_l,AF(π) = 0.80 (wind from astern), δ = 0.55, κ = 1.2. With
γ_B Blendermann's angle (the angle the wind comes FROM, 0 = head wind, 90° = from port):

    CD_l = CD_l,AF · A_F / A_L,    den = 1 − ½ δ (1 − CD_l/CD_t) sin²(2γ_B)
    C_X = −CD_l,AF cos γ_B / den,  C_Y = CD_t sin γ_B / den,
    C_K = κ (s_H / H_M) C_Y,       C_N = (s_L / L_oa − 0.18 (|γ_B| − π/2)) C_Y,
    X = q C_X A_F,  Y = q C_Y A_L,  K = q C_K A_L H_M,  N = q C_N A_L L_oa,   q = ½ ρ_a V_r²,

H_M = A_L / L_oa the mean height of the lateral area, s_H the height of its centroid above the waterline, s_L
the distance of its centroid forward of amidships (blendermann94.m's argument descriptions have s_H and s_L
swapped; its formulas use them as here). Blendermann's formulas are for γ_B in [0, π]; the yaw bracket uses
|γ_B| so that C_N, like C_Y and C_K, is odd in γ_B (port/starboard symmetry). From the travel angle γ of this
table: the wind's velocity in b is V(cos γ, sin γ), the vessel's relative velocity −V(cos γ, sin γ), and
Fossen's γ_B = −atan2(v_r, u_r) = 180° − γ (wrapped to (−180°, 180°]); checks: γ = 180° → γ_B = 0 (head
wind, C_X < 0), γ = 90° → γ_B = 90° (from port, C_Y > 0). Roll moment about the waterline (= about CO);
K = q κ s_H C_Y A_L: the lateral force acting κ s_H above the waterline. Yaw about amidships (= CO).

Projected areas: no wind areas of this vessel are published (MSS has none; osv.m has no superstructure); they
are ESTIMATED below from the main dimensions and a typical 80-90 m PSV arrangement (forecastle, 3-tier
deckhouse and wheelhouse forward, open cargo deck aft with rails and deck cargo), see ``WIND_AREAS``. They give
A_F ≈ 299 m², A_L ≈ 667 m², s_H ≈ 5.9 m, s_L ≈ 10.2 m forward of amidships, L_oa = L = 83 m.

Current: derived from the hydrodynamics of MSS ``osv.m`` (its formulas evaluated for the 83 m OSV),
with the vessel at rest in a current of velocity V (cos γ, sin γ) in b, so that the vessel's velocity through
the water is (u_r, v_r) = −V (cos γ, sin γ):
  surge  X = X_uu |u_r| u_r (osv.m's quadratic surge damping, X_uu = −thrust_max / U_max² = −18131 kg/m < 0)
           = |X_uu| V² cos γ |cos γ|  → value = |X_uu| / (½ ρ_w) cos γ |cos γ|  (ρ_w = 1025);
           osv.m blends this with a linear law below 2 m/s; the table keeps the quadratic part.
  sway   Y = −½ ρ_w T C_d,2D ∫ |v_r| v_r dx over the length L (osv.m's crossflowDrag, Hoerner's C_d,2D(B/2T = 1.8)
           = 0.6664) = ½ ρ_w T L C_d,2D V² sin γ |sin γ| → value = T L C_d,2D sin γ |sin γ|
           (the strip sum in MSS uses 21 strips of L/20, i.e. 5 % more; the crossflow yaw moment is zero for
           r = 0 by fore-aft symmetry of the strips).
  yaw    N = −(A_22 − A_11) u_r v_r, the Munk moment of osv.m's −C_A(ν_r) ν_r (m2c.m: (C_A ν_r)_6 =
           (A_22 − A_11) u_r v_r for r = 0), A_11 = M_A[0][0] = 6.0e5 kg, A_22 = M_A[1][1] = 2.0e6 kg:
           N = −(A_22 − A_11) V² cos γ sin γ → value = −(A_22 − A_11) / ρ_w · sin 2γ (m³).
           Sign: at γ = 45° the water passes from the port quarter; N < 0 turns the bow to port, i.e. broadside
           to the flow (Munk's moment is destabilising), the same sign as the wind's C_N there.
  heave, roll, pitch: 0 (osv.m gives no current load in them).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent

L, B, T = 83.0, 18.0, 5.0
RHO_W = 1025.0
RHO_A = 1.226
# MSS osv.m: forceSurgeDamping.m (Xuu), Hoerner.m (Cd_2D), the hard-coded MA
XUU = -18131.21943  # kg/m, = −thrust_max / U_max² = −(420e3 + 655e3) / 7.7²
CD_2D = 0.6664114741  # Hoerner's 2-D crossflow drag at B/(2T) = 1.8
A11, A22 = 0.6e6, 2.0e6  # M_A[0][0], M_A[1][1], kg

# Blendermann (1994) via MSS blendermann94.m, row 11 "Offshore supply vessel".
CD_T, CD_L_BOW, CD_L_STERN, DELTA, KAPPA = 0.90, 0.55, 0.80, 0.55, 1.2

# Estimated wind areas (see the docstring): (name, lateral m², its centroid height above WL m, its centroid x
# forward of amidships m, frontal m², its centroid height m). Freeboard to main deck 2.5 m (depth 7.5 m at
# T = 5 m), forecastle 2.8 m over the forward 28 m, deckhouse 3 tiers × 2.8 m (20 m long, 16 m wide, front
# 5 m aft of the stem), wheelhouse 3.0 m (12 m long, bridge wings the full 18 m), aft cargo deck 55 m with
# rails / deck cargo 2.5 m high (shielded from ahead by the forecastle and deckhouse).
WIND_AREAS = [
    ("hull above WL", 2.5 * L, 1.25, 0.0, 2.5 * B, 1.25),
    ("forecastle", 2.8 * 28.0, 3.9, L / 2 - 14.0, 2.8 * B, 3.9),
    ("deckhouse", 8.4 * 20.0, 9.5, L / 2 - 15.0, 8.4 * 16.0, 9.5),
    ("wheelhouse", 3.0 * 12.0, 15.2, L / 2 - 11.0, 3.0 * B, 15.2),
    ("mast, funnels, crane", 40.0, 18.0, 25.0, 15.0, 18.0),
    ("aft deck cargo, rails", 2.5 * 55.0, 3.75, -L / 2 + 27.5, 0.0, 0.0),
]

ANGLES = np.arange(0.0, 360.0, 10.0)
COLUMNS = ["angle_deg", "surge", "sway", "heave", "roll", "pitch", "yaw"]


def wind_areas() -> dict[str, float]:
    a = np.array([row[1:] for row in WIND_AREAS])
    a_l, a_f = a[:, 0].sum(), a[:, 3].sum()
    return {
        "A_L": a_l,
        "A_F": a_f,
        "s_H": float((a[:, 0] * a[:, 1]).sum() / a_l),
        "s_L": float((a[:, 0] * a[:, 2]).sum() / a_l),
        "L_oa": L,
        "H_M": a_l / L,
    }


def blendermann(gamma_b: np.ndarray, w: dict[str, float]) -> np.ndarray:
    """C_X, C_Y, C_K, C_N (rows) at Blendermann's angles gamma_b (rad, from-direction, in (−π, π])."""
    g = np.asarray(gamma_b, dtype=float)
    cdl_af = np.where(np.abs(g) <= np.pi / 2, CD_L_BOW, CD_L_STERN)
    cdl = cdl_af * w["A_F"] / w["A_L"]
    den = 1.0 - 0.5 * DELTA * (1.0 - cdl / CD_T) * np.sin(2.0 * g) ** 2
    cx = -cdl_af * np.cos(g) / den
    cy = CD_T * np.sin(g) / den
    ck = KAPPA * (w["s_H"] / w["H_M"]) * cy
    cn = (w["s_L"] / w["L_oa"] - 0.18 * (np.abs(g) - np.pi / 2)) * cy
    return np.array([cx, cy, ck, cn])


def wind_table(w: dict[str, float]) -> np.ndarray:
    gamma = np.radians(ANGLES)
    gamma_b = np.angle(np.exp(1j * (np.pi - gamma)))  # 180° − γ wrapped to (−π, π]
    cx, cy, ck, cn = blendermann(gamma_b, w)
    out = np.zeros((len(ANGLES), 6))
    out[:, 0] = cx * w["A_F"]
    out[:, 1] = cy * w["A_L"]
    out[:, 3] = ck * w["A_L"] * w["H_M"]
    out[:, 5] = cn * w["A_L"] * w["L_oa"]
    return out


def current_table() -> np.ndarray:
    gamma = np.radians(ANGLES)
    c, s = np.cos(gamma), np.sin(gamma)
    out = np.zeros((len(ANGLES), 6))
    out[:, 0] = abs(XUU) / (0.5 * RHO_W) * c * np.abs(c)
    out[:, 1] = T * L * CD_2D * s * np.abs(s)
    out[:, 5] = -(A22 - A11) / RHO_W * np.sin(2.0 * gamma)
    return out


def clean(values: np.ndarray) -> np.ndarray:
    scale = np.abs(values).max(axis=0, keepdims=True)
    return np.where(np.abs(values) < 1e-12 * np.maximum(scale, 1e-300), 0.0, values)


def write(path: Path, header: list[str], values: np.ndarray) -> None:
    with open(path, "w") as f:
        f.writelines(f"# {line}\n" for line in header)
        f.write(",".join(COLUMNS) + "\n")
        f.writelines(
            f"{a:g}," + ",".join(f"{v:.6g}" for v in row) + "\n" for a, row in zip(ANGLES, clean(values))
        )


COMMON = [
    "Frame: project body frame b (Fossen): x forward, y starboard, z down, origin CO = amidships on the waterline; moments about CO (roll + starboard down, yaw + bow to starboard).",
    "angle_deg: the direction the flow TRAVELS relative to the bow, from +x_b toward +y_b: 0 = from astern travelling forward, 90 = travelling to starboard (coming from port), 180 = head-on.",
    "Values: dimensional coefficients C_j*A_j, m2 (surge, sway, heave) and m3 (roll, pitch, yaw): load F_j = 0.5 * rho * V_r^2 * value_j(angle), V_r the relative speed; rho is NOT in the table.",
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out-dir", type=Path, default=ROOT / "crates" / "pipelay" / "data")
    args = parser.parse_args()

    w = wind_areas()
    wind = wind_table(w)
    current = current_table()

    wind_header = [
        "Wind load coefficients of the built-in OSV (pl.Vessel.osv(), Fossen's 83 m supply vessel, MSS osv.m). Produced by scripts/osv_hull_coefficients.py.",
        "Source: Blendermann (1994), J. Wind Eng. Ind. Aerodyn. 51:339-351, as in Fossen's MSS blendermann94.m (Fossen 2021 Handbook, 10.1), data row 'Offshore supply vessel':",
        f"  CD_t = {CD_T}, CD_l,AF(0) = {CD_L_BOW} (head wind), CD_l,AF(pi) = {CD_L_STERN} (from astern), delta = {DELTA}, kappa = {KAPPA}.",
        "Formula (gB = Blendermann's from-angle = 180 - angle_deg, wrapped to (-180, 180]; 0 = head wind): CD_l = CD_l,AF A_F/A_L, den = 1 - 0.5 delta (1 - CD_l/CD_t) sin^2(2 gB),",
        "  C_X = -CD_l,AF cos(gB)/den, C_Y = CD_t sin(gB)/den, C_K = kappa (s_H/H_M) C_Y, C_N = (s_L/L_oa - 0.18 (|gB| - pi/2)) C_Y;",
        "  surge = C_X A_F, sway = C_Y A_L, roll = C_K A_L H_M (= kappa s_H C_Y A_L, about the waterline), yaw = C_N A_L L_oa (about amidships).",
        "Areas (ESTIMATED from the main dimensions and a typical 80-90 m PSV layout - forecastle, 3-tier deckhouse + wheelhouse forward, cargo deck aft; no published data; see the script):",
        (
            f"  A_F = {w['A_F']:.1f} m2, A_L = {w['A_L']:.1f} m2, L_oa = {w['L_oa']:g} m (= L), H_M = A_L/L_oa = {w['H_M']:.3f} m,"
            f" s_H = {w['s_H']:.3f} m (centroid above WL), s_L = {w['s_L']:.3f} m (centroid forward of amidships). Loads scale linearly with the areas."
        ),
        "heave, pitch: 0 (Blendermann gives none). rho: air, e.g. 1.226 kg/m3 (MSS uses 1.224).",
    ] + COMMON
    current_header = [
        "Current load coefficients of the built-in OSV (pl.Vessel.osv(), Fossen's 83 m supply vessel, MSS osv.m). Produced by scripts/osv_hull_coefficients.py.",
        "Source: the hydrodynamics of MSS osv.m (Fossen 2021, eqs. 6.111-6.116), vessel at rest in a current V (cos a, sin a) in b, i.e. moving through the water at (u_r, v_r) = -V (cos a, sin a):",
        f"  surge = |X_uu| / (0.5 rho_w) cos a |cos a|, from osv.m's quadratic surge damping X = X_uu |u_r| u_r, X_uu = -thrust_max/U_max^2 = {XUU:.2f} kg/m (rho_w = {RHO_W:g}; the linear law osv.m blends in below 2 m/s is left out);",
        f"  sway = T L Cd_2D sin a |sin a|, from osv.m's crossflow drag -0.5 rho_w T Cd_2D int |v_r| v_r dx, T = {T:g} m, L = {L:g} m, Hoerner Cd_2D(B/2T = 1.8) = {CD_2D:.4f} (T L Cd_2D = {T * L * CD_2D:.2f} m2);",
        f"  yaw = -(A_22 - A_11)/rho_w sin(2a), the Munk moment N = -(A_22 - A_11) u_r v_r of osv.m's -C_A(nu_r) nu_r, A_11 = M_A[0][0] = {A11:.3g} kg, A_22 = M_A[1][1] = {A22:.3g} kg ((A_22 - A_11)/rho_w = {(A22 - A11) / RHO_W:.2f} m3);",
        "  sign: at 45 deg the water comes from the port quarter and N < 0 turns the bow to port (broadside to the flow, destabilising). The crossflow yaw moment is 0 for a vessel at rest (symmetric strips).",
        "heave, roll, pitch: 0 (osv.m gives no current load in them). rho: sea water, 1025 kg/m3.",
    ] + COMMON

    args.out_dir.mkdir(parents=True, exist_ok=True)
    write(args.out_dir / "osv_wind.csv", wind_header, wind)
    write(args.out_dir / "osv_current.csv", current_header, current)
    print(
        f"wrote {args.out_dir / 'osv_wind.csv'} and {args.out_dir / 'osv_current.csv'} ({len(ANGLES)} rows each)"
    )

    # Checks.
    print("\nwind areas (estimated):")
    for name, al, h, x, af, _hf in WIND_AREAS:
        print(f"  {name:24s} A_L {al:6.1f} m² at h = {h:5.2f} m, x = {x:6.2f} m; A_F {af:6.1f} m²")
    print(
        f"  total A_L = {w['A_L']:.1f} m², A_F = {w['A_F']:.1f} m², s_H = {w['s_H']:.2f} m, s_L = {w['s_L']:.2f} m,"
        f" H_M = {w['H_M']:.2f} m"
    )

    def at(table, angle):
        return table[int(np.argmin(np.abs(ANGLES - angle)))]

    q_w = 0.5 * RHO_A * 20.0**2
    q_c = 0.5 * RHO_W * 1.0**2
    print(
        f"\nchecks (wind 20 m/s, rho_a = {RHO_A}: q = {q_w:.1f} Pa; current 1 m/s, rho_w = {RHO_W:g}: q = {q_c:.1f} Pa)"
    )
    print(
        f"  head wind (180°):      surge {q_w * at(wind, 180)[0] / 1e3:8.2f} kN  (C_X = {at(wind, 180)[0] / w['A_F']:.3f})"
    )
    print(f"  following wind (0°):   surge {q_w * at(wind, 0)[0] / 1e3:8.2f} kN")
    r = at(wind, 90)
    print(
        f"  beam wind (90°):       sway {q_w * r[1] / 1e3:8.2f} kN, roll {q_w * r[3] / 1e3:8.1f} kN·m"
        f" (arm {r[3] / r[1]:.2f} m), yaw {q_w * r[5] / 1e3:8.1f} kN·m (arm {r[5] / r[1]:.2f} m forward)"
    )
    r = at(wind, 270)
    print(
        f"  beam wind (270°):      sway {q_w * r[1] / 1e3:8.2f} kN, roll {q_w * r[3] / 1e3:8.1f} kN·m, yaw {q_w * r[5] / 1e3:8.1f} kN·m"
    )
    r = at(wind, 150)
    print(
        f"  bow-quarter wind (150°, from 30° port bow): surge {q_w * r[0] / 1e3:.2f} kN, sway {q_w * r[1] / 1e3:.2f} kN, yaw {q_w * r[5] / 1e3:.1f} kN·m"
    )
    print(f"  head current (180°):   surge {q_c * at(current, 180)[0] / 1e3:8.2f} kN")
    r = at(current, 90)
    print(f"  beam current (90°):    sway {q_c * r[1] / 1e3:8.2f} kN")
    r = at(current, 45)
    print(
        f"  current 45°:           surge {q_c * r[0] / 1e3:.2f} kN, sway {q_c * r[1] / 1e3:.2f} kN, yaw {q_c * r[5] / 1e3:.1f} kN·m"
        f" (Munk, (A22 − A11)/2 · V² = {(A22 - A11) / 2 / 1e3:.0f} kN·m)"
    )
    sym_w = np.max(np.abs(wind - wind[(36 - np.arange(36)) % 36] * np.array([1, -1, 1, -1, 1, -1])))
    sym_c = np.max(np.abs(current - current[(36 - np.arange(36)) % 36] * np.array([1, -1, 1, -1, 1, -1])))
    print(
        f"  port/starboard symmetry (value(γ) vs mirrored value(360° − γ)): wind {sym_w:.1e}, current {sym_c:.1e}"
    )


if __name__ == "__main__":
    main()
