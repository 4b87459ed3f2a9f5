"""HTML reports of a run and of a sweep: one self-contained file each (figures embedded as PNG, the replays'
plotly.js included), that opens offline in any browser.

```python
from pipelay.report import run_report, sweep_report

run_report("run.nc", "run.html")       # inputs, the run, lay summary and checks, figures, spectra, replay
sweep_report("lay-sweep")              # lay-sweep/report.html: keys, failures, operability maps, worst cases
```

* `pipelay.report.run`: `run_report`, the report of a run (a `Results` or its file);
* `pipelay.report.sweep`: `sweep_report`, the report of a sweep's output folder (``summary.nc``, ``cases/``),
  with the replays of its worst cases written beside their results;
* `pipelay.report.units`: how a quantity is shown (its label, the unit people read; the SI value kept);
* `pipelay.report.html`: the page's frame (the template, tables, figures, escaping, the atomic write).

Imports of pipelay: these modules (which import the engine, `pipelay.results`, `pipelay.analysis`,
`pipelay.plots` and, when they are there, `pipelay.plots.replay` and `pipelay.scenario.scenario_of_results`).
"""

from pipelay.report.run import run_report
from pipelay.report.sweep import sweep_report

__all__ = ["run_report", "sweep_report"]
