#!/usr/bin/env python3
"""rostest node: `roslaunch turtlebot_teleop keyboard_teleop.launch` as typed, on a pseudo-terminal, with
turtlebot_world.launch running. The usage text shows; held 'i' ramps linear.x on cmd_vel_mux/input/teleop by 0.02 a
step up to 0.2 m/s (upstream turtlebot_teleop_key's main loop), the multiplexer hands control to "Teleoperation" and
the robot drives forward; 'k' stops at once; Ctrl-C ends the node with a zero twist and the terminal restored."""
from __future__ import annotations

import os
import signal
import sys
import threading
import time
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from std_msgs.msg import String
from workspace_testing.terminal import PseudoTerminal


class KeyboardTeleopOnPty(unittest.TestCase):
    def setUp(self):
        self.timeout = rospy.get_param("~timeout")
        self.twists = []
        self.actives = []
        self.changed = threading.Condition()
        self.sub = rospy.Subscriber("/cmd_vel_mux/input/teleop", Twist, self.on_twist, queue_size=100)
        self.active_sub = rospy.Subscriber("/cmd_vel_mux/active", String, self.on_active, queue_size=10)
        self.terminal = PseudoTerminal(["roslaunch", "turtlebot_teleop", "keyboard_teleop.launch"])

    def tearDown(self):
        self.sub.unregister()
        self.active_sub.unregister()
        self.terminal.close()

    def on_twist(self, msg):
        with self.changed:
            self.twists.append((msg.linear.x, msg.angular.z))
            self.changed.notify_all()

    def on_active(self, msg):
        with self.changed:
            self.actives.append(msg.data)
            self.changed.notify_all()

    def read_until(self, text):
        seen = self.terminal.read_until(text, self.timeout)
        self.assertTrue(seen, "%r not seen; output: %r" % (text, self.terminal.output[-2000:]))

    def hold(self, key, until):
        """Press `key` every 50 ms (a held key repeats) until until() holds on the recorded twists."""
        deadline = time.monotonic() + self.timeout
        while True:
            self.terminal.write(key)
            with self.changed:
                if self.changed.wait_for(until, 0.05):
                    return
            self.assertLess(time.monotonic(), deadline, "%r: no such twist in %s" % (key, self.twists[-5:]))

    def test_keys_drive_the_robot_through_the_mux(self):
        self.read_until(b"Control Your Turtlebot!")
        self.read_until(b"CTRL-C to quit")
        deadline = time.monotonic() + self.timeout
        while self.sub.get_num_connections() == 0:  # no event to wait on for a connection
            self.assertLess(time.monotonic(), deadline, "turtlebot_teleop_key never connected")
            time.sleep(0.05)
        rospy.wait_for_service("/gazebo/get_model_state", self.timeout)
        get_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        start_x = get_state("mobile_base", "").pose.position.x

        self.hold(b"i", lambda: bool(self.twists) and self.twists[-1][0] >= 0.2 - 1e-9)
        forward = [lin for lin, _ in self.twists if lin > 0]
        steps = [round(b - a, 6) for a, b in zip(forward, forward[1:])]
        self.assertTrue(all(0 <= s <= 0.02 + 1e-6 for s in steps), steps)
        self.assertAlmostEqual(max(forward), 0.2, places=6)
        with self.changed:
            self.assertTrue(self.changed.wait_for(lambda: "Teleoperation" in self.actives, self.timeout), self.actives)
        self.hold(b"i", lambda: get_state("mobile_base", "").pose.position.x > start_x + 0.1)

        self.hold(b"k", lambda: self.twists[-1] == (0.0, 0.0))
        count = len(self.twists)
        self.terminal.write(b"\x03")
        with self.changed:  # the node's last twist is a zero one, then it ends
            self.assertTrue(self.changed.wait_for(lambda: len(self.twists) > count, self.timeout))
        self.assertEqual(self.twists[-1], (0.0, 0.0))
        os.killpg(self.terminal.process.pid, signal.SIGINT)  # roslaunch itself, as Ctrl-C in a terminal would
        self.assertEqual(self.terminal.process.wait(self.timeout), 0)
        self.assertEqual(self.terminal.settings(), self.terminal.settings_before, "terminal settings not restored")


if __name__ == "__main__":
    rospy.init_node("test_keyboard_teleop")
    rostest.rosrun("turtlebot_teleop", "keyboard_teleop", KeyboardTeleopOnPty, sys.argv)
