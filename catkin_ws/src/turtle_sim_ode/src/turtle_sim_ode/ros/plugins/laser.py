"""gazebo_ros_laser's topic (sensors.plugins.laser): sensor_msgs/LaserScan of a ray sensor."""
from __future__ import annotations

from typing import List

import rospy
from sensor_msgs.msg import LaserScan

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.plugin_topics import period, resolve_frame, tf_prefix
from turtle_sim_ode.ros.wire import LaserScanPacker, release
from turtle_sim_ode.sensors.laser import LaserScanner
from turtle_sim_ode.sensors.plugins.laser import LaserConfig


class LaserPublisher(Periodic):
    """sensor_msgs/LaserScan of a ray sensor; rays are cast only when due and someone listens."""

    def __init__(self, scanner: LaserScanner, namespace: str, time_step: float) -> None:
        config = scanner.config
        super().__init__(period(config.update_rate))  # 0: every step, as Gazebo's sensors
        self._scanner = scanner
        self._pub = packed_publisher(plugin_topic(namespace, config.topic), LaserScan)
        # gazebo_ros_laser resolves its frameName with the tf_prefix as GazeboRos does (tf_prefix, else namespace).
        self._packer = LaserScanPacker(
            resolve_frame(tf_prefix(namespace), scanner.frame),
            angle_min=config.min_angle,
            angle_max=config.max_angle,
            angle_increment=config.angle_increment,
            time_increment=0.0,
            scan_time=period(config.update_rate) or time_step,
            range_min=config.range_min,
            range_max=config.range_max,
            beams=config.samples,
        )

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.heard():
            return
        self._pub.publish(self._packer.pack, stamp.secs, stamp.nsecs, self._scanner.scan())

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: LaserConfig) -> List[Periodic]:
    scanner = LaserScanner(context.sim.physics, context.model, config.link, config)
    return [LaserPublisher(scanner, context.namespace, context.sim.physics.time_step)]
