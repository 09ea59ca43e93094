"""gazebo_ros_p3d's topic (world.plugins.p3d): a link's true pose and velocity as nav_msgs/Odometry."""
from __future__ import annotations

from typing import List

import rospy
from nav_msgs.msg import Odometry

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import quat_from_rpy, quat_multiply
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, topic_prefix
from turtle_sim_ode.ros.plugin_topics import Vec3, own_tf_prefix, period, resolve_frame, rotate_inverse
from turtle_sim_ode.ros.wire import OdometryPacker, release
from turtle_sim_ode.world.plugins import GroundTruthConfig
from turtle_sim_ode.world.plugins.p3d import noisy


class GroundTruthPublisher(Periodic):
    """A link's true pose and velocity as nav_msgs/Odometry, published only while subscribed.

    p3d (`twist_in_body` false) gives the twist in the world frame as gazebo_ros_p3d does; the simulator's own
    ground truth gives it in the body frame, as nav_msgs/Odometry asks."""

    def __init__(
        self,
        model: BuiltModel,
        link: str,
        topic: str,
        frame: str,
        rate: float,
        twist_in_body: bool,
        noise: float = 0.0,
        xyz_offset: Vec3 = (0.0, 0.0, 0.0),
        rpy_offset: Vec3 = (0.0, 0.0, 0.0),
    ) -> None:
        super().__init__(period(rate))
        self._model = model
        self._link = link
        self._twist_in_body = twist_in_body
        self._noise = noise
        self._offset = xyz_offset
        w, x, y, z = quat_from_rpy(*rpy_offset)
        self._rotation_offset = (w, x, y, z)
        self._pub = packed_publisher(topic, Odometry)
        self._packer = OdometryPacker(frame, link)

    @classmethod
    def from_p3d(
        cls, model: BuiltModel, link: str, config: GroundTruthConfig, namespace: str, default_rate: float
    ) -> "GroundTruthPublisher":
        return cls(
            model,
            link,
            topic_prefix(namespace) + config.topic,
            # gazebo_ros_p3d.cpp, Load: the frame (not the body) through tf::resolve with the namespace's tf_prefix
            resolve_frame(own_tf_prefix(namespace), config.frame),
            config.update_rate,  # 0: every step, as gazebo_ros_p3d
            False,
            config.gaussian_noise,
            config.xyz_offset,
            config.rpy_offset,
        )

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.heard():
            return
        (px, py, pz), (w, x, y, z) = self._model.link_transform(self._link)
        linear, angular = self._model.link_twist(self._link)
        ow, ox, oy, oz = quat_multiply(self._rotation_offset, (w, x, y, z))
        position = noisy((px + self._offset[0], py + self._offset[1], pz + self._offset[2]), self._noise)
        if self._twist_in_body:
            linear, angular = rotate_inverse((x, y, z, w), linear), rotate_inverse((x, y, z, w), angular)
        linear = noisy(linear, self._noise)
        angular = noisy(angular, self._noise)
        self._pub.publish(self._packer.pack, stamp.secs, stamp.nsecs, position, (ox, oy, oz, ow), linear, angular)

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: GroundTruthConfig) -> List[Periodic]:
    link = context.body_link(config.body, "p3d")
    if link is None:
        return []
    return [
        GroundTruthPublisher.from_p3d(context.model, link, config, context.namespace, context.settings.publish_rate)
    ]
