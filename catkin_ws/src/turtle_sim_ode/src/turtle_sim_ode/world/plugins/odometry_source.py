"""ETH's smb_gazebo OdometrySource (``libodometry_source_plugin.so``, ETHZ-RobotX/smb_common): a link's pose and
twist from the physics state relative to an odometry frame fixed where the link came to rest, as nav_msgs/Odometry
and optionally tf. The course package's plugin library builds empty over the gazebo stand-in; this module does its
work: the tags as its Load reads them and the per-step state of its UpdateChild."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Mapping, Optional, Tuple

from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.models.transforms import (
    Quat,
    Vec3,
    quat_from_rpy,
    quat_multiply,
    quat_normalised,
    quat_rotate,
    rpy_of,
)
from turtle_sim_ode.world.kinematics import conjugate
from turtle_sim_ode.world.plugins.p3d import noisy
from turtle_sim_ode.world.plugins.tags import flag, number, text, triple

ODOMETRY_SOURCE = "libodometry_source_plugin.so"
MODEL_PLUGINS = (ODOMETRY_SOURCE,)
# Sim time between two checks whether the link has come to rest (OdometrySource::UpdateChild: dt > 1.0)
SETTLE_CHECK_PERIOD = 1.0
REQUIRED_TAGS = ("bodyName", "odomFrame", "childOdomFrame", "topicName")


@dataclass
class OdometrySourceConfig:
    """libodometry_source_plugin.so's tags (OdometrySource::Load; defaults from OdometrySource.hpp)."""

    body: str
    topic: str
    odom_frame: str
    child_frame: str
    publish_tf: bool = False
    xyz_offset: Vec3 = (0.0, 0.0, 0.0)
    rpy_offset: Vec3 = (0.0, 0.0, 0.0)
    gaussian_noise: float = 0.0
    update_rate: float = 0.0
    max_linear_speed_before_settle: float = 1e-3
    max_angular_speed_before_settle: float = 1e-2
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> OdometrySourceConfig:
    # Upstream's Load gives up (ROS_FATAL, the plugin does nothing) without these; here the model is refused, naming
    # the tag, as for p3d's bodyName.
    missing = [tag for tag in REQUIRED_TAGS if tag not in plugin.params]
    if missing:
        raise ModelError(f"model '{model_name}': {plugin.filename} needs <{'>, <'.join(missing)}>")
    return OdometrySourceConfig(
        body=text(plugin, "bodyName", ""),
        topic=(plugin.params.get("topicName") or "").strip(),
        odom_frame=text(plugin, "odomFrame", ""),
        child_frame=text(plugin, "childOdomFrame", ""),
        publish_tf=flag(plugin, "publishTf", False),
        xyz_offset=triple(plugin, "xyzOffset"),
        rpy_offset=triple(plugin, "rpyOffset"),
        gaussian_noise=number(plugin, "gaussianNoise", 0.0),
        update_rate=number(plugin, "updateRate", 0.0),
        max_linear_speed_before_settle=number(plugin, "maxLinearSpeedBeforeSettle", 1e-3),
        max_angular_speed_before_settle=number(plugin, "maxAngularSpeedBeforeSettle", 1e-2),
        robot_namespace=robot_namespace_tag(plugin.params),
    )


# A link's world state: position, orientation (w, x, y, z), linear and angular velocity in world axes
LinkState = Tuple[Vec3, Quat, Vec3, Vec3]


@dataclass
class OdometryReading:
    """One message: the pose in the odometry frame (orientation w, x, y, z), the twist, and the variance that
    upstream puts on the diagonals of both covariances (gaussianNoise squared)."""

    position: Vec3
    orientation: Quat
    linear: Vec3
    angular: Vec3
    variance: float


class OdometrySource:
    """OdometrySource::UpdateChild, called every step with the sim time: first it waits for the link to rest (a
    check each second of sim time; once both speeds are under the thresholds, the odometry frame is the link's
    position and heading then), then it gives a reading at ``updateRate`` (0: every step)."""

    def __init__(self, config: OdometrySourceConfig) -> None:
        self.config = config
        self.odom_frame: Optional[Tuple[Vec3, Quat]] = None  # position, heading-only rotation; None: not settled
        self._last: Optional[float] = None
        self._offset_rotation = quat_from_rpy(*config.rpy_offset)

    def update(self, now: float, read_state: Callable[[], LinkState]) -> Optional[OdometryReading]:
        if self._last is None:
            self._last = now  # Load: last_time_ is the sim time the plugin starts at
        if self.odom_frame is None:
            self._settle(now, read_state)
            return None
        if now < self._last:
            self._last = now  # "Negative update time difference detected"
        elapsed = self._since_last(now)
        rate = self.config.update_rate
        if (rate > 0 and elapsed < 1.0 / rate) or elapsed == 0:
            return None
        self._last = now
        return self._reading(read_state())

    def _since_last(self, now: float) -> float:
        """Sim time since the last check or reading, in whole nanoseconds as Gazebo's common::Time counts it."""
        assert self._last is not None
        return round(now - self._last, 9)

    def _settle(self, now: float, read_state: Callable[[], LinkState]) -> None:
        if self._since_last(now) <= SETTLE_CHECK_PERIOD:
            return
        position, orientation, linear, angular = read_state()
        # Upstream compares both speeds with maxAngularSpeedBeforeSettle (maxLinearSpeedBeforeSettle is only logged)
        limit = self.config.max_angular_speed_before_settle
        if math.hypot(*linear) < limit and math.hypot(*angular) < limit:
            self.odom_frame = (position, quat_from_rpy(0.0, 0.0, rpy_of(orientation)[2]))
        else:
            self._last = now  # checked again a second later; last_time_ stays put once settled

    def _reading(self, state: LinkState) -> OdometryReading:
        assert self.odom_frame is not None
        origin, heading = self.odom_frame
        position, orientation, linear, angular = state
        back = conjugate(heading)
        relative = quat_rotate(back, (position[0] - origin[0], position[1] - origin[1], position[2] - origin[2]))
        rotation = quat_multiply(back, orientation)
        # Upstream turns the world velocities by the frame's heading (RotateVector, not its inverse), then into the
        # link's axes relative to the frame: the body-axes twist when the frame's heading is 0, turned by twice
        # that heading otherwise.
        to_link = conjugate(rotation)
        linear = quat_rotate(to_link, quat_rotate(heading, linear))
        angular = quat_rotate(to_link, quat_rotate(heading, angular))
        offset = self.config.xyz_offset
        sigma = self.config.gaussian_noise
        return OdometryReading(
            position=(relative[0] + offset[0], relative[1] + offset[1], relative[2] + offset[2]),
            orientation=quat_normalised(quat_multiply(self._offset_rotation, rotation)),
            linear=noisy(linear, sigma),
            angular=noisy(angular, sigma),
            variance=sigma * sigma,
        )
