#!/usr/bin/env python3
"""rostest node: publish synthetic LaserScans and read scan_monitor's report of their minimum on /rosout."""
import math
import sys
import threading
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import LaserScan


class ScanMonitorTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.reports = []
        cls.changed = threading.Condition()
        cls.rosout = rospy.Subscriber("/rosout", Log, cls.on_log, queue_size=100)
        cls.scans = rospy.Publisher(rospy.get_param("~topic"), LaserScan, queue_size=10)

    @classmethod
    def on_log(cls, log):
        if log.name.endswith("scan_monitor") and ("Smallest" in log.msg or "No valid beam" in log.msg):
            with cls.changed:
                cls.reports.append(log.msg)
                cls.changed.notify_all()

    def report_for(self, ranges, pattern):
        scan = LaserScan()
        scan.header.frame_id = "base_scan"
        scan.angle_min, scan.angle_increment = -1.0, 0.25
        scan.range_min, scan.range_max = 0.1, 10.0
        scan.ranges = ranges
        with self.changed:
            del self.reports[:]
        deadline = rospy.Time.now() + rospy.Duration(20.0)
        while rospy.Time.now() < deadline:
            self.scans.publish(scan)
            with self.changed:
                if self.changed.wait_for(lambda: self.reports, 1.0):
                    report = self.reports[-1]
                    self.assertRegex(report, pattern)
                    return report
        self.fail("no report of scan_monitor on /rosout")

    def test_1_exact_minimum_skipping_invalid_beams(self):
        # beam 6 holds the minimum at -1 + 6 * 0.25 = 0.5 rad; NaN, +inf and below-range_min beams are skipped
        ranges = [3.0, math.nan, 0.05, math.inf, 2.5, 12.0, 0.75, 1.0, 4.0]
        self.report_for(ranges, r"^Smallest distance: \[0\.75\] m at angle \[0\.5\] rad$")

    def test_2_negative_infinity_is_closer_than_range_min(self):
        self.report_for(
            [3.0, 2.0, -math.inf, 0.75], r"^Smallest distance: closer than \[0\.1\] m at angle \[-0\.5\] rad$"
        )

    def test_3_no_valid_beam(self):
        self.report_for([math.nan, math.inf], r"^No valid beam in a scan of \[2\] ranges$")


if __name__ == "__main__":
    rospy.init_node("test_scan_monitor")
    rostest.rosrun("my_first_rospkg", "scan_monitor", ScanMonitorTest, sys.argv)
