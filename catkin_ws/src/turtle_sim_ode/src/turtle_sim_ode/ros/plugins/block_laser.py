"""gazebo_ros_block_laser's topic (sensors.plugins.block_laser): sensor_msgs/PointCloud with one unnamed channel of
intensities, in frameName under the tf_prefix parameter, at the sensor's rate, only while subscribed. The ranges are
the ray shape's (LaserShape()->GetRange in PutLaserData): without the sensor's <ray><noise>, which Gazebo adds to its
own scan message only."""
from __future__ import annotations

from typing import List

import numpy as np
import rospy
from geometry_msgs.msg import Point32
from sensor_msgs.msg import ChannelFloat32, PointCloud

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import period, resolve_frame
from turtle_sim_ode.ros.wire import heard, release
from turtle_sim_ode.sensors.lidar import MultiBeamLidar
from turtle_sim_ode.sensors.plugins.block_laser import BlockLaserConfig, block_points


class BlockLaserPublisher(Periodic):
    def __init__(self, lidar: MultiBeamLidar, config: BlockLaserConfig, namespace: str) -> None:
        super().__init__(period(config.update_rate))
        self._lidar = lidar
        self._config = config
        self._rng = np.random.default_rng()
        self._pub = publisher(plugin_topic(namespace, config.topic), PointCloud, 1)
        prefix = str(rospy.get_param("tf_prefix")) if rospy.has_param("tf_prefix") else ""
        self._frame = resolve_frame(prefix, config.frame)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not heard(self._pub):
            return
        points, intensities = block_points(self._lidar.ranges(noisy=False), self._config, self._rng.normal)
        message = PointCloud(points=[Point32(*point) for point in points.tolist()])
        message.channels = [ChannelFloat32(values=intensities.tolist())]
        message.header.stamp, message.header.frame_id = stamp, self._frame
        self._pub.publish(message)

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: BlockLaserConfig) -> List[Periodic]:
    lidar = MultiBeamLidar(context.sim.physics, context.model, config)
    return [BlockLaserPublisher(lidar, config, context.namespace)]
