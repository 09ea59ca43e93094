#!/usr/bin/env python3
"""pointcloud_to_laserscan_node through ROS: a cloud on /rslidar_points becomes a scan on /scan in the cloud's frame,
with the nearest point per bin; nothing is subscribed upstream until someone listens to the scan (connectCb)."""
import math
import struct
import unittest

import rospy
import rostest
from sensor_msgs.msg import LaserScan, PointCloud2, PointField


def cloud(points, frame="rslidar"):
    message = PointCloud2(height=1, width=len(points), point_step=16, is_dense=True)
    message.header.frame_id = frame
    message.header.stamp = rospy.Time.now()
    message.fields = [PointField(name, 4 * i, PointField.FLOAT32, 1) for i, name in enumerate("xyz")]
    message.row_step = 16 * len(points)
    message.data = b"".join(struct.pack("<ffff", x, y, z, 0.0) for x, y, z in points)
    return message


class CloudToScan(unittest.TestCase):
    def test_a_scan_of_the_nearest_points(self):
        pub = rospy.Publisher("/rslidar_points", PointCloud2, queue_size=1)
        scans = []
        rospy.Subscriber("/scan", LaserScan, scans.append)
        deadline = rospy.Time.now() + rospy.Duration(20)
        while not scans and rospy.Time.now() < deadline:
            pub.publish(cloud([(2.0, 0.0, 0.5), (3.0, 0.0, 0.5), (0.0, -1.0, 0.6), (1.0, 0.0, 0.0)]))
            rospy.sleep(0.1)  # the node subscribes to the cloud once it sees the scan's subscriber
        self.assertTrue(scans, "no scan on /scan")
        scan = scans[-1]
        self.assertEqual(scan.header.frame_id, "rslidar")
        self.assertEqual(len(scan.ranges), math.ceil((1.5708 + 1.5708) / 0.0087))
        self.assertAlmostEqual(scan.ranges[int(1.5708 / 0.0087)], 2.0, places=5)
        self.assertAlmostEqual(scan.ranges[int((1.5708 - math.pi / 2) / 0.0087)], 1.0, places=5)
        self.assertEqual(sum(1 for r in scan.ranges if math.isfinite(r)), 2)


if __name__ == "__main__":
    rospy.init_node("test_cloud_to_scan")
    rostest.rosrun("pointcloud_to_laserscan", "cloud_to_scan", CloudToScan)
