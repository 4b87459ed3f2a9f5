"""Runs streamed to a netCDF file as they go: memory stays flat however long the run.

``Simulation.run(t_end, output=path, record=groups)`` runs the engine in segments of at most ``SEGMENT_BYTES``
(32 MB) of records and about ``SEGMENT_SECONDS`` (2 s) of wall time, appends each segment's records to
``<path>.part`` and closes the file after every append: the ``.part`` file is complete and readable (h5netcdf,
xarray) up to the last segment written, while the run goes on and if the process is killed. When the run ends,
fails (the error is raised again) or is stopped by Ctrl-C, the file is renamed to `path`. The run returns a
Results of the last record only; the whole series is in the file (``pl.load(path)``, or lazily
``xarray.open_dataset(path)``).

The file has the layout of ``Results.to_netcdf`` (pipelay.results.netcdf: the same variables, dimensions and
attributes, the format's version ``pipelay_format`` among them, plus the global attribute ``recorded_groups``)
with ``time``, ``node`` and ``element`` unlimited: with pay-out the mesh grows, and the earlier records' extra
nodes are NaN, as in the engine's own records. ``pl.load`` reads the ``.part`` file too (the records written so
far).

``record`` chooses the variables (``GROUPS``; ``time`` always):

- ``"positions"``, ``"rotations"``, ``"velocities"``: the nodal series of those names (3, 9 and 3 numbers a node);
- ``"section_forces"``: section_forces and tension (7 numbers an element);
- ``"reactions"``: reaction_A and reaction_B;
- ``"energy"``: the energy parts, total_energy, supplied_work, dissipated, pay_out_energy, length, pay_out_speed, iterations, substeps;
- ``"vessel"``: eta, nu, tau, chi, eta_low_frequency, eta_wave_frequency, tau_commanded and, with an
  observer or thrusters, eta_estimate, thrust, azimuth (with a vessel);
- ``"seabed"``: touchdown, touchdown_arc_length, laid_length (with a seabed);
- ``"lay"``: the lay summary (top_tension, departure_angle, …) and roller_reactions (with a vessel; rollers).

Segments do not change the results: each segment but the last ends on a record (a multiple of ``record_every``
steps from the start); its first record, the state the previous segment ended in, is not written again; and the
energy ledger (supplied_work, dissipated, pay_out_energy), which the engine counts from the start of each of its
``run`` calls, is re-based on the start of the whole run. Every number in the file is that of one in-memory run,
bit for bit, except that re-basing the ledger can round a tie the other way: a ledger entry may then differ in
its last bit (one unit in the last place).

Importing it makes ``Simulation.run`` stream when given an `output` path. Imports of pipelay: the engine
(`pipelay._core`) and `pipelay.results.netcdf`.
"""

from __future__ import annotations

import contextlib
import math
import operator
import os
import signal
import threading
import time as clock
import warnings
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from pipelay._core import ConvergenceError, InputError, Results, Simulation
from pipelay.results.netcdf import (
    AXES,
    GROUPS,
    LAYOUT,
    _arrays,
    _file_attributes,
    line_attributes,
    stage_attributes,
    with_stages,
)

__all__ = ["GROUPS", "stream"]

# A segment takes at most about this much memory (bytes): a record is 22 numbers a node, but the engine's
# growing buffers and the array being written out take more, ~64 numbers a node at the peak (benches/memory.py)...
SEGMENT_BYTES = 32 * 2**20
# ... and lasts about this long (s of wall time): the file is at most this far behind the run.
SEGMENT_SECONDS = 2.0
# Fixed records per segment instead (tests); None: chosen from the two above.
SEGMENT_RECORDS: int | None = None
# HDF5 chunks of about this size (bytes) along time.
CHUNK_BYTES = 2**19

# The order of the checkpoint's "ledger" row.
_LEDGER = ("supplied_work", "dissipated", "pay_out_energy", "plastic_dissipation")
_GROWING = ("node", "element")


def record_groups(record: str | Sequence[str] | None) -> tuple[str, ...]:
    """The groups `record` names (all of them for None), checked."""
    if record is None:
        return tuple(GROUPS)
    allowed = f"None (everything) or a tuple of groups from {', '.join(map(repr, GROUPS))}"
    try:
        names = (record,) if isinstance(record, str) else tuple(record)
    except TypeError:
        raise InputError(f"record: {allowed}, got {record!r}") from None
    if not names or any(not isinstance(name, str) or name not in GROUPS for name in names):
        raise InputError(f"record: {allowed}, got {record!r}")
    return tuple(dict.fromkeys(names))


class _Writer:
    """Appends records to ``<target>.part``, opening and closing the file around each append."""

    def __init__(self, target: Path, groups: tuple[str, ...], expected: int) -> None:
        self.target = target
        self.expected = max(expected, 1)  # records the run will have, at most: no chunk longer
        self.part = target.with_name(target.name + ".part")
        self.groups = groups
        self.names = [name for group in groups for name in GROUPS[group]]
        self.records = 0
        self.nodes = 0
        self.rollers = 0
        self.thrusters = 0  # k, the width of the thrusters' series (set before the first append)
        self.hinges = 0  # h, an articulated stinger's hinges (set before the first append)
        self.created = False
        self.broken = False
        self.attributes: dict[str, Any] = {}  # further global attributes (the run's stages)
        target.parent.mkdir(parents=True, exist_ok=True)
        import h5netcdf

        # Fails now, before any simulation, if the file cannot be written.
        h5netcdf.File(self.part, "w", locking=False).close()

    @contextlib.contextmanager
    def appending(
        self, time: np.ndarray, nodes: int, names: list[str], rollers: int
    ) -> Iterator[Callable[[str, np.ndarray], None]]:
        """Opens the file to append the records `time` (R,), `nodes` wide, and yields ``put(name, value)`` that
        writes a variable's (R, ...) values (NaN-padded to the file's width); then closes the file: it is complete
        on disk until the next append. `names`: the variables (created on the first append), `rollers`: k."""
        import h5netcdf
        import h5py

        try:
            # No file locking: a reader holding the .part file open must not stop the run.
            with h5py.File(self.part, "a", locking=False) as file:
                if not self.created:
                    with h5netcdf.File(file, "a") as netcdf:
                        self._create(netcdf, names, nodes, rollers)
                    self.created = True
                # Appending with h5py directly (h5netcdf's bookkeeping costs ~1 ms a variable): the extents of
                # the unlimited dimensions and of the variables along them; new entries are the fill value NaN.
                start, stop = self.records, self.records + len(time)
                if nodes > self.nodes:
                    self.nodes = nodes
                    for name, size in (("node", nodes), ("element", nodes - 1)):
                        file[name].resize((size,))
                        file[name][:] = np.arange(size)
                file["time"].resize((stop,))
                file["time"][start:stop] = time

                def put(name: str, value: np.ndarray) -> None:
                    dataset = file[name]
                    dataset.resize(self._shape(name, stop, self.nodes))
                    dataset[start:stop] = self._padded(name, value)

                yield put
            self.records = stop
        except BaseException:
            self.broken = True
            raise

    def _shape(self, name: str, records: int, nodes: int) -> tuple[int, ...]:
        """The shape of variable `name` with `records` records, `nodes` wide."""
        sizes = {
            "node": nodes,
            "element": nodes - 1,
            "axis": 3,
            "column": 3,
            "dof": 6,
            "roller": self.rollers,
            "thruster": self.thrusters,
            "hinge": self.hinges,
        }
        return (records, *(sizes[dim] for dim in LAYOUT[name][0][1:]))

    def _padded(self, name: str, value: np.ndarray) -> np.ndarray:
        """`value` NaN-padded along the node or element dimension to the file's width."""
        dims = LAYOUT[name][0]
        if len(dims) < 2 or dims[1] not in _GROWING:
            return value
        width = self.nodes if dims[1] == "node" else self.nodes - 1
        if value.shape[1] == width:
            return value
        padded = np.full((value.shape[0], width, *value.shape[2:]), np.nan)
        padded[:, : value.shape[1]] = value
        return padded

    def _create(self, file: Any, names: list[str], nodes: int, rollers: int) -> None:
        """Dimensions, coordinates and (empty) variables, as ``to_xarray`` lays them out."""
        import h5py

        dimensions: dict[str, int | None] = {
            "time": None,
            "node": None,
            "element": None,
            "axis": 3,
            "column": 3,
            "dof": 6,
        }
        if "roller_reactions" in names:
            dimensions["roller"] = rollers
        if "thrust" in names:
            dimensions["thruster"] = self.thrusters
        if "hinge_angles" in names:
            dimensions["hinge"] = self.hinges
        file.dimensions = dimensions
        file.attrs.update({**_file_attributes(), "recorded_groups": " ".join(self.groups), **self.attributes})
        time = file.create_variable(
            "time", ("time",), "f8", fillvalue=np.nan, chunks=(min(4096, self.expected),)
        )
        time.attrs.update({"units": "s", "long_name": "time"})
        node = file.create_variable("node", ("node",), "i8", chunks=(max(nodes, 1),))
        node.attrs["long_name"] = "node index (0: end A, n: end B)"
        element = file.create_variable("element", ("element",), "i8", chunks=(max(nodes - 1, 1),))
        element.attrs["long_name"] = "element index"
        for name in ("axis", "column"):
            file.create_variable(name, (name,), h5py.string_dtype(), data=np.array(AXES, dtype=object))
        dof = file.create_variable("dof", ("dof",), "i8", data=np.arange(6))
        dof.attrs["long_name"] = "component: force/moment or eta/nu entry"
        self.rollers = rollers
        for name in names:
            dims, units, description = LAYOUT[name]
            row = self._shape(name, 0, nodes)[1:]
            along = max(1, min(CHUNK_BYTES // max(8 * math.prod(row), 1), 4096, self.expected))
            variable = file.create_variable(name, dims, "f8", fillvalue=np.nan, chunks=(along, *row))
            variable.attrs.update({"units": units, "long_name": description})

    def finish(self) -> Path | None:
        """Renames the file into place (None, and no file, if nothing was recorded or a write failed)."""
        if self.broken:
            return None
        if not self.created:
            self.part.unlink(missing_ok=True)
            return None
        os.replace(self.part, self.target)
        return self.target


@contextlib.contextmanager
def _deferred_interrupt() -> Iterator[None]:
    """Holds Ctrl-C back while a segment is written (so no half-written chunk), then raises it."""
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda number, frame: caught.append(number))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if caught:
        raise KeyboardInterrupt


def _ledger(simulation: Simulation) -> np.ndarray:
    """(supplied work, dissipated, pay-out energy, plastic dissipation) since the simulation started (J)."""
    return np.asarray(simulation._checkpoint()["ledger"][0])  # type: ignore[attr-defined]


def _last(time: np.ndarray, arrays: dict[str, np.ndarray]) -> Results:
    """The last record as a Results, its node series cut to the nodes it has."""
    nodes = int(np.sum(~np.isnan(arrays["positions"][-1, :, 0])))
    cut = {}
    for name, value in arrays.items():
        dims = LAYOUT[name][0]
        row = value[-1:]
        if len(dims) > 1 and dims[1] in _GROWING:
            row = row[:, : nodes if dims[1] == "node" else nodes - 1]
        cut[name] = np.ascontiguousarray(row)
    return Results._from_arrays(nodes, {**cut, "time": time[-1:]})  # type: ignore[attr-defined]


def stream(
    engine_run: Callable[..., Results],
    simulation: Simulation,
    t_end: float | None,
    progress: bool,
    record_every: int,
    output: str | os.PathLike[str],
    record: str | Sequence[str] | None,
) -> Results:
    """``simulation.run(t_end, progress, record_every, output=output, record=record)``: see ``Simulation.run``."""
    groups = record_groups(record)
    every = operator.index(record_every)
    if every < 1:
        raise InputError(f"record_every: must be an integer >= 1, got {record_every}")
    start, dt = simulation.time, simulation.dt
    if t_end is None:
        t_end = simulation.stages_end
        if t_end is None:
            raise InputError("t_end: must be given for a simulation without stages, got None")
    if not math.isfinite(t_end) or t_end < start:
        raise InputError(f"t_end: must be a finite time >= the current time {start} s, got {t_end}")
    total = max(math.ceil((t_end - start) / dt - 1e-9), 0)  # the engine's step count for one run
    origin = _ledger(simulation)
    nodes = len(simulation.state.positions)
    done, first, records = 0, True, SEGMENT_RECORDS or 8
    last: Results | None = None
    bar = None
    writer = _Writer(Path(output), groups, total // every + 1)
    writer.attributes = stage_attributes(simulation.stage_names, simulation.stage_starts)
    writer.attributes.update(line_attributes(simulation.pipe_walls, simulation.water))
    try:
        if progress and total >= 200:
            from tqdm import tqdm

            bar = tqdm(total=total, unit="step", desc="pipelay")
        while True:
            cap = max(1, SEGMENT_BYTES // (8 * (64 * nodes + 64)))
            steps = min(min(records, cap) * every, total - done)
            before = simulation.time
            offsets = None if first else _ledger(simulation)
            segment_end = before + (steps - 0.5) * dt if steps else before
            started = clock.perf_counter()
            segment, failure, interrupted = _segment(engine_run, simulation, segment_end, every)
            elapsed = clock.perf_counter() - started
            advanced = round((simulation.time - before) / dt)
            try:
                with _deferred_interrupt():  # a whole segment or none: Ctrl-C waits until it is written
                    last = _append(writer, segment, 0 if first else 1, offsets, origin)
                    nodes = segment.nodes
                    del segment
            except KeyboardInterrupt:
                if failure is None:
                    raise
            if bar is not None:
                bar.update(advanced)
            done += advanced
            if failure is not None:
                failure.results = last  # type: ignore[attr-defined]
                raise failure
            if interrupted or done >= total:
                break
            first = False
            if SEGMENT_RECORDS is None:
                rate = advanced / every / max(elapsed, 1e-6)  # records per second
                records = max(1, min(int(rate * SEGMENT_SECONDS), 4 * records))
    except KeyboardInterrupt:
        if last is None:
            raise
        warnings.warn(
            f"run interrupted at t = {simulation.time:.6f} s: returning the results so far", stacklevel=3
        )
    finally:
        if bar is not None:
            bar.close()
        writer.finish()
    assert last is not None
    return with_stages(last, writer.attributes)


def _segment(
    engine_run: Callable[..., Results], simulation: Simulation, t_end: float, every: int
) -> tuple[Results, BaseException | None, bool]:
    """One engine run: its results, the error that stopped it (which holds them), and whether Ctrl-C stopped it
    (the engine then warns and returns what it has; the warning is passed on)."""
    caught: list[warnings.WarningMessage] = []
    failure: BaseException | None = None
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                segment = engine_run(simulation, t_end, False, every)
            except (ConvergenceError, InputError) as error:
                kept = getattr(error, "results", None)
                if kept is None:
                    raise
                segment, failure = kept, error
    finally:
        for warning in caught:
            warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
    interrupted = any("run interrupted" in str(warning.message) for warning in caught)
    return segment, failure, interrupted


# The node and element series: fetched from the engine, written and dropped one at a time.
_LARGE = ("positions", "rotations", "velocities", "section_forces", "tension", "segment")


def _append(
    writer: _Writer, segment: Results, skip: int, offsets: np.ndarray | None, origin: np.ndarray
) -> Results:
    """Appends `segment`'s records from `skip` on and returns its last record. `offsets`: the ledger at the
    segment's start (None for the run's first segment), `origin`: at the run's start."""
    time = segment.time
    # The series a record has a few numbers of (all of them: the last record needs them).
    small = _arrays(segment, [name for group in GROUPS.values() for name in group if name not in _LARGE])
    if offsets is not None:
        # The engine counts a run's ledger from the run's start: the segment has s = W(t) − W(segment start) and
        # the run W(t) − W(run start), computed here as the engine does from W(t) = s + W(segment start).
        for name, at_segment, at_run in zip(_LEDGER, offsets, origin, strict=True):
            small[name] = (small[name] + at_segment) - at_run
    final = {name: value[-1:] for name, value in small.items()}
    names = [name for name in writer.names if name in _LARGE or name in small]
    rollers = small["roller_reactions"].shape[1] if "roller_reactions" in small else 0
    if not writer.created and "thrust" in small:
        writer.thrusters = small["thrust"].shape[1]
    if not writer.created and "hinge_angles" in small:
        writer.hinges = small["hinge_angles"].shape[1]
    nodes = segment.nodes
    if len(time) > skip:
        with writer.appending(time[skip:], nodes, names, rollers) as put:
            for name in names:
                value = _arrays(segment, [name])[name] if name in _LARGE else small[name]
                final[name] = value[-1:].copy()
                put(name, value[skip:])
                del value
    for name in _LARGE:
        if name not in final:
            final[name] = _arrays(segment, [name])[name][-1:].copy()
    return _last(time, final)


def _attach() -> None:
    """Makes ``Simulation.run`` stream when given an `output` path (the engine's run does the rest)."""
    engine_run = getattr(Simulation, "_engine_run", Simulation.run)
    Simulation._engine_run = engine_run  # type: ignore[attr-defined]

    def run(
        self: Simulation,
        t_end: float | None = None,
        progress: bool = True,
        record_every: int = 1,
        *,
        output: str | os.PathLike[str] | None = None,
        record: str | Sequence[str] | None = None,
    ) -> Results:
        """Run to t_end (s; default: the end of the stages), recording the current state and every
        record_every-th step after it.

        Without `output`: returns every record in memory (a Results). With `output` (a path): the records are
        streamed to that netCDF file as the run goes, in segments, so memory stays flat however long the run;
        the file is ``<output>.part`` while the run goes (complete up to the last segment written, readable
        with xarray) and is renamed to `output` when the run ends, fails or is interrupted. Returns a Results of
        the last record only (the whole series is in the file: ``pl.load(output)``). `record` chooses what the
        file holds: None (everything) or some of the groups "positions", "rotations", "velocities",
        "section_forces" (with tension), "reactions" (A and B), "energy" (parts, total, supplied_work,
        dissipated, pay_out_energy, length, pay_out_speed, iterations, substeps), "vessel" (eta, nu, tau, chi), "seabed" (touchdown,
        touchdown_arc_length, laid_length), "lay" (lay summary and roller reactions); time always.

        A progress bar (tqdm) shows on long runs unless progress=False. Ctrl-C stops the run between steps and
        returns what was computed so far (with a warning); a failed step raises ConvergenceError (or InputError
        when a callable fails) whose `results` attribute holds the records before it (streamed: the last one,
        the others being in the file)."""
        if output is None:
            if record is not None:
                raise InputError(
                    f"record: only with an output file to stream to (output=path), got {record!r}"
                )
            return engine_run(self, t_end, progress, record_every)
        return stream(engine_run, self, t_end, progress, record_every, output, record)

    Simulation.run = run  # type: ignore[method-assign]


_attach()
