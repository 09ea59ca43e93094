#!/usr/bin/env python3
"""rostest node: `rosrun rqt_robot_steering rqt_robot_steering _default_topic:=/robot/cmd_vel` under Xvfb.
Expected values from ros-visualization/rqt_robot_steering 0.5.12 (robot_steering.py, RobotSteering.ui): the
screenshot shows the two sliders at zero (half filled: -1..1 m/s, -3..3 rad/s); with the linear slider focused,
W adds a single step (0.01 m/s), Shift+W a page step (0.1), A / Shift+D the same on angular.z; the twist is sent
again and again while it is not zero (a 100 ms QTimer), a zero twist once after Space (and once more for each
further Space); the sliders' fill follows; Ctrl-C ends it with exit code 0."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from typing import Callable, List, Tuple

import numpy as np
import rospy
import rostest
from geometry_msgs.msg import Twist
from workspace_testing.slider_image import grooves
from workspace_testing.tool_window import ToolOnScreen, save_png

TOPIC = "/robot/cmd_vel"
LINEAR_RANGE, ANGULAR_RANGE = (-1.0, 1.0), (-3.0, 3.0)
STOP = (0.0, 0.0)


def fill(value: float, limits: Tuple[float, float]) -> float:
    """How far a slider at ``value`` is filled (from its minimum)."""
    return (value - limits[0]) / (limits[1] - limits[0])


class SteeringKeys(unittest.TestCase):
    def setUp(self) -> None:
        self.timeout = rospy.get_param("~timeout")
        self.shot = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "rqt_robot_steering.png")
        self.twists: List[Tuple[float, float]] = []
        self.stamps: List[float] = []
        self.changed = threading.Condition()
        self.sub = rospy.Subscriber(TOPIC, Twist, self.on_twist, queue_size=100)

    def tearDown(self) -> None:
        self.sub.unregister()

    def on_twist(self, msg: Twist) -> None:
        with self.changed:
            self.twists.append((round(msg.linear.x, 6), round(msg.angular.z, 6)))
            self.stamps.append(time.monotonic())
            self.changed.notify_all()

    def wait_for(self, condition: Callable[[], bool], what: str) -> None:
        with self.changed:
            self.assertTrue(self.changed.wait_for(condition, self.timeout), (what, self.twists[-10:]))

    def screen_shows(self, tool: ToolOnScreen, linear: float, angular: float):
        expected = [round(fill(linear, LINEAR_RANGE), 3), round(fill(angular, ANGULAR_RANGE), 3)]

        def failures_of(image: np.ndarray) -> List[str]:
            found = [round(g.fraction, 3) for g in grooves(image, vertical=True)[:1] + grooves(image)[:1]]
            if len(found) != 2 or any(abs(a - b) > 0.03 for a, b in zip(found, expected)):
                return ["slider fills (linear, angular) %s, expected %s" % (found, expected)]
            return []

        image, failures = tool.wait_for(failures_of, self.timeout)
        if image is not None:
            save_png(image, self.shot)
        self.assertEqual(failures, [], "screenshot %s; output:\n%s" % (self.shot, tool.log()))
        return grooves(image, vertical=True)[0]

    def keys(self, tool: ToolOnScreen, *keys: str) -> None:
        for key in keys:
            subprocess.run(["xdotool", "key", key], env=dict(os.environ, DISPLAY=tool.display), check=True)

    def test_shortcuts_steer_and_the_twists_follow(self) -> None:
        command = ["rosrun", "rqt_robot_steering", "rqt_robot_steering", "_default_topic:=" + TOPIC]
        log = os.path.join(tempfile.gettempdir(), "rqt_robot_steering.log")
        with ToolOnScreen(command, log) as tool:
            linear_slider = self.screen_shows(tool, 0.0, 0.0)
            # focus the linear slider (a click on its handle does not move it): the topic field, focused first,
            # would take the letters as text
            subprocess.run(
                ["xdotool", "mousemove", str(linear_slider.line), str(linear_slider.handle), "click", "1"],
                env=dict(os.environ, DISPLAY=tool.display),
                check=True,
            )
            self.keys(tool, "w")
            self.wait_for(lambda: (0.01, 0.0) in self.twists, "W: +0.01 m/s")
            self.keys(tool, "shift+w", "shift+w", "shift+w", "shift+w", "a", "shift+d")
            moving = (0.41, -0.09)
            self.wait_for(lambda: self.twists[-5:] == [moving] * 5, "repeated while not zero")
            with self.changed:
                first = self.twists.index(moving)
                repeats_took = self.stamps[first + 4] - self.stamps[first]
            self.screen_shows(tool, *moving)

            with self.changed:
                start = len(self.twists)  # the tool may have sent its first zero twist at start: not counted

            def zeros() -> int:
                return self.twists[start:].count(STOP)

            self.keys(tool, "space")
            self.wait_for(lambda: zeros() == 1 and self.twists[-1] == STOP, "Space: a zero twist")
            # as long again as four repeats took: no further zero twist
            time.sleep(repeats_took)  # nothing to wait on: the absence of messages
            with self.changed:
                self.assertEqual(self.twists[start:][-1:], [STOP])
                self.assertEqual(zeros(), 1, "zero sent once only: %s" % self.twists[start:])
            self.keys(tool, "space")
            self.wait_for(lambda: zeros() == 2, "Space at zero: the zero once more")
            self.screen_shows(tool, 0.0, 0.0)
            self.assertEqual(tool.interrupt(15.0), 0, "Ctrl-C; output:\n%s" % tool.log())


if __name__ == "__main__":
    rospy.init_node("test_steering_keys")
    rostest.rosrun("rqt_robot_steering", "steering_keys", SteeringKeys, sys.argv)
