"""hector_gazebo_plugins' GPS topics (world.plugins.hector_gps) under its robotNamespace, at its update rate:
``topicName`` (sensor_msgs/NavSatFix, covariance diagonal known) and ``velocityTopicName``
(geometry_msgs/Vector3Stamped), in ``frameId`` as given; the service ``topicName``/set_reference_geopose
(hector_gazebo_plugins/SetReferenceGeoPose) moves the reference; and the dynamic_reconfigure servers that
GazeboRosGps::Load sets up: ``topicName``/position and /velocity (hector_gazebo_plugins/SensorModelConfig) over the
error models, and ``topicName``/status (hector_gazebo_plugins/GNSSConfig) over the fix's status and services."""
from __future__ import annotations

from typing import List

import rospy
from dynamic_reconfigure.server import Server
from geometry_msgs.msg import Vector3Stamped
from hector_gazebo_plugins.cfg import GNSSConfig
from hector_gazebo_plugins.srv import SetReferenceGeoPose, SetReferenceGeoPoseRequest, SetReferenceGeoPoseResponse
from sensor_msgs.msg import NavSatFix

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import period
from turtle_sim_ode.ros.plugins.hector_reconfigure import close_servers, reconfigure_server, sensor_model_server
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.world.plugins.hector_gps import HectorGps, HectorGpsConfig


class HectorGpsPublisher(Periodic):
    def __init__(self, gps: HectorGps, namespace: str) -> None:
        config = gps.config
        super().__init__(period(config.update_rate))
        self._gps = gps
        fix_topic = plugin_topic(namespace, config.fix_topic)
        self._fix_pub = publisher(fix_topic, NavSatFix, 10)
        self._velocity_pub = publisher(plugin_topic(namespace, config.velocity_topic), Vector3Stamped, 10)
        self._fix = NavSatFix(position_covariance_type=NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN)
        self._velocity = Vector3Stamped()
        self._fix.header.frame_id = self._velocity.header.frame_id = config.frame
        # Last: the service and servers are not among the handles released if a later topic is refused.
        self._set_reference = rospy.Service(
            fix_topic + "/set_reference_geopose", SetReferenceGeoPose, self._on_reference
        )
        where = rospy.resolve_name(fix_topic)
        self._reconfigure_servers: List[Server] = [
            sensor_model_server(gps.position_error, where + "/position", "hector GPS"),
            sensor_model_server(gps.velocity_error, where + "/velocity", "hector GPS"),
            reconfigure_server(
                GNSSConfig,
                where + "/status",
                gps.reconfigure_status,
                lambda: gps.reconfigure_status({}, 0),
                "hector GPS",
            ),
        ]

    def _on_reference(self, request: SetReferenceGeoPoseRequest) -> SetReferenceGeoPoseResponse:
        """The response is empty, as upstream's: a refused pose is a service error the caller sees."""
        position, orientation = request.geo_pose.position, request.geo_pose.orientation
        try:
            self._gps.set_reference(
                position.latitude,
                position.longitude,
                position.altitude,
                (orientation.x, orientation.y, orientation.z, orientation.w),
            )
        except ValueError as error:
            rospy.logwarn("%s/set_reference_geopose refused: %s", self._gps.config.fix_topic, error)
            raise rospy.ServiceException(str(error)) from None
        return SetReferenceGeoPoseResponse()

    def restart(self, now: float) -> None:
        super().restart(now)
        self._gps.reset()

    def publish(self, stamp: rospy.Time, now: float) -> None:
        fix = self._gps.update(now)  # every update, even unheard: the drift goes on
        message, velocity = self._fix, self._velocity
        message.header.stamp = velocity.header.stamp = stamp
        message.latitude, message.longitude, message.altitude = fix.latitude, fix.longitude, fix.altitude
        message.position_covariance = list(fix.position_covariance)
        message.status.status, message.status.service = fix.status, fix.service
        velocity.vector.x, velocity.vector.y, velocity.vector.z = fix.velocity
        self._fix_pub.publish(message)
        self._velocity_pub.publish(velocity)

    def close(self) -> None:
        release(self._fix_pub)
        release(self._velocity_pub)
        self._set_reference.shutdown()
        close_servers(self._reconfigure_servers)


def interfaces(context: ModelContext, config: HectorGpsConfig) -> List[Periodic]:
    link = context.body_link(config.body, "hector GPS")
    if link is None:
        return []
    gps = HectorGps(context.model, link, config, context.sim.spherical_coordinates)
    return [HectorGpsPublisher(gps, context.namespace)]
