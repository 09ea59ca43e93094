#!/usr/bin/env python3
"""rostest node: `rosrun teleop_twist_keyboard teleop_twist_keyboard.py` on a pseudo-terminal. Keys give upstream's
twists on cmd_vel (teleop_twist_keyboard.py 1.0.0: moveBindings times ~speed / ~turn, speedBindings' 10 % steps);
~repeat_rate repeats the last twist and ~key_timeout stops a robot left without keys; Ctrl-C ends it with a zero
twist and the terminal as it was."""
from __future__ import annotations

import sys
import threading
import unittest
from typing import Callable, List, Tuple

import rospy
import rostest
from geometry_msgs.msg import Twist
from workspace_testing.terminal import PseudoTerminal

Motion = Tuple[float, float, float, float]  # linear x, y, z, angular z
STOP: Motion = (0.0, 0.0, 0.0, 0.0)


class Keyboard(unittest.TestCase):
    def setUp(self) -> None:
        self.timeout = rospy.get_param("~timeout")
        self.twists: List[Motion] = []
        self.changed = threading.Condition()
        self.sub = rospy.Subscriber("/cmd_vel", Twist, self.on_twist, queue_size=100)
        self.terminal = None

    def tearDown(self) -> None:
        self.sub.unregister()
        if self.terminal:
            self.terminal.close()

    def on_twist(self, msg: Twist) -> None:
        with self.changed:
            self.twists.append((msg.linear.x, msg.linear.y, msg.linear.z, msg.angular.z))
            self.changed.notify_all()

    def start(self, *params: str) -> None:
        self.terminal = PseudoTerminal(["rosrun", "teleop_twist_keyboard", "teleop_twist_keyboard.py", *params])
        self.read_until(b"CTRL-C to quit")  # printed once a subscriber (this test) is connected

    def read_until(self, text: bytes) -> None:
        seen = self.terminal.read_until(text, self.timeout)
        self.assertTrue(seen, "%r not seen; output: %r" % (text, self.terminal.output[-2000:]))

    def wait_for(self, condition: Callable[[List[Motion]], bool], what: str) -> None:
        with self.changed:
            self.assertTrue(self.changed.wait_for(lambda: condition(self.twists), self.timeout), (what, self.twists))

    def press(self, key: bytes, expected: Motion) -> None:
        count = len(self.twists)
        self.terminal.write(key)
        self.wait_for(lambda twists: len(twists) > count and twists[-1] == expected, "%r -> %s" % (key, expected))

    def quit(self) -> None:
        count = len(self.twists)
        self.terminal.write(b"\x03")
        self.assertEqual(self.terminal.process.wait(self.timeout), 0)
        self.wait_for(lambda twists: len(twists) > count and twists[-1] == STOP, "a zero twist last")
        self.assertEqual(self.terminal.settings(), self.terminal.settings_before, "terminal settings not restored")

    def test_keys_give_upstreams_twists(self) -> None:
        self.start("_speed:=0.5", "_turn:=1.0")
        self.press(b"i", (0.5, 0.0, 0.0, 0.0))
        self.press(b"o", (0.5, 0.0, 0.0, -1.0))
        self.press(b"q", (0.5 * 1.1, 0.0, 0.0, -1.0 * 1.1))
        self.read_until(b"currently:\tspeed 0.55\tturn 1.1")
        self.press(b"J", (0.0, 0.55, 0.0, 0.0))
        self.press(b"t", (0.0, 0.0, 0.55, 0.0))
        self.press(b"k", STOP)
        self.press(b",", (-0.55, 0.0, 0.0, 0.0))
        self.quit()

    def test_repeat_rate_and_key_timeout(self) -> None:
        self.start("_speed:=0.25", "_repeat_rate:=20.0", "_key_timeout:=0.6")
        count = len(self.twists)
        self.terminal.write(b"l")
        # no further key: the twist is repeated, then the key timeout stops the robot
        turning = (0.0, 0.0, 0.0, -1.0)
        self.wait_for(lambda twists: twists[count:].count(turning) >= 3 and twists[-1] == STOP, "repeats, then stop")
        self.quit()

    def test_bad_params_end_the_node_naming_them(self) -> None:
        # a node name of its own: `_key_timeout:=-1` stays on the parameter server
        command = ["rosrun", "teleop_twist_keyboard", "teleop_twist_keyboard.py", "__name:=bad", "_key_timeout:=-1"]
        self.terminal = PseudoTerminal(command)
        self.assertEqual(self.terminal.process.wait(self.timeout), 1)
        self.read_until(b"~key_timeout [-1] is negative")


if __name__ == "__main__":
    rospy.init_node("test_keyboard")
    rostest.rosrun("teleop_twist_keyboard", "keyboard", Keyboard, sys.argv)
