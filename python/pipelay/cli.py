"""The ``pipelay`` command line.

    pipelay run SCENARIO -o RESULTS.nc [--plots DIR] [--checkpoint FILE] [--resume FILE] [--no-progress]
    pipelay static SCENARIO [--plots DIR] [--target QUANTITY=VALUE [--bracket LOW,HIGH]]
    pipelay check SCENARIO
    pipelay plot RESULTS.nc --plots DIR

`pipelay run` streams the records to RESULTS.nc as the run goes (RESULTS.nc.part until it ends; memory stays
flat however long the run), then prints a summary read from the file; --plots reads the whole file back.

Exit codes: 0 success, 1 a failed solve (Newton did not converge; the results computed before the failure are
still written), 2 bad input (the message names the scenario key; no traceback), 130 interrupted by Ctrl-C
(the results computed so far are written, and a checkpoint if asked for).
"""

from __future__ import annotations

import argparse
import copy
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np

import pipelay as pl
from pipelay import plots
from pipelay.lay import TARGETS, find_lay_position
from pipelay.results import checkpoint, load, resume
from pipelay.scenario import Scenario, load_scenario, parse_scenario

INTERRUPTED = 130


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pipelay", description="Offshore pipelay simulation from scenario files."
    )
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="statics, then a simulation to solver.t_end; writes netCDF results")
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
    static = commands.add_parser("static", help="static equilibrium: prints tensions, reactions, vessel pose")
    static.add_argument("scenario", type=Path, help="scenario file (TOML)")
    static.add_argument("--plots", type=Path, help="directory for the tension and bending figure")
    static.add_argument(
        "--target",
        help="move the vessel along e1 until a lay quantity reaches a value, e.g. top_tension=8e5 "
        f"(quantities: {', '.join(TARGETS)})",
    )
    static.add_argument(
        "--bracket",
        help="LOW,HIGH: the vessel positions (η's x, m) to search between; default: searched from vessel.eta "
        "in steps that double from 1 m",
    )
    check = commands.add_parser("check", help="validate a scenario file without solving")
    check.add_argument("scenario", type=Path, help="scenario file (TOML)")
    plot = commands.add_parser("plot", help="figures from a results file")
    plot.add_argument("results", type=Path, help="results file (netCDF) written by `pipelay run`")
    plot.add_argument("--plots", type=Path, required=True, help="directory for figures")
    return parser


def _reference(scenario: Scenario) -> list[float] | None:
    """The controller's η_ref, for the vessel figure."""
    controller = scenario.source.get("controller")
    return (
        list(controller["reference"]) if isinstance(controller, dict) and "reference" in controller else None
    )


def _depth(scenario: Scenario) -> float | None:
    sea = scenario.model.sea
    return sea.depth if sea is not None else None


def _summary(state: pl.State) -> str:
    """Top tension, end reactions and vessel pose of a state, one per line."""
    lines = [
        f"top tension |F_B|       {np.linalg.norm(state.reaction('B')[:3]) / 1e3:12.1f} kN",
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
    summary = state.lay_summary()
    if summary is not None:
        lines.extend(_lay_lines(summary, state.roller_reactions))
    if state.eta is not None:
        lines.append(f"vessel η                {np.array2string(state.eta, precision=3)}")
        lines.append(
            f"thrust τ (surge, sway, yaw) {np.array2string(state.tau[[0, 1, 5]] / 1e3, precision=1)} kN, kN m"
        )
    return "\n".join(lines)


def _lay_lines(summary: dict[str, Any], rollers: np.ndarray | None) -> list[str]:
    """The lay summary of a static state, one quantity per line."""
    liftoff = summary["liftoff_roller"]
    lines = [
        f"lay: top tension        {summary['top_tension'] / 1e3:12.1f} kN (at the tensioner or tower)",
        f"lay: departure angle    {np.degrees(summary['departure_angle']):12.2f}° below horizontal",
        "lay: lift-off roller    "
        + (
            f"{liftoff:12d} of {len(rollers)}"
            if liftoff is not None and rollers is not None
            else "        none"
        ),
        f"lay: layback            {summary['layback']:12.2f} m",
        f"lay: overbend strain    {100 * summary['overbend_strain']:12.4f} %",
        f"lay: sagbend strain     {100 * summary['sagbend_strain']:12.4f} %",
        f"lay: sagbend moment     {summary['sagbend_moment'] / 1e3:12.1f} kN m",
    ]
    if rollers is not None:
        lines.append(f"lay: roller reactions   {np.array2string(rollers / 1e3, precision=1)} kN")
    return lines


def _run_summary(path: Path) -> str:
    """The records, time span and extremes of a run, read from its results file a slice of records at a time:
    top tension, largest bending moment, lay summary, touchdown range."""
    import xarray as xr

    lines = []
    with xr.open_dataset(path, engine="h5netcdf") as data:
        time = data["time"].values
        lines.append(f"results: {path} ({len(time)} records, t = {time[0]:g} … {time[-1]:g} s)")
        if "reaction_B" in data:
            top = np.linalg.norm(data["reaction_B"].values[:, :3], axis=1)
            lines.append(f"top tension |F_B|       {top.min() / 1e3:10.1f} … {top.max() / 1e3:.1f} kN")
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
            ("top_tension", "lay: top tension       ", 1e-3, "kN"),
            ("departure_angle", "lay: departure angle   ", 180 / np.pi, "°"),
            ("overbend_strain", "lay: overbend strain   ", 100.0, "%"),
            ("sagbend_strain", "lay: sagbend strain    ", 100.0, "%"),
        ):
            if key in data:
                series = data[key].values * scale
                if np.any(np.isfinite(series)):
                    lines.append(f"{label} {np.nanmin(series):10.4g} … {np.nanmax(series):.4g} {unit}")
        if "touchdown_arc_length" in data:
            arc = data["touchdown_arc_length"].values
            if np.any(np.isfinite(arc)):
                lines.append(f"touchdown (from A)      {np.nanmin(arc):10.2f} … {np.nanmax(arc):.2f} m")
            else:
                lines.append("touchdown               none: the pipe never touches the seabed")
    return "\n".join(lines)


def _write(args: argparse.Namespace, scenario: Scenario) -> None:
    """The summary of the run streamed to ``args.output``, and its figures (from the file read back)."""
    print(_run_summary(args.output))
    if args.plots:
        for figure in plots.all_figures(
            load(args.output), args.plots, reference=_reference(scenario), depth=_depth(scenario)
        ):
            print(f"figure: {figure}")


def _run(args: argparse.Namespace) -> int:
    scenario = load_scenario(args.scenario)
    if scenario.t_end is None:
        raise pl.InputError(
            "solver.t_end: needed by `pipelay run` (s); use `pipelay static` for statics only"
        )
    model = scenario.model
    if args.resume:
        simulation = resume(model, args.resume)
    else:
        state = model.static(steps=scenario.static_steps, start=scenario.static_start)
        simulation = model.simulation(state=state, dt=scenario.dt)
    status = 0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            # Streamed to the file as the run goes: memory stays flat; the file is complete on failure or Ctrl-C.
            simulation.run(
                scenario.t_end,
                progress=not args.no_progress,
                record_every=scenario.record_every,
                output=args.output,
            )
        except pl.ConvergenceError as failure:
            print(f"pipelay: solve failed: {failure}", file=sys.stderr)
            status = 1
    if any("interrupted" in str(w.message) for w in caught):
        print(
            f"pipelay: interrupted at t = {simulation.time:g} s; keeping the results so far", file=sys.stderr
        )
        status = INTERRUPTED
    _write(args, scenario)
    if args.checkpoint:
        print(f"checkpoint: {checkpoint(simulation, args.checkpoint)} (t = {simulation.time:g} s)")
    return status


def _target(args: argparse.Namespace, scenario: Scenario) -> pl.State:
    """`--target`: the static state with the vessel moved along e1 until the lay quantity hits the value."""
    quantity, _, text = str(args.target).partition("=")
    try:
        value = float(text)
    except ValueError:
        raise pl.InputError(
            f"--target: {args.target!r} must be QUANTITY=VALUE, e.g. top_tension=8e5"
        ) from None
    vessel = scenario.source.get("vessel")
    if not isinstance(vessel, dict):
        raise pl.InputError("--target: needs a [vessel] to move")
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

    found = find_lay_position(build, quantity, value, bracket, start=x0)
    print(
        f"lay position: vessel x = {found.x:.3f} m gives {quantity} = {found.value:.6g} "
        f"({found.solves} static solves)"
    )
    if abs(found.value - value) > 1e-3 * max(abs(value), 1e-12):
        print(
            f"lay position: {quantity} jumps across {value:.6g} there (the lift-off moves to another roller, "
            "say): the closest a static state comes"
        )
    return found.state


def _static(args: argparse.Namespace) -> int:
    scenario = load_scenario(args.scenario)
    if args.target:
        state = _target(args, scenario)
    else:
        state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    print(f"static equilibrium: {state.iterations} Newton iterations in {state.steps} load step(s)")
    print(_summary(state))
    if args.plots:
        path = Path(args.plots) / "tension_bending.png"
        plots.tension_and_bending(state, path=path)
        print(f"figure: {path}")
        if state.lay_summary() is not None:
            path = Path(args.plots) / "lay_configuration.png"
            plots.lay_configuration(state, path=path)
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
    print(f"{args.scenario}: valid: {rod.elements} elements, {rod.length:g} m, {vessel}; {run}")
    return 0


def _plot(args: argparse.Namespace) -> int:
    results = load(args.results)
    for figure in plots.all_figures(results, args.plots):
        print(f"figure: {figure}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``pipelay`` command; returns the exit code."""
    args = _parser().parse_args(argv)
    command = {"run": _run, "static": _static, "check": _check, "plot": _plot}[args.command]
    try:
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
