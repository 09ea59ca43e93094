"""gazebo-classic's RubblePlugin (``libRubblePlugin.so``, plugins/RubblePlugin.cc), a world plugin: on load it
strews <count> pieces named rubble_0, rubble_1, ... Each piece (RubblePlugin::Load) is, at even odds, a 2x4 board
(length uniform in 0.6096..2.4384 m, 0.1016 m wide, 0.0508 m thick; MakeBox) or a cinder block (0.2032 x 0.2032 x
0.4064 m; MakeCinderBlock), with a mass uniform in <min_mass>..<max_mass>, its position uniform per axis between
<bottom_right> and <top_left> and raised so that its unrotated bottom is not below bottom_right's z, turned by roll
uniform in 0..3.1415, pitch in -0.1..0.1, yaw in 0..3.1415; the inertia is upstream's: ixx = m (h^2 + w^2) / 12,
iyy = m (h^2 + d^2) / 12, izz = m (w^2 + d^2) / 12 for the size (w, d, h). Upstream's <velocity_decay> 0.01 of each
piece is not simulated. <min_size> and <max_size> only sized upstream's cylinders, which it no longer makes."""
from __future__ import annotations

import random
from typing import List, Optional, Tuple

from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.text import ModelError, read_number
from turtle_sim_ode.models.description import GazeboPlugin, RobotModel

RUBBLE = "libRubblePlugin.so"
BOARD_LENGTH = (0.6096, 2.4384)  # m: 2 to 8 feet
BOARD_SECTION = (0.1016, 0.0508)  # m: 4 x 2 inches
CINDER_BLOCK = (0.2032, 0.2032, 0.4064)  # m: a standard US cinder block
MAX_COUNT = 1000  # pieces one plugin may make: far beyond a rubble field's use, and the spawn stays quick

Six = Tuple[float, float, float, float, float, float]


def _vector(plugin: GazeboPlugin, tag: str) -> Tuple[float, float, float]:
    given = plugin.params.get(tag, "0 0 0").split()
    if len(given) != 3:
        raise ModelError(f"{RUBBLE} <{tag}>: expected 3 numbers, got {' '.join(given)!r}")
    x, y, z = (read_number(value, f"{RUBBLE} <{tag}>") for value in given)
    return x, y, z


def _piece_sdf(name: str, size: Tuple[float, float, float], mass: float) -> str:
    w, d, h = size
    inertia = "<ixx>%r</ixx><iyy>%r</iyy><izz>%r</izz>" % (
        mass * (h * h + w * w) / 12,
        mass * (h * h + d * d) / 12,
        mass * (w * w + d * d) / 12,
    )
    box = "<geometry><box><size>%r %r %r</size></box></geometry>" % size
    return (
        f'<sdf version="1.5"><model name="{name}"><link name="link">'
        f"<inertial><mass>{mass!r}</mass><inertia>{inertia}</inertia></inertial>"
        f'<collision name="collision">{box}</collision><visual name="visual">{box}</visual>'
        f"</link></model></sdf>"
    )


def rubble(plugin: GazeboPlugin, rng: Optional[random.Random] = None) -> List[Tuple[str, RobotModel, Six]]:
    """(name, model, pose) of each piece the plugin makes; ModelError naming a bad tag."""
    rng = rng or random.Random()
    low, high = _vector(plugin, "bottom_right"), _vector(plugin, "top_left")
    min_mass = read_number(plugin.params.get("min_mass"), f"{RUBBLE} <min_mass>", 0.0)
    max_mass = read_number(plugin.params.get("max_mass"), f"{RUBBLE} <max_mass>", 0.0)
    if not 0 < min_mass <= max_mass:
        raise ModelError(f"{RUBBLE}: masses must be 0 < <min_mass> <= <max_mass>, got {min_mass} and {max_mass}")
    count = read_number(plugin.params.get("count"), f"{RUBBLE} <count>", 0.0, 0.0)
    if count != int(count) or count > MAX_COUNT:
        raise ModelError(f"{RUBBLE} <count>: expected a whole number up to {MAX_COUNT}, got {count}")
    pieces = []
    for index in range(int(count)):
        board = rng.randint(0, 1) == 0
        mass = rng.uniform(min_mass, max_mass)
        x, y, z = (rng.uniform(a, b) for a, b in zip(low, high))
        roll, pitch, yaw = rng.uniform(0.0, 3.1415), rng.uniform(-0.1, 0.1), rng.uniform(0.0, 3.1415)
        size = (rng.uniform(*BOARD_LENGTH),) + BOARD_SECTION if board else CINDER_BLOCK
        z = max(z, low[2] + size[2] / 2)
        name = f"rubble_{index}"
        pieces.append((name, parse_sdf_model(_piece_sdf(name, size, mass)), (x, y, z, roll, pitch, yaw)))
    return pieces
