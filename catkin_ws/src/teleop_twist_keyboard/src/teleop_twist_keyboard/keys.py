"""teleop_twist_keyboard's behaviour without ROS or a terminal: keys -> the twist to publish.

The key layout, the speed factors and the stop rules are those of ros-teleop/teleop_twist_keyboard 1.0.0 (the
Noetic release), teleop_twist_keyboard.py: moveBindings, speedBindings and its main loop.
"""
from __future__ import annotations

from typing import Dict, List, Tuple

USAGE = """
Keyboard teleoperation: each key sets the velocity published on cmd_vel (geometry_msgs/Twist).
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

Sideways too (holonomic bases), with the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)

any other key : stop

q/z : both speeds up/down by 10%
w/x : linear speed only up/down by 10%
e/c : angular speed only up/down by 10%

CTRL-C to quit
"""

# key -> (x, y, z, yaw), each -1, 0 or 1: multiplied by the linear speed (x, y, z) and the turn speed (yaw)
MOVES: Dict[str, Tuple[int, int, int, int]] = {
    "i": (1, 0, 0, 0),
    "o": (1, 0, 0, -1),
    "j": (0, 0, 0, 1),
    "l": (0, 0, 0, -1),
    "u": (1, 0, 0, 1),
    ",": (-1, 0, 0, 0),
    ".": (-1, 0, 0, 1),
    "m": (-1, 0, 0, -1),
    "O": (1, -1, 0, 0),
    "I": (1, 0, 0, 0),
    "J": (0, 1, 0, 0),
    "L": (0, -1, 0, 0),
    "U": (1, 1, 0, 0),
    "<": (-1, 0, 0, 0),
    ">": (-1, -1, 0, 0),
    "M": (-1, 1, 0, 0),
    "t": (0, 0, 1, 0),
    "b": (0, 0, -1, 0),
}
# key -> (factor on the linear speed, factor on the turn speed)
SPEED_STEPS: Dict[str, Tuple[float, float]] = {
    "q": (1.1, 1.1),
    "z": (0.9, 0.9),
    "w": (1.1, 1.0),
    "x": (0.9, 1.0),
    "e": (1.0, 1.1),
    "c": (1.0, 0.9),
}
CTRL_C = "\x03"
STOPPED = (0, 0, 0, 0)
# The usage is shown again with every 15th speed change, so that it stays on screen.
USAGE_EVERY = 15


def speeds_line(speed: float, turn: float) -> str:
    """The line printed after each speed change (upstream's wording, which scripts may read)."""
    return "currently:\tspeed %s\tturn %s " % (speed, turn)


class KeyTeleop:
    """press() per key read ('' when the key timeout passed without one); twist() is then what to publish."""

    def __init__(self, speed: float, turn: float) -> None:
        self.speed = speed
        self.turn = turn
        self.direction = STOPPED
        self.quit = False
        self._speed_changes = 0

    def press(self, key: str) -> Tuple[bool, List[str]]:
        """Apply ``key``: (whether the twist is to be published, the lines to print)."""
        if key in MOVES:
            self.direction = MOVES[key]
            return True, []
        if key in SPEED_STEPS:
            linear_factor, turn_factor = SPEED_STEPS[key]
            self.speed *= linear_factor
            self.turn *= turn_factor
            lines = [speeds_line(self.speed, self.turn)]
            if self._speed_changes == USAGE_EVERY - 1:
                lines.append(USAGE)
            self._speed_changes = (self._speed_changes + 1) % USAGE_EVERY
            return True, lines
        if key == "" and self.direction == STOPPED:
            return False, []  # the key timeout passed and the robot already stands: nothing to say
        self.direction = STOPPED
        self.quit = key == CTRL_C
        return True, []

    def twist(self) -> Tuple[Tuple[float, float, float], float]:
        """((linear x, y, z), angular z)."""
        x, y, z, yaw = self.direction
        return (x * self.speed, y * self.speed, z * self.speed), yaw * self.turn
