#!/usr/bin/env python3
"""rostest node: `rosrun joint_state_publisher_gui joint_state_publisher_gui` under Xvfb with test/urdf's cart.
The screenshot shows a slider per movable joint (four: the mimic joint has none), each filled as far as the
centred joint's value lies in its limits (ros/joint_state_publisher noetic-devel joint_state_publisher_gui:
RANGE, valueToSlider, center); End and Home on the focused head_pan slider send /joint_states to its limits and
move the slider's fill; Ctrl-C ends the window."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import threading
import unittest
from typing import List

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import JointState
from workspace_testing.slider_image import Groove, grooves
from workspace_testing.tool_window import ToolOnScreen, save_png

JOINTS = ["head_pan", "head_tilt", "wheel_joint", "gripper_extension", "gripper_twin_extension"]
LIMITS = {
    "head_pan": (-1.2, 1.5),
    "head_tilt": (0.0, 0.8),
    "wheel_joint": (-3.141592653589793, 3.141592653589793),
    "gripper_extension": (-0.1, 0.2),
}


class SlidersWindow(unittest.TestCase):
    def setUp(self) -> None:
        self.timeout = rospy.get_param("~timeout")
        self.shot = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "jsp_gui_sliders.png")
        self.latest = None
        self.changed = threading.Condition()
        self.sub = rospy.Subscriber("/joint_states", JointState, self.on_state, queue_size=10)

    def tearDown(self) -> None:
        self.sub.unregister()

    def on_state(self, msg: JointState) -> None:
        with self.changed:
            self.latest = dict(zip(msg.name, msg.position))
            self.changed.notify_all()

    def wait_for_joint(self, name: str, value: float) -> None:
        step = (LIMITS[name][1] - LIMITS[name][0]) / 10000.0
        with self.changed:
            reached = self.changed.wait_for(
                lambda: self.latest is not None and abs(self.latest[name] - value) <= step * 1.01, self.timeout
            )
        self.assertTrue(reached, "%s never %s: %s" % (name, value, self.latest))

    def screen_shows(self, tool: ToolOnScreen, fractions: List[float]) -> List[Groove]:
        def failures_of(image: np.ndarray) -> List[str]:
            found = [round(g.fraction, 3) for g in grooves(image)]
            if len(found) != len(fractions) or any(abs(a - b) > 0.03 for a, b in zip(found, fractions)):
                return ["slider fills %s, expected %s" % (found, [round(f, 3) for f in fractions])]
            return []

        image, failures = tool.wait_for(failures_of, self.timeout)
        if image is not None:
            save_png(image, self.shot)
        self.assertEqual(failures, [], "screenshot %s; output:\n%s" % (self.shot, tool.log()))
        return grooves(image)

    def xdotool(self, tool: ToolOnScreen, *args: str) -> None:
        subprocess.run(["xdotool", *args], env=dict(os.environ, DISPLAY=tool.display), check=True)

    def test_sliders_move_the_joint_states(self) -> None:
        log = os.path.join(tempfile.gettempdir(), "jsp_gui_sliders.log")
        with ToolOnScreen(["rosrun", "joint_state_publisher_gui", "joint_state_publisher_gui"], log) as tool:
            with self.changed:
                self.assertTrue(self.changed.wait_for(lambda: self.latest is not None, self.timeout), tool.log())
            self.assertEqual(sorted(self.latest), sorted(JOINTS))
            # centred: each zero's place in its limits, as valueToSlider puts it
            centred = [(0.0 - low) / (high - low) for low, high in LIMITS.values()]
            head_pan = self.screen_shows(tool, centred)[0]
            self.xdotool(tool, "mousemove", str(head_pan.handle), str(head_pan.line), "click", "1")
            self.xdotool(tool, "key", "End")
            self.wait_for_joint("head_pan", 1.5)
            self.screen_shows(tool, [1.0] + centred[1:])
            self.xdotool(tool, "key", "Home")
            self.wait_for_joint("head_pan", -1.2)
            with self.changed:  # the mimic joint (multiplier 1, offset 0) follows its joint
                self.assertEqual(self.latest["gripper_twin_extension"], self.latest["gripper_extension"])
            self.screen_shows(tool, [0.0] + centred[1:])
            self.assertIsNotNone(tool.interrupt(15.0), "Ctrl-C did not end it; output:\n%s" % tool.log())


if __name__ == "__main__":
    rospy.init_node("test_sliders_window")
    rostest.rosrun("joint_state_publisher_gui", "sliders_window", SlidersWindow, sys.argv)
