"""The arithmetic of joint_state_publisher_gui's sliders, without Qt or ROS.

As upstream's (ros/joint_state_publisher, noetic-devel, joint_state_publisher_gui/__init__.py): every slider runs
over the integers 0..RANGE, mapped linearly onto the joint's [min, max]; a joint gets a slider when it is one of
joint_state_publisher's free joints and its limits differ. Slider values are ints: PyQt 5.15 refuses a float in
QSlider.setValue, which is what breaks Debian's 1.15.1 (fixed upstream in "enforce int type for slider values").
"""
from __future__ import annotations

import math
from typing import Dict, List, Mapping, Sequence, Tuple

RANGE = 10000


def value_to_slider(value: float, joint: Mapping[str, float]) -> int:
    return int((value - joint["min"]) * float(RANGE) / (joint["max"] - joint["min"]))


def slider_to_value(slider: int, joint: Mapping[str, float]) -> float:
    return joint["min"] + (joint["max"] - joint["min"]) * (slider / float(RANGE))


def slider_joints(joint_list: Sequence[str], free_joints: Mapping[str, Dict]) -> List[str]:
    """The joints that get a slider, in the robot description's order."""
    return [name for name in joint_list if name in free_joints and free_joints[name]["min"] != free_joints[name]["max"]]


def grid_positions(count: int, rows: int) -> List[Tuple[int, int]]:
    """(row, column) of each of ``count`` sliders on ``rows`` rows, filled column by column."""
    if rows == 0:
        return []
    columns = int(math.ceil(float(count) / rows))
    return [(row, column) for column in range(columns) for row in range(rows)][:count]
