"""velodyne_simulator's topic (sensors.plugins.velodyne): sensor_msgs/PointCloud2 of a multi-beam ray sensor as
GazeboRosVelodyneLaser::OnScan (velodyne_gazebo_plugins 1.0.12) builds it: fields x, y, z, intensity (float32 at 0,
4, 8, 12), ring (uint16 at 16), time (float32 at 18, always 0), point_step 22; points azimuth by azimuth, ring by
ring within each; only ranges within (max(min_range, <range><min>), min(max_range, <range><max>)), with
gaussianNoise added. Not organised (the default): the points in band only, height 1, is_dense. organize_cloud:
width = rings, height = azimuths, NaN points out of band, not dense. Rays are cast only while someone subscribes
(ConnectCb), at the sensor's <update_rate>; each cloud is made and published on the lidar's thread
(sensors.plugins.velodyne's VelodyneScans), stamped with the sim time of the step whose world it shows."""
from __future__ import annotations

from typing import List, Tuple

import numpy as np
import rospy
from sensor_msgs.msg import PointCloud2, PointField

from turtle_sim_ode.ros.camera_topics import packer
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.plugin_topics import period, resolve_frame
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.sensors.lidar import MultiBeamLidar
from turtle_sim_ode.sensors.plugins.velodyne import POINT_STEP, VelodyneConfig, VelodyneScans
from turtle_sim_ode.sensors.scan_thread import cpus_beside_stepping

POINT_FIELDS = [
    PointField("x", 0, PointField.FLOAT32, 1),
    PointField("y", 4, PointField.FLOAT32, 1),
    PointField("z", 8, PointField.FLOAT32, 1),
    PointField("intensity", 12, PointField.FLOAT32, 1),
    PointField("ring", 16, PointField.UINT16, 1),
    PointField("time", 18, PointField.FLOAT32, 1),
]


def velodyne_frame(config: VelodyneConfig, namespace: str) -> str:
    """Load's frame: frameName under the robot namespace (when not "/"), else under the tf_prefix parameter."""
    prefix = namespace
    if not prefix.strip("/"):
        prefix = str(rospy.get_param("tf_prefix", "")) if rospy.has_param("tf_prefix") else ""
    return resolve_frame(prefix.rstrip("/"), config.frame)


class VelodynePublisher(Periodic):
    def __init__(self, lidar: MultiBeamLidar, namespace: str, rng: np.random.Generator) -> None:
        config = lidar.config
        super().__init__(period(config.update_rate))  # 0: every step, as Gazebo's sensors
        self._pub = packed_publisher(plugin_topic(namespace, config.topic), PointCloud2)
        self._message = PointCloud2(fields=POINT_FIELDS, point_step=POINT_STEP)  # filled on the lidar's thread only
        self._message.header.frame_id = velodyne_frame(config, namespace)
        self._pack = packer(self._message)
        self._scans = VelodyneScans(lidar, rng, self._publish_cloud)
        self.scans = 0  # scans cast: none while no one subscribes

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.heard():
            return
        self._scans.scan((stamp.secs, stamp.nsecs))
        self.scans += 1

    def _publish_cloud(self, cloud: np.ndarray, height: int, width: int, dense: bool, stamp: Tuple[int, int]) -> None:
        message = self._message
        message.height, message.width, message.row_step = height, width, POINT_STEP * width
        self._pub.publish(self._pack, *stamp, cloud, dense)

    def close(self) -> None:
        try:
            self._scans.close()
        finally:
            release(self._pub)


def interfaces(context: ModelContext, config: VelodyneConfig) -> List[Periodic]:
    lidar = MultiBeamLidar(context.sim.physics, context.model, config, threads=cpus_beside_stepping())
    return [VelodynePublisher(lidar, context.namespace, np.random.default_rng())]
