"""turtlebot_teleop_key's behaviour without ROS or a terminal: keys -> a smoothed (linear.x, angular.z).

The key map, the speed steps, the ramps and the usage text are those of turtlebot/turtlebot's
turtlebot_teleop/scripts/turtlebot_teleop_key (melodic), so that the keyboard works as the TurtleBot tutorials say.
"""
from __future__ import annotations

from typing import List, Tuple

USAGE = """
Control Your Turtlebot!
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%
space key, k : force stop
anything else : stop smoothly

CTRL-C to quit
"""

# key -> (sign of linear, sign of angular)
MOVES = {
    "i": (1, 0),
    "o": (1, -1),
    "j": (0, 1),
    "l": (0, -1),
    "u": (1, 1),
    ",": (-1, 0),
    ".": (-1, 1),
    "m": (-1, -1),
}
# key -> (factor on the linear speed, factor on the angular speed)
SPEED_STEPS = {
    "q": (1.1, 1.1),
    "z": (0.9, 0.9),
    "w": (1.1, 1.0),
    "x": (0.9, 1.0),
    "e": (1.0, 1.1),
    "c": (1.0, 0.9),
}
FORCE_STOP = (" ", "k")
CTRL_C = "\x03"
# Per loop (one key read, at most 0.1 s): how far the published speeds move toward the target.
LINEAR_STEP = 0.02
ANGULAR_STEP = 0.1
# Loops without a known key before the target drops to zero ("anything else: stop smoothly").
IDLE_LOOPS = 4
# The usage text is shown again after this many speed changes, so it stays on screen.
USAGE_EVERY = 15


def speeds_line(speed: float, turn: float) -> str:
    return "currently:\tspeed %s\tturn %s " % (speed, turn)


def ramp(current: float, target: float, step: float) -> float:
    """One step of at most `step` from current toward target."""
    if target > current:
        return min(target, current + step)
    if target < current:
        return max(target, current - step)
    return target


class KeyboardTeleop:
    """One call of step() per loop of the node: the key read in that loop ('' for none) -> the twist to publish."""

    def __init__(self, speed: float = 0.2, turn: float = 1.0) -> None:
        self.speed = speed
        self.turn = turn
        self.quit = False
        self._direction = (0, 0)
        self._idle = 0
        self._speed_changes = 0
        self.linear = 0.0
        self.angular = 0.0

    def step(self, key: str) -> List[str]:
        """Apply `key`; return the lines to print. After it, (linear, angular) is the twist to publish, unless
        quit is set (Ctrl-C): then the node publishes a zero twist and ends."""
        lines: List[str] = []
        if key in MOVES:
            self._direction = MOVES[key]
            self._idle = 0
        elif key in SPEED_STEPS:
            linear_factor, angular_factor = SPEED_STEPS[key]
            self.speed *= linear_factor
            self.turn *= angular_factor
            self._idle = 0
            lines.append(speeds_line(self.speed, self.turn))
            if self._speed_changes == USAGE_EVERY - 1:
                lines.append(USAGE)
            self._speed_changes = (self._speed_changes + 1) % USAGE_EVERY
        elif key in FORCE_STOP:
            self._direction = (0, 0)
            self.linear = self.angular = 0.0
        else:
            self._idle += 1
            if self._idle > IDLE_LOOPS:
                self._direction = (0, 0)
            if key == CTRL_C:
                self.quit = True
                return lines
        self.linear = ramp(self.linear, self.speed * self._direction[0], LINEAR_STEP)
        self.angular = ramp(self.angular, self.turn * self._direction[1], ANGULAR_STEP)
        return lines

    def twist(self) -> Tuple[float, float]:
        return self.linear, self.angular
