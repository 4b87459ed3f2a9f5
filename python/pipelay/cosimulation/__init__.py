"""Co-simulation: a controller FMU as the vessel's controller (`pl.Controller.fmu`), and pipelay as an FMU
(`pipelay fmu`, `pipelay.cosimulation.build_fmu`) for an FMI master (fmpy, DNV's Open Simulation Platform)."""

from pipelay.cosimulation.controller import Controller, FmuLaw

__all__ = ["Controller", "FmuLaw"]
