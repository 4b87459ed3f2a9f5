"""The tests' DP vessel in waves: the OSV holding a 12-element pipe that rests on the seabed in 800 m of water,
in a JONSWAP sea (Hs 2 m, Tp 8 s, 40 components, its RAOs moving the top), PD station keeping; Δt = 0.2 s, a
record every 0.4 s, about a second of computing for 60 s. Shared by the fatigue, replay and report tests."""

TEMPLATE = """
title = "{title}"

[pipe]
outer_diameter = 0.6
wall_thickness = 0.03
contents_density = 0.0
drag = [0.0, 1.0]
added_mass = [0.0, 1.0]

[rod]
start = [0.0, 0.0, 0.0]
end = [1200.0, 0.0, 0.0]
elements = 12

[sea]
depth = 800.0

[sea.seabed]
stiffness = 1e5
friction = 0.3

[sea.waves]
kind = "jonswap"
hs = 2.0
tp = 8.0
direction = 0.5
seed = 3
components = 40
ramp = 10.0

[supports.A]
kind = "pin"

[vessel]
end = "B"
model = "osv"
eta = [730.0, 0.0, -800.0, 0.0, 0.0, 0.0]
angle = [0.0, -1.33, 0.0]

[controller]
kp = [0.5e6, 0.5e6, 0, 0, 0, 0]
kd = [0.4e7, 0.4e7, 0, 0, 0, 0]
reference = [730.0, 0.0, 0.0, 0.0, 0.0, 0.0]

[solver]
dt = 0.2
t_end = {t_end}
record_every = 2
"""


def scenario_text(title: str, t_end: float = 60.0) -> str:
    """The scenario as TOML text, with its `title` and `solver.t_end` (s)."""
    return TEMPLATE.format(title=title, t_end=t_end)
