"""The lay table: the static lay configuration at each water depth of a route, with the vessel placed so
that a lay quantity reaches its target, as lay engineers draw one up for every job.

```python
import pipelay as pl
from pipelay.analysis.lay_table import write_csv

table = pl.lay_table("examples/s_lay.toml", depths=[100, 150, 200, 250], target={"top_tension": 1.0e6})
table.top_tension.sel(depth=200.0)  # N, an xarray.Dataset indexed by depth (SI units)
write_csv(table, "table.csv")  # people's units: kN, degrees, percent
```

**One depth.** The scenario with ``sea.depth`` set to the depth and the same pipe and equipment. The vessel
stays at the surface: η's z moves with it (the surface is z = −depth, e3 down; an offset of the scenario's
η z from −depth is kept), and a controller's reference moves with the vessel (x with η's x, z with the
surface). The seabed is the flat plane z = 0 through end A: a ``sea.seabed.bathymetry``, which fixes where
the seabed is, is refused.

**The pipe's length.** Deeper water needs more pipe between the seabed and the vessel. At a depth d beyond the
scenario's own d₀ the pipe's reference, of length L₀, is lengthened in proportion to L₀·d/d₀, rounded up to
whole elements of the scenario's element length, at its top: a straight ``[rod]``'s end moves out along its
direction, a ``[line]``'s first segment (the seabed end's) is lengthened, so the segments after it and the
equipment are the same. End A stays at the origin, so the vessel's x grows by the length added. At depths up
to d₀ the reference is the scenario's own. Each depth's length is in the table (``pipe_length``), and
`scenario_at` gives the scenario of one depth. Where the pipe must be lengthened, a ``[rod]`` given by its
nodes, point loads and attachments (their places along the pipe would move) and a vessel at end A are refused:
give the scenario at the deepest depth of the table instead, its reference long enough for it.

**The search.** At each depth `pipelay.analysis.lay.find_lay_position` moves the vessel along e1 until the
target is met (to `tolerance` on x, at most `max_solves` static solves, each with the scenario's
``solver.static_steps`` and ``static_start``). Its start continues along the depths: they are solved from
the one nearest d₀ outward, the deeper ones in increasing and the shallower ones in decreasing order, each
starting where the depths solved before it say: the vessel's offset from the reference's length, x − L(d),
extrapolated linearly in depth from the last two, or, after one, the catenary taken as similar (its
suspended length's excess over its horizontal span, (L − s_td) − layback, growing in proportion to the
depth) from that one, or from the scenario's own static state.

**A row** (SI units, each variable with ``units`` and ``long_name``): `COLUMNS`, from the state found, the
DNV-ST-F101 utilisations with the scenario's ``[checks]`` (``scenario.checks``), and ``failure`` (empty, or
why the depth has no row), ``warning`` (what is suspect in its state, as `PhysicsWarning` says) and
``utilisation_basis`` (what the utilisations assume: grade, safety class, fabrication, condition,
pressures).
Each row is a standalone solve of its depth's scenario with the vessel at the row's x, to the bit. A depth
where the target cannot be met (beyond what the vessel's positions give, where statics fails, a quantity
that jumps across the target, a scenario that does not build at that depth) is a row of NaN with its reason
in ``failure``, never an exception.

**Where it runs.** In this process, one depth after another; with a Dask client, or `workers` > 1, and at
least `DASK_DEPTHS` depths, on Dask (`pipelay.analysis.sweep`'s cluster handling: a local cluster of
`workers` single-threaded processes for the call, or the given client or scheduler address): the depths,
sorted, are cut into as many contiguous runs as there are workers, each run solved as above on one worker.
The rows are in the order of `depths` either way; where the runs start differs, x differs within
`tolerance`.

Imports of pipelay: the package (``pl.checks``, the engine's errors), `pipelay.scenario`,
`pipelay.analysis.lay`, `pipelay.analysis.suspect` and `pipelay.analysis.sweep` (its cluster).
"""

from __future__ import annotations

import copy
import math
import os
import warnings
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

import numpy as np

import pipelay as pl
from pipelay.analysis.lay import MAX_SOLVES, TARGETS, _show, check_target, find_lay_position
from pipelay.analysis.suspect import PhysicsWarning, suspect_state
from pipelay.analysis.sweep import _connected, _refuse_unguarded
from pipelay.scenario import Scenario, load_scenario, parse_scenario

__all__ = [
    "COLUMNS",
    "DASK_DEPTHS",
    "TITLE",
    "Column",
    "lay_table",
    "pipe_length",
    "scenario_at",
    "utilisation_basis",
    "write_csv",
]

TITLE = "pipelay lay table"
"""The ``title`` attribute of a lay table."""

DASK_DEPTHS = 6
"""The fewest depths that run on Dask (with a client, or `workers` > 1); fewer run in this process."""


@dataclass(frozen=True)
class Column:
    """One quantity of a lay table: its SI unit and long name (the Dataset's attributes), and its CSV column's
    header and the factor from SI to the column's unit."""

    units: str
    long_name: str
    header: str
    scale: float = 1.0


COLUMNS: dict[str, Column] = {
    "vessel_x": Column("m", "vessel position along e1 (η's x) at which the target is met", "vessel_x_m"),
    "top_tension": Column(
        "N", "top tension: the effective tension at the tensioner or tower", "top_tension_kN", 1e-3
    ),
    "departure_angle": Column(
        "rad",
        "departure angle below the horizontal where the pipe leaves the equipment",
        "departure_angle_deg",
        180.0 / math.pi,
    ),
    "layback": Column("m", "layback: horizontal distance from the hold point to the touchdown", "layback_m"),
    "overbend_strain": Column(
        "1",
        "overbend strain: largest strain from the hold point to the inflection point",
        "overbend_strain_pct",
        100.0,
    ),
    "sagbend_strain": Column(
        "1",
        "sagbend strain: largest strain from the inflection point to the touchdown",
        "sagbend_strain_pct",
        100.0,
    ),
    "tip_clearance": Column(
        "m",
        "tip clearance: gap between the pipe and the stinger's last roller (<= 0: in contact)",
        "tip_clearance_m",
    ),
    "roller_reaction_max": Column("N", "largest roller load", "roller_reaction_max_kN", 1e-3),
    "liftoff_roller": Column(
        "1",
        "lift-off roller (the last in contact), numbered from 1 at the stinger's vessel end; NaN: none",
        "liftoff_roller",
    ),
    "load_controlled_max": Column(
        "1", "largest DNV-ST-F101 load-controlled utilisation along the pipe", "load_controlled_max"
    ),
    "displacement_controlled_max": Column(
        "1",
        "largest DNV-ST-F101 displacement-controlled utilisation along the pipe",
        "displacement_controlled_max",
    ),
    "propagation_max": Column(
        "1",
        "largest DNV-ST-F101 propagation buckling utilisation along the pipe (> 1: buckle arrestors needed)",
        "propagation_max",
    ),
    "pipe_length": Column(
        "m", "the pipe's reference length at this depth (lengthened with depth)", "pipe_length_m"
    ),
    "solves": Column("1", "static solves the search for the vessel position spent", "solves"),
}
"""The numbers of a lay table's row: name → `Column` (SI units in the Dataset, people's in the CSV)."""

_TEXTS: dict[str, str] = {
    "utilisation_basis": (
        "what the utilisations assume: grade, safety class, fabrication, condition, pressures"
    ),
    "warning": "what is suspect in the depth's state (PhysicsWarning), empty: nothing",
    "failure": "why the depth has no row (its numbers NaN), empty: none",
}
"""The texts of a lay table's row: name → long name."""


# --- one depth's scenario --------------------------------------------------------------------------------


def _own_depth(source: Mapping[str, Any]) -> float:
    """The scenario's water depth d₀ (m); InputError without a sea or a vessel."""
    sea = source.get("sea")
    if not isinstance(sea, Mapping):
        raise pl.InputError("sea: a lay table sets the water depth: the scenario needs a [sea]")
    if not isinstance(source.get("vessel"), Mapping):
        raise pl.InputError(
            "vessel: a lay table places the vessel at each depth: the scenario needs a [vessel]"
        )
    seabed = sea.get("seabed")
    if isinstance(seabed, Mapping) and seabed.get("bathymetry") is not None:
        raise pl.InputError(
            "sea.seabed.bathymetry: a lay table sets the water depth over the flat seabed z = 0 through "
            "end A; a bathymetry fixes where the seabed is: leave it out"
        )
    return float(sea["depth"])


def _reference_length(source: Mapping[str, Any]) -> tuple[float, float]:
    """The reference's length L₀ and the element length of the part a lay table lengthens (m)."""
    line = source.get("line")
    if isinstance(line, Mapping):
        segments = line["segments"]
        first = segments[0]
        return float(sum(s["length"] for s in segments)), float(first["length"]) / int(first["elements"])
    rod = source["rod"]
    if "nodes" in rod:
        nodes = np.asarray(rod["nodes"], dtype=float)
        return float(np.sum(np.linalg.norm(np.diff(nodes, axis=0), axis=1))), math.nan
    length = float(np.linalg.norm(np.subtract(rod["end"], rod["start"])))
    return length, length / int(rod["elements"])


def _added_elements(source: Mapping[str, Any], depth: float) -> int:
    """The elements a lay table adds to the reference at `depth` (m): L₀·(d/d₀ − 1) rounded up to whole
    elements, none at depths up to d₀; InputError where what the scenario has cannot be lengthened."""
    own = _own_depth(source)
    if depth <= own:
        return 0
    length, element = _reference_length(source)
    wanted = length * (depth / own - 1.0)
    why = (
        f"at depth {depth:g} m the lay table lengthens the pipe's reference from {length:g} m (for the "
        f"scenario's depth {own:g} m) to {length * depth / own:g} m"
    )
    instead = (
        f"give the scenario at the deepest depth of the table (sea.depth = {depth:g} m or more, its "
        "reference long enough for it)"
    )
    if "nodes" in (source.get("rod") or {}):
        raise pl.InputError(
            f"rod.nodes: {why}, at its top, which a reference given by its nodes has not; {instead}"
        )
    if source.get("point_loads") or source.get("attachments"):
        key = "point_loads" if source.get("point_loads") else "attachments"
        raise pl.InputError(
            f"{key}: {why}, so their places along the pipe would move; {instead}, or leave them out"
        )
    if source["vessel"]["end"] != "B":
        raise pl.InputError(f"vessel.end: {why} at end B, the top end; the vessel holds end A: {instead}")
    return math.ceil(wanted / element - 1e-9)


def _length(source: Mapping[str, Any], depth: float) -> float:
    """The pipe's reference length at `depth` (m): `pipe_length` of a scenario's document."""
    length, element = _reference_length(source)
    added = _added_elements(source, depth)
    return length + added * element if added else length


def pipe_length(scenario: Scenario | str | os.PathLike[str], depth: float) -> float:
    """The pipe's reference length at `depth` in a lay table of `scenario` (a `Scenario` or a scenario file):
    the scenario's own L₀ at depths up to its depth d₀, beyond it L₀·depth/d₀ rounded up to whole elements
    (m; see the module's documentation). Raises pl.InputError where the pipe cannot be lengthened."""
    return _length(_scenario(scenario).source, _depth(depth, "depth"))


def _at(source: Mapping[str, Any], depth: float, x: float) -> dict[str, Any]:
    """The scenario's document at `depth` (m) with the vessel at η's x = `x` (m)."""
    own = _own_depth(source)
    added = _added_elements(source, depth)
    data = copy.deepcopy(dict(source))
    data["sea"]["depth"] = depth
    vessel = data["vessel"]
    shift, sink = x - float(vessel["eta"][0]), own - depth
    vessel["eta"][0] = x
    vessel["eta"][2] += sink
    controller = data.get("controller")
    if isinstance(controller, dict) and "reference" in controller:
        controller["reference"][0] += shift
        controller["reference"][2] += sink
    if added:
        line = data.get("line")
        if isinstance(line, dict):
            first = line["segments"][0]
            step = first["length"] / first["elements"]
            first["length"] += added * step
            first["elements"] += added
            if line.get("length") is not None:
                line["length"] += added * step
        else:
            rod = data["rod"]
            start, end = np.asarray(rod["start"], dtype=float), np.asarray(rod["end"], dtype=float)
            rod["end"] = (end + (end - start) * added / rod["elements"]).tolist()
            rod["elements"] += added
    return data


def scenario_at(scenario: Scenario | str | os.PathLike[str], depth: float, x: float) -> Scenario:
    """The scenario of one depth of a lay table: `scenario` (a `Scenario` or a scenario file) at water depth
    `depth` (m) with the vessel at η's x = `x` (m), its pipe lengthened as the module's documentation says;
    ``scenario_at(s, d, float(table.vessel_x.sel(depth=d)))`` gives the state of a row.

    Raises pl.InputError where the scenario cannot be taken to that depth (no sea or vessel, a bathymetry, a
    pipe that cannot be lengthened), naming the key."""
    found = _scenario(scenario)
    data = _at(found.source, _depth(depth, "depth"), float(x))
    return parse_scenario(data, f"{found.origin}, at depth {depth:g} m", found.folder)


# --- the search at one depth -------------------------------------------------------------------------------


class _Configured:
    """A scenario's model whose ``static()`` takes the scenario's static steps and start (what
    `find_lay_position` solves)."""

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario

    def static(self) -> pl.State:
        return self.scenario.model.static(steps=self.scenario.static_steps, start=self.scenario.static_start)

    def rest(self) -> pl.State:
        return self.scenario.model.rest()


@dataclass(frozen=True)
class _Point:
    """A depth solved: its depth, the vessel's x, the pipe's length and the suspended pipe's excess of length
    over its horizontal span (m)."""

    depth: float
    x: float
    length: float
    excess: float

    def similar(self, depth: float, length: float) -> float:
        """The vessel's x at `depth` with a pipe of `length` if the catenary were this one scaled (m)."""
        return self.x + (length - self.length) - self.excess * (depth / self.depth - 1.0)


def _excess(state: pl.State, length: float) -> float:
    """The suspended pipe's excess of length over its horizontal span (m): the reference from the touchdown to
    end B less the layback; 0 without a touchdown."""
    summary = cast(dict[str, Any], state.lay_summary())  # a lay position's state has one
    excess = length - float(summary["touchdown_arc_length"]) - float(summary["layback"])
    return excess if math.isfinite(excess) else 0.0


def _guess(history: list[_Point], base: _Point, depth: float, length: float) -> float:
    """Where the search at `depth` starts (m): x − L extrapolated linearly from the last two depths solved,
    or the catenary of the last one (or the scenario's own) scaled."""
    if len(history) >= 2:
        last, before = history[-1], history[-2]
        slope = ((last.x - last.length) - (before.x - before.length)) / (last.depth - before.depth)
        return length + last.x - last.length + slope * (depth - last.depth)
    return (history[-1] if history else base).similar(depth, length)


@dataclass(frozen=True)
class _Job:
    """What a run of depths needs, as plain data (shipped to a Dask worker as it is)."""

    source: dict[str, Any]
    origin: str
    folder: str | None
    target: str
    value: float
    tolerance: float
    max_solves: int
    checks: dict[str, Any]  # keyword arguments of pl.checks.dnv_st_f101: the scenario's [checks]
    base: _Point


def _failed(length: float, why: str) -> dict[str, Any]:
    """The row of a depth where the target is not met: NaN, its pipe length, and why."""
    row: dict[str, Any] = dict.fromkeys(COLUMNS, math.nan) | dict.fromkeys(_TEXTS, "")
    row["pipe_length"] = length
    row["failure"] = why
    return row


def _row(state: pl.State, x: float, length: float, solves: int, checks: Mapping[str, Any]) -> dict[str, Any]:
    """The row of a state found at x with a pipe of `length` (SI units)."""
    summary = cast(dict[str, Any], state.lay_summary())  # the search's state has one
    rollers = state.roller_reactions
    liftoff = summary["liftoff_roller"]
    row: dict[str, Any] = {
        "vessel_x": x,
        "top_tension": float(summary["top_tension"]),
        "departure_angle": float(summary["departure_angle"]),
        "layback": float(summary["layback"]),
        # A lay without a stinger (a J-lay tower) has no overbend, as the summaries say.
        "overbend_strain": math.nan if rollers is None else float(summary["overbend_strain"]),
        "sagbend_strain": float(summary["sagbend_strain"]),
        "tip_clearance": float(summary["tip_clearance"]),
        "roller_reaction_max": float(np.max(rollers)) if rollers is not None and len(rollers) else math.nan,
        "liftoff_roller": math.nan if liftoff is None else float(liftoff + 1),
        "load_controlled_max": math.nan,
        "displacement_controlled_max": math.nan,
        "propagation_max": math.nan,
        "pipe_length": length,
        "solves": float(solves),
        "utilisation_basis": "",
        "warning": "; ".join(message for _, _, message in suspect_state(state)),
        "failure": "",
    }
    if state.section.wall_thickness is not None:
        check = pl.checks.dnv_st_f101(state, **checks)
        row["load_controlled_max"] = float(np.max(check.load_controlled))
        row["displacement_controlled_max"] = float(np.max(check.displacement_controlled))
        row["propagation_max"] = pl.checks.propagation_buckling(state, **checks).max()
        row["utilisation_basis"] = check.basis
    return row


def _solve_depth(job: _Job, depth: float, start: float) -> tuple[dict[str, Any], _Point | None]:
    """The row of one depth, the search starting at x = `start` (m), and the point solved (None: failed)."""
    length = _length(job.source, depth)
    origin = f"{job.origin}, at depth {depth:g} m"

    def build(x: float) -> _Configured:
        return _Configured(parse_scenario(_at(job.source, depth, x), origin, job.folder))

    try:
        with warnings.catch_warnings():
            # Kept in the row's `warning` instead, once for the state found.
            warnings.simplefilter("ignore", PhysicsWarning)
            found = find_lay_position(
                build,  # type: ignore[arg-type]
                job.target,
                job.value,
                start=start,
                tolerance=job.tolerance,
                max_solves=job.max_solves,
                **job.checks,
            )
    except (pl.InputError, pl.ConvergenceError) as error:
        return _failed(length, f"{type(error).__name__}: {error}"), None
    if not found.reached:
        why = (
            f"{job.target} jumps across {_show(job.target, job.value)} at x = {found.x:.3f} m (the lift-off "
            f"moves to another roller, say): the closest static state gives {_show(job.target, found.value)}"
        )
        return _failed(length, why), None
    row = _row(found.state, found.x, length, found.solves, job.checks)
    return row, _Point(depth, found.x, length, _excess(found.state, length))


def _solve_run(
    job: _Job, depths: list[float], solved: Callable[[], object] | None = None
) -> list[dict[str, Any]]:
    """The rows of `depths` (increasing), solved from the one nearest the scenario's depth outward, each
    search starting where the depths solved before it say (`_guess`); `solved` is called after each depth."""
    first = min(range(len(depths)), key=lambda k: abs(depths[k] - job.base.depth))
    rows: dict[int, dict[str, Any]] = {}
    points: dict[int, _Point | None] = {}
    for chain in (range(first, len(depths)), range(first, -1, -1)):
        history: list[_Point] = []
        for k in chain:
            if k not in rows:
                start = _guess(history, job.base, depths[k], _length(job.source, depths[k]))
                rows[k], points[k] = _solve_depth(job, depths[k], start)
                if solved is not None:
                    solved()
            if (point := points[k]) is not None:
                history.append(point)
    return [rows[k] for k in range(len(depths))]


def _task(job: _Job, depths: list[float]) -> list[dict[str, Any]]:
    """`_solve_run` on a Dask worker, with one engine thread (the parallelism is the runs)."""
    os.environ.setdefault("RAYON_NUM_THREADS", "1")
    return _solve_run(job, depths)


# --- the table ---------------------------------------------------------------------------------------------


def _scenario(scenario: Scenario | str | os.PathLike[str]) -> Scenario:
    """A scenario, or the one of a scenario file."""
    return scenario if isinstance(scenario, Scenario) else load_scenario(scenario)


def _depth(value: Any, argument: str) -> float:
    """A water depth (m): a finite number > 0; InputError naming `argument` otherwise."""
    try:
        depth = float(value)
    except (TypeError, ValueError):
        depth = math.nan
    if isinstance(value, bool) or not (math.isfinite(depth) and depth > 0.0):
        raise pl.InputError(f"{argument}: {value!r} is not a water depth; allowed: a finite number > 0 (m)")
    return depth


def _depths(depths: Iterable[float]) -> list[float]:
    """`depths` as distinct water depths (m); InputError naming `depths` otherwise."""
    if isinstance(depths, (str, bytes, Mapping)) or not isinstance(depths, Iterable):
        raise pl.InputError(f"depths: {depths!r} must be a list of water depths (m), e.g. [100, 150, 200]")
    found = [_depth(value, "depths") for value in depths]
    if not found:
        raise pl.InputError("depths: empty; give at least one water depth (m)")
    repeated = sorted({d for d in found if found.count(d) > 1})
    if repeated:
        raise pl.InputError(f"depths: {', '.join(f'{d:g}' for d in repeated)} m given more than once")
    return found


def _target(target: Mapping[str, float]) -> tuple[str, float]:
    """The one lay quantity of `target` and its value (SI units); InputError naming `target` otherwise."""
    if not isinstance(target, Mapping) or len(target) != 1:
        raise pl.InputError(
            f"target: {target!r} must be one lay quantity and its value (SI units), e.g. "
            f"{{'top_tension': 1e6}}; quantities: {', '.join(TARGETS)}"
        )
    ((name, value),) = target.items()
    check_target(name, argument="target")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise pl.InputError(f"target: {name} = {value!r} must be a number ({TARGETS[name]})") from None
    check_target(name, number, argument="target")
    return name, number


def _base(scenario: Scenario, length: float) -> _Point:
    """The scenario's own static state as a point of the continuation (its excess 0 where statics fails)."""
    x = float(scenario.source["vessel"]["eta"][0])
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PhysicsWarning)
            excess = _excess(_Configured(scenario).static(), length)
    except pl.ConvergenceError:
        excess = 0.0
    return _Point(_own_depth(scenario.source), x, length, excess)


def _runs(count: int, depths: list[float]) -> list[list[int]]:
    """The indices of `depths` sorted by depth, cut into `count` contiguous runs (none empty)."""
    order = sorted(range(len(depths)), key=lambda k: depths[k])
    return [[int(k) for k in run] for run in np.array_split(order, min(count, len(order)))]


def lay_table(
    scenario: Scenario | str | os.PathLike[str],
    depths: Iterable[float],
    target: Mapping[str, float],
    *,
    client: Any = None,
    workers: int | None = None,
    tolerance: float = 0.01,
    max_solves: int = MAX_SOLVES,
    progress: bool = False,
) -> Any:
    """The lay table of `scenario` over water depths: at each depth, the static lay configuration with the
    vessel placed along e1 so that the lay quantity of `target` reaches its value (see the module's
    documentation for how a depth is made, the pipe's length and the search).

    Args:
        scenario: a `Scenario` or a scenario file (TOML) with a ``[sea]`` and a ``[vessel]`` holding end B.
        depths: the water depths (m), each > 0 and given once; the rows keep their order.
        target: one lay quantity and its value in SI units, e.g. ``{"top_tension": 1.0e6}`` (N) or
            ``{"sagbend_strain": 0.0015}``: a key of `pipelay.analysis.lay.TARGETS`.
        client: a ``distributed.Client`` or a scheduler address to run the depths on (with at least
            `DASK_DEPTHS` of them); None: in this process, or a local cluster when `workers` > 1.
        workers: processes of the local cluster (None or 1: in this process).
        tolerance: on the vessel's x (m).
        max_solves: the most static solves each depth's search spends.
        progress: show a progress bar over the depths (or the runs, on Dask).

    Returns:
        An ``xarray.Dataset`` indexed by ``depth`` (m): `COLUMNS` (SI units) and the texts ``failure``,
        ``warning`` and ``utilisation_basis``; its attributes name the scenario, the target and its value (SI)
        and the scenario's depth. A depth where the target is not met is a row of NaN with ``failure`` saying
        why. `write_csv` writes it in people's units; ``to_netcdf(path, engine="h5netcdf")`` as it is.

    Raises:
        pl.InputError: a bad scenario (no sea or vessel, a bathymetry, a pipe that cannot be lengthened to the
            deepest depth), depth, target (unknown, out of range, or one the lay equipment fixes), tolerance
            or max_solves: at once, before any depth is solved.
        RuntimeError: a local cluster started from the top level of a script outside
            ``if __name__ == "__main__":`` (as `pl.sweep`).
    """
    found = _scenario(scenario)
    wanted = _depths(depths)
    name, value = _target(target)
    if not (isinstance(tolerance, (int, float)) and math.isfinite(tolerance) and tolerance > 0):
        raise pl.InputError(f"tolerance: {tolerance!r} must be a positive number (m)")
    if isinstance(max_solves, bool) or not isinstance(max_solves, int) or max_solves < 2:
        raise pl.InputError(f"max_solves: {max_solves!r} must be a whole number of static solves, at least 2")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise pl.InputError(f"workers: {workers!r} must be a whole number of processes, at least 1")
    source = found.source
    length = _length(source, _own_depth(source))
    for depth in wanted:  # a pipe that cannot be lengthened is refused before anything is solved
        _length(source, depth)
    check_target(name, rest=found.model.rest(), argument="target")
    job = _Job(
        source=source,
        origin=found.origin,
        folder=found.folder,
        target=name,
        value=value,
        tolerance=float(tolerance),
        max_solves=max_solves,
        checks=dict(found.checks),
        base=_base(found, length),
    )
    rows: list[dict[str, Any] | None] = [None] * len(wanted)
    if len(wanted) >= DASK_DEPTHS and (client is not None or (workers or 1) > 1):
        _on_dask(job, wanted, rows, client, workers, progress)
    else:
        from tqdm import tqdm  # type: ignore[import-untyped]

        (run,) = _runs(1, wanted)
        with tqdm(total=len(wanted), unit="depth", desc="lay table", disable=not progress) as bar:
            for k, row in zip(run, _solve_run(job, [wanted[k] for k in run], bar.update), strict=True):
                rows[k] = row
    return _dataset(job, wanted, rows)  # type: ignore[arg-type]


def _on_dask(
    job: _Job,
    depths: list[float],
    rows: list[dict[str, Any] | None],
    client: Any,
    workers: int | None,
    progress: bool,
) -> None:
    """The rows of `depths` solved on Dask, a run of contiguous depths a worker, into `rows`; a run whose task
    fails (its worker killed, say) gives its depths rows of NaN saying so."""
    from distributed import as_completed
    from tqdm import tqdm  # type: ignore[import-untyped]

    _refuse_unguarded(local=client is None)
    with _connected(client, workers, len(depths)) as active:
        count = workers or max(1, len(active.scheduler_info()["workers"]))
        runs = _runs(count, depths)
        futures = {active.submit(_task, job, [depths[k] for k in run], pure=False): run for run in runs}
        with tqdm(total=len(runs), unit="run", desc="lay table", disable=not progress) as bar:
            for future in as_completed(list(futures)):
                run = futures[future]
                try:
                    solved = future.result()
                except Exception as error:  # noqa: BLE001 - the run's depths fail, the others are kept
                    why = (
                        f"the Dask task of depths {depths[run[0]]:g} … {depths[run[-1]]:g} m failed: {error}"
                    )
                    solved = [_failed(_length(job.source, depths[k]), why) for k in run]
                for k, row in zip(run, solved, strict=True):
                    rows[k] = row
                bar.update()


def _dataset(job: _Job, depths: list[float], rows: list[dict[str, Any]]) -> Any:
    """The rows as an xarray.Dataset indexed by depth."""
    import xarray as xr

    variables: dict[str, Any] = {
        name: (
            "depth",
            np.array([row[name] for row in rows], dtype=float),
            {"units": c.units, "long_name": c.long_name},
        )
        for name, c in COLUMNS.items()
    }
    for name, long_name in _TEXTS.items():
        variables[name] = (
            "depth",
            np.array([row[name] for row in rows], dtype=object),
            {"long_name": long_name},
        )
    unit = TARGETS[job.target].split(",")[0]
    return xr.Dataset(
        variables,
        coords={"depth": ("depth", np.array(depths), {"units": "m", "long_name": "water depth"})},
        attrs={
            "title": TITLE,
            "source": job.origin,
            "target": job.target,
            "target_value": job.value,
            "target_units": unit if unit in ("N", "rad", "m") else "1",
            "tolerance": job.tolerance,
            "scenario_depth": job.base.depth,
            "conventions": "SI units; frame e: origin at the seabed end A, e1 lay direction, e3 down; the "
            "pipe lengthened at its top beyond the scenario's depth, in proportion to the depth",
        },
    )


def utilisation_basis(table: Any) -> str:
    """What a lay table's utilisations assume (its rows' ``utilisation_basis``, the first solved row's; "" when
    no row was solved)."""
    return next((str(text) for text in table["utilisation_basis"].values if text), "")


def write_csv(table: Any, path: str | os.PathLike[str]) -> Path:
    """Writes a lay table (`lay_table`'s Dataset) as CSV in people's units: a column per `COLUMNS` entry under
    its header (``top_tension_kN``, ``departure_angle_deg``, ``sagbend_strain_pct``, ...; the lift-off roller
    numbered from 1, empty where none), then ``utilisation_basis``, ``warning`` and ``failure``; a row per
    depth, in the table's order, ``depth_m`` first; NaN as an empty cell, numbers to 12 significant digits.
    Returns the path."""
    frame = table.to_dataframe()
    columns = {"depth_m": table["depth"].values}
    for name, column in COLUMNS.items():
        columns[column.header] = frame[name].to_numpy() * column.scale
    for name in _TEXTS:
        columns[name] = frame[name].to_numpy()
    import pandas as pd

    written = Path(path)
    pd.DataFrame(columns).to_csv(written, index=False, float_format="%.12g", na_rep="")
    return written
