"""What happens when things go wrong: sizes too large for the machine, numbers out of range, user callables that
raise, states that blow up, and two simulations in two threads."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import numpy as np
import pipelay as pl
import pytest

NAN, INF = float("nan"), float("inf")
SECTION = pl.Section.pipe(0.3, 0.02)


def test_a_rod_too_large_for_the_machine_is_an_input_error_not_an_abort() -> None:
    """10⁹ elements used to abort the interpreter (a failed 24 GB allocation); now the size is checked first and
    the error names the argument, the value and the memory it would take."""
    with pytest.raises(
        pl.InputError, match=r"elements: would need .* GB for the rod's reference.*got 1000000000"
    ):
        pl.Rod.straight((0, 0, 0), (1, 0, 0), 10**9, SECTION)
    with pytest.raises(
        pl.InputError, match=r"rod: would need .* for solving it.*got a rod of 4000000 elements"
    ):
        pl.Model(pl.Rod.straight((0, 0, 0), (1, 0, 0), 4 * 10**6, SECTION))


def test_a_run_whose_records_would_not_fit_is_refused_before_it_starts() -> None:
    model = pl.Model(pl.Rod.straight((0, 0, 0), (10, 0, 0), 10, SECTION))
    model.clamp("A")
    simulation = model.simulation(model.static(), dt=0.1)
    with pytest.raises(pl.InputError, match=r"t_end: would need .* for 10000000001 records of 11 nodes"):
        simulation.run(1e9, progress=False)
    assert simulation.time == 0.0


CONSTRUCTORS: list[tuple[str, Callable[[], object]]] = [
    ("kp", lambda: pl.PID(kp=[NAN] * 6, kd=[0] * 6, reference=[0] * 6)),
    ("kd", lambda: pl.PID(kp=[1] * 6, kd=[INF] * 6, reference=[0] * 6)),
    ("ki", lambda: pl.PID(kp=[1] * 6, kd=[1] * 6, ki=[NAN] * 6, reference=[0] * 6)),
    ("kp", lambda: pl.PID(kp=[-1] * 6, kd=[1] * 6, reference=[0] * 6)),
    ("kd", lambda: pl.PID(kp=[1] * 6, kd=np.triu(np.ones((6, 6))), reference=[0] * 6)),
    ("reference", lambda: pl.PID(kp=[1] * 6, kd=[1] * 6, reference=[NAN] * 6)),
    ("start", lambda: pl.PID(kp=[1] * 6, kd=[1] * 6, reference=[0] * 6, start=NAN)),
    ("integral_limit", lambda: pl.PID(kp=[1] * 6, kd=[1] * 6, reference=[0] * 6, integral_limit=[NAN] * 6)),
    ("thrust_limit", lambda: pl.PID(kp=[1] * 6, kd=[1] * 6, reference=[0] * 6, thrust_limit=[-1] * 3)),
    ("value", lambda: pl.Force([NAN] * 6)),
    ("start", lambda: pl.Force([0] * 6, start=NAN)),
    ("start", lambda: pl.Route([NAN, 0])),
    ("speed", lambda: pl.Route([0, 0], speed=INF)),
    ("target", lambda: pl.TensionControl(NAN, 1e-7)),
    ("gain", lambda: pl.TensionControl(1e6, -1.0)),
    ("filter", lambda: pl.TensionControl(1e6, 1e-7, filter=NAN)),
    ("rate_limit", lambda: pl.TensionControl(1e6, 1e-7, rate_limit=NAN)),
    ("EA", lambda: pl.Section(NAN, 1, 1, 1, 1)),
    ("mass", lambda: pl.Section(1, 1, 1, 1, -1)),
    ("drag", lambda: pl.Section(1, 1, 1, 1, 1, drag=[NAN, 0])),
    ("density", lambda: pl.Section.pipe(0.3, 0.02, density=NAN)),
    ("velocity", lambda: pl.Current.uniform([NAN, 0, 0])),
    ("depth", lambda: pl.Sea(NAN)),
    ("stiffness", lambda: pl.Seabed(stiffness=NAN)),
    ("friction", lambda: pl.Seabed(friction=NAN)),
    ("z", lambda: pl.Bathymetry.flat(NAN)),
    ("stinger radius", lambda: pl.Stinger(NAN, 10, 3)),
    ("rollers", lambda: pl.Stinger(100, 10, 10**12)),
    ("tensioner", lambda: pl.SLay([NAN, 0, 0])),
    ("roller_stiffness", lambda: pl.SLay([0, 0, 0], roller_stiffness=NAN)),
    ("angle", lambda: pl.JLay([0, 0, 0], angle=NAN)),
    ("M", lambda: pl.Vessel(np.full((6, 6), NAN), np.eye(6), np.eye(6))),
    ("nodes", lambda: pl.Rod([[0, 0, 0], [NAN, 0, 0]], SECTION)),
]


@pytest.mark.parametrize(("argument", "build"), CONSTRUCTORS)
def test_every_number_is_checked(argument: str, build: Callable[[], object]) -> None:
    """NaN, infinite, negative or non-symmetric values are refused by name (the PID accepted NaN gains)."""
    with pytest.raises(pl.InputError) as caught:
        build()
    assert str(caught.value).startswith(f"{argument}:"), str(caught.value)


def _swinging_pipe() -> pl.Model:
    """A 20 m pipe hanging from a driven end B in water."""
    model = pl.Model(pl.Rod.straight((0, 0, 20), (0, 0, 0), 10, SECTION), sea=pl.Sea(100.0))
    return model


def test_a_callable_that_raises_stops_the_run_chained_to_the_users_exception() -> None:
    """The drive's own ValueError is the error's __cause__; the message names the callable and the time; the
    records before are kept on the error."""

    class SensorFault(ValueError):
        pass

    def position(t: float) -> list[float]:
        if t >= 1.0:
            raise SensorFault(f"no position fix at {t:.2f} s")
        return [0.1 * t, 0.0, 0.0]

    model = _swinging_pipe()
    model.drive("B", position=position)
    # The step from 1.0 s to 1.1 s asks for the position at its end.
    message = r"drive position: position\(1\.09+\d*\) raised SensorFault: no position fix at 1\.10 s"
    with pytest.raises(pl.InputError, match=message) as caught:
        model.simulation(model.static(), dt=0.1).run(3.0, progress=False)
    assert isinstance(caught.value.__cause__, SensorFault)
    assert str(caught.value.__cause__) == "no position fix at 1.10 s"
    assert caught.value.results.time[-1] == pytest.approx(1.0)


def test_a_state_that_blows_up_stops_the_run_with_a_convergence_error() -> None:
    """A point load that jumps to 1e250 N at t = 0.5 s drives the state to infinity: the step fails with a
    ConvergenceError naming the time, and the records before are kept, all finite."""
    model = _swinging_pipe()
    model.clamp("B")
    model.point_load("A", force=[1.0, 0.0, 0.0], scale=lambda t: 1e250 if t >= 0.5 else 0.0)
    with pytest.raises(pl.ConvergenceError, match=r"time step failed.*t = 0\.5") as caught:
        model.simulation(model.static(), dt=0.1).run(2.0, progress=False)
    kept = caught.value.results
    assert kept.time[-1] == pytest.approx(0.5)
    assert np.isfinite(kept.positions).all()


def test_two_simulations_in_two_threads_run_at_once_and_agree() -> None:
    """The engine releases the GIL while stepping: while two runs go on in two threads, the main thread's Python
    keeps running (its longest pause is a small part of the runs' time, where holding the GIL would stop it for
    a whole run), and the runs give, bit for bit, what they give one after the other. (The engine's own
    threads share the cores between the runs, so their wall time is not the measure.)"""

    def heavy() -> pl.Simulation:
        """A 400 m pipe clamped at B, let go from its straight inclined reference: no Python in the loop."""
        model = pl.Model(pl.Rod.straight((300, 0, 300), (0, 0, 0), 400, SECTION), sea=pl.Sea(500.0))
        model.clamp("B")
        return model.simulation(model.rest(), dt=0.05)

    alone = [heavy().run(8.0, progress=False) for _ in range(2)]
    results: dict[int, pl.Results] = {}

    def work(index: int) -> None:
        results[index] = heavy().run(8.0, progress=False)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    start = time.perf_counter()
    for thread in threads:
        thread.start()
    longest_pause, last = 0.0, time.perf_counter()
    while any(thread.is_alive() for thread in threads):
        now = time.perf_counter()
        longest_pause, last = max(longest_pause, now - last), now
    wall = time.perf_counter() - start
    for thread in threads:
        thread.join()
    print(
        f"two runs at once in two threads {wall:.2f} s; the main thread's longest pause {longest_pause:.3f} s"
    )
    for index in range(2):
        assert np.array_equal(results[index].positions, alone[index].positions)
    assert longest_pause < 0.2 * wall
