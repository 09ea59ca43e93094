"""hector_gazebo_plugins' IMU topics and services (world.plugins.hector_imu), as GazeboRosIMU has them under its
robotNamespace: ``topicName`` (sensor_msgs/Imu in ``frameId``), ``biasTopicName`` (sensor_msgs/Imu: the orientation
error, rate and acceleration biases), ``serviceName`` (std_srvs/Empty: the rate drift back to 0), and
``topicName``/set_accel_bias, /set_rate_bias (hector_gazebo_plugins/SetBias: that drift), at the update rate; and
the dynamic_reconfigure servers ``topicName``/accel, /rate and /yaw (hector_gazebo_plugins/SensorModelConfig) over
the error models, as GazeboRosIMU::Load sets them up when the topic is not empty."""
from __future__ import annotations

from typing import Any, List

import rospy
from dynamic_reconfigure.server import Server
from hector_gazebo_plugins.srv import SetBias, SetBiasResponse
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty, EmptyResponse

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.plugin_topics import period
from turtle_sim_ode.ros.plugins.hector_reconfigure import close_servers, sensor_model_server
from turtle_sim_ode.ros.wire import ImuPacker, PackedPublisher, release
from turtle_sim_ode.world.plugins.hector_imu import HectorImu, HectorImuConfig, SensorError

NO_COVARIANCE = (0.0,) * 9


def _xyzw(q):  # type: ignore[no-untyped-def]
    return (q[1], q[2], q[3], q[0])


class HectorImuPublisher(Periodic):
    def __init__(self, imu: HectorImu, namespace: str) -> None:
        config = imu.config
        super().__init__(period(config.update_rate))
        self._imu = imu
        frame = config.frame or imu.link
        self._publishers: List[PackedPublisher] = []
        self._pub = self._bias_pub = None
        if config.topic:
            self._pub = packed_publisher(plugin_topic(namespace, config.topic), Imu)
            self._publishers.append(self._pub)
        if config.bias_topic:
            self._bias_pub = packed_publisher(plugin_topic(namespace, config.bias_topic), Imu)
            self._publishers.append(self._bias_pub)
        self._packer = ImuPacker(frame)
        self._services: List[rospy.Service] = []
        if config.service:
            self._services.append(rospy.Service(plugin_topic(namespace, config.service), Empty, self._on_calibrate))
        for name, error in (("set_accel_bias", imu.accel_error), ("set_rate_bias", imu.rate_error)):
            handler = self._set_bias(error)
            self._services.append(rospy.Service(plugin_topic(namespace, config.topic + "/" + name), SetBias, handler))
        self._reconfigure_servers: List[Server] = []
        if config.topic:
            for name, error, scalar in (
                ("accel", imu.accel_error, False),
                ("rate", imu.rate_error, False),
                ("yaw", imu.yaw_error, True),
            ):
                where = rospy.resolve_name(plugin_topic(namespace, config.topic + "/" + name))
                self._reconfigure_servers.append(sensor_model_server(error, where, "hector IMU", scalar))

    def _on_calibrate(self, _request: Any) -> EmptyResponse:
        self._imu.rate_error.reset((0.0, 0.0, 0.0))  # ServiceCallback: "imu is always calibrated in sim"
        return EmptyResponse()

    @staticmethod
    def _set_bias(error: SensorError):  # type: ignore[no-untyped-def]
        def handle(request: Any) -> SetBiasResponse:
            bias = (request.bias.x, request.bias.y, request.bias.z)
            error.reset(bias)
            return SetBiasResponse()

        return handle

    def restart(self, now: float) -> None:
        super().restart(now)
        self._imu.reset()  # a world or time reset: GazeboRosIMU::Reset

    def publish(self, stamp: rospy.Time, now: float) -> None:
        reading = self._imu.update(now)  # every update, even unheard: the drift and differences go on
        secs, nsecs = stamp.secs, stamp.nsecs
        orientation_cov, rate_cov, accel_cov = self._imu.covariances()
        if self._pub is not None:
            self._pub.publish(
                self._packer.pack,
                secs,
                nsecs,
                _xyzw(reading.orientation),
                orientation_cov,
                reading.angular_velocity,
                rate_cov,
                reading.linear_acceleration,
                accel_cov,
            )
        if self._bias_pub is not None:
            self._bias_pub.publish(
                self._packer.pack,
                secs,
                nsecs,
                _xyzw(reading.orientation_error),
                NO_COVARIANCE,
                reading.rate_bias,
                NO_COVARIANCE,
                reading.accel_bias,
                NO_COVARIANCE,
            )

    def close(self) -> None:
        for service in self._services:
            service.shutdown()
        close_servers(self._reconfigure_servers)
        for publisher in self._publishers:
            release(publisher)


def interfaces(context: ModelContext, config: HectorImuConfig) -> List[Periodic]:
    link = context.body_link(config.body, "hector IMU")  # no bodyName: the model's canonical link
    if link is None:
        return []
    imu = HectorImu(context.model, link, config, tuple(context.sim.physics.params.gravity))
    return [HectorImuPublisher(imu, context.namespace)]
