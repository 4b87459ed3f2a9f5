"""Sections the tests share: a pipe's section with its bending and torsional stiffness scaled, all else equal
(the cable limit of a pipe, for comparisons with catenaries and MoorPy's lines)."""

from __future__ import annotations

import pipelay as pl


def with_bending_scaled(section: pl.Section, factor: float) -> pl.Section:
    """`section` with its EI and GJ scaled by `factor`; EA, GA, mass, inertia, diameter, drag, added mass kept."""
    return pl.Section(
        EA=section.EA,
        GA=section.GA,
        GJ=section.GJ * factor,
        EI=section.EI[0] * factor,
        mass=section.mass,
        inertia=section.inertia,
        outer_diameter=section.outer_diameter,
        drag=section.drag,
        added_mass=section.added_mass,
    )
