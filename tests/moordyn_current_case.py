"""The peer-code case of statics in a 3-D current, shared by ``tests/test_moordyn_current.py``: the 90 mm
steel wire rope of ``moordyn_case`` held between two fixed points in a steady current across the vertical
plane of its ends, its static shape and end forces found by pipelay (``model.static()``) and by MoorDyn v2.

SI units. Frames as in ``moordyn_case``: pipelay's frame e has its origin at the anchor A (node 0), e1
horizontal towards the top B, e3 pointing down and the sea surface at z = −depth; MoorDyn's frame has z up and
the surface at z = 0, with A at (0, 0, −depth), so (x, y, z)_MoorDyn = (x, y, −depth − z)_e. A and B lie in
the plane y = 0; the current's e2 (y) component is across that plane.

The line (unstretched length 250 m, w = 328.4 N/m, EA = 400 MN, normal Cd = 1.2 on d = 0.09 m) is pinned at
A, 200 m deep, and at B, 150 m across and 180 m up (20 m below the surface); in still water it hangs as an
elastic catenary leaving A almost horizontally, top tension 85.08 kN. Two currents:

* ``UNIFORM``: 1.0 m/s along e2 at every depth, straight across the plane of A and B: the line swings
  downstream by 8.72 m at mid-length (5.8 % of the 150 m span), 9.13 m at most; top tension 86.04 kN;
* ``SHEARED``: a linear profile at 45° to the plane, 1.5 m/s along (e1 + e2)/√2 at the surface falling to zero
  at A's depth (pipelay's ``pl.Current.linear``; in MoorDyn a profile of two rows, at A's depth and at the
  surface): 1.89 m lateral offset at mid-length (1.3 % of the span), 1.97 m at most, the in-plane part pushing
  the line towards B; top tension 86.55 kN.

How the two codes are matched: weight, buoyancy, EA, normal drag on d with axial drag off, the cable (or the
rod with EI = GJ = 10 N·m² that imitates it) exactly as in ``moordyn_case``. pipelay's forces on the supports
are ``state.reaction(end)``, MoorDyn's the forces on its two coupled points (A and B are both coupled points,
held still): both are the force of the line on the support, the end node's half-segment weight and drag
included. Two differences are left, both small against the mesh error at n = 50 (measured when written,
numbers in ``test_moordyn_current.py``):

* pipelay's drag acts on the element's stretched length |x₂ − x₁| (in statics and in time), MoorDyn's on the
  unstretched length: pipelay's drag is larger by the strain T/EA (0.7e-4 at A to 2.2e-4 at B here), and its
  lateral offsets by 1.1e-4 at any n (with EA ten times smaller, by 1.1e-3: the difference scales with the
  strain);
* pipelay takes the current at each element's mid-depth, MoorDyn at the nodes: in the sheared current the
  lateral offsets differ by a further 1.0e-3 at n = 50 and 2.8e-4 at n = 100 (second order).

How MoorDyn takes the current (v2.7.2, the version the ``moordyn`` package installs): the option
``Currents 1`` (steady current grid) with ``WaveKin 0`` in the input file's OPTIONS, and a file
``current_profile.txt`` in the input file's folder: three header lines, then rows ``z ux uy uz`` (z in its
frame, ascending, m; m/s), interpolated linearly in z and held at the end values beyond them. Its
initial-condition solve runs without currents: its log says "Water kinematics for IC gen: No Waves or
Currents" and the current is read only after it ("Water kinematics for runtime"), so a line at its initial
condition has no lateral offset at all. (Calling ``Init`` a second time does run the stationary IC solver in
the current, but its pseudo-time steps, bounded by the axial wave speed, move the soft lateral mode by 0.58 m
of the 8.72 m in 300 s.) MoorDyn's static solution in the current is therefore its own time integration
relaxed to rest: its initial condition (the still-water line), then A and B held still while the line settles
in the current, ``window`` seconds at a time, until no node moves by ``settle`` metres over a window. At rest
the relative velocity is the current itself, so the state it settles to is MoorDyn's static equilibrium,
whatever its time scheme and step. The slowest mode, the line swinging across the current, is overdamped by
the drag and decays by e every ≈ 14 s in the uniform current: ``settle`` = 1e-5 m is reached after 175 s of
simulated time (≈ 6 s of MoorDyn's time at n = 50; 50 s and ≈ 3 s in the sheared current) and leaves the state
within 2e-5 m and 0.01 N of the one settled to 1e-7 m. MoorDyn runs RK4 with internal damping BA = −1
(critical, for the segments' axial oscillation, which the drag hardly damps; it acts on the strain rate and so
vanishes at rest).
"""

from __future__ import annotations

import math
import os
import tempfile
import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import pipelay as pl
from moordyn_case import Case, _quiet, line_section, moordyn_file, moordyn_point

__all__ = [
    "SHEARED",
    "UNIFORM",
    "CurrentCase",
    "Static",
    "current_profile",
    "lateral_offsets",
    "moordyn_input",
    "pipelay_current",
    "pipelay_model",
    "run_moordyn",
    "run_pipelay",
    "shape_at",
]


@dataclass(frozen=True)
class CurrentCase(Case):
    """The line, its two fixed ends and the current: the fields of ``moordyn_case.Case`` (the drive's are not
    used) and the current's. Lengths in m, velocities in m/s, forces in N."""

    rise: float = 180.0  # height of B above A (m)
    current: tuple[float, float, float] = (
        0.0,
        1.0,
        0.0,
    )  # velocity in e (m/s): everywhere, or at the surface
    shear: bool = False  # False: uniform; True: linear from ``current`` at the surface to zero at A's depth

    @property
    def top(self) -> tuple[float, float, float]:
        """Position of B in e (m)."""
        return (self.x0, 0.0, -self.rise)


UNIFORM = CurrentCase()
SHEARED = CurrentCase(current=(1.5 * math.sqrt(0.5), 1.5 * math.sqrt(0.5), 0.0), shear=True)


@dataclass(frozen=True)
class Static:
    """A static solution: node positions (n+1, 3) in e (m), node 0 at A; the forces of the line on the
    supports at A and B (3,) in e (N); the wall time of the solve (s); for MoorDyn, the simulated time it
    relaxed in the current (s) and the largest node displacement over its last window (m), both 0 for
    pipelay."""

    positions: np.ndarray
    force_a: np.ndarray
    force_b: np.ndarray
    wall: float
    relaxed: float = 0.0
    last_motion: float = 0.0

    @property
    def elements(self) -> int:
        """Number of elements (segments) n."""
        return len(self.positions) - 1


def pipelay_current(case: CurrentCase) -> pl.Current:
    """The case's current in pipelay: ``pl.Current.uniform`` or ``pl.Current.linear`` of ``case.current``."""
    if case.shear:
        return pl.Current.linear(case.current)
    return pl.Current.uniform(case.current)


def pipelay_model(n: int, case: CurrentCase = UNIFORM) -> pl.Model:
    """The pipelay model with ``n`` elements (cable elements if ``case.cable``, else the rod with EI = GJ =
    ``case.ei``): a straight stress-free reference from A along e1, A pinned at the origin, B pinned at
    ``case.top``, in the case's current."""
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (case.length, 0.0, 0.0), n, line_section(case))
    sea = pl.Sea(case.depth, density=case.rho_water, current=pipelay_current(case))
    model = pl.Model(rod, sea=sea, gravity=case.gravity)
    model.pin("A")
    model.pin("B", position=case.top)
    return model


def run_pipelay(n: int, case: CurrentCase = UNIFORM) -> Static:
    """pipelay's static solution (``model.static()``, its default start) on ``n`` elements."""
    model = pipelay_model(n, case)
    began = time.perf_counter()
    state = model.static()
    wall = time.perf_counter() - began
    return Static(
        np.array(state.positions, dtype=float),
        np.array(state.reaction("A")[:3], dtype=float),
        np.array(state.reaction("B")[:3], dtype=float),
        wall,
    )


def current_profile(case: CurrentCase) -> str:
    """MoorDyn's ``current_profile.txt`` for the case: three header lines, then ``z ux uy uz`` at A's depth
    and at the surface (z up in MoorDyn's frame, m; velocities in m/s, z components of opposite sign to
    e3's)."""
    ux, uy, uz = case.current
    bottom = (0.0, 0.0, 0.0) if case.shear else (ux, uy, -uz)
    rows = [(-case.depth, bottom), (0.0, (ux, uy, -uz))]
    lines = ["--------------------- MoorDyn steady currents file ---------------------"]
    lines.append("pipelay peer comparison: the current's velocity at each depth")
    lines.append("z (m), ux (m/s), uy (m/s), uz (m/s)")
    lines += [f"{z!r} {u[0]!r} {u[1]!r} {u[2]!r}" for z, u in rows]
    return "\n".join(lines) + "\n"


def moordyn_input(
    n: int, dt: float, case: CurrentCase = UNIFORM, ic_time: float = 60.0, ba: float = -1.0
) -> str:
    """The MoorDyn v2 input file for ``n`` segments, internal step ``dt`` (s, RK4), internal damping ``ba``
    (N·s; negative: minus the damping ratio) and at most ``ic_time`` (s) of its initial-condition solve. A and
    B are coupled points (held still by the caller), the seabed 50 m below A, out of reach; the current from
    ``current_profile.txt`` (``Currents 1``, no waves)."""
    a = (0.0, 0.0, -case.depth)
    b = (case.x0, 0.0, -case.depth + case.rise)
    options = [
        f"{case.depth + 50.0!r}  WtrDpth",
        "1.0  dtIC",
        f"{ic_time!r}  TmaxIC",
        "1e-7  threshIC",
        "0  WaveKin",
        "1  Currents",
    ]
    title = "pipelay peer comparison: steel wire rope between two fixed points in a steady current"
    points = (moordyn_point("Coupled", a), moordyn_point("Coupled", b))
    return moordyn_file(title, n, case, ba, points, dt, "RK4", options)


def run_moordyn(
    n: int,
    dt: float,
    case: CurrentCase = UNIFORM,
    ic_time: float = 60.0,
    window: float = 5.0,
    settle: float = 1e-5,
    max_time: float = 600.0,
) -> Static:
    """MoorDyn's static solution in the current on ``n`` segments: its initial-condition solve (at most
    ``ic_time`` s, without the current, as MoorDyn does it), then its time integration at step ``dt`` (s) with
    A and B held still, ``window`` s at a time, until the largest node displacement over a window is below
    ``settle`` (m). Raises RuntimeError if MoorDyn fails or has not settled after ``max_time`` s."""
    import moordyn  # type: ignore[import-untyped]

    ends = np.array([0.0, 0.0, -case.depth, case.x0, 0.0, -case.depth + case.rise])
    still = np.zeros(6)
    began = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="pipelay-moordyn-current-") as folder:
        path = os.path.join(folder, "line.txt")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(moordyn_input(n, dt, case, ic_time))
        with open(os.path.join(folder, "current_profile.txt"), "w", encoding="utf-8") as handle:
            handle.write(current_profile(case))
        with _quiet():
            system = moordyn.Create(path)
        try:
            with _quiet():
                err = moordyn.Init(system, ends, still)
            if err != 0:
                raise RuntimeError(f"MoorDyn's initialisation failed (error {err}), n = {n}, dt = {dt} s")
            line = moordyn.GetLine(system, 1)
            positions = _node_positions(moordyn, line, n)
            t, motion = 0.0, math.inf
            while motion >= settle:
                if t >= max_time:
                    raise RuntimeError(
                        f"MoorDyn did not settle in the current within {max_time} s (n = {n}, dt = {dt} s): "
                        f"nodes still move by {motion:.3g} m in {window} s"
                    )
                with _quiet():
                    forces = np.array(moordyn.Step(system, ends, still, t, window), dtype=float)
                t += window
                settled = _node_positions(moordyn, line, n)
                motion = float(np.max(np.abs(settled - positions)))
                positions = settled
        finally:
            moordyn.Close(system)
    wall = time.perf_counter() - began
    if not (np.all(np.isfinite(forces)) and np.all(np.isfinite(positions))):
        raise RuntimeError(f"MoorDyn's state is not finite (n = {n}, dt = {dt} s)")
    to_e = np.array([1.0, 1.0, -1.0])
    positions_e = np.column_stack([positions[:, 0], positions[:, 1], -case.depth - positions[:, 2]])
    return Static(positions_e, forces[:3] * to_e, forces[3:] * to_e, wall, t, motion)


def _node_positions(moordyn: Any, line: Any, n: int) -> np.ndarray:
    """The positions (n+1, 3) of a MoorDyn line's nodes in MoorDyn's frame (m)."""
    return np.array([moordyn.GetLineNodePos(line, i) for i in range(n + 1)], dtype=float)


def shape_at(solution: Static, arc_lengths: np.ndarray, length: float) -> np.ndarray:
    """The line's position (k, 3) in e (m) at reference (unstretched) arc lengths from A (m), interpolated
    linearly between the nodes, which sit at equal reference arc lengths along a line of ``length`` (m) in
    both codes."""
    nodes = np.linspace(0.0, length, solution.elements + 1)
    return np.column_stack([np.interp(arc_lengths, nodes, solution.positions[:, k]) for k in range(3)])


def lateral_offsets(solution: Static, length: float) -> tuple[float, float]:
    """The line's offset across the vertical plane of A and B (its e2 component, m): at mid-length
    (interpolated) and the largest at a node."""
    middle = float(shape_at(solution, np.array([0.5 * length]), length)[0, 1])
    return middle, float(np.max(solution.positions[:, 1]))


def study() -> None:
    """Print the resolution study quoted in ``test_moordyn_current.py`` and docs/validation.md: both codes at
    n = 50 and 100 (MoorDyn at dt = 1e-3 and 5e-4 s), pipelay's cable at n = 800 as the continuum, and each
    code's change from n = 50 to 100. ≈ 1 min, most of it MoorDyn's relaxation at n = 100."""
    for name, case in (("uniform", UNIFORM), ("sheared", SHEARED)):
        fine = run_pipelay(800, replace(case, cable=True))
        print(f"{name}: pipelay cable n = 800: {_summary(fine, case)}")
        samples = np.linspace(0.0, case.length, 51)
        runs: dict[tuple[str, int], Static] = {}
        for n, dt in ((50, 1e-3), (100, 5e-4)):
            runs["rod", n] = run_pipelay(n, case)
            runs["cable", n] = run_pipelay(n, replace(case, cable=True))
            runs["MoorDyn", n] = theirs = run_moordyn(n, dt, case)
            for label in ("rod", "cable", "MoorDyn"):
                ours = runs[label, n]
                shape = np.max(np.linalg.norm(ours.positions - theirs.positions, axis=1)) / case.length
                against = f"  shape − MoorDyn's {shape:.1e} L" if ours is not theirs else ""
                print(
                    f"  n = {n} {label:8s} {_summary(ours, case)}{against}"
                    f"  ({ours.wall:.3f} s" + (f", relaxed {ours.relaxed:.0f} s)" if ours.relaxed else ")")
                )
        for label in ("cable", "MoorDyn"):
            coarse, finer = runs[label, 50], runs[label, 100]
            shape = np.linalg.norm(
                shape_at(coarse, samples, case.length) - shape_at(finer, samples, case.length), axis=1
            )
            middle = lateral_offsets(coarse, case.length)[0] / lateral_offsets(finer, case.length)[0] - 1.0
            anchor = np.linalg.norm(coarse.force_a - finer.force_a) / np.linalg.norm(finer.force_a)
            print(
                f"  {label} n = 50 against 100: |F_B| {_ratio(coarse.force_b, finer.force_b):+.1e},"
                f" F_A {anchor:.1e}, lateral mid {middle:+.1e}, shape {np.max(shape) / case.length:.1e} L"
            )


def _ratio(a: np.ndarray, b: np.ndarray) -> float:
    """|a| / |b| − 1 (-)."""
    return float(np.linalg.norm(a) / np.linalg.norm(b) - 1.0)


def _summary(solution: Static, case: CurrentCase) -> str:
    """|F_B| (N), F_A (N) and the lateral offsets (m) of a solution, in one line."""
    middle, largest = lateral_offsets(solution, case.length)
    anchor = np.array2string(solution.force_a, precision=2)
    return (
        f"|F_B| {np.linalg.norm(solution.force_b):.2f} N, F_A {anchor} N,"
        f" lateral {middle:.4f} m at mid-length, {largest:.4f} m at most"
    )


if __name__ == "__main__":
    study()
