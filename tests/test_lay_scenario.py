"""Lay equipment from scenario files and the command line, and the lay-position solver on top of statics."""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import numpy as np
import pipelay as pl
import pytest
from pipelay.cli import main
from pipelay.lay import find_lay_position, lay_quantity
from pipelay.scenario import load_scenario, parse_scenario

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "s_lay.toml"


def _data() -> dict:
    return tomllib.loads(EXAMPLE.read_text())


def _build(x: float) -> pl.Model:
    """The example's model with the vessel at x (m)."""
    data = _data()
    data["vessel"]["eta"][0] = x
    data["controller"]["reference"][0] = x
    return parse_scenario(data).model


def test_example_scenario_builds_an_s_lay() -> None:
    """The example's stinger (200 m radius, 100 m, 15 rollers) carries the pipe; its overbend strain is the
    classic estimate d_o/(2R) + T/EA (R the centreline's radius: the rollers' top line + the pipe's radius) to 5 %."""
    state = load_scenario(EXAMPLE).model.static()
    summary = state.lay_summary()
    assert summary is not None and state.roller_reactions is not None
    assert len(state.roller_reactions) == 15
    assert np.all(state.roller_reactions >= 0.0)
    assert np.count_nonzero(state.roller_reactions) >= 8
    section = state.section
    radius = 200.0 + 0.3
    estimate = 0.3 / radius + summary["top_tension"] / section.EA
    print(f"overbend strain {summary['overbend_strain']:.5f}, estimate {estimate:.5f}")
    assert summary["overbend_strain"] == pytest.approx(estimate, rel=0.05)
    assert summary["overbend_strain"] >= estimate
    # The lift-off is the last loaded roller, and the departure angle is the pipe's slope there.
    assert summary["liftoff_roller"] == int(np.flatnonzero(state.roller_reactions)[-1])
    assert math.isfinite(summary["layback"]) and summary["layback"] > 0.0


def test_j_lay_scenario() -> None:
    """A [vessel.lay] of kind "j-lay": the pipe leaves the tower at π/2 − its lean below the horizontal, turned
    by the vessel's pitch (the tower is fixed to the vessel)."""
    data = _data()
    data["vessel"]["lay"] = {"kind": "j-lay", "position": [0.0, 0.0, -10.0], "angle": 0.3}
    data["vessel"]["eta"][0] = 600.0
    data["controller"]["reference"][0] = 600.0
    data["rod"]["elements"] = 140
    state = parse_scenario(data).model.static()
    summary = state.lay_summary()
    assert summary is not None
    assert state.roller_reactions is None
    assert summary["liftoff_roller"] is None
    pitch = state.eta[4]
    print(f"departure {summary['departure_angle']:.6f} rad, pitch {pitch:.2e} rad")
    assert abs(pitch) > 1e-5
    assert summary["departure_angle"] == pytest.approx(math.pi / 2 - 0.3 + pitch, abs=1e-9)


@pytest.mark.parametrize(
    ("edit", "key"),
    [
        (lambda d: d["vessel"]["lay"].pop("kind"), "vessel.lay.kind"),
        (lambda d: d["vessel"]["lay"].update(position=[0, 0, 0]), "vessel.lay.position"),
        (lambda d: d["vessel"].update(angle=[0, 0.1, 0]), "vessel.angle"),
        (lambda d: d["vessel"]["lay"].update(friction=-0.2), "vessel.lay.friction"),
        (lambda d: d["vessel"]["lay"]["stinger"].update(positions=[[0, 0, 0]]), "vessel.lay.stinger"),
        (lambda d: d["vessel"]["lay"]["stinger"].update(rollers=0), "vessel.lay.stinger.rollers"),
        (lambda d: d["vessel"]["lay"]["stinger"].update(length=1000.0), "vessel.lay.stinger.length"),
        (lambda d: d["vessel"]["lay"]["stinger"].update(radiuss=1.0), "vessel.lay.stinger.radiuss"),
        (lambda d: d["vessel"]["lay"].update(tensioner=[0, float("nan"), 0]), "vessel.lay.tensioner"),
    ],
)
def test_bad_lay_tables_name_their_key(edit, key: str) -> None:
    """Every bad [vessel.lay] value is an InputError that starts with its key path."""
    data = copy.deepcopy(_data())
    edit(data)
    with pytest.raises(pl.InputError) as error:
        parse_scenario(data)
    assert str(error.value).startswith(key), str(error.value)


def test_rollers_given_point_by_point() -> None:
    """[vessel.lay.stinger] with positions: the arc's roller top points, given one by one, make the same
    static state (thin rollers, so that the arc's radial and the points' vertical offset to the axis agree to
    1e-4 m)."""
    data = _data()
    data["vessel"]["lay"]["stinger"]["roller_radius"] = 1e-4
    arc = parse_scenario(data).model.static()
    stinger = pl.Stinger(200.0, 100.0, 15, origin=(-40.0, 0.0, -6.0), roller_radius=1e-4)
    data["vessel"]["lay"]["stinger"] = {"positions": stinger.positions.tolist(), "roller_radius": 1e-4}
    points = parse_scenario(data).model.static()
    change = np.abs(points.roller_reactions - arc.roller_reactions).max() / arc.roller_reactions.max()
    print(f"largest change of a roller reaction: {change:.1e} of the largest")
    assert change < 1e-3
    assert np.allclose(points.positions, arc.positions, atol=1e-4)


def test_find_lay_position_hits_a_top_tension() -> None:
    """Brent's method on statics: the state it returns has the wanted top tension to 0.1 %, and the tension
    grows with the vessel's distance (the search's premise), checked on either side."""
    found = find_lay_position(_build, "top_tension", 1.0e6, start=660.0)
    assert found.state.lay_summary()["top_tension"] == pytest.approx(1.0e6, rel=1e-3)
    below = lay_quantity(_build(found.x - 1.0).static(), "top_tension")
    above = lay_quantity(_build(found.x + 1.0).static(), "top_tension")
    assert below < 1.0e6 < above
    bracketed = find_lay_position(_build, "top_tension", 1.0e6, (found.x - 2.0, found.x + 2.0))
    assert bracketed.x == pytest.approx(found.x, abs=0.02)


def test_find_lay_position_rejects_bad_requests() -> None:
    """Unknown quantities, brackets that do not straddle the value and non-finite numbers are InputErrors."""
    with pytest.raises(pl.InputError, match="target"):
        find_lay_position(_build, "tension", 1e6, start=660.0)
    with pytest.raises(pl.InputError, match="bracket"):
        find_lay_position(_build, "top_tension", 1e6, (650.0, 651.0))
    with pytest.raises(pl.InputError, match="value"):
        find_lay_position(_build, "top_tension", float("nan"), start=660.0)
    with pytest.raises(pl.InputError, match="start"):
        find_lay_position(_build, "top_tension", 1e6)


def test_cli_static_target(capsys: pytest.CaptureFixture[str]) -> None:
    """`pipelay static --target`: exit 0 with the position found; a bad quantity: exit 2 naming --target."""
    assert main(["static", str(EXAMPLE), "--target", "top_tension=1000"]) == 0
    out = capsys.readouterr().out
    assert "lay position: vessel x = " in out and "\ntop tension " in out
    x = float(out.split("vessel x = ")[1].split()[0])
    assert _build(x).static().lay_summary()["top_tension"] == pytest.approx(1.0e6, rel=1e-3)
    assert main(["static", str(EXAMPLE), "--target", "tension=1e6"]) == 2
    assert "target" in capsys.readouterr().err
    assert main(["static", str(EXAMPLE), "--target", "top_tension=x"]) == 2
    assert "--target" in capsys.readouterr().err


def test_cli_run_writes_the_lay_summary(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """`pipelay run` on the example for 4 s: the file holds roller reactions and the lay summary, which reload
    exactly, and the printout gives the lay ranges."""
    data = _data()
    data["solver"]["t_end"] = 4.0
    scenario = tmp_path / "short.toml"
    scenario.write_text(EXAMPLE.read_text().replace("t_end = 60.0", "t_end = 4.0"))
    output = tmp_path / "run.nc"
    assert main(["run", str(scenario), "-o", str(output), "--no-progress", "--plots", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "\ntop tension " in out and "lay: departure angle" in out
    assert (tmp_path / "lay_summary.png").is_file()
    results = pl.load(output)
    assert results.roller_reactions.shape == (len(results.time), 15)
    summary = results.lay_summary()
    assert summary is not None and len(summary["top_tension"]) == len(results.time)
    first = load_scenario(scenario).model.static().lay_summary()
    assert summary["top_tension"][0] == pytest.approx(first["top_tension"], rel=1e-9)


def test_lay_configuration_figure_draws_the_stinger(tmp_path: Path) -> None:
    """The configuration figure draws every roller (loaded ones apart) at its place, names the lift-off roller
    and draws the strain curve."""
    from pipelay import plots

    state = load_scenario(EXAMPLE).model.static()
    figure = plots.lay_configuration(state, path=tmp_path / "lay.png")
    assert (tmp_path / "lay.png").stat().st_size > 10_000
    side = figure.axes[0]
    lines = {line.get_label(): line for line in side.get_lines()}
    loaded, free = lines["roller in contact"], lines["roller"]
    assert len(loaded.get_xdata()) == np.count_nonzero(state.roller_reactions)
    assert len(loaded.get_xdata()) + len(free.get_xdata()) == 15
    drawn = np.sort(np.concatenate([loaded.get_xdata(), free.get_xdata()]))
    assert np.allclose(drawn, np.sort(state.roller_positions[:, 0]))
    # The lift-off roller, the last loaded one, numbered from 1 as people read it.
    last_loaded = int(np.flatnonzero(state.roller_reactions > 0)[-1]) + 1
    assert figure.axes[1].get_title().endswith(f"at roller {last_loaded} of 15")
    strain = figure.axes[2].get_lines()[0].get_ydata()
    assert np.allclose(strain, 100 * state.strain)


def test_statics_find_the_upright_vessel_from_either_start() -> None:
    """From the reference, load stepping can land on the restoring's upside-down equilibrium (the tower's pull
    turns the vessel over); statics check every state (a capsized one is refused: the engine's tests) and their
    other paths find the upright one, the same as from the default start."""
    section = pl.Section.pipe(0.6, 0.03, contents_density=0.0, drag=(0.0, 1.0), added_mass=(0.0, 1.0))
    model = pl.Model(pl.Rod.straight((0, 0, 0), (700, 0, 0), 280, section), pl.Sea(150.0))
    model.pin("A")
    model.attach_vessel("B", pl.Vessel.osv(), eta=[600, 0, -150, 0, 0, 0], lay=pl.JLay((-20, 0, -30), 0.2))
    state = model.static()
    from_reference = model.static(steps=10, start="reference")
    for found in (state, from_reference):
        assert abs(found.eta[3]) < 0.1 and abs(found.eta[4]) < 0.1
    top = state.lay_summary()["top_tension"]
    assert from_reference.lay_summary()["top_tension"] == pytest.approx(top, rel=1e-6)
    assert state.lay_summary()["departure_angle"] == pytest.approx(math.pi / 2 - 0.2 + state.eta[4], abs=1e-9)
