"""gazebo_ros_range's topic (sensors.plugins.range_finder): sensor_msgs/Range of the nearest ray, in frameName under the
tf_prefix parameter, only while subscribed, at the sensor's rate (no faster than the plugin's updateRate)."""
from __future__ import annotations

import random
from typing import List

import rospy
from sensor_msgs.msg import Range

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import period, resolve_frame
from turtle_sim_ode.ros.wire import heard, release
from turtle_sim_ode.sensors.lidar import MultiBeamLidar
from turtle_sim_ode.sensors.plugins.range_finder import RangeConfig, nearest


class RangePublisher(Periodic):
    def __init__(self, lidar: MultiBeamLidar, config: RangeConfig, namespace: str) -> None:
        super().__init__(max(period(config.update_rate), period(config.plugin_rate)))
        self._lidar = lidar
        self._config = config
        self._rng = random.Random()
        self._pub = publisher(plugin_topic(namespace, config.topic), Range, 1)
        prefix = str(rospy.get_param("tf_prefix")) if rospy.has_param("tf_prefix") else ""
        message = Range(radiation_type=config.radiation, field_of_view=config.field_of_view)
        message.min_range, message.max_range = config.range_min, config.range_max
        message.header.frame_id = resolve_frame(prefix, config.frame)
        self._message = message

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not heard(self._pub):
            return
        config = self._config
        self._message.range = nearest(self._lidar.ranges(), config.range_max, config.gaussian_noise, self._rng.gauss)
        self._message.header.stamp = stamp
        self._pub.publish(self._message)

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: RangeConfig) -> List[Periodic]:
    lidar = MultiBeamLidar(context.sim.physics, context.model, config)
    return [RangePublisher(lidar, config, context.namespace)]
