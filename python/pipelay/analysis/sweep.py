"""Operability sweeps: a scenario run over a grid of values of some of its keys, on Dask.

```python
import pipelay as pl

sweep = pl.sweep(
    "lay.toml",
    over={"sea.current.surface_velocity": [[0, -0.4, 0], [0, -0.8, 0]], "pipe.wall_thickness": [0.015, 0.02]},
    output="lay-sweep",
)
sweep.summary  # xarray.Dataset, a dimension per swept key: every case's statistics (lay-sweep/summary.nc)
sweep.failures  # {(surface_velocity, wall_thickness): message} of the cases that failed
```

Every combination of the values in `over` is a case: the scenario's TOML data with those dotted keys set
(`scenario.apply_overrides`). All cases are checked (`scenario.validate_overrides`, then each case parsed)
before anything runs, so a bad key or value raises `pl.InputError` at once, naming it. Instead of a file, a
factory (a picklable callable taking the case {key: value} and returning a `Scenario` or a TOML-like dict)
builds each case on its worker; its cases are checked there, a bad one failing alone.

Each case runs as one task on a Dask cluster (a `distributed.LocalCluster` of one single-threaded process a
core by default, or the given `distributed.Client` or scheduler address): the worker is sent the case's data
(not engine objects), runs statics then the simulation to `solver.t_end` (`run_case`, the same function a
single run uses, so a case's numbers do not depend on where it ran), and writes, each atomically:

* ``<output>/cases/<name>.nc``: the case's results (the layout of `Results.to_netcdf`);
* ``<output>/cases/<name>.json``: the case {key: value} and its statistics (`STATISTICS`), or its failure.

`<name>` is the case's values made filesystem-safe, then a hash of the scenario, the case and the checks: a
case with a JSON file is not run again, so calling `sweep` again with the same output folder reuses the
finished cases (after Ctrl-C, a lost worker or a changed grid) and runs only the rest. A case that fails (a
bad value: `InputError`; Newton not converging: `ConvergenceError`) is recorded with its message and the
others go on. The summary, assembled from the JSON files, is written to ``<output>/summary.nc`` at the end,
and also when Ctrl-C stops the sweep (KeyboardInterrupt is then raised again). The output folder must be on a
filesystem the workers share, at the same path.

Faults. A worker process that dies while it runs a case (killed, out of memory, a crash) is restarted by its
nanny and the case is run again from its start, on any worker; its files are those of an undisturbed run. A
case whose worker dies `ALLOWED_FAILURES` + 1 times (on the sweep's own cluster; a given client's scheduler
keeps its ``distributed.scheduler.allowed-failures``) is a failure of this call ("KilledWorker: ...", not
saved: run again next time) and the others go on. A lost scheduler (its connection closed, or no answer
within `SCHEDULER_TIMEOUT`) stops the sweep with ConnectionError after writing the summary of the finished
cases; calling `sweep` again with the same folder, on a running cluster, runs only the rest. Without a client,
`sweep` must not be called from the top level of a script (it raises RuntimeError): the local cluster's worker
processes start by re-running the script, which would start the sweep again in each of them; put the call
under ``if __name__ == "__main__":``.

Imports of pipelay: the engine, `pipelay.scenario`, `pipelay.results` and `pipelay.analysis.extremes`.
"""

from __future__ import annotations

import ast
import hashlib
import itertools
import json
import linecache
import os
import re
import sys
import time
import warnings
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from types import FrameType
from typing import Any

import numpy as np

from pipelay._core import ConvergenceError, InputError, Model, Results, Simulation
from pipelay.analysis.checks import describe_parameters
from pipelay.analysis.extremes import extremes
from pipelay.results import resume
from pipelay.results.atomic import _atomic_write
from pipelay.scenario import (
    Scenario,
    apply_overrides,
    load_scenario,
    mark_results,
    parse_scenario,
    validate_overrides,
)
from pipelay.scenario.schema import reference_tables

__all__ = [
    "ALLOWED_FAILURES",
    "SCHEDULER_TIMEOUT",
    "STATISTICS",
    "Sweep",
    "case_statistics",
    "run",
    "run_case",
    "start",
    "sweep",
]

Factory = Callable[[dict[str, Any]], "Scenario | dict[str, Any]"]
"""Builds a case's scenario from the case {dotted key: value}."""

STATISTICS: dict[str, tuple[str, str]] = {
    "top_tension_max": ("N", "largest top tension: effective tension at the tensioner, tower or support"),
    "top_tension_min": ("N", "smallest top tension: effective tension at the tensioner, tower or support"),
    "reaction_B_max": ("N", "largest reaction at B |F_B|, the force of the line on what holds end B"),
    "tension_max": ("N", "largest effective axial force along the pipe"),
    "tension_min": ("N", "smallest effective axial force along the pipe (negative: compression)"),
    "moment_max": ("N m", "largest bending moment along the pipe"),
    "strain_max": ("1", "largest longitudinal strain at the outer fibre"),
    "utilisation_max": ("1", "largest DNV-ST-F101 local-buckling utilisation (1: the limit)"),
    "load_controlled_max": ("1", "largest DNV-ST-F101 load-controlled utilisation"),
    "displacement_controlled_max": ("1", "largest DNV-ST-F101 displacement-controlled utilisation"),
    "offset_max": ("m", "largest horizontal distance of the vessel from its position at t = 0"),
    "thrust_max": ("N", "largest horizontal thrust |(tau_surge, tau_sway)|"),
    "touchdown_excursion": (
        "m",
        "largest horizontal distance of the touchdown point from its first position",
    ),
    "passivity_margin_min": (
        "J",
        "min over t of W(t) - (E(t) - E(0)), work supplied less energy gained: 0 to round-off, < 0: made",
    ),
}
"""The statistics of a case (`case_statistics`): name → (units, description). Only those that apply to the
model are computed: the vessel's without a vessel, strain without a section, utilisation without a pipe's
wall thickness (`[pipe]`), the touchdown's without contact are absent (NaN in the summary)."""

SUMMARY_TITLE = "pipelay sweep summary"

ALLOWED_FAILURES = 2
"""Times a case is run again on the sweep's own local cluster after the worker running it died
(``distributed.scheduler.allowed-failures`` of its scheduler): a case whose worker dies once more is a failure."""

SCHEDULER_TIMEOUT = 60.0
"""Longest wait for the scheduler to answer (s): a scheduler silent for longer is taken as lost."""

PROBE_EVERY = 10.0
"""Interval between the sweep's checks that its scheduler still answers (s)."""

POLL = 0.1
"""Interval between the sweep's looks for finished cases (s)."""


# --- one case --------------------------------------------------------------------------------------------


def start(scenario: Scenario, checkpoint: str | os.PathLike[str] | None = None) -> Simulation:
    """The simulation of a scenario from its static state (``model.static`` with the scenario's steps and
    start), or continued from a `checkpoint` file; time step ``scenario.dt`` (s), through the scenario's
    `[[stages]]` if it has any (``scenario.stages``).

    Raises InputError if the scenario has no ``solver.t_end``, ConvergenceError if the statics fail.
    """
    if scenario.t_end is None:
        raise InputError("solver.t_end: needed for a simulation (s); use `pipelay static` for statics only")
    if checkpoint is not None:
        return resume(scenario.model, checkpoint, stages=scenario.stages)
    state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    return scenario.simulation(state)


def run(
    simulation: Simulation, scenario: Scenario, output: str | os.PathLike[str], *, progress: bool = False
) -> bool:
    """Runs `simulation` to ``scenario.t_end`` (s), recording every ``scenario.record_every``-th step,
    streamed to the netCDF file `output` as it goes (complete there also if the run fails or is stopped).

    The file keeps the scenario (`pipelay.scenario.scenario_of_results` reads it back). Returns whether Ctrl-C
    stopped the run early (the results so far are in the file). Raises ConvergenceError if a step fails.
    """
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            simulation.run(
                scenario.t_end,  # type: ignore[arg-type]
                progress=progress,
                record_every=scenario.record_every,
                output=output,
            )
    finally:
        if Path(output).is_file():  # also after a failed step: the records before it are in the file
            mark_results(output, scenario)
    return any("interrupted" in str(warning.message) for warning in caught)


def case_statistics(
    results: Results, model: Model, checks: Mapping[str, Any] | None = None
) -> dict[str, float]:
    """The statistics of a run (`STATISTICS`, SI units): `statistics.extremes` (the top tension, the effective
    tension the tensioner, tower or top support holds, `statistics.top_tension`; the reaction at B |F_B|; axial
    force, moment, strain and, for a pipe with a wall thickness, DNV-ST-F101 utilisation with `checks`, keyword
    arguments of `checks.dnv_st_f101`, default its defaults), the vessel's largest offset from its starting
    position (m) and horizontal thrust (N), the touchdown point's excursion (m) and the passivity margin
    (J)."""
    section = model.rod.section
    dnv = dict(checks or {}) if section.wall_thickness is not None else None
    found = {
        key: value for key, value in extremes(results, model=model, checks=dnv).items() if key in STATISTICS
    }
    if results.eta is not None and results.tau is not None:
        found["offset_max"] = float(np.max(np.hypot(*(results.eta[:, :2] - results.eta[0, :2]).T)))
        found["thrust_max"] = float(np.max(np.hypot(results.tau[:, 0], results.tau[:, 1])))
    touchdown = results.touchdown
    points = None if touchdown is None else touchdown[np.isfinite(touchdown).all(axis=1), :2]
    if points is not None and len(points):
        found["touchdown_excursion"] = float(np.max(np.hypot(*(points - points[0]).T)))
    found["passivity_margin_min"] = -results.passivity_margin()
    return found


def run_case(
    scenario: Scenario, path: str | os.PathLike[str], checks: Mapping[str, Any] | None = None
) -> dict[str, float]:
    """One run of a scenario, as a sweep runs each case: statics, the simulation to ``solver.t_end`` written
    to the netCDF file `path` atomically (only a finished run is there), then its `case_statistics` (read back
    from the file) with `checks`, else the scenario's ``[checks]``.

    Raises InputError (no ``solver.t_end``), ConvergenceError (the file is then not written) or
    KeyboardInterrupt (Ctrl-C; nor is it).
    """
    simulation = start(scenario)

    def write(temporary: Path) -> None:
        if run(simulation, scenario, temporary):
            raise KeyboardInterrupt

    _atomic_write(Path(path), write)
    chosen = scenario.checks if checks is None else checks
    return case_statistics(_Recorded.read(path), scenario.model, chosen)  # type: ignore[arg-type]


class _Recorded:
    """What `case_statistics` reads of a run, read from its results file alone: a long case's file holds
    gigabytes of rotations and velocities (a 3-hour storm: 54 000 records) that a `Results` would load and
    the statistics never look at. The same arrays as `pl.load`'s, so the same statistics to the bit, but for the
    nodes' positions, of which only the depth is read (the statistics look at no other coordinate)."""

    def __init__(self, variables: dict[str, np.ndarray]) -> None:
        self.time = variables["time"]
        self.section_forces = variables["section_forces"]
        self.positions = variables["positions"]
        self._reaction_b = variables["reaction_B"]
        self.eta = variables.get("eta")
        self.tau = variables.get("tau")
        self.touchdown = variables.get("touchdown")
        top = variables.get("top_tension")
        self._summary = None if top is None else {"top_tension": top}
        total, supplied = variables["total_energy"], variables["supplied_work"]
        self._margin = float(np.max(total - total[0] - supplied))

    @classmethod
    def read(cls, path: str | os.PathLike[str]) -> _Recorded:
        """The variables the statistics need, from the results file at `path`, read with h5py (a netCDF-4
        file is HDF5; its variables are datasets at the root): xarray's reading of a long streamed file spends
        seconds on its dimensions. Values equal to a variable's fill value become NaN, as xarray decodes them
        (the writers' fill value is NaN already)."""
        import h5py

        names = ("time", "section_forces", "positions", "reaction_B", "eta", "tau", "touchdown", "top_tension",
                 "total_energy", "supplied_work")  # fmt: skip
        variables = {}
        with h5py.File(path, "r", locking=False) as file:
            for name in names:
                if name not in file:
                    continue
                if name == "positions":
                    # Only the nodes' depth (for the checks' hydrostatic pressure): x and y are left zero.
                    values = np.zeros(file[name].shape)
                    values[:, :, 2] = file[name][:, :, 2]
                else:
                    values = np.asarray(file[name][()], dtype=np.float64)
                fill = file[name].attrs.get("_FillValue")
                if fill is not None and np.isfinite(fill).all():
                    values = np.where(values == np.asarray(fill).item(), np.nan, values)
                variables[name] = values
        return cls(variables)

    def reaction(self, end: str) -> np.ndarray:
        """The rod's force and moment on the support at end B (T, 6): the statistics read no other."""
        if end != "B":
            raise ValueError(f"end: only 'B' is read for the statistics, got {end!r}")
        return self._reaction_b

    def lay_summary(self) -> dict[str, np.ndarray] | None:
        """The lay summary's top tension, the one series the statistics read; None without a vessel."""
        return self._summary

    def passivity_margin(self) -> float:
        """max over t of E(t) − E(0) − W(t) (J), as `Results.passivity_margin`."""
        return self._margin


@dataclass(frozen=True)
class _Case:
    """A case as shipped to a worker: plain data and, for a factory, the factory."""

    values: tuple[Any, ...]  # in the order of `over`
    settings: dict[str, Any]  # {dotted key: value}
    name: str
    origin: str
    folder: str | None  # the scenario file's, for its relative paths
    data: dict[str, Any] | None  # the scenario's TOML data with the settings applied
    factory: Factory | None
    checks: dict[str, Any] | None

    def scenario(self) -> Scenario:
        """The case's scenario, built from its data or by its factory."""
        if self.data is not None:
            return parse_scenario(self.data, self.origin, self.folder)
        built = self.factory(dict(self.settings))  # type: ignore[misc]
        return built if isinstance(built, Scenario) else parse_scenario(built, self.origin)


def _task(case: _Case, directory: Path) -> dict[str, Any]:
    """Runs a case on a worker and writes its JSON record (statistics or failure) atomically; returns it."""
    # One engine thread per worker unless the user says otherwise: a sweep's parallelism is its cases (the
    # engine's results do not depend on its thread count). Read when the engine first runs in this process.
    os.environ.setdefault("RAYON_NUM_THREADS", "1")
    record: dict[str, Any] = {"name": case.name, "case": case.settings}
    try:
        scenario = case.scenario()
        record["statistics"] = run_case(scenario, directory / "cases" / f"{case.name}.nc", case.checks)
        record["checks"] = describe_parameters(scenario.checks if case.checks is None else case.checks)
    except (InputError, ConvergenceError) as error:
        record["error"] = f"{type(error).__name__}: {error}"
    text = json.dumps(record, indent=1, default=str)
    _atomic_write(directory / "cases" / f"{case.name}.json", lambda temporary: temporary.write_text(text))
    return record


def _read(directory: Path, case: _Case) -> dict[str, Any] | None:
    """The record a previous sweep left for `case`, or None."""
    path = directory / "cases" / f"{case.name}.json"
    if not path.is_file():
        return None
    record: dict[str, Any] = json.loads(path.read_text())
    return record if "statistics" in record or "error" in record else None


# --- the grid --------------------------------------------------------------------------------------------


def _grid(over: Mapping[str, Iterable[Any]]) -> dict[str, list[Any]]:
    """`over` as keys to non-empty lists of distinct values (numpy values made plain)."""
    if not isinstance(over, Mapping) or not over:
        raise InputError(f"over: must be a non-empty mapping of dotted scenario keys to values, got {over!r}")
    grid = {}
    for key, given in over.items():
        if not isinstance(key, str):
            raise InputError(f"over: {key!r} is not a dotted scenario key such as 'sea.current.velocity'")
        if isinstance(given, (str, bytes, Mapping)) or not isinstance(given, Iterable):
            raise InputError(f"{key}: must be a list of values, got {given!r}")
        values = [value.tolist() if hasattr(value, "tolist") else value for value in given]
        labels = [_label(value) for value in values]
        if not values or len(set(labels)) < len(labels):
            raise InputError(f"{key}: must be a non-empty list of distinct values, got {values!r}")
        grid[key] = values
    return grid


def _label(value: Any) -> str:
    """A value as text: a string as is, anything else as JSON."""
    return value if isinstance(value, str) else json.dumps(value)


def _hashable(value: Any) -> Any:
    """A case value usable in a dict key: lists become tuples."""
    return tuple(_hashable(v) for v in value) if isinstance(value, list) else value


def _name(settings: Mapping[str, Any], fingerprint: str) -> str:
    """A case's file name: its values, filesystem-safe and shortened, then a hash of the scenario's
    `fingerprint` and the case (unique)."""
    readable = "__".join(
        f"{key.rsplit('.', 1)[-1]}={re.sub(r'[^A-Za-z0-9.+-]+', '_', _label(value)).strip('_')}"
        for key, value in settings.items()
    )[:80]
    digest = hashlib.sha256(json.dumps([fingerprint, list(settings.items())], default=str).encode())
    return f"{readable}-{digest.hexdigest()[:10]}"


def _cases(
    scenario: str | os.PathLike[str] | Factory,
    grid: Mapping[str, list[Any]],
    checks: Mapping[str, Any] | None,
) -> tuple[list[_Case], str]:
    """Every case of the grid, and the scenario's source for the summary. The cases of a file are checked
    here (`validate_overrides`, then each case parsed): a bad key or value raises InputError naming it."""
    checks = None if checks is None else dict(checks)
    base, factory, folder = None, None, None
    if callable(scenario):
        import cloudpickle  # type: ignore[import-untyped]

        factory = scenario
        origin = getattr(scenario, "__qualname__", type(scenario).__name__)
        fingerprint = hashlib.sha256(cloudpickle.dumps(scenario)).hexdigest()
    else:
        origin = os.fspath(scenario)
        folder = str(Path(scenario).absolute().parent)  # for the scenario's relative paths, on every worker
        base = load_scenario(scenario).source
        validate_overrides(base, dict(grid), origin, folder)
        fingerprint = json.dumps(base, sort_keys=True, default=str)
    fingerprint += json.dumps(checks, sort_keys=True, default=str)
    cases = []
    for values in itertools.product(*grid.values()):
        settings = dict(zip(grid, values, strict=True))
        described = ", ".join(f"{key} = {_label(value)}" for key, value in settings.items())
        case = _Case(
            values=tuple(values),
            settings=settings,
            name=_name(settings, fingerprint),
            origin=f"{origin}, sweep case {described}",
            folder=folder,
            data=None if base is None else apply_overrides(base, settings),
            factory=factory,
            checks=checks,
        )
        if case.data is not None:
            case.scenario()
        cases.append(case)
    return cases, origin


# --- where the sweep is called from ----------------------------------------------------------------------

GUARD = 'if __name__ == "__main__":'
UNGUARDED = (
    "pl.sweep was called from the top level of a script: the local cluster's worker processes start by "
    "running the script again (Python's 'spawn' start method), which would start the sweep again in each of "
    f"them. Put the call under `{GUARD}` (or give the address of a running scheduler: client='tcp://...')"
)


def _top_level_frame() -> FrameType | None:
    """The frame of the main script's top-level code that led to this call, or None (an interactive
    interpreter, ``python -c``, a package's ``__main__``: the worker processes do not run it again).

    Raises SystemExit with `UNGUARDED` in a worker process that is running the script again (its top level is
    ``__mp_main__``): a one-line message instead of a traceback from each worker.
    """
    main = sys.modules.get("__main__")
    found = None
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "<module>":
            if frame.f_globals.get("__name__") == "__mp_main__":
                raise SystemExit(f"pipelay: error: {UNGUARDED}")
            if main is not None and frame.f_globals is vars(main):
                found = frame
        frame = frame.f_back  # type: ignore[assignment]
    spec = getattr(main, "__spec__", None)
    if spec is not None and (spec.name == "__main__" or spec.name.endswith(".__main__")):
        return None  # multiprocessing does not import a package's __main__ again
    script = getattr(main, "__file__", None)
    if found is None or script is None:
        return None
    try:  # the script's own code (a compiled script's names its source), not a notebook's cell, say
        same = Path(found.f_code.co_filename).resolve() == Path(script).resolve() or script.endswith(".pyc")
    except (OSError, RuntimeError):
        return None
    return found if same else None


def _guarded(frame: FrameType) -> bool | None:
    """Whether the line `frame` (a script's top level) runs sits in an ``if`` on ``__name__``; None if the
    script's source cannot be read."""
    try:
        tree = ast.parse("".join(linecache.getlines(frame.f_code.co_filename)))
    except (SyntaxError, ValueError):
        return None
    if not tree.body:
        return None
    line = frame.f_lineno
    return any(
        isinstance(node, ast.If)
        and node.lineno <= line <= (node.end_lineno or node.lineno)
        and any(isinstance(name, ast.Name) and name.id == "__name__" for name in ast.walk(node.test))
        for node in ast.walk(tree)
    )


def _refuse_unguarded(local: bool) -> None:
    """Raises RuntimeError (`UNGUARDED`) if the sweep is to start its own local cluster (`local`) from the top
    level of a script outside an ``if __name__ == "__main__":`` block, before anything runs: its worker
    processes would fail to start. In a worker process running such a script again, raises SystemExit."""
    frame = _top_level_frame()
    if not local or frame is None:
        return
    import dask

    if dask.config.get("distributed.worker.multiprocessing-method", "spawn") == "fork":
        return  # a forked worker does not run the script again
    if _guarded(frame) is False:
        raise RuntimeError(UNGUARDED)


# --- the sweep -------------------------------------------------------------------------------------------


@dataclass
class Sweep:
    """The outcome of `sweep`.

    Attributes:
        summary: xarray.Dataset with one dimension per swept key (coordinates: its values; non-numbers as
            JSON text), the statistics of every case (`STATISTICS`; NaN where a case failed or a statistic
            does not apply), ``failed`` (1 for a failed case), ``error`` (its message) and ``case`` (the
            name of its files in ``output/cases``); also in ``output/summary.nc``.
        failures: {case: message} of the failed cases; a case is the tuple of its values in the order of
            `over` (lists as tuples).
        cases: {case: results file (netCDF)} of the finished cases.
        output: the sweep's folder.
    """

    summary: Any
    failures: dict[tuple[Any, ...], str]
    cases: dict[tuple[Any, ...], Path]
    output: Path


def sweep(
    scenario: str | os.PathLike[str] | Factory,
    over: Mapping[str, Iterable[Any]],
    client: Any = None,
    output: str | os.PathLike[str] = "sweep",
    *,
    workers: int | None = None,
    checks: Mapping[str, Any] | None = None,
    progress: bool = True,
) -> Sweep:
    """Runs `scenario` for every combination of the values in `over` on a Dask cluster (see the module's
    documentation); returns the summary and the failures.

    Args:
        scenario: a scenario file (TOML), or a factory: a picklable callable taking the case {key: value}
            and returning a `Scenario` or a TOML-like dict, called on the workers.
        over: dotted scenario keys (``"controller.kp"``) to the values to try; the cases are their product.
        client: a `distributed.Client`, a scheduler address (``"tcp://host:8786"``), or None: a
            `distributed.LocalCluster` of `workers` single-threaded processes for the sweep's duration.
        output: the folder for ``cases/`` and ``summary.nc``; finished cases found there are not run again.
        workers: processes of the local cluster (default: one a core, at most one a case to run).
        checks: keyword arguments of `checks.dnv_st_f101` for the utilisation (default: each case's
            scenario's ``[checks]``, else the checks' defaults).
        progress: show a progress bar over the cases.

    Raises:
        InputError: `over` is not a mapping of keys to lists of distinct values, or (scenario file) a case
            has a bad key or value: at once, before anything runs.
        RuntimeError: no `client`, and the call is at the top level of a script, outside
            ``if __name__ == "__main__":`` (the local cluster's workers would run the script again): at once.
        ConnectionError: the scheduler is lost (its connection closed, or no answer within `SCHEDULER_TIMEOUT`
            s), after writing the summary of the cases finished so far; a second call runs only the rest.
        KeyboardInterrupt: Ctrl-C, after writing the summary of the cases finished so far.
    """
    from tqdm import tqdm  # type: ignore[import-untyped]

    _refuse_unguarded(local=client is None)
    grid = _grid(over)
    cases, origin = _cases(scenario, grid, checks)
    directory = Path(output)
    (directory / "cases").mkdir(parents=True, exist_ok=True)
    records: dict[str, dict[str, Any]] = {}
    for case in cases:
        if (record := _read(directory, case)) is not None:
            records[case.name] = record
    pending = [case for case in cases if case.name not in records]
    _discard_partial(directory, pending)
    bar = tqdm(total=len(cases), initial=len(records), unit="case", desc="sweep", disable=not progress)
    try:
        if pending:
            with _connected(client, workers, len(pending)) as active:
                _compute(active, pending, directory, records, bar)
    except KeyboardInterrupt:
        _discard_partial(directory, [case for case in pending if case.name not in records])
        _write_summary(directory, grid, cases, records, origin)
        raise
    except _Lost as lost:
        # The files are the truth: a case may have finished after its record was last looked for. Its workers
        # may still be running cases: their temporary files stay theirs.
        for case in pending:
            if case.name not in records and (record := _read(directory, case)) is not None:
                records[case.name] = record
        _write_summary(directory, grid, cases, records, origin)
        unfinished = sum(case.name not in records for case in pending)
        raise ConnectionError(
            f"sweep: lost the Dask scheduler at {lost.address} ({lost.reason}) with {unfinished} of the "
            f"{len(pending)} cases to run not finished; the finished ones are kept in {directory / 'cases'} "
            f"(and in {directory / 'summary.nc'}): call pl.sweep again with the same output folder, on a running "
            "cluster, to run only the rest"
        ) from None
    finally:
        bar.close()
    _discard_partial(directory, pending)  # every task is over: what is left is a killed worker's
    return _write_summary(directory, grid, cases, records, origin)


def _discard_partial(directory: Path, cases: Iterable[_Case]) -> None:
    """Removes the temporary files of runs of `cases` that were stopped (Ctrl-C, a killed worker)."""
    for case in cases:
        for stale in (directory / "cases").glob(f".{case.name}.*"):
            stale.unlink(missing_ok=True)


@contextmanager
def _connected(client: Any, workers: int | None, pending: int) -> Iterator[Any]:
    """The client to run on: `client`, a client of the scheduler at the address `client`, or of a local
    cluster of single-threaded processes (closed afterwards)."""
    from distributed import Client, LocalCluster

    if isinstance(client, str):
        with Client(client) as remote:
            yield remote
    elif client is not None:
        yield client
    else:
        import dask

        count = min(workers or os.cpu_count() or 1, pending)
        try:
            # Dask starts its workers with MALLOC_TRIM_THRESHOLD_=65536, returning freed memory to the system
            # at once: a case's engine then runs 5 % slower than in its own process (the J-lay example at
            # 3000 s, 16.4 s against 15.6 s). glibc's own threshold instead.
            settings = {
                "distributed.scheduler.allowed-failures": ALLOWED_FAILURES,
                "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None,
            }
            with dask.config.set(settings):
                cluster = LocalCluster(
                    n_workers=count, threads_per_worker=1, processes=True, dashboard_address=":0"
                )
        except Exception as error:
            # Workers that did not start because each ran the script again (the script's source unread):
            # they said so, one line each; say it here too, without the cluster's traceback.
            frame = _top_level_frame()
            if frame is None or _guarded(frame):
                raise
            raise RuntimeError(f"{UNGUARDED}; the local cluster did not start: {error}") from None
        with cluster, Client(cluster) as local:
            yield local


def _compute(
    client: Any,
    pending: list[_Case],
    directory: Path,
    records: dict[str, dict[str, Any]],
    bar: Any,
) -> None:
    """Runs the pending cases, one task each, putting their records in `records` as they finish (`_outcome`).
    A finished task is let go at once: a worker lost afterwards does not make the scheduler run its case again.
    No wait is unbounded: the scheduler is asked every `PROBE_EVERY` s whether it is still there. With no
    worker (an adaptive or batch cluster may start them later), it waits, warning once after
    `SCHEDULER_TIMEOUT` s.

    Raises _Lost if the scheduler is lost (the client's connection closed, or no answer within
    `SCHEDULER_TIMEOUT`), with the cases finished so far in `records`. Ctrl-C cancels the tasks not finished.
    """
    from distributed import as_completed

    # An absolute path: the workers may run elsewhere (on a filesystem shared at the same path).
    futures = {client.submit(_task, case, directory.absolute(), pure=False): case for case in pending}
    address = client.scheduler.address
    finished = as_completed(list(futures), loop=client.loop)
    probed, workerless = time.monotonic(), None
    try:
        while futures:
            batch = finished.next_batch(block=False)
            if not batch:
                if time.monotonic() - probed > PROBE_EVERY:
                    workers = _probe(client, address)
                    probed = time.monotonic()
                    if workers:
                        workerless = None
                    elif workerless is None:
                        workerless = probed
                    elif probed - workerless > SCHEDULER_TIMEOUT:
                        warnings.warn(
                            f"sweep: the scheduler at {address} has had no worker for {SCHEDULER_TIMEOUT:g} s; the"
                            " sweep waits for one (Ctrl-C stops it and keeps the finished cases)",
                            RuntimeWarning,
                            stacklevel=3,
                        )
                        workerless = float("inf")  # once
                time.sleep(POLL)
                continue
            for future in batch:
                case = futures.pop(future)
                record = _outcome(future, case, directory, client, address)
                if record is None:  # its result was lost after it finished, and its record is not on disk
                    futures[future] = case
                    finished.add(future)  # the scheduler runs it again
                    continue
                records[case.name] = record
                bar.update()
            # Let the scheduler forget the finished tasks (and their workers the records) at once: a worker
            # lost later does not make it run their cases again.
            del batch, future
    except KeyboardInterrupt:
        client.cancel(list(futures))
        raise


def _outcome(future: Any, case: _Case, directory: Path, client: Any, address: str) -> dict[str, Any] | None:
    """The record of a case whose task is over (`future`): the task's, or a failure of this call only (not
    saved: the next call runs the case again) if the task failed in another way: its worker died
    `ALLOWED_FAILURES` + 1 times (KilledWorker), a full disk, a task cancelled by someone else. None if the
    result was lost after the task finished (its worker gone) and the case's record is not on disk either.

    Raises _Lost if the task was cancelled because the scheduler is lost."""
    from concurrent.futures import CancelledError

    from distributed.scheduler import KilledWorker

    if future.status in ("pending", "lost"):
        return _read(directory, case)
    try:
        record: dict[str, Any] = future.result(timeout=SCHEDULER_TIMEOUT)
        return record
    except KilledWorker as error:
        message = (
            f"KilledWorker: the worker running this case died {error.allowed_failures + 1} times (a crash, a"
            f" kill or too much memory; distributed.scheduler.allowed-failures = {error.allowed_failures});"
            " not saved: the next call runs it again"
        )
    except CancelledError as error:
        # Cancelled as the client lost its connection: the case did not finish, even if the client reconnects
        # for a moment to a scheduler still shutting down (and answers a probe).
        if getattr(error, "reason", None) == "scheduler-connection-lost":
            raise _Lost(address, "the connection to it closed") from None
        _probe_settled(client, address)  # raises _Lost if the scheduler is lost
        message = f"{type(error).__name__}: {error}"
    except TimeoutError as error:
        if future.status != "error":  # not the task's own error: no result within the timeout
            _probe(client, address)
            return _read(directory, case)
        message = f"{type(error).__name__}: {error}"
    except Exception as error:  # noqa: BLE001 - recorded as the case's failure
        # A task that failed because its scheduler went away (its comm closed as the cluster shut down) did
        # not finish: raise _Lost rather than record its failure.
        if isinstance(error, (OSError, ConnectionError)) or "Comm" in type(error).__name__:
            _probe_settled(client, address)
        else:
            _probe(client, address)
        message = f"{type(error).__name__}: {error}"
    return {"name": case.name, "error": message}


class _Lost(Exception):
    """The scheduler at `address` is lost, for `reason`."""

    def __init__(self, address: str, reason: str) -> None:
        super().__init__(address, reason)
        self.address, self.reason = address, reason


def _probe_settled(client: Any, address: str) -> None:
    """`_probe`, and again after `SETTLE` (s) if the scheduler still answers: a task cancelled, or cut off from
    its comm, while the cluster shuts down sees its scheduler answer for a moment longer. Raises _Lost if it is
    lost by then."""
    _probe(client, address)
    time.sleep(SETTLE)
    _probe(client, address)


SETTLE = 1.0
"""How long (s) a case cancelled or cut off waits before its scheduler is taken to be alive (`_probe_settled`)."""


def _probe(client: Any, address: str) -> int:
    """The number of workers of `client`'s scheduler (at `address`). Raises _Lost if the scheduler is lost:
    the client's connection is not up, or the scheduler does not answer within `SCHEDULER_TIMEOUT` (s)."""
    if client.status != "running":
        raise _Lost(address, "the connection to it closed")
    try:
        identity = client.sync(client.scheduler.identity, n_workers=0, callback_timeout=SCHEDULER_TIMEOUT)
    except (OSError, TimeoutError, RuntimeError):
        raise _Lost(address, f"no answer within {SCHEDULER_TIMEOUT:g} s") from None
    return int(identity["n_workers"])


def _unit(key: str) -> str:
    """The unit of a dotted scenario key, from the scenario reference ("1" for a number without one, "" for a
    key it does not know or one that holds a table)."""
    table, _, leaf = re.sub(r"\[\d+\]", "", key).rpartition(".")
    for entry in reference_tables():
        if table in entry.paths:
            for variant in entry.variants:
                for row in variant.rows:
                    if row.key == leaf and row.takes:
                        return row.unit or "1"
    return ""


def _write_summary(
    directory: Path,
    grid: Mapping[str, list[Any]],
    cases: list[_Case],
    records: Mapping[str, dict[str, Any]],
    origin: str,
) -> Sweep:
    """The summary of the cases' records as a Sweep; writes ``summary.nc`` atomically."""
    import xarray as xr

    shape = tuple(len(values) for values in grid.values())
    names = [name for name in STATISTICS if any(name in r.get("statistics", {}) for r in records.values())]
    arrays = {name: np.full(shape, np.nan) for name in names}
    failed = np.zeros(shape, dtype=np.int8)
    error = np.full(shape, "", dtype=object)
    files = np.full(shape, "", dtype=object)
    failures, finished = {}, {}
    for case, index in zip(cases, itertools.product(*map(range, shape)), strict=True):
        files[index] = case.name
        record = records.get(case.name)
        if record is None:
            continue
        key = tuple(_hashable(value) for value in case.values)
        if "error" in record:
            failed[index], error[index] = 1, record["error"]
            failures[key] = record["error"]
            continue
        finished[key] = directory / "cases" / f"{case.name}.nc"
        for name, value in record["statistics"].items():
            if name in arrays:
                arrays[name][index] = value
    dims = list(grid)
    coords = {}
    for dim, values in grid.items():
        numeric = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)
        coordinate = np.asarray(values) if numeric else np.array([_label(v) for v in values], dtype=object)
        coords[dim] = (dim, coordinate, {"units": _unit(dim), "long_name": f"scenario key {dim}"})
    variables = {
        name: (dims, array, {"units": STATISTICS[name][0], "long_name": STATISTICS[name][1]})
        for name, array in arrays.items()
    }
    if "utilisation_max" in variables:
        bases = sorted(
            {str(record.get("checks", "")) for record in records.values() if "statistics" in record}
        )
        variables["utilisation_max"][2]["checks"] = "; ".join(basis for basis in bases if basis)
    variables["failed"] = (dims, failed, {"units": "1", "long_name": "1: the case failed (see error)"})
    variables["error"] = (dims, error, {"long_name": "the failed case's error message"})
    variables["case"] = (dims, files, {"long_name": "name of the case's files in cases/ (.nc, .json)"})
    summary = xr.Dataset(
        variables,
        coords=coords,
        attrs={
            "title": SUMMARY_TITLE,
            "source": origin,
            "swept_keys": json.dumps(dims),
            "conventions": "SI units; frame e: origin at the seabed end, e1 lay direction, e3 down",
            "created": datetime.now(UTC).isoformat(timespec="seconds"),
            "cases": len(cases),
            "finished": len(finished),
            "failed": len(failures),
        },
    )
    # Not under a distributed client's lock (xarray takes one when a client is the default): the scheduler may
    # be gone, and a summary of numpy arrays needs no dask.
    import dask

    with dask.config.set(scheduler="synchronous"):
        _atomic_write(directory / "summary.nc", lambda path: summary.to_netcdf(path, engine="h5netcdf"))
    return Sweep(summary=summary, failures=failures, cases=finished, output=directory)
