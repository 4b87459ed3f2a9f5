"""Attachments (`pl.Clump`, `model.attach`): clump weights and buoyancy modules at a point of the line.

A vertical line hanging from its top carries, at every element, the net weight of what hangs below it: a
buoyancy module makes the tension drop by its net buoyancy exactly; its drag in a uniform current is the top's
horizontal reaction; in time, the energy ledger closes with the attachment's inertia, weight and drag in it.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.scenario import load_scenario

G, RHO = 9.81, 1025.0
LENGTH, ELEMENTS = 500.0, 50  # m; 10 m elements
MODULE = pl.Clump(mass=800.0, volume=2.5, drag_area=3.0, added_mass=1.0)  # buoyant: 2.5 t of water


def hanging(
    arc_length: float | None, current: float = 0.0, drag: tuple[float, float] = (0.0, 0.0)
) -> pl.Model:
    """A flooded 0.3 m pipe hanging from its top B in 800 m of water, end A free below, with the module at
    `arc_length` from A (none if None)."""
    section = pl.Section.pipe(0.3, 0.015, contents_density=RHO, drag=drag, added_mass=(0.0, 1.0))
    rod = pl.Rod.straight((0.0, 0.0, 0.0), (0.0, 0.0, -LENGTH), ELEMENTS, section)
    model = pl.Model(rod, sea=pl.Sea(800.0, current=pl.Current.uniform((current, 0.0, 0.0))))
    model.pin("B")
    if arc_length is not None:
        assert model.attach(arc_length, MODULE) == 0
    return model


def net_weight(clump: pl.Clump) -> float:
    return (clump.mass - RHO * clump.volume) * G


def test_a_buoyancy_module_lowers_the_tension_above_it_by_its_net_buoyancy() -> None:
    plain = hanging(None).static()
    w = plain.reaction("B")[2] / LENGTH  # the pipe's submerged weight per length (N/m)
    assert w == pytest.approx(pl.Section.pipe(0.3, 0.015, contents_density=RHO).submerged_weight, rel=1e-9)
    buoyed = hanging(200.0).static()  # at node 20
    tension = buoyed.tension
    # The element above the node carries the module's net weight (negative: buoyancy) on top of one more
    # element's weight.
    assert tension[20] - tension[19] == pytest.approx(w * 10.0 + net_weight(MODULE), rel=1e-9)
    assert tension[30] == pytest.approx(w * 305.0 + net_weight(MODULE), rel=1e-9)
    assert tension[10] == pytest.approx(w * 105.0, rel=1e-9)
    assert buoyed.reaction("B")[2] == pytest.approx(w * LENGTH + net_weight(MODULE), rel=1e-9)
    # Mid-element, the module's load is shared by the element's two nodes.
    between = hanging(205.0).static().tension
    assert between[20] == pytest.approx(w * 205.0 + 0.5 * net_weight(MODULE), rel=1e-9)
    np.testing.assert_allclose(buoyed.attachment_forces, [[0.0, 0.0, net_weight(MODULE)]], rtol=1e-12)
    assert plain.attachment_forces.shape == (0, 3)


def test_the_modules_drag_in_a_current_is_the_tops_horizontal_reaction() -> None:
    """The pipe itself has no drag: all the current pushes is the module, ½ρ C_dA U² at any angle."""
    state = hanging(200.0, current=0.8).static()
    drag = 0.5 * RHO * MODULE.drag_area * 0.8**2
    assert state.reaction("B")[0] == pytest.approx(drag, rel=1e-9)
    np.testing.assert_allclose(state.attachment_forces[0], [drag, 0.0, net_weight(MODULE)], rtol=1e-9)
    assert state.positions[0, 0] > 1.0  # the line swings downstream


def test_the_energy_ledger_closes_every_step_with_an_attachment() -> None:
    """Driven at its top in a current, with drag on pipe and module: E_{n+1} − E_n = W − D each step."""
    model = hanging(200.0, current=0.6, drag=(0.1, 1.2))
    model_state = model.static()
    driven = hanging(200.0, current=0.6, drag=(0.1, 1.2))
    driven.drive("B", position=lambda t: (4.0 * math.sin(0.5 * t), 0.0, -LENGTH))
    results = driven.simulation(state=model_state, dt=0.2).run(40.0, progress=False)
    energy = results.energy["total"]
    balance = np.diff(energy) - np.diff(results.supplied_work) + np.diff(results.dissipated)
    scale = np.abs(energy).max()
    assert np.abs(balance).max() < 1e-9 * scale, np.abs(balance).max() / scale
    assert results.dissipated[-1] > 0.0 and results.supplied_work[-1] != 0.0


@pytest.mark.parametrize(
    ("build", "named"),
    [
        (lambda: hanging(None).attach(LENGTH + 1.0, MODULE), "arc_length"),
        (lambda: hanging(None).attach(-1.0, MODULE), "arc_length"),
        (lambda: hanging(None).attach(float("nan"), MODULE), "arc_length"),
        (lambda: pl.Clump(mass=-1.0), "mass"),
        (lambda: pl.Clump(mass=1.0, volume=float("inf")), "volume"),
        (lambda: pl.Clump(mass=1.0, drag_area=-2.0), "drag_area"),
    ],
)
def test_bad_attachments_are_input_errors_naming_them(build: object, named: str) -> None:
    with pytest.raises(pl.InputError, match=f"^{named}"):
        build()  # type: ignore[operator]


def _pulse(t: float, speed: float = 0.5, duration: float = 30.0, ramp: float = 10.0) -> float:
    """`speed` (m/s) for `duration` s with smooth ramps: pays out speed·duration = 15 m."""

    def smooth(t: float) -> float:
        s = min(max(t / ramp, 0.0), 1.0)
        return s * s * (3.0 - 2.0 * s)

    return speed * (smooth(t) - smooth(t - duration))


def test_a_line_with_an_attachment_pays_out_at_end_b() -> None:
    """Attachments are placed from end A, so pay-out at end B leaves the module on its material: 15 m paid out
    through a tensioner (a drive) at B, the ledger closes and the line settles to the statics of the longer
    line with the module at the same distance from A. Measured when written: balance 7e-14 of the stored
    energy; the settled top tension within 1e-7 of the statics'."""
    model = hanging(200.0)
    model.drive("B", position=lambda t: (0.0, 0.0, -LENGTH))
    model.pay_out("B", _pulse)
    results = model.simulation(model.static(), dt=0.05).run(90.0, progress=False)
    energy = results.energy["total"]
    balance = energy - energy[0] - results.supplied_work + results.dissipated
    assert np.abs(balance).max() < 1e-11 * np.abs(energy).max()
    assert results.length[-1] == pytest.approx(LENGTH + 15.0, abs=1e-9)
    section = pl.Section.pipe(0.3, 0.015, contents_density=RHO, drag=(0.0, 0.0), added_mass=(0.0, 1.0))
    longer = pl.Model(
        pl.Rod.straight((0.0, 0.0, 0.0), (0.0, 0.0, -LENGTH - 15.0), ELEMENTS, section), sea=pl.Sea(800.0)
    )
    longer.pin("B")
    longer.attach(200.0, MODULE)
    expected = np.linalg.norm(longer.static().reaction("B")[:3])
    late = results.time > 70.0
    top = np.linalg.norm(results.reaction("B")[late, :3], axis=1).mean()
    assert top == pytest.approx(expected, rel=1e-5)


def test_attachments_and_pay_out_where_they_cannot_go_together() -> None:
    """Pay-out at end A would move the line's material past attachments placed from A; the end element that
    pay-out grows cannot carry one; pay-in stops at one."""
    model = hanging(200.0)
    model.drive("A", position=lambda t: (0.0, 0.0, 0.0))
    with pytest.raises(pl.InputError, match="^end.*pay out at end B"):
        model.pay_out("A", 0.1)
    model = hanging(LENGTH - 3.0)
    model.drive("B", position=lambda t: (0.0, 0.0, -LENGTH))
    with pytest.raises(pl.InputError, match="^end.*carries an attachment"):
        model.pay_out("B", 0.1)
    model = hanging(None)
    model.drive("B", position=lambda t: (0.0, 0.0, -LENGTH))
    model.pay_out("B", 0.1)
    with pytest.raises(pl.InputError, match="^arc_length.*pay-out grows"):
        model.attach(LENGTH - 3.0, MODULE)
    model = hanging(LENGTH - 25.0)
    model.drive("B", position=lambda t: (0.0, 0.0, -LENGTH))
    model.pay_out("B", -1.0)
    simulation = model.simulation(model.static(), dt=0.05)
    with pytest.raises(pl.InputError, match="pay-in has reached the attachment at 475 m"):
        simulation.run(60.0, progress=False)
    assert 15.0 < simulation.state.time < 25.0


def test_scenario_files_take_attachments(tmp_path: Path) -> None:
    text = """
[pipe]
outer_diameter = 0.3
wall_thickness = 0.015
contents_density = 1025.0
drag = [0.0, 0.0]
[rod]
start = [0, 0, 0]
end = [0, 0, -500]
elements = 50
[sea]
depth = 800.0
[supports.B]
kind = "pin"
[[attachments]]
arc_length = 200.0
mass = 800.0
volume = 2.5
drag_area = 3.0
"""
    path = tmp_path / "module.toml"
    path.write_text(text)
    state = load_scenario(path).model.static()
    assert state.reaction("B")[2] == pytest.approx(hanging(200.0).static().reaction("B")[2], rel=1e-12)
    path.write_text(text.replace("arc_length = 200.0", "arc_length = 900.0"))
    with pytest.raises(pl.InputError, match=r"^attachments\[0\]\.arc_length"):
        load_scenario(path)
