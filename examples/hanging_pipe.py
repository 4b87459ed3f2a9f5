"""Static shape of a 1200 m steel pipe hanging in 800 m of water.

The pipe (outer diameter 0.6 m, wall 15 mm, steel 7850 kg/m³, E = 207 GPa) is pinned at the seabed, at the
origin A = (0, 0, 0), and at the top B = (850, 0, −800) m at the sea surface; e3 points down, so the sea surface
is the plane z = −800 m. It is flooded (contents: sea water, 1025 kg/m³), so its submerged weight is the paper's
(m_P − ρ_w A) g = 1845.7 N/m: an *empty* pipe of these dimensions floats (its submerged weight is −720 N/m).

The rod's stress-free reference is straight and horizontal, along e1; the solver starts Newton from Irvine's
elastic catenary through A and B (``model.static()``'s default for a line held at both ends).

Prints the top tension (kN: the effective tension of the top element, as `pipelay static` prints it), the
reaction at B |F_B| (kN: the pull on the top support, Irvine's cable tension at B), the horizontal tension (kN)
and the touchdown angle (deg, of the pipe axis at A above the seabed), and writes a side view to
``hanging_pipe.png`` in the directory given by ``--out``.

Usage::

    python examples/hanging_pipe.py [--out DIR] [--elements N]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib
import numpy as np
import pipelay as pl

matplotlib.use("Agg")

LENGTH = 1200.0  # m, unstretched pipe length
DEPTH = 800.0  # m, water depth
TOP = (850.0, 0.0, -DEPTH)  # m, top end B at the sea surface
OUTER_DIAMETER = 0.6  # m
WALL_THICKNESS = 0.015  # m
SEA_WATER = 1025.0  # kg/m³


def solve(elements: int = 100) -> pl.State:
    """Static equilibrium of the pinned–pinned flooded pipe with ``elements`` elements."""
    section = pl.Section.pipe(OUTER_DIAMETER, WALL_THICKNESS, contents_density=SEA_WATER)
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (LENGTH, 0.0, 0.0), elements, section)
    model = pl.Model(rod, sea=pl.Sea(DEPTH, density=SEA_WATER))
    model.pin("A")
    model.pin("B", position=TOP)
    return model.static()


def summary(state: pl.State) -> dict[str, float]:
    """Top tension (kN, the top element's effective tension), reaction at B |F_B| (kN), horizontal tension (kN)
    and touchdown angle (deg) of a solved state."""
    force_a = state.reaction("A")[:3]
    force_b = state.reaction("B")[:3]
    axis_a = state.rotations[0][:, 0]  # t1 at A, in e
    touchdown = math.degrees(math.atan2(-axis_a[2], math.hypot(axis_a[0], axis_a[1])))  # above the seabed
    return {
        "top_tension_kN": float(state.tension[-1]) / 1e3,
        "reaction_B_kN": float(np.linalg.norm(force_b)) / 1e3,
        "horizontal_tension_kN": float(math.hypot(force_a[0], force_a[1])) / 1e3,
        "touchdown_angle_deg": touchdown,
    }


def plot(state: pl.State, path: Path) -> None:
    """Side view (x against elevation above the seabed, −z) with the sea surface and the seabed."""
    import matplotlib.pyplot as plt  # after matplotlib.use("Agg")

    x = state.positions[:, 0]
    elevation = -state.positions[:, 2]
    fig, ax = plt.subplots(figsize=(8.0, 6.0), constrained_layout=True)
    left, right = -50.0, TOP[0] + 100.0
    ax.axhline(DEPTH, color="tab:blue", linewidth=1.0, label="sea surface")
    ax.axhline(0.0, color="saddlebrown", linewidth=1.5, label="seabed")
    ax.fill_between([left, right], 0.0, -40.0, color="tan", alpha=0.5)
    ax.plot(x, elevation, color="black", linewidth=2.0, label=f"pipe ({len(x) - 1} elements)")
    ax.plot([x[0], x[-1]], [elevation[0], elevation[-1]], "o", color="tab:red", label="pinned ends A, B")
    ax.set_xlim(left, right)
    ax.set_ylim(-40.0, DEPTH + 60.0)
    ax.set_aspect("equal")
    ax.set_xlabel("horizontal distance x (m)")
    ax.set_ylabel("elevation above the seabed −z (m)")
    ax.set_title("1200 m flooded steel pipe (OD 0.6 m, wall 15 mm) in 800 m of water")
    ax.legend(loc="upper left")
    ax.grid(True, alpha=0.3)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """Solve, print the results and write the picture."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("."), help="directory for hanging_pipe.png")
    parser.add_argument("--elements", type=int, default=100, help="number of elements (default 100)")
    args = parser.parse_args(argv)

    state = solve(args.elements)
    results = summary(state)
    print(f"elements                {args.elements}")
    print(f"Newton iterations       {state.iterations} in {state.steps} load step(s)")
    print(f"top tension             {results['top_tension_kN']:.1f} kN (effective, the top element)")
    print(f"reaction at B |F_B|     {results['reaction_B_kN']:.1f} kN")
    print(f"horizontal tension      {results['horizontal_tension_kN']:.1f} kN")
    print(f"touchdown angle         {results['touchdown_angle_deg']:.2f} deg")

    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / "hanging_pipe.png"
    plot(state, path)
    print(f"picture                 {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
