"""What the ROS adapters of the gazebo_ros plugins (ros.plugins) share: GazeboRos's tf_prefix and frame resolution,
rate to period, and the odometry covariances the drive plugins report."""
from __future__ import annotations

from typing import Optional, Sequence, Tuple

import rospy

# Diagonal covariances as the Kobuki driver reports them: x, y and yaw measured, the rest unknown.
ODOM_POSE_COVARIANCE = [
    0.1,
    0,
    0,
    0,
    0,
    0,
    0,
    0.1,
    0,
    0,
    0,
    0,
    0,
    0,
    1e6,
    0,
    0,
    0,
    0,
    0,
    0,
    1e6,
    0,
    0,
    0,
    0,
    0,
    0,
    1e6,
    0,
    0,
    0,
    0,
    0,
    0,
    0.05,
]
ODOM_TWIST_COVARIANCE = ODOM_POSE_COVARIANCE
# gazebo_ros_diff_drive's /odom (GazeboRosDiffDrive::publishOdometry, either odometrySource): x, y and yaw
# measured, z, roll and pitch unknown; no twist covariance.
DIFF_DRIVE_POSE_COVARIANCE = tuple(
    {0: 1e-5, 7: 1e-5, 14: 1e12, 21: 1e12, 28: 1e12, 35: 1e-3}.get(index, 0.0) for index in range(36)
)
DIFF_DRIVE_TWIST_COVARIANCE = (0.0,) * 36
# The frame kobuki_gazebo_plugins stamps /joint_states with (resolved with the tf_prefix).
KOBUKI_JOINT_STATES_FRAME = "base_link"
Vec3 = Tuple[float, float, float]


def period(rate: float) -> float:
    """Seconds of sim time between messages at ``rate`` Hz; rate 0 means every step, as in Gazebo."""
    return 1.0 / rate if rate > 0 else 0.0


def rotate_inverse(q: Sequence[float], v: Sequence[float]) -> Vec3:
    """Rotate vector v by the inverse of unit quaternion q (x, y, z, w): world axes to body axes."""
    x, y, z, w = -q[0], -q[1], -q[2], q[3]
    vx, vy, vz = v
    tx, ty, tz = 2 * (y * vz - z * vy), 2 * (z * vx - x * vz), 2 * (x * vy - y * vx)
    return (vx + w * tx + y * tz - z * ty, vy + w * ty + z * tx - x * tz, vz + w * tz + x * ty - y * tx)


def tf_prefix(namespace: str, otherwise: Optional[str] = None) -> str:
    """The tf_prefix gazebo_plugins' GazeboRos (diff drive, Kobuki) gives a plugin in ``namespace``: the
    ``tf_prefix`` parameter searched upwards from the namespace, else the namespace itself without its trailing
    slash. Plugins that call tf::getPrefixParam instead (skid steer) pass ``otherwise=""``."""
    parts = [part for part in namespace.strip("/").split("/") if part]
    for depth in range(len(parts), -1, -1):
        key = "/" + "/".join(parts[:depth] + ["tf_prefix"])
        if rospy.has_param(key):
            return str(rospy.get_param(key))
    return namespace.rstrip("/") if otherwise is None else otherwise


def own_tf_prefix(namespace: str) -> str:
    """The ``tf_prefix`` parameter of ``namespace`` itself (no search upwards), else "": what gazebo_ros_p3d and
    gazebo_ros_bumper read (ros::NodeHandle(robotNamespace).getParam("tf_prefix"))."""
    key = "/" + "/".join([part for part in namespace.strip("/").split("/") if part] + ["tf_prefix"])
    return str(rospy.get_param(key, ""))


def resolve_frame(prefix: str, frame: str) -> str:
    """tf::resolve: a frame with a leading slash as it is (without the slash), else under ``prefix``."""
    if frame.startswith("/"):
        return frame[1:]
    prefix = prefix.lstrip("/")
    return f"{prefix}/{frame}" if prefix else frame
