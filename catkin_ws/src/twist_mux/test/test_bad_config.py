#!/usr/bin/env python3
"""rostest node: twist_mux with configurations it cannot use ends at once with exit code 1 and a fatal message
naming the parameter, the entry and the bad value; one without ~locks runs (upstream only logs that, twist_mux.cpp
TwistMux::getTopicHandles)."""
from __future__ import annotations

import subprocess
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist

ENTRY = {"name": "joy", "topic": "joy_vel", "timeout": 0.5, "priority": 100}
CASES = [
    ("topics", [dict(ENTRY, priority="high")], "~topics[0].priority [high] is not an integer"),
    ("topics", [dict(ENTRY, timeout=-1.0)], "~topics[0].timeout [-1] is negative"),
    ("topics", [{"name": "joy", "timeout": 0.5, "priority": 1}], "~topics[0] has no 'topic'"),
    ("locks", {"pause": dict(ENTRY, topic="")}, "~locks.pause.topic [] is not a non-empty string"),
    ("locks", "pause", "~locks [pause] is neither a list nor a dict"),
]


class BadConfig(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("bad_config")
        cls.limit = rospy.get_param("~exit_limit")

    def run_mux(self, name: str, params: dict) -> subprocess.CompletedProcess:
        for key, value in params.items():
            rospy.set_param("/%s/%s" % (name, key), value)
        return subprocess.run(
            ["rosrun", "twist_mux", "twist_mux", "__name:=" + name],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            universal_newlines=True,
            timeout=self.limit,
        )

    def test_bad_entries_end_the_node_naming_the_value(self) -> None:
        for index, (param, value, message) in enumerate(CASES):
            with self.subTest(message=message):
                result = self.run_mux("bad_%d" % index, {param: value})
                self.assertEqual(result.returncode, 1, result.stdout)
                self.assertIn("Bad twist_mux configuration: " + message, result.stdout)

    def test_without_locks_the_node_runs(self) -> None:
        rospy.set_param("/no_locks/topics", [ENTRY])
        command = Twist()
        command.linear.x = 0.25
        joy = rospy.Publisher("/joy_vel", Twist, queue_size=1)
        timer = rospy.Timer(rospy.Duration(0.1), lambda _event: joy.publish(command))
        process = subprocess.Popen(["rosrun", "twist_mux", "twist_mux", "__name:=no_locks"], start_new_session=True)
        try:
            forwarded = rospy.wait_for_message("/cmd_vel_out", Twist, self.limit)
            self.assertEqual(forwarded.linear.x, 0.25)
        finally:
            timer.shutdown()
            process.terminate()
            process.wait(self.limit)


if __name__ == "__main__":
    rostest.rosrun("twist_mux", "bad_config", BadConfig)
