"""Benchmark: the robustness campaign. Realistic S-lay and J-lay cases from a seeded generator, each solved in
statics and its converged state checked for physical sense; every K-th case also run 30 s in time with its current
and waves, and every K-th searched for a vessel position that reaches a target known to be reachable. Prints
Markdown tables.

Not a test. The cases come from ``tests/lay_cases.py`` (shared with ``tests/test_robustness.py``, whose fixed cases
it draws): S-lay in 30–1000 m and J-lay in 300–3000 m, API 5L pipes of 6–32", bare, 3LPE-coated or concrete-coated,
empty or flooded, currents of 0–1.2 m/s toward any heading (uniform, sheared or a power law), JONSWAP waves or none,
DP or the vessel held by its static thrust; each designed with catenary and stinger equations so that it is
*sensible* (the rules are in ``lay_cases.RULES``; draws that break one are thrown away and counted). Case i of seed
S depends on (S, i) only, so any case replays alone.

Per case:

* statics as ``pipelay static`` solves them (``model.static(steps, start)`` of the scenario); the outcome is
  "converged", a failure named from the error's message ("load step fell below (loads)" when it fell below
  while the loads were brought in, "(supports)" while the supports were moved to their positions, "capsized",
  "Newton did not converge", "catenary start", "input error", "panic", ...), a "timeout" or a "crash" of the
  process, or, for a
  converged state that ``lay_cases.physical_problems`` finds non-physical (the pipe through the stinger, a roller
  overloaded, the pipe through the seabed, compression at the hold point, deflected against the current, a strain
  beyond 5 × yield), "non-physical: <what>", the worst kind: a state accepted that is wrong. Suspect states
  (``pipelay.PhysicsWarning``: strain beyond yield, heel) are listed, not counted as failures;
* dynamics (every ``--dynamics-every`` case whose statics converged): ``--seconds`` s at the scenario's Δt = 0.1 s
  with the current, waves and DP of the case; it fails on an error or when a number blows up (not finite, a node
  more than max(50 m, depth/2) from its static position, the top tension beyond 10 × the static one);
* the target search (every ``--target-every`` case): ``find_lay_position`` for the top tension or the layback (at
  random) that statics give with the vessel where the design's equations put a horizontal tension 5–15 % above or
  below the case's, searched from the case's position; reachable by construction (when statics converge there,
  physically). It succeeds when it returns that value within 0.1 % (or that position within 2 cm).

The campaign runs in one worker process at a time (restarted after a timeout or a crash), the engine on
``--threads`` threads (1 by default: ``RAYON_NUM_THREADS``), so that it leaves the machine's other core free.

Usage::

    python benches/robustness.py [--cases 200] [--seed 1] [--dynamics-every 4] [--target-every 4] [--out records.json]
    python benches/robustness.py --seed 1 --case 17 > case17.toml    # one case: its scenario as TOML, its outcome
    pipelay static case17.toml                                         #   in comments; replay it
    python benches/robustness.py --table records.json                # the tables again from saved records
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import multiprocessing
import multiprocessing.connection
import os
import re
import statistics
import sys
import time
import warnings
from collections import Counter
from collections.abc import Iterable
from dataclasses import asdict, replace
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import lay_cases
from machine import machine

KINDS = ("s-lay", "j-lay")
TARGET_CHANGE = (0.05, 0.15)
"""By how much (a share, either way) the target's catenary horizontal tension differs from the case's: the target's
vessel position is where the design's equations put that tension (a fraction of a metre from the case's in shallow
water, metres in deep)."""
TARGET_TOLERANCE = 0.01
"""find_lay_position's tolerance on x (m)."""


# Scenario documents as TOML.


def _toml_value(value: Any, indent: str = "") -> str:
    """A TOML value: a bool, number, string or array (arrays of arrays one row a line)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        if value and all(isinstance(item, list) for item in value):
            rows = ",\n".join(f"{indent}    {_toml_value(item)}" for item in value)
            return f"[\n{rows},\n{indent}]"
        return "[" + ", ".join(_toml_value(item) for item in value) + "]"
    raise TypeError(f"no TOML for {value!r}")


def to_toml(document: dict[str, Any], prefix: str = "") -> str:
    """A scenario document (nested dicts, arrays of tables as lists of dicts) as TOML text."""
    lines: list[str] = []
    tables: list[tuple[str, Any]] = []
    for key, value in document.items():
        if isinstance(value, dict) or (isinstance(value, list) and value and isinstance(value[0], dict)):
            tables.append((key, value))
        else:
            lines.append(f"{key} = {_toml_value(value)}")
    for key, value in tables:
        if isinstance(value, dict):
            lines += ["", f"[{prefix}{key}]", to_toml(value, f"{prefix}{key}.")]
        else:
            for item in value:
                lines += ["", f"[[{prefix}{key}]]", to_toml(item, f"{prefix}{key}.")]
    return "\n".join(lines).strip("\n")


# One case.


def failure_kind(error: BaseException) -> str:
    """The kind of a failure, from the exception and its message."""
    import pipelay as pl

    message = str(error)
    if type(error).__name__ == "PanicException":
        return "panic"
    if isinstance(error, pl.InputError):
        if "no vessel position" in message or "bracket" in message:
            return "not bracketed"
        return "input error"
    if isinstance(error, pl.ConvergenceError):
        if "load step fell below" in message and "lay position search" not in message:
            loads = re.search(r"at load factor ([0-9.]+)", message)
            if loads and float(loads.group(1)) < 1.0:
                return "load step fell below (loads)"
            return "load step fell below (supports)"
        for words, kind in (
            ("lay position search: statics failed", "statics failed in the search"),
            ("capsized", "capsized"),
            ("Newton did not converge", "Newton did not converge"),
            ("catenary", "catenary start"),
        ):
            if words in message:
                return kind
        return "convergence (other)"
    return f"exception ({type(error).__name__})"


def _outcome(error: BaseException, started: float) -> dict[str, Any]:
    """The record of a failed solve."""
    return {
        "ok": False,
        "kind": failure_kind(error),
        "message": str(error)[:400],
        "seconds": time.perf_counter() - started,
    }


def _solve(model: Any, scenario: Any) -> tuple[Any, list[str]]:
    """The static state as `pipelay static` solves it, and the PhysicsWarnings it raised."""
    import pipelay as pl

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", pl.PhysicsWarning)
        state = model.static(steps=scenario.static_steps, start=scenario.static_start)
    return state, [str(w.message) for w in caught if isinstance(w.message, pl.PhysicsWarning)]


def _summary(state: Any, case: lay_cases.LayCase) -> dict[str, float | None]:
    """The solved numbers worth keeping: lay summary, largest roller reaction, touchdown's sideways offset."""
    summary = state.lay_summary() or {}
    keep = (
        "top_tension",
        "departure_angle",
        "layback",
        "sagbend_strain",
        "overbend_strain",
        "liftoff_roller",
    )
    values: dict[str, float | None] = {
        key: (None if summary.get(key) is None else float(summary[key])) for key in keep
    }
    reactions = state.roller_reactions
    values["max_roller_reaction"] = None if reactions is None else float(np.max(reactions))
    touchdown = state.touchdown
    values["touchdown_y"] = None if touchdown is None else float(touchdown.position[1])
    positions = np.asarray(state.positions)
    values["largest_offset"] = float(positions[int(np.argmax(np.abs(positions[:, 1]))), 1])
    if case.kind == "s-lay":
        values["min_roller_gap"] = float(np.min(lay_cases.roller_gaps(state, case)))
    return values


def _build(case: lay_cases.LayCase, x: float) -> Any:
    """The case's model with the vessel at x (m), the DP's reference moved with it."""
    from pipelay.scenario import parse_scenario

    data = copy.deepcopy(case.scenario)
    x0 = data["vessel"]["eta"][0]
    data["vessel"]["eta"][0] = x
    if "controller" in data:
        data["controller"]["reference"][0] += x - x0
    return parse_scenario(data).model


def run_dynamics(
    case: lay_cases.LayCase, model: Any, state: Any, seconds: float, dt: float
) -> dict[str, Any]:
    """A run of `seconds` from the static state; blown up when not finite, a node more than max(50 m, depth/2)
    from its static position or the top tension beyond 10 × the static one."""
    started = time.perf_counter()
    try:
        simulation = model.simulation(state=state, dt=dt)
        results = simulation.run(seconds, progress=False, record_every=max(1, round(1.0 / dt)))
    except BaseException as error:
        if isinstance(error, KeyboardInterrupt):
            raise
        return _outcome(error, started)
    elapsed = time.perf_counter() - started
    positions = np.asarray(results.positions)
    eta = np.asarray(results.eta)
    energy = np.asarray(results.energy["total"])
    summary = results.lay_summary() or {}
    top = np.asarray(summary.get("top_tension", np.zeros(1)))
    record: dict[str, Any] = {"ok": True, "kind": "ran", "message": "", "seconds": elapsed}
    finite = all(np.all(np.isfinite(array)) for array in (positions, eta, energy, top))
    if not finite:
        return record | {"ok": False, "kind": "blown up", "message": "non-finite numbers in the records"}
    moved = float(np.max(np.linalg.norm(positions - positions[0], axis=2)))
    static_top = abs(float(top[0])) if top.size else 0.0
    ratio = float(np.max(np.abs(top))) / static_top if static_top > 0.0 else 0.0
    record |= {
        "max_displacement": moved,
        "top_tension_ratio": ratio,
        "passivity_margin": results.passivity_margin(),
    }
    if moved > max(50.0, 0.5 * case.choices.depth):
        return record | {"ok": False, "kind": "blown up", "message": f"a node moved {moved:.1f} m"}
    if ratio > 10.0:
        return record | {
            "ok": False,
            "kind": "blown up",
            "message": f"top tension {ratio:.1f} × the static one",
        }
    return record


def run_target(case: lay_cases.LayCase) -> dict[str, Any]:
    """The target search for a value reachable by construction: the top tension or the layback (at random) of the
    physical static state with the vessel where the design's equations put a horizontal tension 5–15 % above or
    below the case's (half and a quarter as far where statics fail there or give a non-physical state). Found: the
    value within 0.1 %, or the position within twice the search's tolerance (where the quantity is steep)."""
    import pipelay as pl
    from pipelay.analysis.lay import find_lay_position, lay_quantity

    rng = np.random.default_rng([case.seed, case.index, 7])
    quantity = "top_tension" if rng.random() < 0.5 else "layback"
    x0 = float(case.scenario["vessel"]["eta"][0])
    change = float(rng.uniform(*TARGET_CHANGE)) * (1.0 if rng.random() < 0.5 else -1.0)
    shift = lay_cases.vessel_position(case, case.design["a"] * (1.0 + change)) - x0
    record: dict[str, Any] = {"quantity": quantity, "x_start": x0, "x_target": x0 + shift}
    value, why = math.nan, ""
    for _ in range(
        3
    ):  # the target's position, nearer the case's where statics there fail or are non-physical
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", pl.PhysicsWarning)
                truth = _build(case, x0 + shift).static()
            value = lay_quantity(truth, quantity)
        except BaseException as error:
            if isinstance(error, KeyboardInterrupt):
                raise
            why = str(error)[:400]
        else:
            problems = lay_cases.physical_problems(truth, case)
            if not problems and math.isfinite(value):
                break
            why = "; ".join(message for _, message in problems) or f"{quantity} undefined"
        value, shift = math.nan, 0.5 * shift
    record["x_target"] = x0 + shift
    if not math.isfinite(value):
        return record | {"reachable": False, "ok": False, "kind": "unreachable", "message": why}
    record |= {"reachable": True, "value": value}
    started = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pl.PhysicsWarning)
            found = find_lay_position(
                lambda x: _build(case, x), quantity, value, start=x0, step=1.0, tolerance=TARGET_TOLERANCE
            )
    except BaseException as error:
        if isinstance(error, KeyboardInterrupt):
            raise
        outcome = _outcome(error, started)
        if outcome["kind"] == "statics failed in the search":
            where = "at the start" if f"x = {x0:.3f} m" in outcome["message"] else "on the way"
            outcome["kind"] += f" ({where})"
        return record | outcome
    seconds = time.perf_counter() - started
    record |= {"seconds": seconds, "solves": found.solves, "x_found": found.x, "value_found": found.value}
    near = abs(found.x - record["x_target"]) <= 2.0 * TARGET_TOLERANCE
    if abs(found.value - value) > 1e-3 * abs(value) and not near:
        message = (
            f"{found.value:.6g} at x = {found.x:.3f} m for {value:.6g} at x = {record['x_target']:.3f} m"
        )
        return record | {"ok": False, "kind": "value missed", "message": message}
    return record | {"ok": True, "kind": "found", "message": ""}


def campaign_case(seed: int, index: int, planar: bool = False) -> lay_cases.LayCase:
    """Case `index` of seed `seed`; `planar`: with the current's component across the lay plane left out (a
    diagnostic: the same case, its current in the pipe's plane)."""
    case = lay_cases.draw(seed, index)
    c = case.choices
    if not planar or c.current == 0.0:
        return case
    along = c.current * math.cos(math.radians(c.current_heading_deg))
    choices = replace(c, current=round(abs(along), 4), current_heading_deg=0.0 if along >= 0.0 else 180.0)
    return lay_cases.design(choices, index, seed)


def run_case(
    seed: int, index: int, dynamics: bool, target: bool, seconds: float, planar: bool = False
) -> dict[str, Any]:
    """Case `index` of seed `seed`: statics and the physical check, then dynamics and the target search if asked."""
    from pipelay.scenario import parse_scenario

    case = campaign_case(seed, index, planar)
    record: dict[str, Any] = {
        "index": index,
        "seed": seed,
        "kind": case.kind,
        "label": case.label,
        "elements": int(case.design["elements"]),
        "cross_current": lay_cases.current_cross(case),
        "choices": asdict(case.choices),
        "design": case.design,
        "dynamics": None,
        "target": None,
    }
    started = time.perf_counter()
    try:
        scenario = parse_scenario(copy.deepcopy(case.scenario))
        started = time.perf_counter()
        state, suspects = _solve(scenario.model, scenario)
    except BaseException as error:
        if isinstance(error, KeyboardInterrupt):
            raise
        record["statics"] = _outcome(error, started)
    else:
        elapsed = time.perf_counter() - started
        problems = lay_cases.physical_problems(state, case)
        record["statics"] = {
            "ok": not problems,
            "kind": f"non-physical: {problems[0][0]}" if problems else "converged",
            "message": "; ".join(message for _, message in problems),
            "seconds": elapsed,
            "iterations": int(state.iterations),
            "steps": int(state.steps),
        }
        record["suspects"] = suspects
        record["solved"] = _summary(state, case)
        if dynamics:
            record["dynamics"] = run_dynamics(case, scenario.model, state, seconds, scenario.dt)
    if target:
        record["target"] = run_target(case)
    return record


# The worker process.


def _worker(connection: multiprocessing.connection.Connection) -> None:
    """Runs the cases it receives (run_case's arguments) until it receives None."""
    while True:
        try:
            job = connection.recv()
        except EOFError:  # the campaign is gone
            return
        if job is None:
            return
        connection.send(run_case(*job))


class Worker:
    """One worker process, restarted after a timeout or a crash."""

    def __init__(self) -> None:
        """No process yet: the first case starts it."""
        self.context = multiprocessing.get_context("spawn")
        self.process: Any = None
        self.connection: Any = None

    def start(self) -> None:
        """A new worker process, the engine's threads as RAYON_NUM_THREADS says."""
        ours, theirs = self.context.Pipe()
        self.process = self.context.Process(target=_worker, args=(theirs,), daemon=True)
        self.process.start()
        theirs.close()
        self.connection = ours

    def run(self, job: tuple[Any, ...], timeout: float) -> dict[str, Any] | str:
        """The record of a case, or why there is none ("timeout", "crash (exit code ...)")."""
        if self.process is None or not self.process.is_alive():
            self.start()
        self.connection.send(job)
        if not self.connection.poll(timeout):
            self.process.kill()
            self.process.join()
            self.process = None
            return "timeout"
        try:
            return self.connection.recv()
        except EOFError:
            self.process.join()
            code = self.process.exitcode
            self.process = None
            return f"crash (exit code {code})"

    def stop(self) -> None:
        """Ends the worker when it is idle."""
        if self.process is not None and self.process.is_alive():
            self.connection.send(None)
            self.process.join(10)


def _lost(seed: int, index: int, why: str, timeout: float, planar: bool) -> dict[str, Any]:
    """The record of a case whose process timed out or crashed."""
    case = campaign_case(seed, index, planar)
    return {
        "index": index,
        "seed": seed,
        "kind": case.kind,
        "label": case.label,
        "elements": int(case.design["elements"]),
        "cross_current": lay_cases.current_cross(case),
        "choices": asdict(case.choices),
        "design": case.design,
        "statics": {"ok": False, "kind": why.split(" (")[0], "message": why, "seconds": timeout},
        "dynamics": None,
        "target": None,
    }


# Tables.


def _percent(part: int, whole: int) -> str:
    """ "12.5 % (1/8)", or "–" of nothing."""
    return "–" if whole == 0 else f"{100.0 * part / whole:.1f} % ({part}/{whole})"


def _median(values: list[float], digits: int) -> str:
    """The median with `digits` decimals, or "–" of nothing."""
    return "–" if not values else f"{statistics.median(values):.{digits}f}"


def _seconds(values: list[float]) -> str:
    """Median / max of times (s), or "–" of nothing."""
    return "–" if not values else f"{statistics.median(values):.3f} / {max(values):.3f}"


def summary_table(records: list[dict[str, Any]]) -> list[str]:
    """Per lay kind and overall: statics, non-physical states, dynamics and target success, statics time."""
    lines = [
        (
            "| lay | cases | statics success | non-physical accepted | dynamics success | target success "
            "| statics time, median / max (s) | dynamics, s per simulated s | target search time, median (s) |"
        ),
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for name, chosen in (
        *((kind, [r for r in records if r["kind"] == kind]) for kind in KINDS),
        ("all", records),
    ):
        statics = [r["statics"] for r in chosen]
        ok = sum(s["ok"] for s in statics)
        bad = sum(s["kind"].startswith("non-physical") for s in statics)
        dynamics = [r["dynamics"] for r in chosen if r.get("dynamics")]
        targets = [r["target"] for r in chosen if r.get("target") and r["target"].get("reachable")]
        times = [
            s["seconds"] for s in statics if s["kind"] == "converged" or s["kind"].startswith("non-physical")
        ]
        speed = [r["dynamics"]["seconds"] / r["dynamics_seconds"] for r in chosen if r.get("dynamics")]
        search = [t["seconds"] for t in targets if "seconds" in t]
        lines.append(
            f"| {name} | {len(chosen)} | {_percent(ok, len(chosen))} | {bad} "
            f"| {_percent(sum(d['ok'] for d in dynamics), len(dynamics))} "
            f"| {_percent(sum(t['ok'] for t in targets), len(targets))} | {_seconds(times)} "
            f"| {_median(speed, 3)} | {_median(search, 2)} |"
        )
    return lines


def _examples(indices: Iterable[int], count: int = 6) -> str:
    """The first `count` case indices, "…" for the rest."""
    chosen = sorted(indices)
    text = ", ".join(str(i) for i in chosen[:count])
    return text + (", …" if len(chosen) > count else "")


def failures_table(records: list[dict[str, Any]]) -> list[str]:
    """Failures by kind, statics, dynamics and target search apart, with example cases."""
    lines = ["| stage | kind | S-lay | J-lay | all | cases |", "|---|---|---:|---:|---:|---|"]
    for stage in ("statics", "dynamics", "target"):
        found: dict[str, list[dict[str, Any]]] = {}
        for record in records:
            outcome = record.get(stage)
            if not outcome or outcome["ok"] or (stage == "target" and not outcome.get("reachable")):
                continue
            found.setdefault(outcome["kind"], []).append(record)
        for kind, chosen in sorted(found.items(), key=lambda item: (-len(item[1]), item[0])):
            counts = Counter(r["kind"] for r in chosen)
            lines.append(
                f"| {stage} | {kind} | {counts['s-lay']} | {counts['j-lay']} | {len(chosen)} "
                f"| {_examples(r['index'] for r in chosen)} |"
            )
    return lines


def conditions_table(records: list[dict[str, Any]]) -> list[str]:
    """Statics success by the current's crossing of the lay plane, DP and waves."""
    lines = ["| condition | S-lay | J-lay | all |", "|---|---:|---:|---:|"]

    def crossing(r: dict[str, Any]) -> str:
        if r["choices"]["current"] == 0.0:
            return "no current"
        return (
            "current in the lay plane (cross < 0.05 m/s)"
            if abs(r["cross_current"]) < 0.05
            else "current across"
        )

    groups = [
        ("no current", lambda r: crossing(r) == "no current"),
        ("current in the lay plane (cross < 0.05 m/s)", lambda r: crossing(r).startswith("current in")),
        ("current across (cross ≥ 0.05 m/s)", lambda r: crossing(r) == "current across"),
        ("DP", lambda r: r["choices"]["dp"]),
        ("held by static thrust", lambda r: not r["choices"]["dp"]),
        ("with waves", lambda r: r["choices"]["hs"] > 0.0),
        ("500 elements", lambda r: r["elements"] == 500),
    ]
    for name, test in groups:
        cells = []
        for kind in (*KINDS, None):
            chosen = [r for r in records if test(r) and (kind is None or r["kind"] == kind)]
            cells.append(_percent(sum(r["statics"]["ok"] for r in chosen), len(chosen)))
        lines.append(f"| {name} | {' | '.join(cells)} |")
    return lines


def elements_table(records: list[dict[str, Any]]) -> list[str]:
    """Statics time of the 500-element cases that converged."""
    chosen = [r for r in records if r["elements"] == 500]
    converged = [r["statics"] for r in chosen if r["statics"]["kind"] == "converged"]
    return [
        "| 500-element cases | converged (physical) | statics time, median / max (s) | iterations, median |",
        "|---:|---:|---:|---:|",
        (
            f"| {len(chosen)} | {len(converged)} | {_seconds([s['seconds'] for s in converged])} "
            f"| {_median([s['iterations'] for s in converged], 0)} |"
        ),
    ]


def print_tables(header: dict[str, Any], records: list[dict[str, Any]]) -> None:
    """The campaign's tables, Markdown."""
    print(f"`{header['command']}`; {header['machine']}; engine on {header['threads']} thread(s)")
    print()
    print("\n".join(summary_table(records)))
    print()
    print("Failures by kind (cases by index):")
    print()
    print("\n".join(failures_table(records)))
    print()
    print("Statics success by condition:")
    print()
    print("\n".join(conditions_table(records)))
    print()
    print("\n".join(elements_table(records)))
    rejected = header.get("rejections", {})
    if rejected:
        print()
        print(
            f"Draws thrown away as not sensible ({sum(rejected.values())} for {len(records)} cases): "
            + ", ".join(
                f"{rule} {count}" for rule, count in sorted(rejected.items(), key=lambda item: -item[1])
            )
        )


# Command line.


def _command(args: argparse.Namespace) -> str:
    """The command line that reproduces the table."""
    words = ["python benches/robustness.py", f"--cases {args.cases}", f"--seed {args.seed}"]
    words += [f"--dynamics-every {args.dynamics_every}", f"--target-every {args.target_every}"]
    if args.seconds != 30.0:
        words.append(f"--seconds {args.seconds:g}")
    if args.planar:
        words.append("--planar")
    return " ".join(words)


def replay(args: argparse.Namespace) -> int:
    """`--case I`: the case's scenario as TOML, then its outcome as TOML comments."""
    case = campaign_case(args.seed, args.case, args.planar)
    print(
        f"# robustness case {args.case} of seed {args.seed}{' (planar)' if args.planar else ''}: {case.label}"
    )
    print("# design: " + ", ".join(f"{key} = {value:.6g}" for key, value in case.design.items()))
    print(to_toml(case.scenario))
    sys.stdout.flush()
    if args.no_run:
        return 0
    record = run_case(args.seed, args.case, True, True, args.seconds, args.planar)
    print()
    for stage in ("statics", "dynamics", "target"):
        if record.get(stage):
            shown = {k: v for k, v in record[stage].items() if v not in ("", None)}
            print(f"# {stage}: " + json.dumps(shown, default=str))
    if record.get("solved"):
        print("# solved: " + json.dumps(record["solved"]))
    for suspect in record.get("suspects", []):
        print(f"# suspect: {suspect}")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=200, help="number of cases (default 200)")
    parser.add_argument("--seed", type=int, default=1, help="the campaign's seed (default 1)")
    parser.add_argument("--dynamics-every", type=int, default=4, help="run every K-th case in time (0: none)")
    parser.add_argument(
        "--target-every", type=int, default=4, help="search every K-th case's target (0: none)"
    )
    parser.add_argument("--seconds", type=float, default=30.0, help="simulated time of a dynamics run (s)")
    parser.add_argument("--timeout", type=float, default=600.0, help="wall time allowed per case (s)")
    parser.add_argument("--threads", type=int, default=1, help="the engine's threads (RAYON_NUM_THREADS)")
    parser.add_argument(
        "--planar",
        action="store_true",
        help="leave out the currents' components across the lay plane (diagnostic)",
    )
    parser.add_argument("--out", type=Path, help="write the per-case records (JSON) here")
    parser.add_argument("--case", type=int, help="replay one case: its scenario as TOML and its outcome")
    parser.add_argument("--no-run", action="store_true", help="with --case: print the scenario only")
    parser.add_argument("--table", type=Path, help="print the tables of saved records instead of running")
    args = parser.parse_args(argv)
    if args.table:
        saved = json.loads(args.table.read_text())
        print_tables(saved["header"], saved["records"])
        return 0
    os.environ["RAYON_NUM_THREADS"] = str(args.threads)
    if args.case is not None:
        return replay(args)
    rejections: Counter[str] = Counter()
    for index in range(args.cases):
        lay_cases.draw(args.seed, index, rejections)
    header = {
        "command": _command(args),
        "machine": machine(),
        "threads": args.threads,
        "seed": args.seed,
        "cases": args.cases,
        "rejections": dict(rejections),
    }
    worker = Worker()
    records: list[dict[str, Any]] = []
    try:
        for index in range(args.cases):
            dynamics = args.dynamics_every > 0 and index % args.dynamics_every == 0
            target = args.target_every > 0 and index % args.target_every == args.target_every // 2
            job = (args.seed, index, dynamics, target, args.seconds, args.planar)
            outcome = worker.run(job, args.timeout)
            if isinstance(outcome, str):
                record = _lost(args.seed, index, outcome, args.timeout, args.planar)
            else:
                record = outcome
            record["dynamics_seconds"] = args.seconds
            records.append(record)
            statics = record["statics"]
            print(
                f"case {index}: {statics['kind']} ({statics['seconds']:.2f} s) {record['label']}",
                file=sys.stderr,
                flush=True,
            )
            if args.out:
                args.out.write_text(json.dumps({"header": header, "records": records}, indent=1, default=str))
    finally:
        worker.stop()
    print_tables(header, records)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
