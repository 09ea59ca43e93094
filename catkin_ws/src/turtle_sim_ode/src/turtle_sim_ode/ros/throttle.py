"""Warnings repeated at most once a period of wall time. rospy's logwarn_throttle measures ROS time, which is sim
time here: a simulator running 50 times faster than real time repeated them 50 times as often."""
from __future__ import annotations

import time
from typing import Dict

import rospy

_last_warned: Dict[str, float] = {}


def logwarn_every(period: float, key: str, message: str) -> None:
    """``message`` as a warning, unless the warning ``key`` was given less than ``period`` wall seconds ago."""
    now = time.monotonic()
    last = _last_warned.get(key)
    if last is None or now - last >= period:
        _last_warned[key] = now
        rospy.logwarn(message)
