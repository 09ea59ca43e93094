#!/usr/bin/env python3
"""rostest node: ekf_localization_node with one bad private parameter at a time exits non-zero, its fatal message
naming the parameter and the value (params.py's checks, run by the node at start-up)."""
from __future__ import annotations

import subprocess
import unittest

import rospy
import rostest

BAD = [  # (private params on the command line, what the fatal message says)
    (["_frequency:=0"], "~frequency is [0]"),
    (["_two_d_mode:=maybe"], "~two_d_mode is ['maybe']"),
    (["_world_frame:=earth"], "world_frame [earth]"),
    (["_odom0:=wheel/odom", "_odom0_config:=[1, 0, 1]"], "~odom0_config is [[1, 0, 1]]"),
]


class BadParams(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("bad_params")
        cls.timeout = rospy.get_param("~exit_timeout")

    def run_node(self, name: str, *params: str) -> subprocess.CompletedProcess:
        command = ["rosrun", "robot_localization", "ekf_localization_node", "__name:=" + name] + list(params)
        return subprocess.run(
            command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=self.timeout
        )

    def test_each_bad_value_stops_the_node_with_its_name(self):
        for index, (params, message) in enumerate(BAD):
            result = self.run_node("bad_%d" % index, *params)
            self.assertNotEqual(result.returncode, 0, result.stdout)
            self.assertIn("FATAL", result.stdout)
            self.assertIn(message, result.stdout)


if __name__ == "__main__":
    rostest.rosrun("robot_localization", "bad_params", BadParams)
