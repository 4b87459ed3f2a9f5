"""Drives and pay-out speeds given as tables of samples, interpolated in the engine (no Python per step):
they reproduce the same runs with callables, and bad tables or times outside them are input errors."""

from __future__ import annotations

import numpy as np
import pipelay as pl
import pytest
from moordyn_case import CASE, drive_tables, pipelay_model
from test_pay_out import SECTION, _hanging, _pulse, _top_tension


def test_a_drive_table_sampled_at_the_steps_reproduces_the_callable_drive() -> None:
    """The driven hanging line, its top given by callables and by a table of the same positions at every step
    time (and the velocity at t = 0): top tension and positions agree to round-off of the step times."""
    dt, t_end, n = 0.1, 6.0, 20
    callable_run = pipelay_model(n).simulation(dt=dt).run(t_end, progress=False)

    table_run = pipelay_model(n, tables=drive_tables(dt, t_end)).simulation(dt=dt).run(t_end, progress=False)

    tension = np.linalg.norm(callable_run.reaction("B")[:, :3], axis=1)
    table_tension = np.linalg.norm(table_run.reaction("B")[:, :3], axis=1)
    assert np.max(np.abs(table_tension - tension)) < 1e-7 * np.mean(tension)
    assert np.max(np.abs(table_run.positions - callable_run.positions)) < 1e-9 * CASE.length


def test_a_position_table_without_velocity_starts_at_its_slope() -> None:
    """Without `velocity`, the node starts with the slope of the table's first segment."""
    model = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 4, SECTION))
    model.pin("A")
    model.drive("B", position=[[0.0, 10.0, 0.0, 0.0], [2.0, 10.0, 1.0, 0.0]])
    first = model.simulation(model.rest(), dt=0.1).run(0.1, progress=False)
    assert np.allclose(first.velocities[0, -1], [0.0, 0.5, 0.0], rtol=0, atol=1e-15)


def test_a_pay_out_speed_table_equals_the_callable_speed() -> None:
    """The pay-out pulse of test_pay_out given as a table at every step time: the same run to round-off."""
    dt, t_end = 0.05, 40.0
    model = _hanging(speed=_pulse)
    reference = model.simulation(model.static(), dt=dt).run(t_end, progress=False)
    # The speed is sampled at the steps' midpoints, where the engine evaluates it.
    times = np.concatenate([[0.0], (np.arange(round(t_end / dt)) + 0.5) * dt, [t_end]])
    table = np.column_stack([times, [_pulse(t) for t in times]])
    model = _hanging(speed=table)
    run = model.simulation(model.static(), dt=dt).run(t_end, progress=False)
    # Nodes not yet paid out are NaN in both.
    assert np.array_equal(np.isnan(run.positions), np.isnan(reference.positions))
    assert np.max(np.abs(_top_tension(run) - _top_tension(reference))) < 1e-6 * np.max(
        _top_tension(reference)
    )
    assert np.nanmax(np.abs(run.positions - reference.positions)) < 1e-9


@pytest.mark.parametrize(
    ("table", "message"),
    [
        (
            [[0.0, 1.0, 2.0]],
            r"position: must be a callable of time t \(s\) or a table of rows \[t, x, y, z\]",
        ),
        ([[0.0, 10, 0, 0]], r"position: .*at least two rows"),
        (
            [[0.0, 10, 0, 0], [0.0, 11, 0, 0]],
            r"position: must increase strictly from row to row, got times 0 then 0 s",
        ),
        ([[0.0, 10, 0, 0], [1.0, np.nan, 0, 0]], r"position: must hold finite numbers, got NaN"),
    ],
)
def test_bad_drive_tables_are_input_errors(table: list[list[float]], message: str) -> None:
    model = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 4, SECTION))
    with pytest.raises(pl.InputError, match=message):
        model.drive("B", position=table)


def test_a_run_past_the_end_of_a_table_stops_with_an_input_error_and_keeps_its_records() -> None:
    model = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 4, SECTION))
    model.pin("A")
    model.drive("B", position=[[0.0, 10.0, 0.0, 0.0], [1.0, 10.0, 0.1, 0.0]])
    sim = model.simulation(model.rest(), dt=0.25)
    message = r"drive position: must lie within the table's times \[0, 1\] s, got t = 1.25"
    with pytest.raises(pl.InputError, match=message) as failure:
        sim.run(2.0, progress=False)
    assert len(failure.value.results) == 5  # t = 0 … 1.0


def test_bad_pay_out_speed_tables_are_input_errors() -> None:
    model = _hanging()
    with pytest.raises(
        pl.InputError, match=r"speed: must increase strictly from row to row, got times 1 then 1 s"
    ):
        model.pay_out("B", speed=[[0.0, 0.1], [1.0, 0.2], [1.0, 0.3]])
    with pytest.raises(pl.InputError, match=r"speed: must be a number \(m/s\), a callable of t or a table"):
        model.pay_out("B", speed=[[0.0, 0.1, 0.2], [1.0, 0.2, 0.3]])
