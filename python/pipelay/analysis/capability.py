"""DP capability: the largest wind a vessel's thrusters hold at each heading, with the pipe's pull on it.

A static balance, as DNV-ST-0111 level 1 does it: for an environment coming from a heading relative to the
bow (0 head-on, 90° from starboard, clockwise seen from above), the largest 1-hour mean wind speed at 10 m at
which the thrusters, allocated without rate limits (``Vessel.allocate``), deliver the thrust that balances

* the mean wind on the hull, ½ρ_a V² C_wind(γ);
* a co-linear current of `current` m/s, ½ρ_w U_c² C_current(γ);
* the mean wave drift of the co-linear sea that goes with the wind on the Beaufort scale: H_s the WMO scale's
  probable wave height at the wind speed V (m/s), T_p = 4.2 √H_s, JONSWAP (γ = 3.3);
* the pipe's force and moment on the vessel (body frame), from a static solve of the model.

The engine does the search (``pipelay._core.dp_capability_wind``, a bisection to 1 mm/s); this module reads
a model, a scenario or a vessel, finds the pipe's load, checks the arguments and returns a `Capability`, which
draws itself as the usual polar plot (`pipelay.plots.capability`) and lists itself as a table.

Usage::

    import numpy as np
    import pipelay as pl
    from pipelay.analysis import dp_capability

    capability = dp_capability("examples/s_lay.toml")         # the scenario's vessel and static pipe load
    capability.table()                                       # heading_deg, wind_speed
    capability.plot(path="capability.png")
    bare = dp_capability(pl.Vessel.osv())                    # the vessel alone: no pipe load

Imports of pipelay: the engine, and `pipelay.scenario` (when given a scenario file) and `pipelay.plots` (when
drawing), looked up when used.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from pipelay import _core
from pipelay._core import InputError, Model, State, Vessel

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from pipelay.scenario import Scenario

__all__ = ["DEFAULT_HEADINGS", "Capability", "dp_capability"]

DEFAULT_HEADINGS: npt.NDArray[np.float64] = np.radians(np.arange(0.0, 360.0, 15.0))
"""Every 15° from head-on (rad)."""

_FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Capability:
    """A DP capability envelope: the largest wind speed held at each heading.

    Attributes:
        headings: where the environment comes from (rad, relative to the bow: 0 head-on, π/2 from starboard,
            π from astern, 3π/2 from port), as given.
        wind_speed: the largest 1-hour mean wind speed at 10 m held at each heading (m/s); 0 where even calm
            cannot be held (the pipe's load with the current is beyond the thrusters); `max_wind` where it is
            held up to the search's limit.
        pipe_load: the pipe's force and moment on the vessel the envelope holds against (6,) (body frame: N,
            N·m; x forward, y to starboard, z down).
        current: the co-linear current's speed (m/s).
        max_wind: the search's upper limit (m/s).
        label: what the envelope is of (a scenario's title, or a description), for the figure's title.
    """

    headings: _FloatArray
    wind_speed: _FloatArray
    pipe_load: _FloatArray
    current: float
    max_wind: float
    label: str

    @property
    def heading_deg(self) -> _FloatArray:
        """The headings in degrees (environment from, relative to the bow, clockwise)."""
        return np.degrees(self.headings)

    @property
    def at_limit(self) -> npt.NDArray[np.bool_]:
        """Where the wind is held up to `max_wind`: the envelope lies beyond the search there."""
        return np.asarray(self.wind_speed >= self.max_wind)

    def table(self) -> Any:
        """The envelope as a ``pandas.DataFrame``: one row per heading, columns ``heading_deg`` (deg,
        environment from, relative to the bow) and ``wind_speed`` (m/s, 1-hour mean at 10 m); its ``attrs``
        hold the current (m/s), the pipe load (N, N·m) and the label."""
        import pandas as pd

        frame = pd.DataFrame({"heading_deg": self.heading_deg, "wind_speed": self.wind_speed})
        frame.attrs.update(
            current=self.current, max_wind=self.max_wind, pipe_load=self.pipe_load.tolist(), label=self.label
        )
        return frame

    def plot(self, ax: Axes | None = None, path: str | os.PathLike[str] | None = None) -> Figure:
        """The polar capability plot (`pipelay.plots.capability`): 0° at the top, clockwise, the heading
        the environment comes from, the wind speed (m/s) radially, the pipe load in the title; drawn on `ax`
        (polar axes) if given, saved to `path` if given."""
        from pipelay.plots.capability import capability

        return capability(self, ax=ax, path=path)


def _headings(headings: object) -> _FloatArray:
    """`headings` as a 1-D array of finite angles (rad)."""
    try:
        values = np.atleast_1d(np.asarray(headings, dtype=np.float64))
    except (TypeError, ValueError):
        raise InputError(f"headings: must be angles (rad), got {headings!r}") from None
    if values.ndim != 1 or len(values) == 0:
        raise InputError(
            f"headings: must be a 1-D sequence of at least one angle (rad), got shape {values.shape}"
        )
    if not np.all(np.isfinite(values)):
        raise InputError(f"headings: must be finite angles (rad), got {values.tolist()}")
    return values


def _speed(name: str, value: object, allow_zero: bool) -> float:
    """`value` as a finite speed ≥ 0 (or > 0) m/s."""
    try:
        speed = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"{name}: must be a speed (m/s), got {value!r}") from None
    if not math.isfinite(speed) or speed < 0.0 or (speed == 0.0 and not allow_zero):
        bound = "≥ 0" if allow_zero else "> 0"
        raise InputError(f"{name}: must be a finite speed {bound} m/s, got {value!r}")
    return speed


def _load(value: object) -> _FloatArray:
    """`value` as a finite force and moment (6,)."""
    try:
        load = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"pipe_load: must be 6 numbers (N, N·m), got {value!r}") from None
    if load.shape != (6,) or not np.all(np.isfinite(load)):
        raise InputError(
            "pipe_load: must be 6 finite numbers, the pipe's force and moment on the vessel (body frame, N, "
            f"N·m), got {np.array2string(load, precision=4)}"
        )
    return load


def _model_vessel(model: Model) -> Vessel:
    """The vessel attached to `model`."""
    if model.vessel is None:
        raise InputError(
            "model_or_scenario: has no vessel to hold the pipe (a scenario's [vessel], a model's attach_vessel)"
        )
    return model.vessel


def _static_pipe_load(model: Model, steps: int | None = None, start: str = "auto") -> _FloatArray:
    """The pipe's force and moment on the vessel (6,) (body frame) in the model's static state."""
    state: State = model.static(steps=steps, start=start)  # type: ignore[arg-type]
    if state.chi is None:
        raise InputError("model_or_scenario: the model has no vessel (attach_vessel) to hold the pipe")
    return np.asarray(state.chi, dtype=np.float64)


def _resolve(subject: object, vessel: Vessel | None, solve: bool) -> tuple[Vessel, _FloatArray, str]:
    """The vessel, the pipe's load (a static solve's, when `solve`; else zero, to be replaced by the caller's)
    and a label of what `subject` is."""
    from pipelay.scenario import Scenario, load_scenario

    if isinstance(subject, Vessel):
        if vessel is not None:
            raise InputError("vessel: give the vessel once, as model_or_scenario or as vessel=")
        return subject, np.zeros(6), "vessel alone"
    file = None
    if isinstance(subject, str | os.PathLike):
        file = Path(subject).stem
        subject = load_scenario(subject)
    if isinstance(subject, Scenario):
        title = subject.source.get("title")
        label = str(title) if title else (file or "scenario")
        found = vessel if vessel is not None else _model_vessel(subject.model)
        if not solve:
            return found, np.zeros(6), label
        return found, _static_pipe_load(subject.model, subject.static_steps, subject.static_start), label
    if isinstance(subject, Model):
        found = vessel if vessel is not None else _model_vessel(subject)
        return found, (_static_pipe_load(subject) if solve else np.zeros(6)), "model"
    raise InputError(
        "model_or_scenario: must be a pl.Model with a vessel, a scenario (a pipelay.scenario.Scenario or the "
        f"path of a scenario file) or a pl.Vessel, got {type(subject).__name__}"
    )


def dp_capability(
    model_or_scenario: Model | Scenario | Vessel | str | os.PathLike[str],
    headings: Sequence[float] | npt.ArrayLike = DEFAULT_HEADINGS,
    *,
    current: float = 0.75,
    max_wind: float = 60.0,
    pipe_load: npt.ArrayLike | None = None,
    vessel: Vessel | None = None,
    label: str | None = None,
) -> Capability:
    """The DP capability envelope of a vessel holding a pipe: at each heading the largest wind speed its
    thrusters balance, with the co-linear current and sea that go with it and the pipe's load.

    Args:
        model_or_scenario: a `pl.Model` with a vessel attached (its static state gives the pipe's load), a
            scenario (a parsed
            `pipelay.scenario.Scenario`, or the path of a scenario file: its `[vessel]`, and the pipe's load
            from its statics), or a `pl.Vessel` alone (no pipe: a zero load unless `pipe_load` is given).
        headings: where the environment comes from (rad, relative to the bow: 0 head-on, π/2 from starboard,
            clockwise seen from above); default every 15°.
        current: the co-linear current's speed (m/s, ≥ 0).
        max_wind: the search's upper limit (m/s, > 0): headings held up to it report it.
        pipe_load: the pipe's force and moment on the vessel (6,) (body frame, N and N·m; a pipe pulling aft
            has a negative x component); None: from a static solve of the model (zero for a vessel alone).
        vessel: the vessel whose thrusters hold the load, for a model (required) or a scenario whose vessel
            is given by its matrices; None: the scenario's `[vessel]` (``model = "osv"``).
        label: what the envelope is of, for the figure; None: the scenario's title or file name, "model" or
            "vessel alone".

    Returns:
        The `Capability`: headings, wind speeds (m/s), the pipe load used, the current, the limit and the
        label.

    Raises:
        pipelay.InputError: naming the argument: headings not finite, a current < 0, max_wind ≤ 0, a pipe load
            not 6 finite numbers, a model or scenario without a vessel, a model without `vessel`, a vessel
            without thrusters.
        pipelay.ConvergenceError: the static solve for the pipe's load failed.
    """
    angles = _headings(headings)
    current = _speed("current", current, allow_zero=True)
    max_wind = _speed("max_wind", max_wind, allow_zero=False)
    given = None if pipe_load is None else _load(pipe_load)
    if vessel is not None and not isinstance(vessel, Vessel):
        raise InputError(f"vessel: must be a pl.Vessel, got {type(vessel).__name__}")
    found, solved, default_label = _resolve(model_or_scenario, vessel, solve=given is None)
    load = solved if given is None else given
    speeds = _core.dp_capability_wind(found, angles, load, current=current, max_wind=max_wind)
    frozen = [np.array(a, dtype=np.float64) for a in (angles, speeds, load)]
    for array in frozen:
        array.setflags(write=False)
    return Capability(
        headings=frozen[0],
        wind_speed=frozen[1],
        pipe_load=frozen[2],
        current=current,
        max_wind=max_wind,
        label=default_label if label is None else str(label),
    )
