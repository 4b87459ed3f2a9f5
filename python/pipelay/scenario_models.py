"""The old import path of the scenario format's models, kept for compatibility.

``pipelay.scenario_models`` was one module; its names now live in the package `pipelay.scenario`:
`pipelay.scenario.values` (what one key takes, the `Table` base, the words of messages),
`pipelay.scenario.models` (the tables, every model), `pipelay.scenario.schema` (`KEYS`, `TABLES`) and
`pipelay.scenario.checking` (`explain`). This module re-exports them.
"""

from pipelay.scenario.checking import explain
from pipelay.scenario.models import *
from pipelay.scenario.schema import KEYS, TABLES
from pipelay.scenario.values import *

__all__ = [
    "KEYS",
    "MAX_ELEMENTS",
    "TABLES",
    "ScenarioFile",
    "Table",
    "Value",
    "explain",
    "join",
    "rule",
    "show",
    "suggest",
]
