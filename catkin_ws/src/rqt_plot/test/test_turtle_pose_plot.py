#!/usr/bin/env python3
"""rostest node: `rosrun rqt_plot rqt_plot /turtle1/pose/x:y:theta` under Xvfb while turtle1 drives a circle: the
tool is the node rqt_gui_py_node_<pid> subscribed to /turtle1/pose, its screenshot holds the three curves in
rqt_plot's first three colours (DataPlot._colors: blue, red, cyan), and Ctrl-C ends it with exit code 0."""
from __future__ import annotations

import os
import sys
import tempfile
import threading
import unittest

import numpy as np
import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose
from workspace_testing.tool_window import ToolOnScreen, matches, save_png

CURVES = {"/turtle1/pose/x": (0, 0, 255), "/turtle1/pose/y": (255, 0, 0), "/turtle1/pose/theta": (0, 255, 255)}


def subscribers_of(topic: str):
    for name, nodes in rosgraph.Master("/test").getSystemState()[1]:
        if name == topic:
            return nodes
    return []


class PlotShowsPose(unittest.TestCase):
    def test_pose_curves(self):
        timeout = rospy.get_param("~timeout")
        min_pixels = rospy.get_param("~min_curve_pixels")
        shot_path = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "rqt_plot_pose.png")
        rospy.wait_for_message("/turtle1/pose", Pose, timeout)
        cmd_vel = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        driving = threading.Event()

        def drive():
            twist = Twist()
            twist.linear.x, twist.angular.z = 1.5, 1.0
            rate = rospy.Rate(10)
            while not driving.is_set() and not rospy.is_shutdown():
                cmd_vel.publish(twist)
                rate.sleep()

        driver = threading.Thread(target=drive, daemon=True)
        driver.start()
        log_path = os.path.join(tempfile.gettempdir(), "rqt_plot_pose.log")
        try:
            with ToolOnScreen(["rosrun", "rqt_plot", "rqt_plot", "/turtle1/pose/x:y:theta"], log_path) as tool:
                node = "/rqt_gui_py_node_%d" % tool.process.pid

                def failures_of(image: np.ndarray):
                    found = (
                        ["%s not subscribed to /turtle1/pose" % node]
                        if node not in subscribers_of("/turtle1/pose")
                        else []
                    )
                    for curve, colour in CURVES.items():
                        count = int(np.count_nonzero(matches(image, colour, 10)))
                        if count < min_pixels:
                            found.append("%s: %d pixels of %s" % (curve, count, colour))
                    return found

                image, failures = tool.wait_for(failures_of, timeout)
                if image is not None:
                    save_png(image, shot_path)
                self.assertEqual(failures, [], "screenshot %s; tool output:\n%s" % (shot_path, tool.log()))
                self.assertEqual(tool.interrupt(15.0), 0, "Ctrl-C; tool output:\n%s" % tool.log())
        finally:
            driving.set()
            driver.join()


if __name__ == "__main__":
    rospy.init_node("test_turtle_pose_plot")
    rostest.rosrun("rqt_plot", "turtle_pose_plot", PlotShowsPose, sys.argv)
