#!/usr/bin/env python3
"""rostest node: scan_monitor on the simulated TurtleBot's /scan reports the distance of a box spawned at a
known pose (read from its log on /rosout)."""
import math
import os
import re
import sys
import threading
import unittest

import rospkg
import rospy
import rostest
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Log

REPORT = re.compile(r"^Smallest distance: \[([0-9.e+-]+)\] m at angle \[([0-9.e+-]+)\] rad$")


class ScanMonitorOnTheSimulator(unittest.TestCase):
    def test_box_distance(self):
        box_x = rospy.get_param("~box_x")
        expected = box_x - 0.1  # the box is a 0.2 m cube; the laser sits above base_footprint
        reports, changed = [], threading.Condition()

        def on_log(log):
            match = REPORT.match(log.msg) if log.name.endswith("scan_monitor") else None
            if match:
                with changed:
                    reports.append((float(match.group(1)), float(match.group(2))))
                    changed.notify_all()

        rospy.Subscriber("/rosout", Log, on_log, queue_size=100)
        rospy.wait_for_service("/gazebo/spawn_urdf_model", timeout=60)
        box_file = os.path.join(rospkg.RosPack().get_path("turtle_sim_ode"), "test", "models", "box.urdf")
        with open(box_file) as urdf:
            spawn = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)
            result = spawn("scan_box", urdf.read(), "", Pose(Point(box_x, 0, 0.1), Quaternion(0, 0, 0, 1)), "")
        self.assertTrue(result.success, result.status_message)
        with changed:
            seen = changed.wait_for(lambda: any(abs(d - expected) < 0.5 for d, _ in reports), 30.0)
        self.assertTrue(seen, "no report near the box: %s" % reports[-5:])
        distance, angle = [r for r in reports if abs(r[0] - expected) < 0.5][-1]
        self.assertAlmostEqual(distance, expected, delta=rospy.get_param("~tolerance"))
        self.assertLess(abs(math.atan2(math.sin(angle), math.cos(angle))), 0.05)


if __name__ == "__main__":
    rospy.init_node("test_scan_monitor_sim")
    rostest.rosrun("my_first_rospkg", "scan_monitor_sim", ScanMonitorOnTheSimulator, sys.argv)
