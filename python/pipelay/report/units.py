"""How the reports show a quantity to people: a label in words and the unit an engineer reads (kN, kN·m,
degrees, percent), while the cell keeps the exact SI value in ``data-value`` and names its SI unit in
``data-unit``.

```python
from pipelay.report.units import quantity

top = quantity("top_tension")      # label "top tension", SI unit "N", shown in kN
top.cell(902_600.0, id="x")        # prints 902.6, data-value="902600.0", data-unit="N"
```

Rollers are numbered from 1 where people read them (`roller_cell`: "roller 12 of 15"); their ``data-value``
is the Python index, from 0 (``state.lay_summary()["liftoff_roller"]`` indexes ``state.roller_reactions``).

Imports of pipelay: `pipelay.report.html`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from pipelay.report.html import Cell, number

__all__ = ["QUANTITIES", "Quantity", "quantity", "roller_cell"]


@dataclass(frozen=True)
class Quantity:
    """A quantity as a report shows it.

    Attributes
    ----------
    label : str
        What it is, in words ("top tension").
    unit : str
        Its SI unit, that of the values pipelay computes and files hold ("N", "N m", "rad", "1", "m").
    shown : str
        The unit people read it in ("kN", "kN·m", "°", "%"; "" for a plain number).
    scale : float
        The shown number is the SI value times `scale` (1e-3 for kN, 180/π for degrees, 100 for percent).
    """

    label: str
    unit: str
    shown: str
    scale: float = 1.0

    @property
    def heading(self) -> str:
        """The label with the shown unit, for a column or an axis: "top tension (kN)"."""
        return f"{self.label} ({self.shown})" if self.shown else self.label

    def cell(self, value: Any, *, id: str | None = None, digits: int = 6) -> Cell:
        """A numeric cell printing `value` (SI) in the shown unit, with the exact SI value in ``data-value``
        (``"nan"`` for None) and the SI unit in ``data-unit``."""
        if value is None:
            exact, shown = "nan", None
        else:
            exact, shown = repr(float(value)), float(value) * self.scale
        return Cell(number(shown, digits), id=id, data={"value": exact, "unit": self.unit}, numeric=True)


_KN = ("kN", 1e-3)
_KNM = ("kN·m", 1e-3)
_DEGREES = ("°", 180.0 / math.pi)
_PERCENT = ("%", 100.0)
_PLAIN = ("", 1.0)


def _entry(label: str, unit: str, shown: tuple[str, float] | None = None) -> Quantity:
    text, scale = shown if shown is not None else (unit, 1.0)
    return Quantity(label, unit, text, scale)


QUANTITIES: dict[str, Quantity] = {
    # The lay summary (Results.lay_summary()).
    "top_tension": _entry("top tension", "N", _KN),
    "departure_angle": _entry("departure angle", "rad", _DEGREES),
    "liftoff_roller": _entry("lift-off roller", "1", _PLAIN),
    "liftoff_arc_length": _entry("lift-off point, arc length from A", "m"),
    "inflection_arc_length": _entry("inflection point, arc length from A", "m"),
    "layback": _entry("layback", "m"),
    "touchdown_arc_length": _entry("touchdown, arc length from A", "m"),
    "overbend_strain": _entry("overbend strain", "1", _PERCENT),
    "sagbend_strain": _entry("sagbend strain", "1", _PERCENT),
    "sagbend_moment": _entry("sagbend bending moment", "N m", _KNM),
    "tip_clearance": _entry("stinger tip clearance", "m"),
    "tip_offset": _entry("lateral offset at the stinger tip", "m"),
    "boxes_left": _entry("roller boxes the pipe is leaving", "1", _PLAIN),
    "residual_curvature": _entry("residual curvature of the laid pipe", "1/m"),
    # The extremes of a run and a sweep's statistics (pipelay.analysis.sweep.STATISTICS).
    "top_tension_max": _entry("largest top tension", "N", _KN),
    "top_tension_min": _entry("smallest top tension", "N", _KN),
    "reaction_B_max": _entry("largest reaction at B |F_B|", "N", _KN),
    "tension_max": _entry("largest effective axial force", "N", _KN),
    "tension_min": _entry("smallest effective axial force", "N", _KN),
    "moment_max": _entry("largest bending moment", "N m", _KNM),
    "strain_max": _entry("largest strain", "1", _PERCENT),
    "utilisation_max": _entry("largest DNV-ST-F101 utilisation", "1", _PLAIN),
    "load_controlled_max": _entry("largest load-controlled utilisation", "1", _PLAIN),
    "displacement_controlled_max": _entry("largest displacement-controlled utilisation", "1", _PLAIN),
    "offset_max": _entry("largest vessel offset", "m"),
    "thrust_max": _entry("largest horizontal thrust", "N", _KN),
    "touchdown_excursion": _entry("touchdown excursion", "m"),
    "passivity_margin_min": _entry("least work supplied less energy gained", "J"),
    # The stage summary (Results.stage_summary()); strain_max, utilisation_max and top_tension_* as above.
    "start": _entry("start", "s"),
    "end": _entry("end", "s"),
    "wire_tension_max": _entry("largest wire tension", "N", _KN),
    "wire_tension_min": _entry("smallest wire tension", "N", _KN),
    "pipe_force_min": _entry("smallest axial force in the pipe", "N", _KN),
    "touchdown_min": _entry("touchdown nearest A, arc length", "m"),
    "touchdown_max": _entry("touchdown farthest from A, arc length", "m"),
    "roller_reaction_max": _entry("largest roller load", "N", _KN),
    "tip_clearance_min": _entry("least stinger tip clearance", "m"),
    "head_x": _entry("laydown head x at the stage's end", "m"),
    "head_z": _entry("laydown head z at the stage's end", "m"),
    "head_height_min": _entry("laydown head's least height above the seabed", "m"),
    # Spectra.
    "hang_off_moment": _entry("bending moment at the hang-off", "N m", _KNM),
}
"""The quantities the reports show, by the name pipelay gives them (a lay summary key, a statistic, a stage
summary column): label, SI unit and the unit people read."""

_SHOWN = {"N": _KN, "N m": _KNM, "rad": _DEGREES}


def quantity(name: str, unit: str = "") -> Quantity:
    """The quantity `name` of `QUANTITIES`; for a name not there, one labelled by the name (underscores as
    spaces) whose SI `unit` is shown as kN, kN·m or degrees for N, N m or rad, else as it is."""
    found = QUANTITIES.get(name)
    if found is not None:
        return found
    return _entry(name.replace("_", " "), unit, _SHOWN.get(unit))


def roller_cell(index: Any, count: int | None, *, id: str | None = None, noun: str = "roller") -> Cell:
    """A cell naming a roller (or a roller box, `noun` "box") by its number from 1, "roller 12 of 15" (`count`
    of them; "—" for None or NaN: none), with the Python index from 0 in ``data-value`` and ``data-unit``
    "index from 0"."""
    if index is None or not math.isfinite(float(index)):
        return Cell("—", id=id, data={"value": "nan", "unit": "index from 0"}, numeric=True)
    text = f"{noun} {round(float(index)) + 1}" + (f" of {count}" if count is not None else "")
    return Cell(text, id=id, data={"value": repr(float(index)), "unit": "index from 0"}, numeric=True)
