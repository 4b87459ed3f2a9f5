"""`pl.PhysicsWarning`: a solution that solved but whose physics is suspect says where and how much.

Strain beyond the steel's yield (the rod is linear elastic), the pipe in compression at the hold point, the
vessel heeled beyond 10°; a sound solution warns of nothing.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pipelay as pl
import pytest
from pipelay.analysis import suspect
from pipelay.scenario import load_scenario

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def physics_warnings(call: object) -> tuple[object, list[str]]:
    """What `call()` returns, and the messages of the PhysicsWarnings it raised."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        value = call()  # type: ignore[operator]
    return value, [str(w.message) for w in caught if issubclass(w.category, pl.PhysicsWarning)]


def overstretched(grade: str | None = None) -> pl.Model:
    """100 m of steel pipe pinned with its ends 400 m apart: 300 % strain."""
    section = pl.Section.pipe(0.3, 0.02, grade=grade)
    model = pl.Model(pl.Rod.straight((0, 0, 0), (100, 0, 0), 20, section), sea=pl.Sea(200.0))
    model.pin("A")
    model.pin("B", position=(400.0, 0.0, 0.0))
    return model


def test_a_pipe_pinned_far_beyond_its_length_warns_of_its_strain() -> None:
    state, messages = physics_warnings(lambda: overstretched().static())
    assert len(messages) == 1
    strain = float(np.abs(state.strain).max())  # type: ignore[attr-defined]
    assert strain == pytest.approx(3.0, rel=1e-6)
    message = messages[0]
    assert f"strain {100 * strain:.3g} %" in message and "linear elastic" in message
    # X65 by default: SMYS 450 MPa over E = 207 GPa.
    assert f"yield strain {100 * 450e6 / 207e9:.3g} % of X65" in message
    element = int(re.search(r"in element (\d+)", message).group(1))  # type: ignore[union-attr]
    assert abs(state.strain[element]) == pytest.approx(strain, rel=1e-12)  # type: ignore[attr-defined]
    # The section's own grade sets the limit.
    _, x80 = physics_warnings(lambda: overstretched("X80").static())
    assert f"{100 * 555e6 / 207e9:.3g} % of X80" in x80[0]


def test_a_run_warns_of_what_its_records_show() -> None:
    model = overstretched()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pl.PhysicsWarning)
        state = model.static()
    _, messages = physics_warnings(lambda: model.simulation(state, dt=0.1).run(1.0, progress=False))
    assert len(messages) == 1 and "at t = 1 s" in messages[0] and "yield strain" in messages[0]


def test_compression_at_the_hold_point_is_named_with_its_tension() -> None:
    """The paper's scenario file clamps the pipe at the vessel's CO horizontally, and its EI = 1e11 N·m² is
    1e11 / (207e9 π 0.6⁴/64) = 76 times a solid steel bar's of its 0.6 m diameter: the pipe is pushed there,
    and the warning says what makes it so."""
    scenario = load_scenario(EXAMPLES / "jensen2009.toml")
    state, messages = physics_warnings(lambda: scenario.model.static())
    top = state.lay_summary()["top_tension"]  # type: ignore[attr-defined]
    assert top < 0
    bar = 207e9 * math.pi * 0.6**4 / 64.0
    assert len(messages) == 1
    assert messages[0].startswith(
        f"the pipe is in compression at the hold point: top tension {top / 1e3:.4g} kN; "
    )
    assert f"EI = 1e+11 N·m² is {1e11 / bar:.0f} times a solid steel bar's" in messages[0]


def test_a_heeled_vessel_is_named_with_its_angle() -> None:
    section = pl.Section.pipe(0.3, 0.02)
    sound = SimpleNamespace(
        lay_summary=lambda: {"top_tension": 1e5},
        strain=np.array([1e-4, 2e-4]),
        reference_arc_length=np.array([0.0, 10.0, 20.0]),
        section=section,
        eta=np.array([0.0, 0.0, 0.0, math.radians(9.9), 0.0, 0.0]),
    )
    assert suspect.suspect_state(sound) == []
    messages = lambda state: [message for _, _, message in suspect.suspect_state(state)]
    heeled = SimpleNamespace(**{**vars(sound), "eta": np.array([0.0, 0, 0, math.radians(-12.5), 0.0, 0.0])})
    assert messages(heeled) == [
        "the vessel heels (roll) 12.5°, beyond 10° (its hydrostatics are linear in small angles)"
    ]
    assert suspect.suspect_state(heeled)[0][:2] == ("heel", pytest.approx(math.radians(12.5)))
    trimmed = SimpleNamespace(**{**vars(sound), "eta": np.array([0.0, 0, 0, 0.0, math.radians(11.0), 0.0])})
    assert "trims (pitch) 11.0°" in messages(trimmed)[0]


def test_a_sound_lay_warns_of_nothing() -> None:
    scenario = load_scenario(EXAMPLES / "s_lay.toml")
    _, messages = physics_warnings(lambda: scenario.model.static())
    assert messages == []
    section = pl.Section.pipe(0.6, 0.015, contents_density=1025.0)
    model = pl.Model(pl.Rod.straight((0, 0, 0), (1200, 0, 0), 50, section), sea=pl.Sea(800.0))
    model.pin("A")
    model.pin("B", position=(850.0, 0.0, -800.0))
    _, messages = physics_warnings(lambda: model.static())
    assert messages == []


def test_pipelay_static_prints_the_warning(capsys: pytest.CaptureFixture[str]) -> None:
    from pipelay.cli import main

    assert main(["static", str(EXAMPLES / "jensen2009.toml")]) == 0
    err = capsys.readouterr().err
    assert re.search(
        r"^warning: the pipe is in compression at the hold point: top tension -\S+ kN; its bending stiffness",
        err,
        re.MULTILINE,
    )


def test_the_command_line_keeps_the_worst_of_each_kind(capsys: pytest.CaptureFixture[str]) -> None:
    """A run warns once per kind, with its worst: the statics' and the run's strains give one line."""
    with suspect.worst_of_each_kind() as worst:
        model = overstretched()
        model.simulation(model.static(), dt=0.1).run(0.5, progress=False)
    assert list(worst) == ["strain"]
    assert worst["strain"].size == pytest.approx(3.0, rel=1e-3)
