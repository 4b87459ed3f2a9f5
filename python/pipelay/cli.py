"""The ``pipelay`` command line.

    pipelay run SCENARIO -o RESULTS.nc [--plots DIR] [--checkpoint FILE] [--resume FILE] [--no-progress]
    pipelay static SCENARIO [--plots DIR] [--target QUANTITY=VALUE[UNIT] [--bracket LOW,HIGH] [--max-solves N]]
    pipelay check SCENARIO
    pipelay plot RESULTS.nc --plots DIR
    pipelay sweep SCENARIO --over KEY=V1,V2,... [--over ...] -o DIR [--scheduler ADDRESS | --workers N]
    pipelay plot DIR/summary.nc --variable NAME [--limit VALUE] [--select KEY=VALUE] [-o FILE]
    pipelay schema [-o FILE]
    pipelay capability SCENARIO [--headings-step DEG] [--current M/S] [--max-wind M/S] [--plot FILE]
    pipelay fatigue SCENARIO --scatter TABLE.csv --hours H -o DIR [--curve D] [--environment ENV] [--scf F]
        [--method rainflow|dirlik|narrow_band] [--start S] [--scheduler ADDRESS | --workers N]
    pipelay view RESULTS.nc [-o RUN.html] [--video RUN.mp4] [--colour tension|moment|strain|utilisation]
        [--frames N] [--scenario SCENARIO]
    pipelay report RESULTS.nc|SWEEP_DIR [-o REPORT.html] [--scenario SCENARIO]
    pipelay lay-table SCENARIO --depths FROM:TO:STEP|D1,D2,... --target QUANTITY=VALUE[UNIT] -o TABLE.csv
        [--netcdf TABLE.nc] [--plot FILE] [--max-solves N] [--scheduler ADDRESS | --workers N]

    pipelay --version

--plots DIR makes DIR (and its parents) before anything is solved. `pipelay static` prints the top tension
(the effective tension where the vessel holds the pipe), the reaction's magnitude at end B, the touchdown, the
lay summary (over a stinger: the lift-off roller, overbend strain, tip clearance and roller reactions, rollers
numbered from 1, the first on the stinger), the DNV-ST-F101 checks and the vessel's pose.
`pipelay run` streams the records to RESULTS.nc as the run goes (RESULTS.nc.part until it ends; memory stays
flat however long the run), then prints a summary read from the file; --plots reads the whole file back.
`pipelay static --target` moves the vessel along e1 until a lay quantity reaches VALUE, in the unit `pipelay
static` prints it in (kN, degrees, m, %) or in the UNIT given (pipelay.analysis.lay.find_lay_position, at most
--max-solves static solves).
`pipelay sweep` runs the scenario for every combination of the --over values on Dask
(pipelay.analysis.sweep): a local cluster of --workers processes (default: one a core) or the scheduler at
--scheduler; the cases' results and the summary go to DIR (DIR/summary.nc), and finished cases found there
are not run again. `pipelay plot`
on a summary draws the operability map of a statistic over two swept keys. `pipelay schema` prints the
scenario files' JSON Schema. `pipelay capability` solves the scenario's statics for the pipe's load on the
vessel and prints the DP capability envelope (pipelay.analysis.capability): the largest wind speed the
thrusters hold at each heading the environment comes from, with a co-linear current and the Beaufort scale's sea.
`pipelay fatigue` runs the scenario in every sea state of the scatter diagram TABLE.csv (columns hs, tp,
probability and optionally heading in degrees) as a sweep, and prints the fatigue damage of a standby of H hours
(pipelay.analysis.fatigue): DNV-RP-C203 curve --curve in --environment, with the thickness effect of each
segment's wall; DIR/fatigue.nc holds the damage along the pipe and DIR/damage.png draws it.
`pipelay view` writes the 3-D replay of a run as one HTML file that opens offline in a browser
(pipelay.plots.replay), and with --video an mp4 (pipelay.plots.video); `pipelay report` writes the HTML report
of a run or of a sweep's folder (pipelay.report). Both rebuild the model (rollers, seabed, waves, section) from
the scenario the results file keeps (written by `pipelay run` and sweeps), or from --scenario.
`pipelay lay-table` places the vessel at each water depth so that the --target is met, as `static --target`
(pipelay.analysis.lay_table), and writes the table in kN, degrees and percent (TABLE.csv), in SI units
(--netcdf) and its figure (--plot); a depth where the target is not met is a row without numbers, its reason
printed, and exits 1.

Exit codes: 0 success, 1 a failed solve (Newton did not converge; the results computed before the failure are
still written; for a sweep: a case failed, the others are written), 2 bad input (the message names the
scenario key; no traceback), 130 interrupted by Ctrl-C (the results computed so far are written, and a
checkpoint if asked for; for a sweep: the finished cases and the summary).
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import re
import sys
import tomllib
from pathlib import Path
from typing import Any

import numpy as np

import pipelay as pl
from pipelay import plots
from pipelay.analysis.capability import dp_capability
from pipelay.analysis.lay import (
    MAX_SOLVES,
    RANGES,
    TARGETS,
    TargetNotReached,
    check_target,
    find_lay_position,
)
from pipelay.analysis.suspect import PhysicsWarning, worst_of_each_kind
from pipelay.analysis.sweep import SUMMARY_TITLE, _label, sweep
from pipelay.analysis.sweep import run as run_simulation
from pipelay.analysis.sweep import start as start_simulation
from pipelay.results import checkpoint, load
from pipelay.scenario import Scenario, load_scenario, parse_scenario

INTERRUPTED = 130

_TARGET_UNITS: dict[str, tuple[str, dict[str, float], str]] = {
    "top_tension": ("kN", {"kN": 1e3, "N": 1.0, "MN": 1e6}, "1000 (kN), 1e6N, 1MN"),
    "departure_angle": (
        "°",
        {"deg": math.pi / 180, "°": math.pi / 180, "rad": 1.0},
        "62 (degrees below the horizontal), 62deg, 62°, 1.08rad",
    ),
    "layback": ("m", {"m": 1.0}, "500 (m)"),
    "touchdown_arc_length": ("m", {"m": 1.0}, "200 (m from end A)"),
    "sagbend_strain": ("%", {"%": 0.01}, "0.15 (%), 0.15%"),
    "overbend_strain": ("%", {"%": 0.01}, "0.2 (%)"),
    "sagbend_utilisation": ("", {"": 1.0}, "0.8"),
}
"""`--target`'s quantities: the unit `pipelay static` prints each in (a bare number's unit), the units that may
be written after the number with their size in SI units (rad for angles, a fraction for strains), examples."""

_NUMBER = re.compile(r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*)")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pipelay", description="Offshore pipelay simulation from scenario files."
    )
    parser.add_argument("--version", action="version", version=f"pipelay {pl.__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser(
        "run",
        help="statics, then a simulation to solver.t_end (or through the stages); writes netCDF results",
    )
    run.add_argument("scenario", type=Path, help="scenario file (TOML)")
    run.add_argument(
        "-o",
        "--output",
        type=Path,
        required=True,
        help="results file (netCDF), written as the run goes (OUTPUT.part until it ends)",
    )
    run.add_argument("--plots", type=Path, help="directory for figures (reads the whole results file back)")
    run.add_argument(
        "--checkpoint", type=Path, help="write the final (or interrupted) state here to resume later"
    )
    run.add_argument("--resume", type=Path, help="continue from a checkpoint instead of the static state")
    run.add_argument("--no-progress", action="store_true", help="no progress bar")
    static = commands.add_parser(
        "static",
        help="static equilibrium: prints the top tension, reactions, lay summary, checks and vessel pose",
    )
    static.add_argument("scenario", type=Path, help="scenario file (TOML)")
    static.add_argument(
        "--plots", type=Path, help="directory for the tension and bending (and lay configuration) figures"
    )
    static.add_argument(
        "--target",
        metavar="QUANTITY=VALUE[UNIT]",
        help="move the vessel along e1 until a lay quantity reaches a value, in the unit this command prints "
        "it in or with a unit: "
        + "; ".join(f"{q}={_TARGET_UNITS[q][2]}" for q in TARGETS).replace("%", "%%")
        + "; a target the lay equipment fixes (a J-lay's departure angle) is refused",
    )
    static.add_argument(
        "--bracket",
        metavar="LOW,HIGH",
        help="the vessel positions (η's x, m) to search between; default: searched from vessel.eta "
        "both ways in steps that double from 1 m, around positions where statics fails",
    )
    static.add_argument(
        "--max-solves",
        type=int,
        default=MAX_SOLVES,
        metavar="N",
        help=f"the most static solves the search spends (default: {MAX_SOLVES}); without an answer by then it "
        "prints the closest state found and exits 2",
    )
    check = commands.add_parser("check", help="validate a scenario file without solving")
    check.add_argument("scenario", type=Path, help="scenario file (TOML)")
    plot = commands.add_parser("plot", help="figures from a results file, or a sweep's operability map")
    plot.add_argument(
        "results", type=Path, help="results file (netCDF) written by `pipelay run`, or a sweep's summary.nc"
    )
    plot.add_argument("--plots", type=Path, help="directory for figures (results file)")
    plot.add_argument("--variable", help="summary.nc: the statistic to map, e.g. top_tension_max")
    plot.add_argument(
        "--limit", type=float, help="summary.nc: draw the contour where the statistic equals this"
    )
    plot.add_argument("--x", help="summary.nc: the swept key along x (default: the first)")
    plot.add_argument("--y", help="summary.nc: the swept key along y (default: the second, if any)")
    plot.add_argument(
        "--select",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="summary.nc: one value of another swept key (default: one panel per value)",
    )
    plot.add_argument("-o", "--output", type=Path, help="summary.nc: the figure (default: DIR/VARIABLE.png)")
    sweeping = commands.add_parser(
        "sweep", help="run a scenario over a grid of values of some of its keys, on Dask"
    )
    sweeping.add_argument("scenario", type=Path, help="scenario file (TOML)")
    sweeping.add_argument(
        "--over",
        action="append",
        required=True,
        metavar="KEY=V1,V2,...",
        help='a dotted scenario key and its values (TOML values: 0.5, [0, -0.8, 0], "osv"); repeat it for '
        "more keys",
    )
    sweeping.add_argument(
        "-o",
        "--output",
        type=Path,
        required=True,
        help="folder for cases/ and summary.nc (finished cases reused)",
    )
    _cluster_arguments(sweeping)
    _fatigue_parser(commands)
    _view_parsers(commands)
    _lay_table_parser(commands)
    _fmu_parser(commands)
    capability = commands.add_parser(
        "capability",
        help="DP capability: the largest wind held at each heading, with the pipe's static pull",
    )
    capability.add_argument("scenario", type=Path, help="scenario file (TOML) with a [vessel]")
    capability.add_argument(
        "--headings-step",
        type=float,
        default=15.0,
        metavar="DEG",
        help="degrees between the headings, from 0 (head-on) clockwise (default: 15)",
    )
    capability.add_argument(
        "--current", type=float, default=0.75, metavar="M/S", help="co-linear current (m/s, default: 0.75)"
    )
    capability.add_argument(
        "--max-wind",
        type=float,
        default=60.0,
        metavar="M/S",
        help="the search's upper limit on the wind speed (m/s, default: 60)",
    )
    capability.add_argument("--plot", type=Path, metavar="FILE", help="save the polar plot here (PNG)")
    schema = commands.add_parser("schema", help="the JSON Schema of scenario files")
    schema.add_argument("-o", "--output", type=Path, help="write it to this file instead of printing it")
    return parser


def _reference(scenario: Scenario) -> list[float] | None:
    """The controller's fixed η_ref (m, rad, in e as η) for the vessel figure, NaN (not drawn) in the degrees of
    freedom it leaves free (K_p's row zero), and in x and y when a lay-tension loop moves the set-point; None
    without a fixed reference."""
    controller = scenario.source.get("controller")
    if not isinstance(controller, dict) or "reference" not in controller:
        return None
    gains = np.asarray(controller["kp"], dtype=float)
    held = np.any(gains != 0.0, axis=1) if gains.ndim == 2 else gains != 0.0
    if "tension" in controller:
        held[:2] = False
    return [
        float(value) if hold else float("nan")
        for value, hold in zip(controller["reference"], held, strict=True)
    ]


def _depth(scenario: Scenario) -> float | None:
    sea = scenario.model.sea
    return sea.depth if sea is not None else None


def _summary(state: pl.State, checks: dict[str, Any]) -> str:
    """Top tension, end reactions, touchdown, lay summary, checks and vessel pose of a state, one per line.

    The top tension is the effective tension where the vessel holds the pipe (the tensioner, tower or winch;
    `lay_summary()["top_tension"]`), without a vessel the effective axial force of the element at end B; the
    reaction at B is the magnitude of the force the pipe exerts there.
    """
    summary = state.lay_summary()
    top, where = (
        (state.tension[-1], "the element at end B")
        if summary is None
        else (summary["top_tension"], "at the vessel's hold point")
    )
    lines = [
        f"top tension             {top / 1e3:12.1f} kN (effective, {where})",
        f"reaction at B |F_B|     {np.linalg.norm(state.reaction('B')[:3]) / 1e3:12.1f} kN",
        f"largest axial force     {np.max(state.tension) / 1e3:12.1f} kN",
        f"reaction at A (force)   {np.array2string(state.reaction('A')[:3] / 1e3, precision=1)} kN",
    ]
    bending = np.hypot(state.section_forces[:, 4], state.section_forces[:, 5])
    if len(bending):
        worst = int(np.argmax(bending))
        arc = float(np.sum(np.linalg.norm(np.diff(state.positions, axis=0), axis=1)[:worst]))
        lines.append(
            f"largest bending moment  {bending[worst] / 1e3:12.1f} kN m (element {worst}, ~{arc:.1f} m from A)"
        )
    if state.laid_length is not None:
        touchdown = state.touchdown
        where = (
            f"{touchdown.arc_length:12.2f} m from A at {np.array2string(touchdown.position, precision=2)} m"
            if touchdown is not None
            else "    none: the pipe does not touch the seabed"
        )
        lines.append(f"touchdown               {where}")
        lines.append(f"laid length             {state.laid_length:12.2f} m")
    if summary is not None:
        lines.extend(_lay_lines(summary, state.roller_reactions, pl.support_loads(state)))
        if len(state.hinge_angles) > 0:
            angles = ", ".join(f"{np.degrees(a):.2f}°" for a in state.hinge_angles)
            lines.append(
                f"lay: hinge angles        {angles} (sections 1 to {len(state.hinge_angles)}, + aft end down)"
            )
    if state.section.wall_thickness is not None and len(state.tension):
        lines.extend(_check_lines(state, checks))
    if state.eta is not None and state.tau is not None:
        lines.append(f"vessel η                {np.array2string(state.eta, precision=3)}")
        lines.append(
            f"thrust τ (surge, sway, yaw) {np.array2string(state.tau[[0, 1, 5]] / 1e3, precision=1)} kN, kN m"
        )
    return "\n".join(lines)


def _check_lines(state: pl.State, checks: dict[str, Any]) -> list[str]:
    """The largest DNV-ST-F101 utilisations of a state of a pipe with the scenario's `[checks]` (else the
    checks' defaults), each with its element and distance from end A, the basis they are taken on, and the
    propagation buckling check with its arrestor advice."""
    check = pl.checks.dnv_st_f101(state, **checks)
    propagation = pl.checks.propagation_buckling(state, **checks)
    arcs = state.reference_arc_length
    lines = [f"checks: {check.basis}"]
    for name, values in (
        ("load-controlled", check.load_controlled),
        ("displacement-controlled", check.displacement_controlled),
        ("propagation buckling", propagation.utilisation),
    ):
        worst = int(np.argmax(values))
        middle = 0.5 * (arcs[worst] + arcs[worst + 1])
        lines.append(f"DNV-ST-F101 {name:<24s}{values[worst]:8.3f} (element {worst}, {middle:.1f} m from A)")
    if propagation.arrestors is not None:
        lines.append(f"DNV-ST-F101 propagation buckling: {propagation.arrestors}")
    return lines


def _lay_lines(
    summary: dict[str, Any], rollers: np.ndarray | None, supports: pl.SupportLoads | None = None
) -> list[str]:
    """The lay summary of a static state, one quantity per line: departure angle, layback and sagbend for every
    lay, and over a stinger (`rollers`: its rollers' reactions, N; `supports`: its supports' loads) the
    lift-off roller, overbend strain, tip clearance and offset, the rollers' reactions, and on roller boxes
    each box's vertical and lateral load and whether the pipe stays in its boxes. Rollers (boxes) are numbered
    from 1, the first on the stinger, to its tip (`summary["liftoff_roller"]` is the 0-based index of the
    support); without a stinger (a J-lay's tower, a pipe clamped at the vessel) there is no overbend."""
    layback = summary["layback"]
    lines = [f"lay: departure angle    {np.degrees(summary['departure_angle']):12.2f}° below horizontal"]
    count = len(supports.vertical) if supports is not None else 0 if rollers is None else len(rollers)
    support = "box" if supports is not None and supports.boxes else "roller"
    if rollers is not None:
        liftoff = summary["liftoff_roller"]
        lines.append(
            f"lay: lift-off {support:<10s}"
            + (
                f"{liftoff + 1:12d} of {count}"
                if liftoff is not None
                else "        none: the pipe touches no roller"
            )
        )
    lines.append(
        "lay: layback            "
        + (f"{layback:12.2f} m" if np.isfinite(layback) else "        none: no touchdown")
    )
    if rollers is not None:
        lines.append(f"lay: overbend strain    {100 * summary['overbend_strain']:12.4f} %")
    lines += [
        f"lay: sagbend strain     {100 * summary['sagbend_strain']:12.4f} %",
        f"lay: sagbend moment     {summary['sagbend_moment'] / 1e3:12.1f} kN m",
    ]
    residual = summary.get("residual_curvature", float("nan"))
    if np.isfinite(residual):
        radius = f"radius {1 / residual:.4g} m" if residual > 0 else "straight"
        lines.append(f"lay: residual curvature {residual:12.4e} 1/m of the laid pipe ({radius})")
    if rollers is not None:
        lines.append(
            f"lay: tip clearance      {summary['tip_clearance']:12.3f} m at {support} {count}, the stinger's tip "
            "(≤ 0: the pipe rests on it)"
        )
        lines.append(
            f"lay: tip offset         {summary['tip_offset']:12.3f} m to starboard of the tip's centre"
        )
        if supports is not None and supports.boxes:
            lines += _box_lines(supports)
        else:
            lines.append(
                f"lay: roller reactions (kN), rollers 1 (the first on the stinger) to {count} (its tip):"
            )
            cells = [f"{k + 1:5d}: {force / 1e3:6.1f}" for k, force in enumerate(rollers)]
            lines += ["    " + "".join(cells[i : i + 8]) for i in range(0, len(cells), 8)]
    return lines


def _box_lines(supports: pl.SupportLoads) -> list[str]:
    """Each roller box's loads on the pipe, vertical (up) and lateral (to starboard) in kN, and whether the pipe
    stays in its boxes."""
    stays = "yes" if supports.stays_in_boxes else f"no: it is leaving {supports.boxes_left} of them"
    count = len(supports.vertical)
    lines = [
        f"lay: pipe in its boxes  {stays}",
        f"lay: roller box loads on the pipe (kN, vertical up / lateral to starboard), boxes 1 to {count}:",
    ]
    cells = [
        f"{b + 1:5d}: {up / 1e3:6.1f} /{side / 1e3:6.1f}"
        for b, (up, side) in enumerate(zip(supports.vertical, supports.lateral, strict=True))
    ]
    return lines + ["    " + "".join(cells[i : i + 5]) for i in range(0, len(cells), 5)]


def _run_summary(path: Path) -> str:
    """The records, time span and extremes of a run, read from its results file a slice of records at a time:
    top tension (`pl.statistics.top_tension`: at the tensioner, tower or top support), the reaction at B
    |F_B|, largest bending moment, lay summary (the overbend strain and tip offset with a stinger's rollers
    only, and when the pipe leaves its roller boxes; the laid pipe's residual curvature where its wall
    yields), touchdown range."""
    import xarray as xr

    lines = []
    with xr.open_dataset(path, engine="h5netcdf") as data:
        time = data["time"].values
        lines.append(f"results: {path} ({len(time)} records, t = {time[0]:g} … {time[-1]:g} s)")
        if "top_tension" in data or ("section_forces" in data and data.sizes["element"] > 0):
            top = pl.statistics.top_tension(data) / 1e3
            lines.append(f"top tension             {np.nanmin(top):10.1f} … {np.nanmax(top):.1f} kN")
        if "reaction_B" in data:
            reaction = np.linalg.norm(data["reaction_B"].values[:, :3], axis=1) / 1e3
            lines.append(f"reaction at B |F_B|     {reaction.min():10.1f} … {reaction.max():.1f} kN")
        if "section_forces" in data and data.sizes["element"] > 0:
            forces = data["section_forces"]
            rows = max(1, 2**22 // (forces.shape[1] * forces.shape[2]))  # 32 MB at a time
            blocks = (forces[i : i + rows].values for i in range(0, len(time), rows))
            # nanmax: with pay-out the shorter meshes' rows end in NaN.
            moment = np.concatenate([np.nanmax(np.hypot(b[..., 4], b[..., 5]), axis=1) for b in blocks])
            lines.append(
                f"largest bending moment  {moment.max() / 1e3:10.1f} kN m (t = {time[np.argmax(moment)]:g} s)"
            )
        for key, label, scale, unit in (
            ("departure_angle", "lay: departure angle   ", 180 / np.pi, "°"),
            ("overbend_strain", "lay: overbend strain   ", 100.0, "%"),
            ("sagbend_strain", "lay: sagbend strain    ", 100.0, "%"),
            ("tip_offset", "lay: tip offset        ", 1.0, "m to starboard"),
            ("residual_curvature", "lay: residual curvature", 1.0, "1/m of the laid pipe"),
        ):
            if key in data and (key not in ("overbend_strain", "tip_offset") or "roller_reactions" in data):
                series = data[key].values * scale
                if np.any(np.isfinite(series)):
                    lines.append(f"{label} {np.nanmin(series):10.4g} … {np.nanmax(series):.4g} {unit}")
        if "boxes_left" in data and np.nanmax(data["boxes_left"].values, initial=0.0) > 0:
            left = data["boxes_left"].values
            first = time[np.argmax(left > 0)]
            lines.append(
                f"lay: pipe leaving boxes  up to {int(np.nanmax(left))} of them, first at t = {first:g} s"
            )
        if "touchdown_arc_length" in data:
            arc = data["touchdown_arc_length"].values
            if np.any(np.isfinite(arc)):
                lines.append(f"touchdown (from A)      {np.nanmin(arc):10.2f} … {np.nanmax(arc):.2f} m")
            else:
                lines.append("touchdown               none: the pipe never touches the seabed")
    return "\n".join(lines)


def _write(args: argparse.Namespace, scenario: Scenario) -> None:
    """The summary of the run streamed to ``args.output`` (and of each stage, for a staged run), and its figures
    (from the file read back)."""
    print(_run_summary(args.output))
    if scenario.stages is not None:
        print(_stage_table(load(args.output), scenario.model))
    if args.plots:
        for figure in plots.all_figures(
            load(args.output), args.plots, reference=_reference(scenario), depth=_depth(scenario)
        ):
            print(f"figure: {figure}")


def _run(args: argparse.Namespace) -> int:
    scenario = load_scenario(args.scenario)
    print(f"scenario: {scenario.source.get('title', args.scenario)}")
    status = 0
    with worst_of_each_kind() as suspects:
        simulation = start_simulation(scenario, args.resume)
        try:
            # Streamed to the file as the run goes: memory stays flat; the file is complete on failure or
            # Ctrl-C.
            if run_simulation(simulation, scenario, args.output, progress=not args.no_progress):
                print(
                    f"pipelay: interrupted at t = {simulation.time:g} s; keeping the results so far",
                    file=sys.stderr,
                )
                status = INTERRUPTED
        except pl.ConvergenceError as failure:
            print(f"pipelay: solve failed: {failure}", file=sys.stderr)
            status = 1
    _write(args, scenario)
    _print_suspects(suspects)
    if args.checkpoint:
        print(f"checkpoint: {checkpoint(simulation, args.checkpoint)} (t = {simulation.time:g} s)")
    return status


def _stage_table(results: pl.Results, model: pl.Model) -> str:
    """Each stage's extremes (``Results.stage_summary``) as a table: tensions in kN, strain in %, lengths in m."""
    summary = results.stage_summary(model)
    columns = {
        "top_tension_max": ("top T max kN", 1e-3),
        "top_tension_min": ("top T min kN", 1e-3),
        "wire_tension_max": ("wire T max kN", 1e-3),
        "pipe_force_min": ("pipe N min kN", 1e-3),
        "strain_max": ("strain max %", 100.0),
        "roller_reaction_max": ("roller max kN", 1e-3),
        "tip_clearance_min": ("tip gap min m", 1.0),
        "touchdown_max": ("touchdown m", 1.0),
        "head_height_min": ("head height m", 1.0),
    }
    width = max(len(name) for name in summary["name"])
    lines = [
        "stages:",
        " ".join([f"{'':{width}}", f"{'start s':>9}", *(f"{t:>14}" for t, _ in columns.values())]),
    ]
    for _, row in summary.iterrows():
        cells = [f"{row[key] * scale:14.4g}" for key, (_, scale) in columns.items()]
        lines.append(" ".join([f"{row['name']:{width}}", f"{row['start']:9.1f}", *cells]))
    return "\n".join(lines)


def _print_suspects(suspects: dict[str, PhysicsWarning]) -> None:
    """The worst `PhysicsWarning` of each kind, one line each on standard error."""
    for warning in suspects.values():
        print(f"warning: {warning}", file=sys.stderr)


def _target_value(text: str) -> tuple[str, float]:
    """`--target QUANTITY=VALUE[UNIT]`: the quantity and its value in SI units (rad, a fraction for strains):
    a bare number is in the unit `pipelay static` prints the quantity in (kN, degrees, m, %), or a unit is
    written after it (700kN, 62deg, 1.08rad, 0.15%); out of range is an InputError naming --target."""
    quantity, equals, given = text.partition("=")
    quantity = quantity.strip()
    if quantity not in TARGETS:
        raise pl.InputError(f"--target: {quantity!r} is not a lay quantity; allowed: {', '.join(TARGETS)}")
    printed, units, examples = _TARGET_UNITS[quantity]
    number = _NUMBER.fullmatch(given.strip())
    if not equals or number is None:
        raise pl.InputError(
            f"--target: {text!r} must be QUANTITY=VALUE[UNIT], e.g. {quantity}={examples.split(',')[0]}"
        )
    unit = number[2].strip() or printed
    if unit not in units:
        allowed = ", ".join(u for u in units if u) or "none"
        raise pl.InputError(
            f"--target: {text!r}: {unit!r} is not a unit of {quantity}; allowed: {allowed} (a bare number is "
            f"in {printed or 'no unit'}, as `pipelay static` prints it)"
        )
    value = float(number[1]) * units[unit]
    low, high = RANGES[quantity]
    if not (math.isfinite(value) and low < value <= high):
        size, space = units[printed], "" if printed in ("°", "") else " "
        span = f"> {low / size:g}" if math.isinf(high) else f"in ({low / size:g}, {high / size:g}]"
        what = "an angle" if quantity == "departure_angle" else "a value"
        below = " below the horizontal" if quantity == "departure_angle" else ""
        raise pl.InputError(
            f"--target: {text!r} is {value / size:g}{space}{printed}, out of range; allowed: {what} {span}"
            f"{space}{printed}{below} (e.g. {quantity}={examples})"
        )
    return quantity, value


def _target(args: argparse.Namespace, scenario: Scenario) -> pl.State:
    """`--target`: the static state with the vessel moved along e1 until the lay quantity hits the value; without
    one, the closest state found is printed before the error."""
    quantity, value = _target_value(str(args.target))
    vessel = scenario.source.get("vessel")
    if not isinstance(vessel, dict):
        raise pl.InputError("--target: needs a [vessel] to move")
    if args.max_solves < 2:
        raise pl.InputError(f"--max-solves: {args.max_solves} must be at least 2 (static solves)")
    x0 = float(vessel["eta"][0])
    bracket = None
    if args.bracket:
        try:
            low, high = (float(v) for v in str(args.bracket).split(","))
        except ValueError:
            raise pl.InputError(f"--bracket: {args.bracket!r} must be LOW,HIGH (m)") from None
        bracket = (low, high)

    def build(x: float) -> pl.Model:
        data = copy.deepcopy(scenario.source)
        data["vessel"]["eta"][0] = x
        controller = data.get("controller")
        if isinstance(controller, dict) and "reference" in controller:
            controller["reference"][0] += x - x0
        return parse_scenario(data, str(args.scenario)).model

    check_target(quantity, rest=build(x0).rest(), argument="--target")
    unit, units, _ = _TARGET_UNITS[quantity]

    def shown(si: float) -> str:
        return f"{si / units[unit]:.6g}" + ("" if unit in ("°", "") else " ") + unit

    try:
        found = find_lay_position(
            build, quantity, value, bracket, start=x0, max_solves=args.max_solves, **scenario.checks
        )
    except TargetNotReached as missed:
        if missed.closest is not None:
            print(
                f"lay position: not reached; the closest state found: vessel x = {missed.closest.x:.3f} m "
                f"gives {quantity} = {shown(missed.closest.value)}"
            )
            print(_summary(missed.closest.state, scenario.checks))
        raise
    print(
        f"lay position: vessel x = {found.x:.3f} m gives {quantity} = {shown(found.value)} "
        f"({found.solves} static solves)"
    )
    if not found.reached:
        print(
            f"lay position: {quantity} jumps across {shown(value)} there (the lift-off moves to "
            "another roller, say): the closest a static state comes"
        )
    return found.state


def _reeling_lines(reel_lay: pl.ReelLay, section: pl.Section) -> list[str]:
    """The pipe's reeling, for a reel-lay: the straightener's setting, the largest strain on the reel, and
    the residual curvature and accumulated plastic strain ("% plastic") the pipe enters the water with."""
    history = reel_lay.history(section)
    residual = history["residual_curvature"]
    radius = f"radius {1 / abs(residual):.4g} m" if abs(residual) > 1e-12 else "straight"
    setting = reel_lay.straightener.curvature
    radii = f"reel {reel_lay.reel_radius:g} m, aligner {reel_lay.aligner_radius:g} m"
    accumulated = 100 * history["accumulated_plastic_strain"]
    return [
        f"reel-lay: straightener   {setting:12.4e} 1/m ({radii})",
        f"reel-lay: reeling strain {100 * np.max(history['strain']):12.4f} % (the wall's largest)",
        f"reel-lay: entering with  {residual:12.4e} 1/m residual curvature ({radius}), {accumulated:.4f} % plastic",
    ]


def _static(args: argparse.Namespace) -> int:
    scenario = load_scenario(args.scenario)
    print(f"scenario: {scenario.source.get('title', args.scenario)}")
    with worst_of_each_kind() as suspects:
        if args.target:
            state = _target(args, scenario)
        else:
            state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    print(f"static equilibrium: {state.iterations} Newton iterations in {state.steps} load step(s)")
    print(_summary(state, scenario.checks))
    reel_lay = scenario.model.reel_lay
    if reel_lay is not None:
        print("\n".join(_reeling_lines(reel_lay, state.section)))
    _print_suspects(suspects)
    if args.plots:
        path = Path(args.plots) / "tension_bending.png"
        plots.tension_and_bending(state, path=path)
        print(f"figure: {path}")
        if state.lay_summary() is not None:
            path = Path(args.plots) / "lay_configuration.png"
            plots.lay_configuration(state, path=path, **scenario.checks)
            print(f"figure: {path}")
    return 0


def _check(args: argparse.Namespace) -> int:
    scenario = load_scenario(args.scenario)
    rod = scenario.model.rod
    vessel = "with a vessel" if "vessel" in scenario.source else "without a vessel"
    run = (
        f"simulation to {scenario.t_end:g} s with dt = {scenario.dt:g} s"
        if scenario.t_end
        else "statics only"
    )
    if scenario.stages is not None:
        run += f" through {len(scenario.stages)} stages ({', '.join(scenario.stages.names)})"
    print(f"{args.scenario}: valid: {rod.elements} elements, {rod.length:g} m, {vessel}; {run}")
    return 0


def _plot(args: argparse.Namespace) -> int:
    if args.variable is not None:
        return _operability(args)
    if args.plots is None:
        raise pl.InputError(
            "--plots: the directory for a results file's figures (or --variable for a summary.nc)"
        )
    results = load(args.results)
    for figure in plots.all_figures(results, args.plots):
        print(f"figure: {figure}")
    return 0


def _values(text: str) -> list[Any]:
    """`V1,V2,...` as TOML values (numbers, arrays, quoted strings), or as words if they are not TOML."""
    try:
        return list(tomllib.loads(f"values = [{text}]")["values"])
    except tomllib.TOMLDecodeError:
        return text.split(",")


def _pairs(option: str, texts: list[str]) -> dict[str, list[Any]]:
    """`KEY=V1,V2,...` options as {key: values}."""
    pairs: dict[str, list[Any]] = {}
    for text in texts:
        key, equals, values = text.partition("=")
        key = key.strip()
        if not equals or not key or not values.strip():
            raise pl.InputError(f"{option}: {text!r} must be KEY=V1,V2,..., e.g. controller.start=0,10")
        if key in pairs:
            raise pl.InputError(f"{option}: {key} given twice")
        pairs[key] = _values(values)
    return pairs


def _sweep(args: argparse.Namespace) -> int:
    done = sweep(
        args.scenario,
        _pairs("--over", args.over),
        client=args.scheduler,
        output=args.output,
        workers=args.workers,
        progress=not args.no_progress,
    )
    cases = int(done.summary.attrs["cases"])
    print(f"sweep: {cases} cases, {len(done.cases)} finished, {len(done.failures)} failed")
    for case, message in done.failures.items():
        print(f"pipelay: case {case} failed: {message}", file=sys.stderr)
    print(f"summary: {done.output / 'summary.nc'}")
    return 1 if done.failures else 0


def _operability(args: argparse.Namespace) -> int:
    """`pipelay plot summary.nc --variable NAME`: the operability map."""
    import xarray as xr

    with xr.open_dataset(args.results, engine="h5netcdf") as opened:
        summary = opened.load()
    if summary.attrs.get("title") != SUMMARY_TITLE:
        raise pl.InputError(
            f"--variable: {args.results} is not a sweep's summary.nc (a results file: --plots)"
        )
    keys = list(json.loads(summary.attrs["swept_keys"]))
    statistics = [str(name) for name in summary.data_vars if name not in ("failed", "error", "case")]
    if args.variable not in statistics:
        raise pl.InputError(
            f"--variable: {args.variable!r} is not in the summary; one of {', '.join(statistics)}"
        )
    selection = {}
    for key, values in _pairs("--select", args.select).items():
        if key not in keys or len(values) != 1:
            raise pl.InputError(f"--select: KEY=VALUE with KEY one of {', '.join(keys)}, got {key}")
        coordinate = summary[key].values
        value = values[0] if coordinate.dtype.kind in "iuf" else _label(values[0])
        if value not in coordinate.tolist():
            raise pl.InputError(
                f"--select: {key} = {values[0]!r} is not swept; the values are {coordinate.tolist()}"
            )
        selection[key] = value
    free = [key for key in keys if key not in selection]
    x = args.x or free[0]
    y = args.y or next((key for key in free if key != x), None)
    for given in (x, y):
        if given is not None and given not in free:
            raise pl.InputError(f"--x, --y: {given!r} is not a swept key left free; one of {', '.join(free)}")
    path = args.output or Path(args.results).parent / f"{args.variable}.png"
    plots.operability(summary.sel(selection), args.variable, x, y, limit=args.limit, path=path)
    print(f"figure: {path}")
    return 0


def _cluster_arguments(command: argparse.ArgumentParser) -> None:
    """The Dask cluster's arguments of a command that runs cases (--scheduler or --workers) and
    --no-progress."""
    where = command.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://10.0.0.1:8786")
    where.add_argument("--workers", type=int, help="local worker processes (default: one a core)")
    command.add_argument("--no-progress", action="store_true", help="no progress bar")


def _view_parsers(commands: Any) -> None:
    """The arguments of `pipelay view` and `pipelay report` (the replay's module, which imports plotly, is
    imported when they run)."""
    view = commands.add_parser("view", help="the 3-D replay of a run as one HTML file (and a video)")
    view.add_argument("results", type=Path, help="results file (netCDF) of a run")
    view.add_argument("-o", "--output", type=Path, help="the HTML file (default: RESULTS with .html)")
    view.add_argument("--video", type=Path, help="also write a video of the run (mp4)")
    view.add_argument(
        "--colour", default="tension", help="what colours the pipe: tension, moment, strain or utilisation"
    )
    view.add_argument("--frames", type=int, default=300, help="at most this many frames (records decimated)")
    view.add_argument(
        "--scenario", type=Path, help="scenario file of the run, where the results file does not keep it"
    )
    report = commands.add_parser("report", help="the HTML report of a run, or of a sweep's folder")
    report.add_argument(
        "results", type=Path, help="results file (netCDF) of a run, or a sweep's output folder"
    )
    report.add_argument(
        "-o",
        "--output",
        type=Path,
        help="the report (default: RESULTS-report.html beside RESULTS, or DIR/report.html)",
    )
    report.add_argument(
        "--scenario", type=Path, help="scenario file of the run, where the results file does not keep it"
    )


def _scenario_of(results: Path, given: Path | None) -> Scenario | None:
    """The scenario of a results file: --scenario's, else the one the file keeps, else None (said)."""
    from pipelay.scenario import scenario_of_results

    if given is not None:
        return load_scenario(given)
    scenario = scenario_of_results(results)
    if scenario is None:
        print(
            f"note: {results} keeps no scenario (give --scenario): no rollers, bathymetry or waves drawn",
            file=sys.stderr,
        )
    return scenario


def _view(args: argparse.Namespace) -> int:
    """`pipelay view RESULTS.nc`: the replay (HTML) and, with --video, the video."""
    from pipelay.plots.replay import replay
    from pipelay.plots.video import video

    results = load(args.results)
    scenario = _scenario_of(args.results, args.scenario)
    model = None if scenario is None else scenario.model
    output = args.output or args.results.with_suffix(".html")
    checks = None if scenario is None else scenario.checks
    replay(results, model, colour=args.colour, max_frames=args.frames, path=output, checks=checks)
    print(f"replay: {output}")
    if args.video is not None:
        video(results, args.video, model, colour=args.colour, checks=checks)
        print(f"video: {args.video}")
    return 0


def _report(args: argparse.Namespace) -> int:
    """`pipelay report RESULTS.nc|DIR`: the report of a run or a sweep's folder."""
    from pipelay.report import run_report, sweep_report

    if args.results.is_dir():
        written = sweep_report(args.results, args.output)
    else:
        scenario = _scenario_of(args.results, args.scenario)
        output = args.output or args.results.with_name(f"{args.results.stem}-report.html")
        written = run_report(args.results, output, scenario=scenario)
    print(f"report: {written}")
    return 0


def _fatigue_parser(commands: Any) -> None:
    """The arguments of `pipelay fatigue`."""
    from pipelay.analysis.fatigue import DNV_CLASSES, ENVIRONMENTS, METHODS

    fatigue = commands.add_parser(
        "fatigue", help="fatigue damage of a standby over a scatter diagram of sea states (DNV-RP-C203)"
    )
    fatigue.add_argument("scenario", type=Path, help="scenario file (TOML) with [sea.waves] and solver.t_end")
    fatigue.add_argument(
        "--scatter",
        type=Path,
        required=True,
        help="CSV of sea states: columns hs (m), tp (s), probability and optionally heading (deg)",
    )
    fatigue.add_argument("--hours", type=float, required=True, help="the standby's duration (h)")
    fatigue.add_argument(
        "-o", "--output", type=Path, required=True, help="folder for cases/, fatigue.nc and damage.png"
    )
    fatigue.add_argument(
        "--curve", default="D", choices=DNV_CLASSES, help="DNV-RP-C203 S-N class (default D)"
    )
    fatigue.add_argument(
        "--environment",
        default="seawater_cp",
        choices=ENVIRONMENTS,
        help="S-N environment (default seawater_cp)",
    )
    fatigue.add_argument("--scf", type=float, default=1.0, help="stress concentration factor (default 1)")
    fatigue.add_argument(
        "--method", default="rainflow", choices=METHODS, help="cycle counting (default rainflow)"
    )
    fatigue.add_argument(
        "--start", type=float, help="leave out the records before this time (s): the start-up transient"
    )
    _cluster_arguments(fatigue)


def _fatigue(args: argparse.Namespace) -> int:
    """`pipelay fatigue SCENARIO --scatter TABLE --hours H -o DIR`: the standby's damage over the scatter
    diagram, each segment's S-N curve with the thickness effect of its wall."""
    from pipelay.analysis.fatigue import SNCurve, read_scatter, scatter_damage

    scatter = read_scatter(args.scatter)
    scenario = load_scenario(args.scenario)
    curves = [
        SNCurve.dnv(args.curve, environment=args.environment, thickness=section.wall_thickness)
        for section in scenario.model.rod.sections
    ]
    found = scatter_damage(
        args.scenario,
        scatter,
        curves,
        hours=args.hours,
        scf=args.scf,
        method=args.method,
        start=args.start,
        output=args.output,
        client=args.scheduler,
        workers=args.workers,
        progress=not args.no_progress,
    )
    element, angle = found.worst()
    print(
        f"fatigue: {args.hours:g} h standby over {len(scatter)} sea states; DNV-RP-C203 {args.curve} "
        f"({args.environment}), SCF {args.scf:g}, {args.method.replace('_', ' ')}"
    )
    print(
        f"largest damage {found.max():.4g} at element {element} ({found.arc_length[element]:.1f} m from end A), "
        f"hot spot {np.degrees(angle):.0f} deg; life at this rate {args.hours / found.max():.4g} h"
    )
    heading = scatter.heading
    print(
        f"{'sea state':>9} {'Hs m':>6} {'Tp s':>6} {'heading deg':>11} {'probability':>11} {'damage/h':>10} {'share':>6}"
    )
    point = int(np.argmax(found.angles == angle))
    hourly = found.hourly[:, element, point]
    for k in range(len(scatter)):
        direction = "scenario" if heading is None else f"{np.degrees(heading[k]):.1f}"
        share = scatter.probability[k] * hourly[k] * args.hours / found.max()
        print(
            f"{k:9d} {scatter.hs[k]:6.2f} {scatter.tp[k]:6.2f} {direction:>11} {scatter.probability[k]:11.4g} "
            f"{hourly[k]:10.3g} {share:6.1%}"
        )
    for k, message in found.failures.items():
        print(f"pipelay: sea state {k} failed: {message}", file=sys.stderr)
    found.to_xarray().to_netcdf(args.output / "fatigue.nc", engine="h5netcdf")
    found.plot(path=args.output / "damage.png")
    print(f"damage: {args.output / 'fatigue.nc'}; figure: {args.output / 'damage.png'}")
    return 1 if found.failures else 0


def _fmu_parser(commands: Any) -> None:
    """The arguments of `pipelay fmu`."""
    fmu = commands.add_parser(
        "fmu", help="the scenario as an FMI 2.0 co-simulation FMU (the plant: pipe and vessel, driven by τ)"
    )
    fmu.add_argument("scenario", type=Path, help="scenario file (TOML) with a [vessel]")
    fmu.add_argument(
        "-o", "--output", type=Path, required=True, help="the FMU (NAME.fmu; NAME its model identifier)"
    )
    fmu.add_argument(
        "--kind",
        choices=["plant", "pipe"],
        default="plant",
        help="plant: the pipe and the vessel, inputs the thrust τ in surge, sway and yaw; pipe: the pipe alone, "
        "inputs the vessel's pose and velocity, out its force on the vessel (a vessel without a stinger)",
    )
    fmu.add_argument(
        "--parameter",
        action="append",
        metavar="KEY",
        help="a dotted scenario key (a number in the scenario) the master may set, repeatable; default: every "
        "number of sea.current, sea.waves and sea.wind",
    )


def _fmu(args: argparse.Namespace) -> int:
    from pipelay.cosimulation.build import build_fmu

    path = build_fmu(args.scenario, args.output, kind=args.kind, parameters=args.parameter)
    print(f"FMU: {path} (FMI 2.0 co-simulation; runs where Python and pipelay are installed)")
    return 0


def _lay_table_parser(commands: Any) -> None:
    """The arguments of `pipelay lay-table`."""
    table = commands.add_parser(
        "lay-table", help="the lay table: the vessel placed to meet a target at each water depth, as CSV"
    )
    table.add_argument("scenario", type=Path, help="scenario file (TOML) with a [sea] and a [vessel]")
    table.add_argument(
        "--depths",
        required=True,
        metavar="FROM:TO:STEP|D1,D2,...",
        help="the water depths (m): FROM to TO (included when on the grid) in steps of STEP, or a list",
    )
    table.add_argument(
        "--target",
        required=True,
        metavar="QUANTITY=VALUE[UNIT]",
        help="the lay quantity the vessel's position meets at each depth, as `pipelay static --target`: "
        + "; ".join(f"{q}={_TARGET_UNITS[q][2]}" for q in TARGETS).replace("%", "%%"),
    )
    table.add_argument(
        "-o", "--output", type=Path, required=True, help="the table (CSV, kN, degrees, percent)"
    )
    table.add_argument("--netcdf", type=Path, help="also write the table here (netCDF, SI units)")
    table.add_argument(
        "--plot", type=Path, metavar="FILE", help="the figure of the table against depth (PNG)"
    )
    table.add_argument(
        "--max-solves",
        type=int,
        default=MAX_SOLVES,
        metavar="N",
        help=f"the most static solves each depth's search spends (default: {MAX_SOLVES})",
    )
    _cluster_arguments(table)


def _depth_values(text: str) -> list[float]:
    """`--depths`: FROM:TO:STEP (m; TO included when on the grid, to 1e-9 of STEP) or D1,D2,... as numbers."""
    parts = text.split(":")
    try:
        numbers = [float(part) for part in (parts if len(parts) == 3 else text.split(","))]
    except ValueError:
        numbers = []
    if not numbers or not all(math.isfinite(n) for n in numbers) or len(parts) not in (1, 3):
        raise pl.InputError(f"--depths: {text!r} must be FROM:TO:STEP or D1,D2,... (m), e.g. 100:1000:50")
    if len(parts) == 1:
        return numbers
    first, last, step = numbers
    if not (step > 0 and last >= first):
        raise pl.InputError(
            f"--depths: {text!r}: FROM:TO:STEP needs STEP > 0 and TO ≥ FROM, e.g. 100:1000:50"
        )
    count = math.floor((last - first) / step + 1e-9) + 1
    return [round(first + k * step, 9) for k in range(count)]


def _lay_table(args: argparse.Namespace) -> int:
    """`pipelay lay-table SCENARIO --depths ... --target ... -o TABLE.csv`: the table printed in people's
    units, written as CSV (and netCDF, and its figure); a depth where the target is not met printed with its
    reason on standard error (exit 1)."""
    from pipelay.analysis.lay_table import COLUMNS, utilisation_basis, write_csv

    quantity, value = _target_value(str(args.target))
    table = pl.lay_table(
        args.scenario,
        _depth_values(str(args.depths)),
        {quantity: value},
        client=args.scheduler,
        workers=args.workers,
        max_solves=args.max_solves,
        progress=not args.no_progress,
    )
    unit, units, _ = _TARGET_UNITS[quantity]
    space = "" if unit in ("°", "") else " "
    print(f"lay table: {args.scenario}, vessel placed for {quantity} = {value / units[unit]:g}{space}{unit}")
    columns = (  # in the CSV's units (`COLUMNS`)
        ("depth m", "depth", ".1f"),
        ("vessel x m", "vessel_x", ".2f"),
        ("top T kN", "top_tension", ".1f"),
        ("depart. °", "departure_angle", ".2f"),
        ("layback m", "layback", ".1f"),
        ("overbend %", "overbend_strain", ".4f"),
        ("sagbend %", "sagbend_strain", ".4f"),
        ("tip gap m", "tip_clearance", ".3f"),
        ("roller kN", "roller_reaction_max", ".1f"),
        ("lift-off", "liftoff_roller", ".0f"),
        ("LC util.", "load_controlled_max", ".3f"),
        ("DC util.", "displacement_controlled_max", ".3f"),
        ("PB util.", "propagation_max", ".3f"),
    )
    print(" ".join(f"{title:>11}" for title, *_ in columns))
    for k in range(table.sizes["depth"]):
        cells = []
        for _, name, form in columns:
            scale = COLUMNS[name].scale if name in COLUMNS else 1.0
            number = float(table[name].values[k]) * scale
            cells.append(f"{number:11{form}}" if math.isfinite(number) else f"{'–':>11}")
        print(" ".join(cells))
    print("lift-off: the last roller in contact, numbered from 1 at the stinger's vessel end")
    basis = utilisation_basis(table)
    if basis:
        print(f"utilisations (LC load-, DC displacement-controlled, PB propagation buckling): {basis}")
    depths = table["depth"].values
    for depth, text in zip(depths, table["warning"].values, strict=True):
        if text:
            print(f"warning: depth {depth:g} m: {text}", file=sys.stderr)
    failed = [(depth, text) for depth, text in zip(depths, table["failure"].values, strict=True) if text]
    for depth, text in failed:
        print(f"pipelay: depth {depth:g} m: target not met: {text}", file=sys.stderr)
    print(f"table: {write_csv(table, args.output)}")
    if args.netcdf:
        table.to_netcdf(args.netcdf, engine="h5netcdf")
        print(f"table (netCDF, SI units): {args.netcdf}")
    if args.plot:
        plots.lay_table(table, path=args.plot)
        print(f"figure: {args.plot}")
    return 1 if failed else 0


def _capability(args: argparse.Namespace) -> int:
    """`pipelay capability SCENARIO`: the DP capability envelope with the pipe's static load, as a table of
    heading (deg, environment from) and wind speed (m/s); --plot saves the polar plot."""
    step = float(args.headings_step)
    if not (np.isfinite(step) and 0.0 < step <= 360.0):
        raise pl.InputError(f"--headings-step: must be in (0, 360] degrees, got {args.headings_step!r}")
    headings = np.radians(np.arange(0.0, 360.0 - 1e-9, step))
    scenario = load_scenario(args.scenario)
    with worst_of_each_kind() as suspects:
        found = dp_capability(scenario, headings, current=args.current, max_wind=args.max_wind)
    _print_suspects(suspects)
    load = found.pipe_load + 0.0  # no −0.0 shown
    print(f"DP capability: {found.label}")
    print(
        f"pipe load on the vessel (body frame, static): X {load[0] / 1e3:.1f} kN, Y {load[1] / 1e3:.1f} kN, "
        f"N {load[5] / 1e3:.1f} kN m"
    )
    print("heading: where the environment comes from, relative to the bow, clockwise (90 = from starboard)")
    print(
        f"current {found.current:g} m/s and the Beaufort scale's sea (H_s of the WMO scale, T_p = 4.2 √H_s) with it"
    )
    print(f"{'heading deg':>11} {'wind m/s':>9}")
    for heading, speed, limited in zip(found.heading_deg, found.wind_speed, found.at_limit, strict=True):
        print(f"{heading:11.1f} {speed:9.2f}" + ("  (held to --max-wind)" if limited else ""))
    if args.plot:
        found.plot(path=args.plot)
        print(f"figure: {args.plot}")
    return 0


def _schema(args: argparse.Namespace) -> int:
    try:
        from pipelay.scenario import json_schema
    except ImportError:
        raise pl.InputError("schema: this pipelay has no pipelay.scenario.json_schema yet") from None
    text = json.dumps(json_schema(), indent=2)
    if args.output is None:
        print(text)
    else:
        Path(args.output).write_text(text + "\n")
        print(f"schema: {args.output}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``pipelay`` command; returns the exit code."""
    args = _parser().parse_args(argv)
    command = {
        "run": _run,
        "static": _static,
        "check": _check,
        "plot": _plot,
        "sweep": _sweep,
        "schema": _schema,
        "capability": _capability,
        "fatigue": _fatigue,
        "view": _view,
        "report": _report,
        "lay-table": _lay_table,
        "fmu": _fmu,
    }[args.command]
    try:
        if getattr(args, "plots", None) is not None:
            # Made before solving: an unwritable place fails at once, not after a long solve.
            args.plots.mkdir(parents=True, exist_ok=True)
        return command(args)
    except pl.InputError as error:
        print(f"pipelay: error: {error}", file=sys.stderr)
        return 2
    except pl.ConvergenceError as error:
        print(f"pipelay: solve failed: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        print(f"pipelay: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("pipelay: interrupted", file=sys.stderr)
        return INTERRUPTED


if __name__ == "__main__":
    raise SystemExit(main())
