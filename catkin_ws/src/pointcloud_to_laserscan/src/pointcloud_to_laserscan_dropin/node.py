"""The ROS interface of pointcloud_to_laserscan_node: ``cloud_in`` (sensor_msgs/PointCloud2) in, ``scan``
(sensor_msgs/LaserScan) out, subscribed to the cloud only while someone listens to the scan (connectCb), the cloud
brought into ``~target_frame`` through tf2 when it is set and differs from the cloud's frame."""
from __future__ import annotations

import multiprocessing
import sys
import threading
from typing import Any, Dict, Optional

import numpy as np
import rospy
import tf2_ros
from sensor_msgs.msg import LaserScan, PointCloud2, PointField

from pointcloud_to_laserscan_dropin.scan import ParamError, ScanParams, cloud_xyz, project


def rotation_matrix(x: float, y: float, z: float, w: float) -> np.ndarray:
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


class PointCloudToLaserScan(rospy.SubscribeListener):
    def __init__(self, params: ScanParams) -> None:
        super().__init__()
        self.params = params
        queue = params.concurrency_level or multiprocessing.cpu_count()  # 0: one a core, as upstream
        self._queue_size = queue
        self._lock = threading.Lock()
        self._sub: Optional[rospy.Subscriber] = None
        self._tf: Optional[tf2_ros.Buffer] = None
        if params.target_frame:
            self._tf = tf2_ros.Buffer()
            self._listener = tf2_ros.TransformListener(self._tf)
        self._pub = rospy.Publisher("scan", LaserScan, queue_size=10, subscriber_listener=self)

    # connectCb / disconnectCb
    def peer_subscribe(self, topic_name: str, topic_publish: Any, peer_publish: Any) -> None:
        with self._lock:
            if self._sub is None:
                rospy.loginfo("Got a subscriber to scan, starting subscriber to pointcloud")
                self._sub = rospy.Subscriber("cloud_in", PointCloud2, self._on_cloud, queue_size=self._queue_size)

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        with self._lock:
            if num_peers == 0 and self._sub is not None:
                rospy.loginfo("No subscibers to scan, shutting down subscriber to pointcloud")
                self._sub.unregister()
                self._sub = None

    def _on_cloud(self, cloud: PointCloud2) -> None:
        params = self.params
        offsets: Dict[str, int] = {
            f.name: f.offset for f in cloud.fields if f.datatype == PointField.FLOAT32 and f.name in "xyz"
        }
        count = cloud.width * cloud.height
        if len(offsets) < 3 or cloud.point_step <= 0 or len(cloud.data) < count * cloud.point_step:
            rospy.logwarn_throttle(
                1.0, "cloud_in: a cloud without float32 x, y, z or with too little data (%d points): ignored" % count
            )
            return
        xyz = cloud_xyz(cloud.data, cloud.point_step, count, offsets, cloud.is_bigendian)
        frame = params.target_frame or cloud.header.frame_id
        rotation = translation = None
        if frame != cloud.header.frame_id and self._tf is not None:
            try:
                transform = self._tf.lookup_transform(
                    frame, cloud.header.frame_id, cloud.header.stamp, rospy.Duration(params.transform_tolerance)
                ).transform
            except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException) as error:
                rospy.logwarn_throttle(
                    1.0,
                    "Can't transform pointcloud from frame %s to %s at time %s, reason: %s"
                    % (cloud.header.frame_id, frame, cloud.header.stamp, error),
                )
                return
            q, t = transform.rotation, transform.translation
            rotation, translation = rotation_matrix(q.x, q.y, q.z, q.w), (t.x, t.y, t.z)
        scan = LaserScan()
        scan.header.stamp = cloud.header.stamp
        scan.header.frame_id = frame
        scan.angle_min, scan.angle_max, scan.angle_increment = (
            params.angle_min,
            params.angle_max,
            params.angle_increment,
        )
        scan.time_increment, scan.scan_time = 0.0, params.scan_time
        scan.range_min, scan.range_max = params.range_min, params.range_max
        scan.ranges = project(xyz, params, rotation, translation).tolist()
        self._pub.publish(scan)


def main() -> int:
    rospy.init_node("pointcloud_to_laserscan")
    given = {
        name: rospy.get_param("~" + name) for name in ScanParams.__dataclass_fields__ if rospy.has_param("~" + name)
    }
    try:
        params = ScanParams.from_params(given)
    except ParamError as error:
        rospy.logfatal("pointcloud_to_laserscan: %s", error)
        return 1
    PointCloudToLaserScan(params)
    rospy.spin()  # returns at shutdown; it raises no ROSInterruptException (rospy/client.py, spin)
    return 0


if __name__ == "__main__":
    sys.exit(main())
