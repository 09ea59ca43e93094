"""The IMU plugins' topic (gazebo_ros_imu, gazebo_ros_imu_sensor; the Kobuki's gyro): sensor_msgs/Imu of a link."""
from __future__ import annotations

from typing import Dict, List, Tuple

import rospy
from sensor_msgs.msg import Imu

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.plugin_topics import period
from turtle_sim_ode.ros.wire import ImuPacker, PackedPublisher, release
from turtle_sim_ode.sensors.imu import ImuReading, ImuSensor
from turtle_sim_ode.sensors.plugins.imu import ImuConfig


def publish_reading(pub: PackedPublisher, packer: ImuPacker, stamp: rospy.Time, reading: ImuReading) -> None:
    pub.publish(
        packer.pack,
        stamp.secs,
        stamp.nsecs,
        reading.orientation,
        reading.orientation_covariance,
        reading.angular_velocity,
        reading.angular_velocity_covariance,
        reading.linear_acceleration,
        reading.linear_acceleration_covariance,
    )


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
        publish_reading(self._pub, self._packer, stamp, reading)

    def close(self) -> None:
        release(self._pub)


class ImuGroup(Periodic):
    """Every IMU plugin of a model on one link at one rate (Gazebo's are separate sensors that read alike but for
    their noise): the link is read once per due time and that exact reading shared; only the IMUs someone listens to
    add their own noise and are packed. 300 IMUs on a link cost about what one does, not 300 times as much."""

    def __init__(self, sensors: List[ImuSensor], topics: List[str], frames: List[str], rate: float) -> None:
        super().__init__(period(rate))  # rate 0: every step, as gazebo_plugins has it
        self._exact = ImuSensor(sensors[0].model, sensors[0].link, sensors[0].gravity)
        self._sensors = sensors
        self._pubs = [packed_publisher(topic, Imu) for topic in topics]
        self._packers = [ImuPacker(frame) for frame in frames]
        self._heard: List[int] = []  # the IMUs someone listens to, found again when subscribers come or go
        self._subscribers_changed = True
        for pub in self._pubs:
            pub.on_subscribers_changed(self._on_subscribers_changed)

    def _on_subscribers_changed(self) -> None:
        self._subscribers_changed = True

    def restart(self, now: float) -> None:
        super().restart(now)
        self._exact.reset()  # a world or time reset is a jump the acceleration must not see

    def publish(self, stamp: rospy.Time, now: float) -> None:
        exact = self._exact.exact(now)  # every time, even unheard: acceleration differences need each reading
        if self._subscribers_changed:
            self._subscribers_changed = False
            self._heard = [index for index, pub in enumerate(self._pubs) if pub.heard()]
        for index in self._heard:
            publish_reading(self._pubs[index], self._packers[index], stamp, self._sensors[index].with_noise(exact))

    def close(self) -> None:
        for pub in self._pubs:
            release(pub)


def grouped_interfaces(contexts: List[ModelContext], configs: List[ImuConfig]) -> List[Periodic]:
    """One ImuGroup per link and rate for a model's IMU plugins (``contexts[i]`` is ``configs[i]``'s)."""
    groups: Dict[Tuple[str, float], List[Tuple[ModelContext, ImuConfig]]] = {}
    for context, config in zip(contexts, configs):
        model = context.model
        if config.link not in model.links:
            rospy.logwarn("model %s: IMU link [%s] does not exist: not published", model.name, config.link)
            continue
        groups.setdefault((config.link, config.update_rate), []).append((context, config))
    interfaces: List[Periodic] = []
    for (link, rate), members in groups.items():
        gravity = tuple(members[0][0].sim.physics.params.gravity)
        sensors = [ImuSensor(context.model, link, gravity, config.noise) for context, config in members]
        topics = [plugin_topic(context.namespace, config.topic) for context, config in members]
        interfaces.append(ImuGroup(sensors, topics, [config.frame or link for _, config in members], rate))
    return interfaces
