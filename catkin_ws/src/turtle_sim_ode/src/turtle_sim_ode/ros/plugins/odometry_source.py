"""smb_gazebo OdometrySource's topic and tf (world.plugins.odometry_source): nav_msgs/Odometry on ``topicName`` in
the robot namespace, from ``odomFrame`` to ``childOdomFrame`` (both as written, no tf_prefix), and the same
transform on /tf where ``publishTf`` (and the node's publish_tf) asks; stamped with the step's sim time."""
from __future__ import annotations

from typing import List, Optional

import rospy
from nav_msgs.msg import Odometry

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.wire import OdometryPacker, PackedPublisher, TransformPacker, release
from turtle_sim_ode.world.plugins.odometry_source import LinkState, OdometrySource, OdometrySourceConfig

# The diagonal of a 6x6 covariance, row-major (nav_msgs/Odometry)
DIAGONAL = (0, 7, 14, 21, 28, 35)


class OdometrySourcePublisher(Periodic):
    def __init__(self, context: ModelContext, link: str, config: OdometrySourceConfig) -> None:
        super().__init__(0.0)  # every step: the plugin keeps its own settle checks and rate (OdometrySource)
        self._model = context.model
        self._link = link
        self._source = OdometrySource(config)
        self._topic = plugin_topic(context.namespace, config.topic)
        self._pub = packed_publisher(self._topic, Odometry)
        variance = config.gaussian_noise**2
        covariance = tuple(variance if index in DIAGONAL else 0.0 for index in range(36))
        self._packer = OdometryPacker(config.odom_frame, config.child_frame, covariance, covariance)
        publish_tf = config.publish_tf and context.settings.publish_tf
        self._tf: Optional[PackedPublisher] = context.tf_broadcaster if publish_tf else None
        self._tf_packer = TransformPacker(config.odom_frame, config.child_frame)

    def _state(self) -> LinkState:
        position, orientation = self._model.link_transform(self._link)
        linear, angular = self._model.link_twist(self._link)
        return position, orientation, linear, angular

    def publish(self, stamp: rospy.Time, now: float) -> None:
        settled = self._source.odom_frame is not None
        reading = self._source.update(now, self._state)
        if not settled and self._source.odom_frame is not None:
            origin = self._source.odom_frame[0]
            rospy.loginfo("%s: odometry frame set where the link came to rest %s", self._topic, origin)
        if reading is None:
            return
        w, x, y, z = reading.orientation
        secs, nsecs = stamp.secs, stamp.nsecs
        if self._pub.heard():  # lock-free: asked at every reading
            self._pub.publish(
                self._packer.pack, secs, nsecs, reading.position, (x, y, z, w), reading.linear, reading.angular
            )
        if self._tf is not None:
            self._tf.publish(self._tf_packer.pack, secs, nsecs, reading.position, (x, y, z, w))

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: OdometrySourceConfig) -> List[Periodic]:
    if not config.topic:
        # OdometrySource::UpdateChild publishes nothing, tf included, with an empty topicName
        rospy.logwarn("model %s: %s has an empty <topicName>: nothing published", context.name, "odometry_source")
        return []
    link = context.body_link(config.body, "odometry_source")
    if link is None:
        return []
    return [OdometrySourcePublisher(context, link, config)]
