"""The lay-position search: brackets as sign changes, gaps where statics fails, the bound on solves, the closest
state when there is no answer, targets the lay equipment fixes, and `--target`'s units."""

from __future__ import annotations

import copy
import math
import time
import tomllib
from collections.abc import Callable
from pathlib import Path

import pipelay as pl
import pytest
from pipelay.analysis.lay import (
    MAX_SOLVES,
    TargetNotReached,
    _Probes,
    _refine,
    _search_bracket,
    find_lay_position,
    lay_quantity,
)
from pipelay.cli import _target_value, main
from pipelay.scenario import parse_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
S_LAY = EXAMPLES / "s_lay.toml"
J_LAY = EXAMPLES / "j_lay_dp.toml"


def _search(miss: Callable[[float], float], start: float, limit: int = MAX_SOLVES) -> tuple:
    """`_search_bracket` then `_refine` (to 0.01 m) on a synthetic miss: (bracket, narrowed, positions tried,
    probes)."""
    tried: list[float] = []

    def counted(x: float) -> float:
        tried.append(x)
        return miss(x)

    probes = _Probes(counted, limit)
    bracket = _search_bracket(probes, start, 1.0)
    narrowed = _refine(probes, *bracket, 0.01) if bracket is not None else None
    return bracket, narrowed, tried, probes


def _no_state(x: float) -> float:
    raise pl.ConvergenceError(f"statics failed at x = {x}")


def test_a_sign_change_inside_the_first_step_is_the_bracket() -> None:
    """The issue's miss: 573 kN at x = 657.35 m and 598 kN at 658.35 m for a 583.8 kN target (the old search
    stepped away from it). Start and first step bracket it after two solves, and the Illinois method puts x at
    657.35 + 10.8/25 = 657.782 m within 0.01 m in three more."""
    bracket, narrowed, tried, _ = _search(lambda x: 573.0 + 25.0 * (x - 657.35) - 583.8, 657.35)
    assert bracket == (657.35, 658.35)
    assert tried[:2] == [657.35, 658.35]
    low, high = narrowed
    assert high - low <= 0.01
    assert low - 1e-9 <= 657.35 + 10.8 / 25.0 <= high + 1e-9
    assert len(tried) <= 5


@pytest.mark.parametrize(("root", "most"), [(700.0, 9), (600.0, 10)])
def test_a_monotone_miss_far_away_either_way(root: float, most: int) -> None:
    """From 657.35 m, a root 42.65 m ahead or 57.35 m behind: doubling steps bracket it (the first step tells
    which way) and the whole search takes at most `most` solves."""
    bracket, narrowed, tried, _ = _search(lambda x: 25.0 * (x - root), 657.35)
    assert bracket[0] <= root <= bracket[1]
    assert narrowed[0] - 1e-9 <= root <= narrowed[1] + 1e-9 and narrowed[1] - narrowed[0] <= 0.01
    print(f"root {root}: {len(tried)} solves")
    assert len(tried) <= most


def test_a_quantity_that_turns_back_is_searched_at_its_extremum() -> None:
    """A narrow hump, 0.3 − (x − 640)²/4 (a quantity with a maximum, like the overbend strain's minimum near
    x = 658 m in s_lay.toml): from 660 m the
    doubling steps 645 → 629 jump over both roots (640 ± 1.095 m); the parabola through the last three points
    finds the hump and a root, to 0.01 m, in at most 16 solves. A hump that stays 0.5 below the target is no
    bracket, and the closest position found is its top to 0.5 m after at most 15 solves."""
    bracket, narrowed, tried, _ = _search(lambda x: 0.3 - (x - 640.0) ** 2 / 4.0, 660.0)
    assert bracket is not None
    root = min((640.0 - math.sqrt(1.2), 640.0 + math.sqrt(1.2)), key=lambda r: abs(r - narrowed[0]))
    assert narrowed[0] - 1e-9 <= root <= narrowed[1] + 1e-9 and narrowed[1] - narrowed[0] <= 0.01
    assert len(tried) <= 16
    bracket, _, tried, probes = _search(lambda x: -0.5 - (x - 640.0) ** 2 / 4.0, 660.0)
    assert bracket is None
    assert abs(probes.closest() - 640.0) < 0.5
    assert len(tried) <= 15


def test_failed_solves_are_gaps_the_search_steps_past() -> None:
    """Statics fails for 665 < x < 668 m and the root is at 670.5 m: from 660 m the step into the gap halves,
    and the doubling from the good side steps past it to the root (within 0.01 m, at most 12 solves, at least
    one failed)."""

    def miss(x: float) -> float:
        return _no_state(x) if 665.0 < x < 668.0 else x - 670.5

    _, narrowed, tried, probes = _search(miss, 660.0)
    assert narrowed[0] - 1e-9 <= 670.5 <= narrowed[1] + 1e-9 and narrowed[1] - narrowed[0] <= 0.01
    assert probes.failures and len(tried) <= 12


def test_a_root_inside_a_gap_is_narrowed_to_the_gaps_edge() -> None:
    """Statics fails for 662 < x < 663 m, where the root (662.5 m) lies: the bracket (661, 663) narrows to the
    gap's edge, 662 m within 0.01 m, in at most 20 solves, and stays wider than the tolerance (no answer)."""

    def miss(x: float) -> float:
        return _no_state(x) if 662.0 < x < 663.0 else x - 662.5

    bracket, narrowed, tried, _ = _search(miss, 660.0)
    assert bracket == (661.0, 663.0)
    assert narrowed[1] == 663.0 and 661.99 <= narrowed[0] <= 662.0
    assert len(tried) <= 20


def test_a_wall_of_failures_and_a_miss_that_grows_the_other_way_end_the_search() -> None:
    """Statics fails beyond 663 m and the root is at 680 m behind it; the other way the miss grows: no
    bracket, the closest is 663 m (the last good position before the wall), after at most 10 solves (three
    failed solves in a row, or three steps in a row away from the target, give a direction up)."""

    def miss(x: float) -> float:
        return _no_state(x) if x > 663.0 else x - 680.0

    bracket, _, tried, probes = _search(miss, 660.0)
    assert bracket is None
    assert probes.closest() == 663.0
    assert len(tried) <= 10


def test_the_bound_on_solves_holds() -> None:
    """A miss that never changes sign nor grows: exactly `limit` solves, 40 (MAX_SOLVES) by default or 7."""
    for limit in (MAX_SOLVES, 7):
        bracket, _, tried, _ = _search(lambda x: 1.0, 0.0, limit)
        assert bracket is None and len(tried) == limit


def _s_lay(calls: list[float] | None = None, data: dict | None = None) -> Callable[[float], pl.Model]:
    """The model of s_lay.toml (or of `data`) with the vessel at x; `calls` collects the x of every model
    built."""
    source = data if data is not None else tomllib.loads(S_LAY.read_text())

    def build(x: float) -> pl.Model:
        if calls is not None:
            calls.append(x)
        edited = copy.deepcopy(source)
        edited["vessel"]["eta"][0] = x
        edited["controller"]["reference"][0] += x - source["vessel"]["eta"][0]
        return parse_scenario(edited).model

    return build


def test_s_lay_top_tension_inside_the_first_step() -> None:
    """s_lay.toml: 1068.8 kN at its start x = 660 m, 1151.4 kN at 661 m; 1100 kN is found between them, to
    0.1 %, in at most 6 static solves."""
    found = find_lay_position(_s_lay(), "top_tension", 1.1e6, start=660.0)
    assert 660.0 < found.x < 661.0
    assert found.reached and found.value == pytest.approx(1.1e6, rel=1e-3)
    assert found.solves <= 6


def test_s_lay_departure_angle_jumps_across_the_target() -> None:
    """s_lay.toml's departure angle jumps from 29.40° (lift-off at roller 14) to 27.88° (roller 13) near
    x = 659.18 m: a target of 29° is not reached, and the state returned is the closest, 29.40°, with the
    other side of the jump below 29° within 0.01 m."""
    build = _s_lay()
    found = find_lay_position(build, "departure_angle", math.radians(29.0), start=660.0)
    assert not found.reached
    assert math.degrees(found.value) == pytest.approx(29.40, abs=0.01)
    assert found.x == pytest.approx(659.18, abs=0.01)
    beyond = [
        math.degrees(lay_quantity(build(found.x + dx).static(), "departure_angle")) for dx in (-0.01, 0.01)
    ]
    assert min(beyond) < 29.0 < max(beyond)


@pytest.mark.filterwarnings("ignore::pipelay.PhysicsWarning")  # the positions tried, solved again
def test_a_target_beyond_the_solves_reports_the_closest_state() -> None:
    """50 kN needs the vessel near x = 604 m (13 solves from 660 m); with max_solves = 8 the search stops
    after exactly 8 static solves with TargetNotReached naming the closest position tried, x = 597 m at
    28.4 kN, whose state it carries; no other position tried comes closer."""
    calls: list[float] = []
    build = _s_lay(calls)
    with pytest.raises(TargetNotReached, match=r"x = 597\.000 m with 28391 N \(28\.391 kN\)") as missed:
        find_lay_position(build, "top_tension", 5e4, start=660.0, max_solves=8)
    closest = missed.value.closest
    assert isinstance(missed.value, pl.InputError)
    assert len(calls) - 1 == 8 == closest.solves  # one model for the lay-kind check, at rest
    assert closest.x == 597.0 and not closest.reached
    assert closest.value == pytest.approx(28390.9, abs=0.1)
    assert lay_quantity(closest.state, "top_tension") == closest.value
    for x in set(calls[1:]) - {597.0}:
        assert abs(lay_quantity(_s_lay()(x).static(), "top_tension") - 5e4) > abs(closest.value - 5e4)


def test_j_lay_departure_angle_and_overbend_are_refused_before_any_solve() -> None:
    """On j_lay_dp.toml the tower fixes the departure angle (the issue's 1.45 rad searched for 291 s) and there
    is no overbend: InputErrors naming the reason, from the model at rest, within 2 s, with no static solve."""
    data = tomllib.loads(J_LAY.read_text())
    calls: list[float] = []
    build = _s_lay(calls, data)
    began = time.perf_counter()
    with pytest.raises(pl.InputError, match="departure_angle is fixed by the lay equipment"):
        find_lay_position(build, "departure_angle", 1.45, start=880.0)
    with pytest.raises(pl.InputError, match="overbend_strain has no meaning"):
        find_lay_position(build, "overbend_strain", 0.001, start=880.0)
    assert calls == [880.0, 880.0]
    assert time.perf_counter() - began < 2.0


def test_j_lay_cli_names_target(capsys: pytest.CaptureFixture[str]) -> None:
    """On the command line the J-lay's departure angle exits 2 with a message that starts with --target and
    names the tower."""
    assert main(["static", str(J_LAY), "--target", "departure_angle=83"]) == 2
    err = capsys.readouterr().err
    assert "--target: departure_angle is fixed" in err and "J-lay tower" in err


def test_values_in_radians_out_of_range_are_refused() -> None:
    """The Python API takes radians: 85 (degrees by mistake) is refused at once, with its value in radians."""
    with pytest.raises(pl.InputError, match=r"value: departure_angle = 85.0 is out of range.*1.484 rad"):
        find_lay_position(_s_lay(), "departure_angle", 85.0, start=660.0)
    with pytest.raises(pl.InputError, match=r"\(0, 0.05\]"):
        find_lay_position(_s_lay(), "sagbend_strain", 0.15, start=660.0)
    with pytest.raises(pl.InputError, match="max_solves"):
        find_lay_position(_s_lay(), "top_tension", 1e6, start=660.0, max_solves=1)


def test_cli_target_units() -> None:
    """`--target` reads the unit `pipelay static` prints (degrees, kN, %) or the one written: 62, 62deg, 62°
    and 1.0821041362364843rad are the same radians; 700, 700kN, 0.7MN and 7e5N the same newtons; 0.15 and
    0.15% the same strain."""
    radians = math.radians(62.0)
    for text in ("62", "62deg", "62°", " 62 deg", f"{radians!r}rad"):
        assert _target_value(f"departure_angle={text}") == (
            "departure_angle",
            pytest.approx(radians, rel=1e-15),
        )
    assert _target_value("departure_angle=62")[1] == radians
    for text in ("700", "700kN", "0.7MN", "7e5N"):
        assert _target_value(f"top_tension={text}") == ("top_tension", pytest.approx(7e5, rel=1e-15))
    for text in ("0.15", "0.15%"):
        assert _target_value(f"sagbend_strain={text}") == ("sagbend_strain", pytest.approx(0.0015, rel=1e-15))
    assert _target_value("layback=500m") == ("layback", 500.0)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("departure_angle=95", r"'departure_angle=95' is 95°, out of range; allowed: an angle in \(0, 90\]°"),
        ("departure_angle=0", r"is 0°, out of range"),
        ("departure_angle=-5deg", r"is -5°, out of range"),
        ("departure_angle=2rad", r"is 114.592°, out of range"),
        ("sagbend_strain=7", r"is 7 %, out of range; allowed: a value in \(0, 5\] %"),
        ("top_tension=-3", r"is -3 kN, out of range; allowed: a value > 0 kN"),
        ("departure_angle=62grad", r"'grad' is not a unit of departure_angle; allowed: deg, °, rad"),
        ("top_tension=1e6kg", r"'kg' is not a unit of top_tension"),
        ("top_tension=x", r"must be QUANTITY=VALUE\[UNIT\]"),
        ("tension=1000", r"'tension' is not a lay quantity"),
    ],
)
def test_cli_target_out_of_range_or_unknown_unit(text: str, message: str) -> None:
    """Out of range, an unknown unit or no number: an InputError naming --target, the value and what is
    allowed."""
    with pytest.raises(pl.InputError, match=r"^--target: .*" + message):
        _target_value(text)


def test_cli_target_beyond_reach_prints_the_closest_state(capsys: pytest.CaptureFixture[str]) -> None:
    """`pipelay static s_lay.toml --target top_tension=50 --max-solves 4`: exit 2, the closest state's summary
    on stdout (x = 657 m, the position tried nearest 50 kN) and the error on stderr naming the 4 solves."""
    assert main(["static", str(S_LAY), "--target", "top_tension=50", "--max-solves", "4"]) == 2
    captured = capsys.readouterr()
    assert "the closest state found: vessel x = 657.000 m" in captured.out
    assert "\ntop tension " in captured.out and "lay: lift-off roller" in captured.out
    assert "4 static solves" in captured.err and "no vessel position reaches top_tension" in captured.err
