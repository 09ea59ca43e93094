"""Where the viewer first looks from: a Gazebo user camera pose (the world's <gui><camera><pose>, else Gazebo's
default) as rviz's orbit view, without ROS."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

Vec3 = Tuple[float, float, float]

# gazebo-classic's user camera starts at (5, -5, 2), pitch 0.275643, yaw 2.35619 (gui/MainWindow_TEST.cc checks it),
# where a world's <gui><camera><pose> does not say.
DEFAULT_USER_CAMERA = (5.0, -5.0, 2.0, 0.0, 0.275643, 2.35619)
MIN_FOCUS_DISTANCE = 1.0
MAX_ORBIT_PITCH = math.pi / 2 - 0.001  # rviz's orbit view stops just short of straight down


@dataclass(frozen=True)
class OrbitView:
    """rviz's orbit view: the camera at ``distance`` from ``focal_point``, seen from the focal point in direction
    ``yaw`` (about z, from x) and ``pitch`` (up from the ground plane)."""

    focal_point: Vec3
    distance: float
    yaw: float
    pitch: float


def orbit_view(pose: Tuple[float, float, float, float, float, float]) -> OrbitView:
    """The orbit view that shows what a Gazebo camera at ``pose`` (x y z roll pitch yaw; it looks along its x and
    its z is up on the screen) shows: focused on the point of its line of sight nearest the world's origin (at
    least MIN_FOCUS_DISTANCE ahead), with the screen's up the camera's (a top-down camera keeps its heading)."""
    x, y, z, _, pitch, yaw = pose
    # The camera's x (line of sight) and z (screen up), roll aside.
    forward = (math.cos(pitch) * math.cos(yaw), math.cos(pitch) * math.sin(yaw), -math.sin(pitch))
    up = (math.sin(pitch) * math.cos(yaw), math.sin(pitch) * math.sin(yaw), math.cos(pitch))
    distance = max(-(x * forward[0] + y * forward[1] + z * forward[2]), MIN_FOCUS_DISTANCE)
    focal = (x + distance * forward[0], y + distance * forward[1], z + distance * forward[2])
    # Seen from the focal point the camera lies back along the line of sight; near vertical its heading is the
    # horizontal part of its up vector, which rviz's orbit shows upwards on the screen when behind the camera.
    level = math.hypot(forward[0], forward[1])
    if forward[2] < 0 and level < math.hypot(up[0], up[1]):
        orbit_yaw = math.atan2(-up[1], -up[0])
    else:
        orbit_yaw = math.atan2(-forward[1], -forward[0])
    orbit_pitch = min(math.asin(max(-1.0, min(1.0, -forward[2]))), MAX_ORBIT_PITCH)
    return OrbitView(focal, distance, orbit_yaw, orbit_pitch)
