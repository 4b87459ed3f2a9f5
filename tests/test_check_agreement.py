"""One DNV-ST-F101 utilisation: the command line, the lay figure, the report and Python give the same numbers
for the same state and parameters (the scenario's ``[checks]``), and a flooded pipe's checks match a hand
calculation with its contents' pressure inside."""

from __future__ import annotations

import math
import re
import subprocess
import sys
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pipelay as pl
import pytest
from pipelay import plots
from pipelay.report import run_report
from pipelay.scenario import parse_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
G = 9.81


def _scenario(name: str, checks: dict[str, Any] | None = None) -> Any:
    data = tomllib.loads((EXAMPLES / name).read_text())
    data.pop("checks", None)
    if checks is not None:
        data["checks"] = checks
    return parse_scenario(data, origin=str(EXAMPLES / name), folder=EXAMPLES)


def _cli_utilisations(path: Path) -> dict[str, float]:
    command = [sys.executable, "-m", "pipelay", "static", str(path)]
    done = subprocess.run(command, check=True, capture_output=True, text=True, timeout=300)
    found = re.findall(
        r"DNV-ST-F101 (load-controlled|displacement-controlled|propagation buckling)\s+([\d.]+)", done.stdout
    )
    assert re.search(r"^checks: DNV-ST-F101, X\d\d, safety class \w+ ", done.stdout, flags=re.MULTILINE)
    return {name: float(value) for name, value in found}


@pytest.mark.parametrize(
    ("example", "checks"),
    [("s_lay_concrete.toml", {"safety_class": "low", "fabrication": "uoe"}), ("j_lay_dp.toml", None)],
)
def test_cli_figure_report_and_python_agree(
    example: str, checks: dict[str, Any] | None, tmp_path: Path
) -> None:
    scenario = _scenario(example, checks)
    path = tmp_path / example
    table = "".join(f'{key} = "{value}"\n' for key, value in (checks or {}).items())
    own = (
        (EXAMPLES / example).read_text().split("\n[checks]")[0]
    )  # the example's own [checks] is its last table
    path.write_text(own + ("\n[checks]\n" + table if checks else ""))
    state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    check = pl.checks.dnv_st_f101(state, **scenario.checks)
    propagation = pl.checks.propagation_buckling(state, **scenario.checks)
    python = {
        "load-controlled": check.load_controlled.max(),
        "displacement-controlled": check.displacement_controlled.max(),
        "propagation buckling": propagation.utilisation.max(),
    }
    if checks is not None:
        assert "safety class low" in check.basis and "uoe (α_fab 0.85)" in check.basis
    # the command line prints them to 3 decimals
    cli = _cli_utilisations(path)
    assert cli.keys() == python.keys()
    for name, value in python.items():
        assert cli[name] == pytest.approx(value, abs=5e-4)

    # the figure's legend states each check's largest value
    figure = plots.lay_configuration(state, **scenario.checks)
    legend = [text.get_text() for text in figure.axes[3].get_legend().get_texts()]
    for name, value in python.items():
        assert any(line.startswith(f"{name}: {value:.3f}") for line in legend), legend

    # the report of a run from that state: its first record is the static state
    results = scenario.model.simulation(state=state, dt=scenario.dt).run(2 * scenario.dt, progress=False)
    page = run_report(results, tmp_path / "report.html", scenario=scenario, replay=False).read_text()
    for key, name in (
        ("load_controlled", "load-controlled"),
        ("displacement_controlled", "displacement-controlled"),
        ("propagation", "propagation buckling"),
    ):
        cell = re.search(rf'id="check-{key}"[^>]*data-value="([^"]+)"', page)
        assert cell is not None
        assert float(cell.group(1)) == pytest.approx(python[name], rel=1e-6)
    assert check.basis.split(", ")[2] in page  # the safety class stated beside them


def test_hanging_pipe_checks_are_finite_and_match_a_hand_calculation() -> None:
    scenario = _scenario("hanging_pipe.toml")
    state = scenario.model.static()
    check = pl.checks.dnv_st_f101(state)
    assert np.all(np.isfinite(check.load_controlled)) and np.all(np.isfinite(check.displacement_controlled))
    # flooded: p_i = ρ_c g h = p_e at every element (1025 kg/m³ inside and out), no pressure term
    z_mid = 0.5 * (state.positions[:-1, 2] + state.positions[1:, 2])
    depth_below_surface = np.clip(800.0 + z_mid, 0.0, None)
    np.testing.assert_allclose(check.internal_pressure, 1025.0 * G * depth_below_surface, rtol=1e-12)
    np.testing.assert_allclose(check.external_pressure, check.internal_pressure, rtol=1e-12)
    # by hand at the governing element: X65, D = 0.6 m, t = 15 mm (D/t = 40), safety class medium
    d, t = 0.6, 0.015
    f_y, f_u = 450e6 * 0.96, 535e6 * 0.96
    beta = (60.0 - d / t) / 90.0
    alpha_c = (1.0 - beta) + beta * f_u / f_y
    m_p, s_p = f_y * (d - t) ** 2 * t, f_y * math.pi * (d - t) * t
    gamma = 1.15 * 1.14
    k = check.worst_element("load_controlled")
    moment = math.hypot(*state.section_forces[k, 4:6])
    tension = state.tension[k]
    hand = (gamma * moment / (alpha_c * m_p) + (gamma * tension / (alpha_c * s_p)) ** 2) ** 2
    assert check.load_controlled[k] == pytest.approx(hand, rel=1e-12)
    alpha_gw = 1.0 - 0.4 * (d / t - 20.0) / 40.0
    allowable = 0.78 * (t / d - 0.01) * 0.93**-1.5 * alpha_gw / 2.5
    k = check.worst_element("displacement_controlled")
    assert check.displacement_controlled[k] == pytest.approx(abs(state.strain[k]) / allowable, rel=1e-12)
    assert check.load_controlled.max() < 1.0 and check.displacement_controlled.max() < 1.0
    # no propagation either: the pressures balance
    assert pl.checks.propagation_buckling(state).max() == 0.0
