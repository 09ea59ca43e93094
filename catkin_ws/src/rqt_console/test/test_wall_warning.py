#!/usr/bin/env python3
"""rostest node: `rosrun rqt_console rqt_console` under Xvfb, then turtle1 driven into the wall: turtlesim's
"Oh no! I hit the wall!" reaches /rosout_agg, the tool (node rqt_gui_py_node_<pid>, subscribed to /rosout_agg)
shows Warn rows (rqt_console's Warn colour, Qt.darkYellow, in the Severity column), and Ctrl-C ends it with 0."""
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
from rosgraph_msgs.msg import Log
from workspace_testing.tool_window import ToolOnScreen, matches, save_png

WARN_COLOUR = (128, 128, 0)  # Qt.darkYellow
WALL = "Oh no! I hit the wall!"


def subscribers_of(topic: str):
    for name, nodes in rosgraph.Master("/test").getSystemState()[1]:
        if name == topic:
            return nodes
    return []


class ConsoleShowsWallWarning(unittest.TestCase):
    def test_wall_warning(self):
        timeout = rospy.get_param("~timeout")
        min_pixels = rospy.get_param("~min_warn_pixels")
        shot_path = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "rqt_console_wall.png")
        warned = threading.Event()
        rospy.Subscriber("/rosout_agg", Log, lambda log: WALL in log.msg and log.level == Log.WARN and warned.set())
        cmd_vel = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        log_path = os.path.join(tempfile.gettempdir(), "rqt_console_wall.log")
        with ToolOnScreen(["rosrun", "rqt_console", "rqt_console"], log_path) as tool:
            node = "/rqt_gui_py_node_%d" % tool.process.pid
            _, failures = tool.wait_for(
                lambda image: [] if node in subscribers_of("/rosout_agg") else ["not subscribed"], timeout
            )
            self.assertEqual(failures, [], "%s never subscribed to /rosout_agg:\n%s" % (node, tool.log()))
            twist = Twist()
            twist.linear.x = 3.0
            rate = rospy.Rate(10)
            deadline = rospy.Time.now() + rospy.Duration(timeout)
            while not warned.is_set() and rospy.Time.now() < deadline:
                cmd_vel.publish(twist)
                rate.sleep()
            self.assertTrue(warned.is_set(), "turtlesim never warned %r on /rosout_agg" % WALL)

            def failures_of(image: np.ndarray):
                count = int(np.count_nonzero(matches(image, WARN_COLOUR, 24)))
                return [] if count >= min_pixels else ["%d pixels of the Warn colour %s" % (count, WARN_COLOUR)]

            image, failures = tool.wait_for(failures_of, timeout)
            if image is not None:
                save_png(image, shot_path)
            self.assertEqual(failures, [], "screenshot %s; tool output:\n%s" % (shot_path, tool.log()))
            self.assertEqual(tool.interrupt(15.0), 0, "Ctrl-C; tool output:\n%s" % tool.log())


if __name__ == "__main__":
    rospy.init_node("test_wall_warning")
    rostest.rosrun("rqt_console", "wall_warning", ConsoleShowsWallWarning, sys.argv)
