#!/usr/bin/env python3
"""rostest node: with draw_square running, turtle1 drives 2 m straight ahead from the middle, stops, and turns a
quarter turn to the left at that corner."""
from __future__ import annotations

import math
import sys
import threading
import unittest

import rospy
import rostest

from turtlesim.msg import Pose

CENTRE = 499 / 45.0 / 2.0


class DrawSquare(unittest.TestCase):
    def test_first_side_and_corner(self):
        timeout = rospy.get_param("~timeout")
        tolerance = rospy.get_param("~position_tolerance")
        changed = threading.Condition()
        poses = []

        def on_pose(pose: Pose) -> None:
            with changed:
                poses.append(pose)
                changed.notify_all()

        sub = rospy.Subscriber("/turtle1/pose", Pose, on_pose, queue_size=100)
        try:
            with changed:
                turned = changed.wait_for(
                    lambda: poses and abs(poses[-1].theta - math.pi / 2) < 0.02 and poses[-1].x > CENTRE + 1.5,
                    timeout,
                )
                self.assertTrue(turned, "turtle1 did not reach the first corner and turn; last pose %s" % poses[-1:])
                corner = poses[-1]
        finally:
            sub.unregister()
        self.assertAlmostEqual(corner.x, CENTRE + 2.0, delta=tolerance)
        self.assertAlmostEqual(corner.y, CENTRE, delta=tolerance)


if __name__ == "__main__":
    rospy.init_node("test_draw_square")
    rostest.rosrun("turtlesim", "draw_square", DrawSquare, sys.argv)
