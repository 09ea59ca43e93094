"""The IMU plugins' topic (gazebo_ros_imu, gazebo_ros_imu_sensor; the Kobuki's gyro): sensor_msgs/Imu of a link."""
from __future__ import annotations

from typing import List, Optional

import rospy
from sensor_msgs.msg import Imu

from turtle_sim_ode.models.builder import BuiltModel
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.plugin_topics import Vec3, period
from turtle_sim_ode.ros.wire import ImuPacker, release
from turtle_sim_ode.sensors.imu import ImuSensor
from turtle_sim_ode.sensors.plugins.imu import ImuConfig


class ImuPublisher(Periodic):
    """sensor_msgs/Imu of a link: the Kobuki's gyro, or an IMU plugin's (libgazebo_ros_imu*.so)."""

    def __init__(self, sensor: ImuSensor, topic: str, frame: str, rate: float) -> None:
        super().__init__(period(rate))  # rate 0: every step, as gazebo_plugins has it
        self._sensor = sensor
        self._pub = packed_publisher(topic, Imu)
        self._packer = ImuPacker(frame)

    def restart(self, now: float) -> None:
        super().restart(now)
        self._sensor.reset()  # a world or time reset is a jump the acceleration must not see

    def publish(self, stamp: rospy.Time, now: float) -> None:
        reading = self._sensor.read(now)  # every time, even unheard: acceleration differences need each reading
        self._pub.publish(
            self._packer.pack,
            stamp.secs,
            stamp.nsecs,
            reading.orientation,
            reading.orientation_covariance,
            reading.angular_velocity,
            reading.angular_velocity_covariance,
            reading.linear_acceleration,
            reading.linear_acceleration_covariance,
        )

    def close(self) -> None:
        release(self._pub)


def imu_publisher(model: BuiltModel, config: ImuConfig, gravity: Vec3, namespace: str) -> Optional[Periodic]:
    if config.link not in model.links:
        rospy.logwarn("model %s: IMU link [%s] does not exist: not published", model.name, config.link)
        return None
    topic = plugin_topic(namespace, config.topic)
    sensor = ImuSensor(model, config.link, gravity, config.noise)
    return ImuPublisher(sensor, topic, config.frame or config.link, config.update_rate)


def interfaces(context: ModelContext, config: ImuConfig) -> List[Periodic]:
    publisher = imu_publisher(context.model, config, tuple(context.sim.physics.params.gravity), context.namespace)
    return [publisher] if publisher is not None else []
