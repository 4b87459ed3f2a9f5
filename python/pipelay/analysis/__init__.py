"""Analyses on top of the engine's states and results: what a run or a lay configuration means.

* `pipelay.analysis.checks`: DNV-ST-F101 local-buckling checks of a state (``pl.checks``);
* `pipelay.analysis.extremes`: the extremes of a run and the utilisation of every element at every record;
* `pipelay.analysis.statistics`: those, and the statistics of time series: response spectra, most probable
  maxima (``pl.statistics``);
* `pipelay.analysis.lay`: where to put the vessel for a wanted lay configuration (``pl.lay``,
  ``pl.find_lay_position``);
* `pipelay.analysis.lay_table`: the lay table, that configuration at each water depth (``pl.lay_table``);
* `pipelay.analysis.sweep`: operability sweeps of a scenario on Dask (``pl.sweep``);
* `pipelay.analysis.stages`: what each stage of a staged lay did (``Results.stage_summary``);
* `pipelay.analysis.fatigue`: S-N curves, rainflow and spectral damage, the fatigue of a run and of a standby
  over a scatter diagram (``pl.fatigue``);
* `pipelay.analysis.capability`: the DP capability envelope of a vessel holding a pipe (``dp_capability``,
  ``Capability``, exported here).

Imports of pipelay: the engine, `pipelay.results` and `pipelay.scenario` (the sweep); neither of those imports
this package.
"""

from pipelay.analysis.capability import Capability, dp_capability

__all__ = ["Capability", "dp_capability"]
