"""hector_gazebo_plugins' GPS topics (world.plugins.hector_gps) under its robotNamespace, at its update rate:
``topicName`` (sensor_msgs/NavSatFix, covariance diagonal known) and ``velocityTopicName``
(geometry_msgs/Vector3Stamped), in ``frameId`` as given. Not offered: the set_reference_geopose service
(geographic_msgs) and the dynamic_reconfigure servers."""
from __future__ import annotations

from typing import List

import rospy
from geometry_msgs.msg import Vector3Stamped
from sensor_msgs.msg import NavSatFix

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import period
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.world.plugins.hector_gps import HectorGps, HectorGpsConfig


class HectorGpsPublisher(Periodic):
    def __init__(self, gps: HectorGps, namespace: str) -> None:
        config = gps.config
        super().__init__(period(config.update_rate))
        self._gps = gps
        namespace = namespace or config.robot_namespace
        self._fix_pub = publisher(plugin_topic(namespace, config.fix_topic), NavSatFix, 10)
        self._velocity_pub = publisher(plugin_topic(namespace, config.velocity_topic), Vector3Stamped, 10)
        self._fix = NavSatFix(position_covariance_type=NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN)
        self._fix.status.status, self._fix.status.service = config.status, config.service
        self._velocity = Vector3Stamped()
        self._fix.header.frame_id = self._velocity.header.frame_id = config.frame

    def restart(self, now: float) -> None:
        super().restart(now)
        self._gps.reset()

    def publish(self, stamp: rospy.Time, now: float) -> None:
        fix = self._gps.update(now)  # every update, even unheard: the drift goes on
        message, velocity = self._fix, self._velocity
        message.header.stamp = velocity.header.stamp = stamp
        message.latitude, message.longitude, message.altitude = fix.latitude, fix.longitude, fix.altitude
        message.position_covariance = list(fix.position_covariance)
        velocity.vector.x, velocity.vector.y, velocity.vector.z = fix.velocity
        self._fix_pub.publish(message)
        self._velocity_pub.publish(velocity)

    def close(self) -> None:
        release(self._fix_pub)
        release(self._velocity_pub)


def interfaces(context: ModelContext, config: HectorGpsConfig) -> List[Periodic]:
    model = context.model
    link = config.body or model.root_link
    if link not in model.links:
        rospy.logwarn("model %s: hector GPS bodyName [%s] is not a link: not published", context.name, link)
        return []
    gps = HectorGps(model, link, config, context.sim.spherical_coordinates)
    return [HectorGpsPublisher(gps, context.namespace)]
