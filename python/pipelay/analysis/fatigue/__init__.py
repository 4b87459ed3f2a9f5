"""Fatigue of the pipe: S-N curves, cycle counting, Miner's sum and spectral damage; the hot-spot stresses and
damage of a run; the damage of a standby over a scatter diagram of sea states.

* `pipelay.analysis.fatigue.curves`: `SNCurve`, the S-N curves of DNV-RP-C203 (2016) in air, in seawater
  with cathodic protection and under free corrosion, with the thickness effect (``SNCurve.dnv``), or a
  user's curve of one or two slopes (``SNCurve.user``); `DNV_CLASSES`, `ENVIRONMENTS`;
* `pipelay.analysis.fatigue.counting`: rainflow counting of a stress history after ASTM E1049-85
  (`rainflow`, `cycle_ranges`) and the Palmgren–Miner sum of counted cycles on a curve (`miner`);
* `pipelay.analysis.fatigue.spectral`: the expected damage of a stationary Gaussian stress process from its
  PSD, by Dirlik's cycle distribution or the narrow-band (Rayleigh) one (`spectral_damage`), or from a time
  series through its Welch PSD (`series_spectral_damage`); `SPECTRAL_METHODS`;
* `pipelay.analysis.fatigue.stresses`: the stress histories of a run at hot spots around the wall of every
  element, axial and bending, times the SCF (`hot_spot_stresses`);
* `pipelay.analysis.fatigue.damage`: their Miner's sums over a duration (`damage`, a `Damage`);
* `pipelay.analysis.fatigue.scatter`: the damage of a standby over a scatter diagram (`read_scatter`,
  `scatter_damage`, a `ScatterDamage`), each sea state a case of a sweep.

```python
from pipelay.analysis import fatigue

curve = fatigue.SNCurve.dnv("D", environment="seawater_cp", thickness=0.03)
curve.cycles(80.0)                                   # N at a stress range of 80 MPa
damage = fatigue.miner(fatigue.rainflow(stress), curve)   # stress: a history in MPa
d = fatigue.damage(results, curve, scf=1.2, duration=3600.0, start=90.0)   # a run's, per element and hot spot
d.max(), d.worst(), d.plot()
```

Units: stress and stress range in MPa (N/mm²), as the S-N tables; frequency in Hz; time in s; thickness in
m. Bad input raises `pipelay.InputError` naming the argument, the value and what is allowed.

Third-party libraries: `rainflow` (the counting) and FLife (spectral moments and the Dirlik and narrow-band
densities, imported when a spectral damage is first computed).

Imports of pipelay: `pipelay.analysis.checks` (its input errors), `pipelay.analysis.statistics` (the
spectrum of a series) and, for the scatter diagram, `pipelay.scenario`, `pipelay.results` and
`pipelay.analysis.sweep`.
"""

from pipelay.analysis.fatigue.counting import cycle_ranges, miner, rainflow
from pipelay.analysis.fatigue.curves import DNV_CLASSES, ENVIRONMENTS, SNCurve
from pipelay.analysis.fatigue.damage import METHODS, Damage, damage, damage_of_stresses
from pipelay.analysis.fatigue.scatter import (
    PROBABILITY_TOLERANCE,
    ScatterDamage,
    ScatterDiagram,
    read_scatter,
    scatter_damage,
    scatter_diagram,
)
from pipelay.analysis.fatigue.spectral import SPECTRAL_METHODS, series_spectral_damage, spectral_damage
from pipelay.analysis.fatigue.stresses import HotSpotStresses, hot_spot_stresses

__all__ = [
    "DNV_CLASSES",
    "ENVIRONMENTS",
    "METHODS",
    "PROBABILITY_TOLERANCE",
    "SPECTRAL_METHODS",
    "Damage",
    "HotSpotStresses",
    "SNCurve",
    "ScatterDamage",
    "ScatterDiagram",
    "cycle_ranges",
    "damage",
    "damage_of_stresses",
    "hot_spot_stresses",
    "miner",
    "rainflow",
    "read_scatter",
    "scatter_damage",
    "scatter_diagram",
    "series_spectral_damage",
    "spectral_damage",
]
