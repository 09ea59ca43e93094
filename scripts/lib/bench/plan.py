"""What the benchmark's sections share (scripts/bench_sim.py): the robot and its circle, the sizes of a full and a
quick run, and the error that marks a section as not measured."""
from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Tuple

from ros_run.processes import ToolError

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
PACKAGE = os.path.join(REPO, "catkin_ws", "src", "turtle_sim_ode")
URDF_PATH = os.path.join(PACKAGE, "urdf", "turtlebot.urdf")
MODEL = "mobile_base"
CIRCLE = (0.5, 0.5)  # v (m/s), w (rad/s): a circle of radius v / w
STARTUP_TIMEOUT_S = 60.0
CALLER_ID = "/bench_sim"  # towards the master, when not a node


@dataclass(frozen=True)
class Plan:
    """Sizes and durations of one run."""

    physics_steps: int  # per timed repeat
    physics_repeats: int  # the best repeat counts
    circle_seconds: float  # sim seconds driven for the circle fit
    robot_counts: Tuple[int, ...]
    time_steps: Tuple[float, ...]
    warmup_s: float  # wall seconds before a window
    window_s: float  # wall seconds measured, full node unthrottled
    real_time_window_s: float
    launch_runs: int


FULL = Plan(2000, 10, 20.0, (1, 5, 10), (0.001, 0.01), 3.0, 10.0, 30.0, 3)
QUICK = Plan(1000, 5, 10.0, (1, 2), (0.001, 0.01), 1.0, 3.0, 5.0, 1)


class BenchError(ToolError):
    """A measurement could not be made (the message says why)."""
