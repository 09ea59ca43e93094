"""geometry_msgs and std_msgs values to and from plain tuples."""
from __future__ import annotations

from typing import Sequence, Tuple

from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from std_msgs.msg import ColorRGBA

Vec3 = Tuple[float, float, float]


def xyz(vector) -> Vec3:
    return (vector.x, vector.y, vector.z)


def quaternion_of(pose: Pose) -> Tuple[float, float, float, float]:
    q = pose.orientation
    return (q.x, q.y, q.z, q.w)


def pose_msg(position: Sequence[float], quaternion: Sequence[float]) -> Pose:
    return Pose(Point(*position), Quaternion(*quaternion))


def rgba(colour: ColorRGBA) -> Tuple[float, float, float, float]:
    return (colour.r, colour.g, colour.b, colour.a)


def twist_msg(linear: Sequence[float], angular: Sequence[float]) -> Twist:
    return Twist(Vector3(*linear), Vector3(*angular))
