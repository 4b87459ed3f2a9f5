"""Peer-code comparison with MoorDyn v2: added mass by direction, on a heavy pipe lying partly on the seabed.

The case (the machinery of ``moordyn_seabed_case``): a 2000 m flooded steel pipe (0.6 m × 15 mm, 478 kg/m, EA
5.7 GN) anchored on a flat seabed in 800 m of water, its top 1400 m across and 800 m up, about 1070 m of it laid;
seabed kBot = 3 MPa/m, cBot = 120 kPa·s/m, no friction; added mass Ca = 1 across the pipe and 0 along it in
both codes (MoorDyn: Ca = 1, CaAx = 0), normal drag 1.2. From rest the top is driven 10 m in surge at a 12 s
period (ramped over 20 s) to t = 40 s: the top tension swings by a third of its mean. n = 100 elements in both,
pipelay dt = 0.05 s, MoorDyn dt = 1 ms (RK4).

Measured when written: the top-tension histories differ by at most 1.8 % of the mean (rms 0.60 %); with
pipelay's added mass isotropic (the normal coefficient along the pipe too, as before it honoured the axial one)
they differ by 9.1 % (rms 3.8 %): the axial added mass of a heavy pipe moving along itself is what set them
apart. The static top tensions differ by 0.26 %. Runtime ≈ 5 s.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from moordyn_seabed_case import (
    SEABED_CASE,
    max_relative_error,
    rms_relative_error,
    run_moordyn,
    run_pipelay,
)

pytest.importorskip("moordyn")

ELEMENTS = 100
DT_PIPELAY = 0.05  # s
DT_MOORDYN = 1.0e-3  # s

_D, _T = 0.6, 0.015  # m
_AREA = math.pi / 4.0 * (_D**2 - (_D - 2 * _T) ** 2)
PIPE = replace(
    SEABED_CASE,
    length=2000.0,
    diameter=_D,
    mass=7850.0 * _AREA + 1025.0 * math.pi / 4.0 * (_D - 2 * _T) ** 2,
    ea=207e9 * _AREA,
    ei=207e9 * math.pi / 64.0 * (_D**4 - (_D - 2 * _T) ** 4),
    depth=800.0,
    x0=1400.0,
    rise=800.0,
    amp_x=10.0,
    amp_z=0.0,
    period=12.0,
    ramp=20.0,
    t_end=40.0,
    kbot=3.0e6,
    cbot=1.2e5,
    ca=1.0,
    ca_axial=0.0,
)


def test_axial_added_mass_is_what_matches_moordyn() -> None:
    ours = run_pipelay(ELEMENTS, DT_PIPELAY, PIPE)
    theirs = run_moordyn(ELEMENTS, DT_MOORDYN, PIPE)
    isotropic = run_pipelay(ELEMENTS, DT_PIPELAY, replace(PIPE, ca_axial=1.0))
    assert abs(ours.static_tension / theirs.static_tension - 1.0) < 0.005
    swing = (theirs.tension.max() - theirs.tension.min()) / theirs.tension.mean()
    assert swing > 0.25, swing
    error, rms = max_relative_error(ours, theirs), rms_relative_error(ours, theirs)
    assert error < 0.03 and rms < 0.01, (error, rms)
    # The same run with the normal coefficient along the pipe too is several times further from MoorDyn.
    assert rms_relative_error(isotropic, theirs) > 3.0 * rms, (rms_relative_error(isotropic, theirs), rms)
    assert max_relative_error(isotropic, theirs) > 0.06
