"""Fatigue of the pipe: S-N curves, cycle counting, Miner's sum and spectral damage.

* `pipelay.analysis.fatigue.curves`: `SNCurve`, the S-N curves of DNV-RP-C203 (2016) in air, in seawater
  with cathodic protection and under free corrosion, with the thickness effect (``SNCurve.dnv``), or a
  user's curve of one or two slopes (``SNCurve.user``); `DNV_CLASSES`, `ENVIRONMENTS`;
* `pipelay.analysis.fatigue.counting`: rainflow counting of a stress history after ASTM E1049-85
  (`rainflow`, `cycle_ranges`) and the Palmgren–Miner sum of counted cycles on a curve (`miner`);
* `pipelay.analysis.fatigue.spectral`: the expected damage of a stationary Gaussian stress process from its
  PSD, by Dirlik's cycle distribution or the narrow-band (Rayleigh) one (`spectral_damage`), or from a time
  series through its Welch PSD (`series_spectral_damage`); `SPECTRAL_METHODS`.

```python
from pipelay.analysis import fatigue

curve = fatigue.SNCurve.dnv("D", environment="seawater_cp", thickness=0.03)
curve.cycles(80.0)                                   # N at a stress range of 80 MPa
damage = fatigue.miner(fatigue.rainflow(stress), curve)   # stress: a history in MPa
```

Units: stress and stress range in MPa (N/mm²), as the S-N tables; frequency in Hz; time in s; thickness in
m. Bad input raises `pipelay.InputError` naming the argument, the value and what is allowed.

Third-party libraries: `rainflow` (the counting) and FLife (spectral moments and the Dirlik and narrow-band
densities, imported when a spectral damage is first computed).

Imports of pipelay: `pipelay.analysis.checks` (its input errors) and `pipelay.analysis.statistics` (the
spectrum of a series).
"""

from pipelay.analysis.fatigue.counting import cycle_ranges, miner, rainflow
from pipelay.analysis.fatigue.curves import DNV_CLASSES, ENVIRONMENTS, SNCurve
from pipelay.analysis.fatigue.spectral import SPECTRAL_METHODS, series_spectral_damage, spectral_damage

__all__ = [
    "DNV_CLASSES",
    "ENVIRONMENTS",
    "SPECTRAL_METHODS",
    "SNCurve",
    "cycle_ranges",
    "miner",
    "rainflow",
    "series_spectral_damage",
    "spectral_damage",
]
