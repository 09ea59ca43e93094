#!/usr/bin/env python3
"""rostest node (issue #26): spawn, teleport and cmd_vel with NaN, infinities and huge numbers, and turtle names
ROS cannot use, against a running turtlesim_node; then the same with generated values (Hypothesis, fixed seed).
Non-finite spawn and teleport values and illegal names fail the call with a message (as the original fails a call
whose handler throws); a non-finite cmd_vel is ignored with a throttled warning; after each input the node answers
and /turtle1/pose keeps coming, finite."""
from __future__ import annotations

import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from rosgraph_msgs.msg import Log
from workspace_testing.timing import assert_within, best_seconds, timed

from turtlesim.msg import Pose
from turtlesim.srv import Kill, Spawn, TeleportAbsolute, TeleportRelative

NAN, INF = float("nan"), float("inf")
# The services' and Twist's numbers: float32 (spawn, teleport) and float64 (cmd_vel); float32's extremes fit both.
values = st.one_of(
    st.floats(min_value=0.5, max_value=10.5),
    st.sampled_from([NAN, INF, -INF, 3.4e38, -3.4e38, 1e-45, -0.0]),
    st.floats(allow_nan=True, allow_infinity=True, width=32),
)


class Poses:
    """/turtle1/pose: the newest message and a way to wait for the next ones."""

    def __init__(self) -> None:
        self.count, self.last = 0, None
        self._changed = threading.Condition()
        self._sub = rospy.Subscriber("/turtle1/pose", Pose, self._on_pose, queue_size=10)

    def _on_pose(self, msg: Pose) -> None:
        with self._changed:
            self.count, self.last = self.count + 1, msg
            self._changed.notify_all()

    def wait_next(self, count: int, timeout: float) -> Pose:
        with self._changed:
            start = self.count
            assert self._changed.wait_for(lambda: self.count >= start + count, timeout), "/turtle1/pose stopped"
            return self.last


class BadValues(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("bad_values")
        cls.limit = rospy.get_param("~wait_limit")
        cls.ratio = rospy.get_param("~answer_time_ratio")
        cls.examples = rospy.get_param("~examples")
        for name in ("spawn", "kill", "turtle1/teleport_absolute", "turtle1/teleport_relative"):
            rospy.wait_for_service(name, 30)
        cls.spawn = rospy.ServiceProxy("spawn", Spawn)
        cls.kill = rospy.ServiceProxy("kill", Kill)
        cls.teleport = rospy.ServiceProxy("turtle1/teleport_absolute", TeleportAbsolute)
        cls.relative = rospy.ServiceProxy("turtle1/teleport_relative", TeleportRelative)
        cls.cmd = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=10)
        cls.poses = Poses()
        cls.warnings = []
        rospy.Subscriber("/rosout", Log, lambda m: m.level == Log.WARN and cls.warnings.append(m.msg), queue_size=100)
        cls.poses.wait_next(1, 30)
        deadline = time.monotonic() + 20
        while cls.cmd.get_num_connections() == 0 and time.monotonic() < deadline:
            rospy.rostime.wallsleep(0.02)  # rospy offers no event for a new subscriber
        pose = cls.poses.wait_next(1, cls.limit)
        cls.reference = best_seconds(lambda: cls.teleport(pose.x, pose.y, pose.theta))

    def alive(self) -> None:
        """The node answers within answer_time_ratio times a reference call of the same run, and /turtle1/pose comes
        on, finite and on the canvas."""
        pose = self.poses.wait_next(3, self.limit)
        state = (pose.x, pose.y, pose.theta, pose.linear_velocity, pose.angular_velocity)
        self.assertTrue(all(math.isfinite(v) for v in state), state)
        _, took = timed(lambda: self.teleport(pose.x, pose.y, pose.theta))  # a call that must be answered
        assert_within(took, self.reference, self.ratio, "teleport_absolute")

    def refused(self, call, *args) -> str:
        with self.assertRaises(rospy.ServiceException) as raised:
            call(*args)
        self.alive()
        return str(raised.exception)

    def test_a_non_finite_spawn_fails_naming_the_value(self) -> None:
        for bad in (NAN, INF, -INF):
            self.assertIn("is not a finite number", self.refused(self.spawn, 1.0, 1.0, bad, "t_bad"))

    def test_a_non_finite_teleport_fails(self) -> None:
        self.assertIn("is not a finite number", self.refused(self.teleport, NAN, 1.0, 0.0))
        self.assertIn("is not a finite number", self.refused(self.relative, INF, 0.0))

    def test_an_illegal_name_fails_the_spawn(self) -> None:
        for name in ("a b", "1x", "a//b"):
            self.assertIn("not a legal ROS graph name", self.refused(self.spawn, 1.0, 1.0, 0.0, name))

    def test_a_non_finite_cmd_vel_is_ignored_with_a_throttled_warning(self) -> None:
        before = len(self.warnings)
        for _ in range(20):
            self.cmd.publish(Twist(Vector3(NAN, 0, 0), Vector3(0, 0, INF)))
            rospy.rostime.wallsleep(0.02)  # 20 commands over 0.4 s: one warning a second at most
        self.alive()
        ignored = [w for w in self.warnings[before:] if "cmd_vel of turtle [turtle1]" in w and "ignored" in w]
        self.assertTrue(1 <= len(ignored) <= 2, ignored)

    def test_generated_values(self) -> None:
        @settings(
            max_examples=self.examples,
            derandomize=True,
            deadline=None,
            database=None,
            suppress_health_check=[HealthCheck.too_slow],
        )
        @given(kind=st.sampled_from(["spawn", "teleport", "relative", "cmd_vel"]), a=values, b=values, c=values)
        def check(kind: str, a: float, b: float, c: float) -> None:
            try:
                if kind == "spawn":
                    name = self.spawn(a, b, c, "").name
                    self.kill(name)
                elif kind == "teleport":
                    self.teleport(a, b, c)
                elif kind == "relative":
                    self.relative(a, b)
                else:
                    self.cmd.publish(Twist(Vector3(a, b, 0), Vector3(0, 0, c)))
            except rospy.ServiceException as error:
                self.assertIn("not a finite number", str(error))
            self.alive()

        check()


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "bad_values", BadValues, sys.argv)
