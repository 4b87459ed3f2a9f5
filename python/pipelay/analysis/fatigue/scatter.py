"""Fatigue damage over a wave scatter diagram: every sea state run, its damage per hour weighted by its
probability and scaled to a standby's duration.

```python
from pipelay import fatigue

scatter = fatigue.read_scatter("scatter.csv")      # columns hs (m), tp (s), heading (deg), probability
curve = fatigue.SNCurve.dnv("D", environment="seawater_cp", thickness=0.025)
result = fatigue.scatter_damage("j_lay_waves.toml", scatter, curve, hours=72, start=90.0, output="fatigue")
result.max(), result.worst()        # the largest damage over the 72 h standby, and where
result.plot()                        # the damage along the pipe
```

Each sea state i is a case of `pipelay.analysis.sweep` (on Dask; finished cases in `output` are reused): the
scenario with ``sea.waves.hs``, ``sea.waves.tp`` and, if the table has headings, ``sea.waves.direction`` set
to the row's. Its damage per hour d_i (each hot spot of each element, `damage` with duration 3600 s, the
records from `start` on) is weighted by the row's probability p_i; over a standby of `hours`

    D = hours · Σ_i p_i d_i          (at each hot spot; Miner's rule sums over sea states as over cycles)

The probabilities must sum to 1 (the table is the distribution of the sea states the standby may see).

Imports of pipelay: the engine (its errors), `pipelay.scenario`, `pipelay.results`, `pipelay.analysis.sweep`,
`pipelay.analysis.checks` (input errors) and the fatigue package's own modules.
"""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from pipelay.analysis.checks import _Described, _input_error, _number
from pipelay.analysis.fatigue.curves import SNCurve
from pipelay.analysis.fatigue.damage import Damage, damage
from pipelay.analysis.sweep import sweep
from pipelay.results import load
from pipelay.scenario import Scenario, apply_overrides, load_scenario, parse_scenario, validate_overrides

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "PROBABILITY_TOLERANCE",
    "ScatterDamage",
    "ScatterDiagram",
    "read_scatter",
    "scatter_damage",
    "scatter_diagram",
]

FloatArray = NDArray[np.float64]

PROBABILITY_TOLERANCE = 1e-3
"""How far the probabilities of a scatter diagram may sum from 1 (tables are given to a few digits)."""

HOUR = 3600.0


@dataclass(frozen=True, eq=False)
class ScatterDiagram:
    """Sea states and their probabilities (one entry per sea state).

    Attributes
    ----------
    hs : ndarray (k,)
        Significant wave height (m).
    tp : ndarray (k,)
        Peak period (s).
    probability : ndarray (k,)
        Probability of each sea state (they sum to 1).
    heading : ndarray (k,) or None
        The waves' direction (rad, as ``sea.waves.direction``: from e1 toward e2); None: the scenario's.
    """

    hs: FloatArray
    tp: FloatArray
    probability: FloatArray
    heading: FloatArray | None = None

    def __post_init__(self) -> None:
        columns = {"hs": self.hs, "tp": self.tp, "probability": self.probability}
        if self.heading is not None:
            columns["heading"] = self.heading
        sizes = {name: np.shape(values) for name, values in columns.items()}
        if len(set(sizes.values())) != 1 or len(sizes["hs"]) != 1 or sizes["hs"][0] == 0:
            raise _input_error("scatter", _Described(str(sizes)), "columns of one equal length ≥ 1")
        for name, values in columns.items():
            if not np.isfinite(values).all():
                raise _input_error(f"scatter.{name}", values.tolist(), "finite numbers")
        for name in ("hs", "tp"):
            if np.any(columns[name] <= 0.0):
                raise _input_error(f"scatter.{name}", columns[name].tolist(), "numbers > 0")
        if np.any(self.probability < 0.0):
            raise _input_error("scatter.probability", self.probability.tolist(), "probabilities ≥ 0")
        total = float(np.sum(self.probability))
        if abs(total - 1.0) > PROBABILITY_TOLERANCE:
            raise _input_error(
                "scatter.probability",
                _Described(f"probabilities summing to {total:.6g}"),
                f"probabilities summing to 1 (within {PROBABILITY_TOLERANCE:g})",
            )

    def __len__(self) -> int:
        return int(self.hs.size)

    def settings(self, index: int) -> dict[str, float]:
        """The scenario keys the sea state `index` sets."""
        case = {"sea.waves.hs": float(self.hs[index]), "sea.waves.tp": float(self.tp[index])}
        if self.heading is not None:
            case["sea.waves.direction"] = float(self.heading[index])
        return case


def scatter_diagram(
    hs: Sequence[float],
    tp: Sequence[float],
    probability: Sequence[float],
    heading: Sequence[float] | None = None,
) -> ScatterDiagram:
    """A scatter diagram from its columns: hs (m), tp (s), probability, heading (rad) or None."""
    return ScatterDiagram(
        hs=np.asarray(hs, dtype=np.float64),
        tp=np.asarray(tp, dtype=np.float64),
        probability=np.asarray(probability, dtype=np.float64),
        heading=None if heading is None else np.asarray(heading, dtype=np.float64),
    )


def read_scatter(path: str | os.PathLike[str]) -> ScatterDiagram:
    """The scatter diagram of a CSV file with a header row naming the columns ``hs`` (m), ``tp`` (s),
    ``probability`` and optionally ``heading`` (degrees: the waves' direction relative to e1, the vessel's
    heading, toward e2, as ``sea.waves.direction`` in rad); one row per sea state; ``#`` starts a comment line.

    Raises InputError naming the file and the problem: a missing column, a value that is not a number,
    probabilities that do not sum to 1, sea states with Hs or Tp ≤ 0.
    """
    target = Path(path)
    if not target.is_file():
        raise _input_error("scatter", str(target), "a CSV file of sea states", "is no file")
    lines = [
        line for line in target.read_text().splitlines() if line.strip() and not line.lstrip().startswith("#")
    ]
    reader = csv.DictReader(lines)
    header = [name.strip() for name in (reader.fieldnames or [])]
    # Each row by its header's names as stripped, so that "hs, tp" names the columns hs and tp.
    rows = [{(key or "").strip(): value for key, value in row.items()} for row in reader]
    missing = [name for name in ("hs", "tp", "probability") if name not in header]
    if missing:
        raise _input_error(
            f"scatter ({target})",
            _Described(f"columns {header}"),
            "columns hs, tp, probability [, heading]",
            f"lacks {', '.join(missing)}",
        )
    columns: dict[str, list[float]] = {name: [] for name in header}
    for number, row in enumerate(rows, start=2):
        for name in header:
            text = (row.get(name) or "").strip()
            try:
                columns[name].append(float(text))
            except ValueError:
                raise _input_error(
                    f"scatter ({target}), row {number}, column {name}", text, "a number"
                ) from None
    heading = columns.get("heading")
    return scatter_diagram(
        columns["hs"],
        columns["tp"],
        columns["probability"],
        None if heading is None else np.radians(heading),
    )


@dataclass(frozen=True, eq=False)
class ScatterDamage:
    """The damage of a standby over a scatter diagram.

    Attributes
    ----------
    scatter : ScatterDiagram
        The sea states.
    hourly : ndarray (k, n, points)
        Each sea state's damage per hour at each element and hot spot (NaN for a failed sea state).
    values : ndarray (n, points)
        The standby's damage D = hours · Σ p_i d_i over the finished sea states.
    hours : float
        The standby's duration (h).
    arc_length : ndarray (n,)
        Each element midpoint's distance along the line from end A (m).
    angles : ndarray (points,)
        The hot spots' angles (rad).
    failures : dict of int to str
        The sea states that failed (index → message); their probability is missing from `values`.
    cases : dict of int to Path
        Each finished sea state's results file.
    """

    scatter: ScatterDiagram
    hourly: FloatArray
    values: FloatArray
    hours: float
    arc_length: FloatArray
    angles: FloatArray
    failures: dict[int, str] = field(default_factory=dict)
    cases: dict[int, Path] = field(default_factory=dict)

    @property
    def per_element(self) -> FloatArray:
        """The largest damage around each element's section over the standby (n,)."""
        return self.damage().per_element

    def max(self) -> float:
        """The largest damage along the line over the standby."""
        return self.damage().max()

    def worst(self) -> tuple[int, float]:
        """The element (index from end A) and hot-spot angle (rad) of the largest damage."""
        return self.damage().worst()

    def damage(self) -> Damage:
        """The standby's damage as a `Damage` (duration hours × 3600 s), to plot or rank like a run's."""
        return Damage(
            values=self.values,
            angles=self.angles,
            arc_length=self.arc_length,
            duration=self.hours * HOUR,
            record=math.nan,
            method="scatter diagram",
        )

    def plot(self, ax: Axes | None = None, path: str | os.PathLike[str] | None = None) -> Figure:
        """The standby's damage along the line (`pipelay.plots.fatigue.damage_along`)."""
        return self.damage().plot(ax=ax, path=path)

    def to_xarray(self) -> Any:
        """The result as an ``xarray.Dataset``: the sea states, their hourly damage and the standby's."""
        import xarray as xr

        heading = self.scatter.heading
        data = {
            "hs": ("sea_state", self.scatter.hs, {"units": "m", "long_name": "significant wave height"}),
            "tp": ("sea_state", self.scatter.tp, {"units": "s", "long_name": "peak period"}),
            "probability": ("sea_state", self.scatter.probability, {"units": "1"}),
            "hourly_damage": (
                ("sea_state", "element", "hot_spot"),
                self.hourly,
                {"units": "1/h", "long_name": "Miner's sum per hour of each sea state"},
            ),
            "damage": (
                ("element", "hot_spot"),
                self.values,
                {"units": "1", "long_name": f"Miner's sum over the {self.hours:g} h standby"},
            ),
            "failed": (
                "sea_state",
                np.array([int(k in self.failures) for k in range(len(self.scatter))], dtype=np.int8),
                {"long_name": "1: the sea state's run failed"},
            ),
        }
        if heading is not None:
            data["heading"] = ("sea_state", heading, {"units": "rad", "long_name": "wave direction"})
        coords = {
            "arc_length": ("element", self.arc_length, {"units": "m", "long_name": "from end A"}),
            "angle": ("hot_spot", self.angles, {"units": "rad", "long_name": "around the section"}),
        }
        return xr.Dataset(data, coords=coords, attrs={"hours": self.hours, "title": "pipelay fatigue"})


@dataclass(frozen=True)
class _SeaStateCase:
    """Builds the scenario of one sea state on a sweep's worker (picklable: plain data)."""

    data: dict[str, Any]
    origin: str
    folder: str
    scatter: ScatterDiagram

    def __call__(self, case: dict[str, Any]) -> Scenario:
        index = int(case["sea_state"])
        settings = self.scatter.settings(index)
        return parse_scenario(
            apply_overrides(self.data, settings), f"{self.origin}, sea state {index}", self.folder
        )


def scatter_damage(
    scenario: str | os.PathLike[str],
    scatter: ScatterDiagram | str | os.PathLike[str],
    curve: SNCurve | Sequence[SNCurve],
    *,
    hours: float,
    scf: float | Sequence[float] = 1.0,
    method: str = "rainflow",
    start: float | None = None,
    points: int = 8,
    surface: str = "outer",
    output: str | os.PathLike[str] = "fatigue",
    client: Any = None,
    workers: int | None = None,
    progress: bool = True,
) -> ScatterDamage:
    """The damage of a standby of `hours` over the sea states of `scatter` (see the module).

    Parameters
    ----------
    scenario : path
        A scenario file with ``[sea.waves]`` and ``solver.t_end``: one sea state's run.
    scatter : ScatterDiagram or path
        The sea states (a CSV file: `read_scatter`).
    curve, scf, method, points, surface
        As `damage`.
    hours : float
        The standby's duration (h, > 0).
    start : float or None
        Records before this time (s) are left out of each run's damage (the start-up transient).
    output, client, workers, progress
        As `pipelay.sweep`: the folder of the cases (``output/cases``; finished ones are reused), the Dask
        cluster.

    Raises
    ------
    pipelay.InputError
        A bad argument, a scenario without waves or ``solver.t_end``, a sea state the scenario does not
        accept (before anything runs).
    """
    span = _number("hours", hours, positive=True)
    diagram = scatter if isinstance(scatter, ScatterDiagram) else read_scatter(scatter)
    origin = os.fspath(scenario)
    base = load_scenario(scenario)
    if "waves" not in base.source.get("sea", {}):
        raise _input_error(
            "scenario", origin, "a scenario with [sea.waves] (a sea state to vary)", "has no waves"
        )
    if base.t_end is None:
        raise _input_error("scenario", origin, "a scenario with solver.t_end (a run)", "has no solver.t_end")
    folder = str(Path(scenario).absolute().parent)
    overrides = {key: [diagram.settings(k)[key] for k in range(len(diagram))] for key in diagram.settings(0)}
    validate_overrides(base.source, overrides, origin, folder)
    build = _SeaStateCase(data=base.source, origin=origin, folder=folder, scatter=diagram)
    for index in range(len(diagram)):
        build({"sea_state": index})  # every sea state checked before anything runs
    run = sweep(
        build,
        over={"sea_state": list(range(len(diagram)))},
        client=client,
        output=output,
        workers=workers,
        progress=progress,
    )
    failures = {int(key[0]): message for key, message in run.failures.items()}
    cases = {int(key[0]): path for key, path in run.cases.items()}
    hourly: FloatArray | None = None
    arc_length = angles = None
    for index, path in sorted(cases.items()):
        found = damage(
            load(path),
            curve,
            scf=scf,
            duration=HOUR,
            method=method,
            points=points,
            surface=surface,
            start=start,
        )
        if hourly is None:
            hourly = np.full((len(diagram), *found.values.shape), np.nan)
            arc_length, angles = found.arc_length, found.angles
        hourly[index] = found.values
    if hourly is None or arc_length is None or angles is None:
        raise _input_error(
            "scatter",
            _Described(f"{len(failures)} sea states, all failed"),
            "at least one sea state that runs",
            "; ".join(f"{k}: {m}" for k, m in sorted(failures.items())),
        )
    finished = sorted(cases)
    values = span * np.einsum("k,knp->np", diagram.probability[finished], hourly[finished])
    return ScatterDamage(
        scatter=diagram,
        hourly=hourly,
        values=values,
        hours=span,
        arc_length=arc_length,
        angles=angles,
        failures=failures,
        cases=cases,
    )
