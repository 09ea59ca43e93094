"""Values of an SDF ``<sensor>`` element (URDF ``<gazebo><sensor>`` blocks are the same), with the one number reader
and a message naming the sensor and the tag."""
from __future__ import annotations

import math
from typing import Optional, Sequence, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, child_text, read_number
from turtle_sim_ode.physics import sanity


def number_at(element: Optional[Element], path: str, default: float, what: str) -> float:
    return read_number(child_text(element, path), f"{what} <{path}>", default)


def rate_at(element: Optional[Element], tags: Sequence[str], default: float, what: str) -> float:
    for tag in tags:
        if child_text(element, tag) is not None:
            value = number_at(element, tag, default, what)
            if value < 0:
                raise ModelError(f"{what} <{tag}> must be >= 0, got {value}")
            return value
    return default


def sensor_pose(sensor: Element, what: str) -> Tuple[float, float, float, float, float, float]:
    pose_text = child_text(sensor, "pose")
    if pose_text is None:
        return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    try:
        pose = tuple(float(v) for v in pose_text.split())
    except ValueError:
        pose = ()
    if len(pose) != 6 or not all(math.isfinite(v) for v in pose):
        raise ModelError(f"{what} <pose> must be 6 finite numbers, got '{pose_text}'")
    for value in pose:  # within the world's lengths, not subnormal (physics.sanity)
        sanity.number(value, f"{what} <pose>", -sanity.MAX_LENGTH, sanity.MAX_LENGTH, ModelError)
    return pose  # type: ignore[return-value]


def int_at(element: Optional[Element], path: str, default: int, what: str) -> int:
    text = child_text(element, path)
    try:
        value = default if text is None else int(text)
    except ValueError:
        raise ModelError(f"{what} <{path}> must be an integer, got '{text}'") from None
    if not 1 <= value <= 8192:
        raise ModelError(f"{what} <{path}> must be in 1..8192, got {value}")
    return value
