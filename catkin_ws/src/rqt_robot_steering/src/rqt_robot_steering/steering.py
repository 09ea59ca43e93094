"""rqt_robot_steering's rules without Qt or ROS (ros-visualization/rqt_robot_steering 0.5.12, robot_steering.py):
the sliders hold thousandths of m/s and rad/s; keys and buttons move them by a single step (10) or a page step
(100); the twist is sent on every change and every 100 ms while it is not zero, and a zero twist only once, "so
other devices can take control".
"""
from __future__ import annotations

from typing import Dict, Optional, Tuple

SLIDER_FACTOR = 1000.0  # slider units per m/s or rad/s
SINGLE_STEP = 10
PAGE_STEP = 100
PUBLISH_PERIOD_MS = 100
# The spin boxes' initial limits (m/s, rad/s) and their bounds, from upstream's RobotSteering.ui.
LINEAR_LIMITS = (-1.0, 1.0)
ANGULAR_LIMITS = (-3.0, 3.0)
LIMIT_BOUND = 10.0
LIMIT_STEP = 0.1
DEFAULT_TOPIC = "/cmd_vel"

# Shortcut key -> (slider, steps): "linear" or "angular", +1/-1 steps, or 0 to reset. With Shift, the step is a
# page step; Space (with or without Shift) stops both.
SHORTCUTS: Dict[str, Tuple[str, int]] = {
    "W": ("linear", 1),
    "X": ("linear", 0),
    "S": ("linear", -1),
    "A": ("angular", 1),
    "Z": ("angular", 0),
    "D": ("angular", -1),
}


def slider_units(speed: float) -> int:
    """A speed limit in slider units (an int: QSlider takes no float)."""
    return int(round(speed * SLIDER_FACTOR))


def stepped(value: int, steps: int, strong: bool) -> int:
    """The slider value after a shortcut: ``steps`` single (or page, ``strong``) steps, or 0 for steps == 0."""
    return value + steps * (PAGE_STEP if strong else SINGLE_STEP) if steps else 0


class TwistGate:
    """Decides which twists go out: every non-zero one, and a zero one only once after something else."""

    def __init__(self) -> None:
        self.zero_sent = False

    def next_twist(self, linear_units: int, angular_units: int) -> Optional[Tuple[float, float]]:
        """(linear.x, angular.z) to publish for the sliders' values, or None."""
        twist = (linear_units / SLIDER_FACTOR, angular_units / SLIDER_FACTOR)
        if twist == (0.0, 0.0):
            if self.zero_sent:
                return None
            self.zero_sent = True
            return twist
        self.zero_sent = False
        return twist

    def resend_zero(self) -> None:
        """Stop pressed with the sliders already at zero: the next zero goes out again."""
        self.zero_sent = False
