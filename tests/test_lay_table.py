"""The lay table over water depths: each row a standalone solve of its depth (the depth, the vessel's η z and
the pipe's length set by hand from the documented rules), the target met, a depth where it cannot be met a row
of NaN with its reason, the CSV in people's units, the command line, the figure, the runs on Dask, and bad
input refused before any solve."""

from __future__ import annotations

import contextlib
import io
import math
import re
import tomllib
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import distributed
import numpy as np
import pandas as pd
import pipelay as pl
import pytest
import xarray as xr
from pipelay import plots
from pipelay.analysis.lay import REACHED
from pipelay.analysis.lay_table import COLUMNS, pipe_length, scenario_at
from pipelay.cli import _depth_values, main
from pipelay.scenario import parse_scenario

S_LAY = Path(__file__).resolve().parent.parent / "examples" / "s_lay.toml"
"""A 700 m pipe of 280 elements in 150 m of water over a 15-roller stinger: a static solve takes 0.02–0.1 s
near the lay position."""
OWN_DEPTH = 150.0
LENGTH = 700.0
ELEMENTS = 280


def source() -> dict[str, Any]:
    """The S-lay scenario's document."""
    return tomllib.loads(S_LAY.read_text())


def standalone(depth: float, x: float) -> tuple[pl.State, Any, float, str]:
    """The S-lay solved on its own at `depth` with the vessel at x, built by hand from the documented rules:
    sea.depth, η's z = −depth, the controller's reference following the vessel (x with η's x, z with the
    surface), and beyond 150 m the rod lengthened at its top to 700·depth/150 m, rounded up to whole 2.5 m
    elements. Returns the state, the scenario, the pipe's length and the PhysicsWarnings of the solve."""
    data = source()
    added = math.ceil((LENGTH * depth / OWN_DEPTH - LENGTH) / (LENGTH / ELEMENTS)) if depth > OWN_DEPTH else 0
    length = LENGTH + added * LENGTH / ELEMENTS
    data["sea"]["depth"] = depth
    reference = data["controller"]["reference"]
    reference[0] += x - data["vessel"]["eta"][0]
    reference[2] += OWN_DEPTH - depth
    data["vessel"]["eta"] = [x, 0.0, -depth, 0.0, 0.0, 0.0]
    data["rod"]["end"] = [length, 0.0, 0.0]
    data["rod"]["elements"] = ELEMENTS + added
    scenario = parse_scenario(data)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", pl.PhysicsWarning)
        state = scenario.model.static(steps=scenario.static_steps, start=scenario.static_start)
    suspect = "; ".join(str(w.message) for w in caught if issubclass(w.category, pl.PhysicsWarning))
    return state, scenario, length, suspect


def assert_row_is(table: xr.Dataset, depth: float) -> None:
    """The table's row at `depth` equals the standalone solve with the vessel at the row's x, to 1e-9."""
    row = table.sel(depth=depth)
    state, scenario, length, suspect = standalone(depth, float(row.vessel_x))
    summary = state.lay_summary()
    check = pl.checks.dnv_st_f101(state, **scenario.checks)
    expected = {
        "top_tension": summary["top_tension"],
        "departure_angle": summary["departure_angle"],
        "layback": summary["layback"],
        "overbend_strain": summary["overbend_strain"],
        "sagbend_strain": summary["sagbend_strain"],
        "tip_clearance": summary["tip_clearance"],
        "roller_reaction_max": np.max(state.roller_reactions),
        "liftoff_roller": summary["liftoff_roller"] + 1,
        "load_controlled_max": np.max(check.load_controlled),
        "displacement_controlled_max": np.max(check.displacement_controlled),
        "propagation_max": pl.checks.propagation_buckling(state, **scenario.checks).max(),
        "pipe_length": length,
    }
    for name, value in expected.items():
        assert float(row[name]) == pytest.approx(float(value), rel=1e-9, abs=1e-12), (depth, name)
    assert str(row.utilisation_basis.values) == check.basis
    assert str(row.warning.values) == suspect
    assert str(row.failure.values) == ""


@pytest.fixture(scope="module")
def table() -> xr.Dataset:
    """Shallower than the scenario, its own depth, and deeper (the pipe lengthened from 700 to 887.5 m): the
    vessel placed for a top tension of 1000 kN."""
    return pl.lay_table(S_LAY, depths=[120.0, 150.0, 190.0], target={"top_tension": 1.0e6})


def test_each_row_is_a_standalone_solve_with_its_target_met(table: xr.Dataset) -> None:
    assert table["depth"].values.tolist() == [120.0, 150.0, 190.0]
    for depth in (120.0, 150.0, 190.0):
        assert_row_is(table, depth)
    # The target met within the search's 0.1 %, at every depth.
    assert np.all(np.abs(table.top_tension.values - 1.0e6) <= REACHED * 1.0e6)
    # 700·190/150 = 886.7 m, rounded up to 355 elements of 2.5 m; shallower depths keep the scenario's pipe.
    assert table.pipe_length.values.tolist() == [700.0, 700.0, 887.5]
    assert pipe_length(S_LAY, 190.0) == 887.5
    # scenario_at gives the row's model: the same state.
    row = table.sel(depth=190.0)
    at = scenario_at(S_LAY, 190.0, float(row.vessel_x))
    state = at.model.static(steps=at.static_steps, start=at.static_start)
    assert state.lay_summary()["top_tension"] == float(row.top_tension)
    assert state.eta[2] == pytest.approx(-190.0, abs=1.0)  # heave finds its equilibrium near the surface


def test_units_and_names(table: xr.Dataset) -> None:
    for name, column in COLUMNS.items():
        assert table[name].attrs == {"units": column.units, "long_name": column.long_name}
    assert table["depth"].attrs["units"] == "m"
    assert table.attrs["target"] == "top_tension" and table.attrs["target_value"] == 1.0e6
    assert table.attrs["target_units"] == "N"


@dataclass(frozen=True)
class Command:
    """A run of `pipelay lay-table`: its exit code, what it printed, and the folder of its files."""

    code: int
    out: str
    err: str
    folder: Path


@pytest.fixture(scope="module")
def command(tmp_path_factory: pytest.TempPathFactory) -> Command:
    """`pipelay lay-table` for a top tension of 200 kN: at 150 m the vessel finds it, at 300 m (a pipe of
    1400 m; the pipe's submerged weight over the depth alone, w·h = 1.294 kN/m × 300 m = 388 kN, is nearly
    twice the target) no position gives it. Writes table.csv, table.nc and table.png."""
    folder = tmp_path_factory.mktemp("lay-table")
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(
            ["lay-table", str(S_LAY), "--depths", "150,300", "--target", "top_tension=200",
             "-o", str(folder / "table.csv"), "--netcdf", str(folder / "table.nc"),
             "--plot", str(folder / "table.png"), "--no-progress"]
        )  # fmt: skip
    return Command(code, out.getvalue(), err.getvalue(), folder)


@pytest.fixture(scope="module")
def unreachable(command: Command) -> xr.Dataset:
    """The table of `command`, as its netCDF file holds it (SI units)."""
    with xr.open_dataset(command.folder / "table.nc", engine="h5netcdf") as opened:
        return opened.load()


def test_a_depth_where_the_target_cannot_be_met_is_a_row_of_nan_with_its_reason(
    unreachable: xr.Dataset,
) -> None:
    assert pl.Section.pipe(0.6, 0.03).submerged_weight * 300.0 > 2.0e5
    met, missed = unreachable.sel(depth=150.0), unreachable.sel(depth=300.0)
    assert abs(float(met.top_tension) - 2.0e5) <= REACHED * 2.0e5
    assert_row_is(unreachable, 150.0)
    for name in COLUMNS:
        if name != "pipe_length":
            assert math.isnan(float(missed[name])), name
    assert float(missed.pipe_length) == 1400.0
    reason = str(missed.failure.values)
    assert reason.startswith("TargetNotReached:") and "top_tension = 200000 N (200 kN)" in reason


def test_a_quantity_that_jumps_across_the_target_is_a_row_of_nan() -> None:
    """A departure angle of 29° at 150 m: where the lift-off moves from one roller to the next the angle jumps
    across 29°, so no state has it. The failure names the place: standalone solves 1 cm either side of it give
    angles on either side of 29°, more than a degree apart (a jump, not a slope of 1° per cm)."""
    found = pl.lay_table(S_LAY, depths=[150.0], target={"departure_angle": math.radians(29.0)})
    reason = str(found.failure.values[0])
    assert math.isnan(float(found.departure_angle[0])) and "departure_angle jumps across" in reason
    x = float(re.search(r"at x = ([\d.]+) m", reason)[1])
    angles = [standalone(150.0, x + dx)[0].lay_summary()["departure_angle"] for dx in (-0.01, 0.01)]
    assert min(angles) < math.radians(29.0) < max(angles)
    assert abs(angles[1] - angles[0]) > math.radians(1.0)


def test_the_command_line_writes_the_table_in_peoples_units(
    command: Command, unreachable: xr.Dataset
) -> None:
    """Exit 1 (a depth failed, said on standard error with its reason); the CSV is the netCDF's table (SI
    units, with units attributes) in kN, degrees and percent, the lift-off roller from 1, the failed depth's
    cells empty; the figure is written."""
    assert command.code == 1
    assert "pipelay: depth 300 m: target not met: TargetNotReached" in command.err
    assert "table: " in command.out and (command.folder / "table.png").is_file()
    written = pd.read_csv(command.folder / "table.csv", keep_default_na=False, na_values=[""])
    assert written.columns[0] == "depth_m" and "top_tension_kN" in written.columns
    assert {"departure_angle_deg", "sagbend_strain_pct", "roller_reaction_max_kN"} <= set(written.columns)
    for name, column in COLUMNS.items():
        expected = unreachable[name].values * column.scale
        np.testing.assert_allclose(written[column.header].to_numpy(dtype=float), expected, rtol=1e-11)
    assert written["top_tension_kN"][0] == pytest.approx(float(unreachable.top_tension[0]) / 1e3, rel=1e-11)
    assert written["departure_angle_deg"][0] == pytest.approx(
        math.degrees(float(unreachable.departure_angle[0]))
    )
    assert written["failure"][1] == str(unreachable.failure.values[1])
    assert math.isnan(written["top_tension_kN"][1])
    assert (
        unreachable.top_tension.attrs["units"] == "N" and unreachable.departure_angle.attrs["units"] == "rad"
    )


def test_the_figure_draws_each_quantity_against_depth(unreachable: xr.Dataset) -> None:
    figure = plots.lay_table(unreachable)
    axes = figure.axes
    assert len(axes) == 8
    (tension,) = [line for line in axes[0].lines if line.get_gid() == "top_tension"]
    np.testing.assert_array_equal(tension.get_xdata(), [150.0, 300.0])
    np.testing.assert_allclose(tension.get_ydata(), unreachable.top_tension.values / 1e3)
    failed = [line for line in axes[3].lines if line.get_linestyle() == ":"]
    assert [line.get_xdata()[0] for line in failed] == [300.0]
    strain = next(line for line in axes[4].lines if line.get_gid() == "sagbend_strain")
    assert strain.get_ydata()[0] == pytest.approx(100.0 * float(unreachable.sagbend_strain[0]))


def test_many_depths_run_on_dask_in_the_order_given(table: xr.Dataset) -> None:
    """Six depths on two worker processes, given out of order, as two tasks: the rows keep the order, each
    meets the target, lies within 2 × 0.01 m of the in-process table's x (each is within 0.01 m of the exact
    position) and is a standalone solve."""
    depths = [170.0, 120.0, 160.0, 150.0, 190.0, 140.0]
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
        distributed.get_task_stream(client) as stream,
    ):
        found = pl.lay_table(S_LAY, depths=depths, target={"top_tension": 1.0e6}, client=client)
    # Two tasks, one a worker, each a run of three contiguous depths.
    assert len(stream.data) == 2 and all(task["key"].startswith("_task") for task in stream.data)
    assert found["depth"].values.tolist() == depths
    assert np.all(np.abs(found.top_tension.values - 1.0e6) <= REACHED * 1.0e6)
    for depth in (120.0, 150.0, 190.0):
        assert abs(float(found.vessel_x.sel(depth=depth)) - float(table.vessel_x.sel(depth=depth))) <= 0.02
    assert_row_is(found, 170.0)


def test_depths_on_the_command_line() -> None:
    assert _depth_values("100:1000:50") == [100.0 + 50.0 * k for k in range(19)]
    assert _depth_values("100:990:50")[-1] == 950.0
    assert _depth_values("0.1:0.3:0.1") == [0.1, 0.2, 0.3]
    assert _depth_values("120,150") == [120.0, 150.0]
    for bad in ("100:50:10", "100:200:0", "100:200", "deep", "100,nan"):
        with pytest.raises(pl.InputError, match="--depths"):
            _depth_values(bad)


@pytest.mark.parametrize(
    ("change", "depths", "target", "named"),
    [
        (None, [], {"top_tension": 1e6}, "depths: empty"),
        (None, [150.0, -10.0], {"top_tension": 1e6}, "depths: -10.0"),
        (None, [150.0, 150.0], {"top_tension": 1e6}, "depths: 150 m given more than once"),
        (None, [150.0], {"top_tension": 1e6, "layback": 500.0}, "target:"),
        (None, [150.0], {"top_tensions": 1e6}, "target: 'top_tensions'"),
        (None, [150.0], {"departure_angle": 62.0}, "target: departure_angle = 62.0 is out of range"),
        ("bathymetry", [150.0], {"top_tension": 1e6}, "sea.seabed.bathymetry"),
        ("point load", [200.0], {"top_tension": 1e6}, "point_loads"),
        ("nodes", [200.0], {"top_tension": 1e6}, "rod.nodes"),
        ("no stinger", [150.0], {"departure_angle": 0.5}, "departure_angle is fixed by the lay equipment"),
    ],
)
def test_bad_input_is_refused_before_any_solve(
    change: str | None, depths: list[float], target: dict, named: str
) -> None:
    data = source()
    if change == "bathymetry":
        data["sea"]["seabed"]["bathymetry"] = {"kind": "plane", "gradient": [0.01, 0.0]}
    elif change == "point load":
        data["point_loads"] = [{"node": 100, "force": [0.0, 0.0, 1e3]}]
    elif change == "nodes":
        data["rod"] = {"nodes": np.linspace([0.0, 0.0, 0.0], [700.0, 0.0, 0.0], 281).tolist()}
    elif change == "no stinger":
        del data["vessel"]["lay"]["stinger"]
    with pytest.raises(pl.InputError, match=named.replace("(", r"\(")):
        pl.lay_table(parse_scenario(data), depths=depths, target=target)


def test_a_j_lay_table_has_no_stinger_columns() -> None:
    """examples/j_lay_dp.toml (a tower, no stinger) at 800 and 1000 m for 700 kN: the overbend strain, tip
    clearance and roller columns are empty, as the summaries print them, while the sagbend and the checks are
    those of a standalone solve; the lay summary's data still hold the strain below the tower."""
    scenario = S_LAY.parent / "j_lay_dp.toml"
    table = pl.lay_table(scenario, depths=[800.0, 1000.0], target={"top_tension": 7e5})
    for name in ("overbend_strain", "tip_clearance", "roller_reaction_max", "liftoff_roller"):
        assert np.all(np.isnan(table[name].values)), name
    assert np.all(np.isfinite(table["sagbend_strain"].values))
    deep = scenario_at(scenario, 1000.0, float(table["vessel_x"].values[1]))
    state = deep.model.static(steps=deep.static_steps, start=deep.static_start)
    summary = state.lay_summary()
    assert float(table["sagbend_strain"].values[1]) == pytest.approx(summary["sagbend_strain"], rel=1e-9)
    assert summary["overbend_strain"] > 0.0  # the bend below the tower, in the data, not named an overbend
