#!/usr/bin/env python3
"""rostest node for tutorial 8: `roslaunch beginner_tutorials turtlemimic.launch`, then
`rostopic pub /turtlesim1/turtle1/cmd_vel ...` as the tutorial types it; turtlesim2's turtle, driven by the mimic
(C++ or Python, ~mimic_type), must move the same way and end where turtlesim1's turtle ends."""
from __future__ import annotations

import os
import shlex
import subprocess
import sys
import threading
import unittest

import rospy
import rostest

from turtlesim.msg import Pose
from workspace_testing.processes import stop_group as stop

ENV = {k: v for k, v in os.environ.items() if k != "DISPLAY"}  # headless: no window to open here


class LastPoses:
    def __init__(self, names):
        self.poses = {name: [] for name in names}
        self.changed = threading.Condition()
        self.subs = [rospy.Subscriber(name, Pose, self.on_pose, callback_args=name, queue_size=100) for name in names]

    def on_pose(self, pose: Pose, name: str) -> None:
        with self.changed:
            self.poses[name].append(pose)
            self.changed.notify_all()

    def wait_until(self, predicate, timeout: float) -> bool:
        with self.changed:
            return self.changed.wait_for(lambda: predicate(self.poses), timeout)

    def close(self) -> None:
        for sub in self.subs:
            sub.unregister()


def moved_then_stopped(poses) -> bool:
    return (
        any(p.linear_velocity > 0 for p in poses)
        and len(poses) > 20
        and all(p.linear_velocity == 0.0 and p.angular_velocity == 0.0 for p in poses[-20:])
    )


class TurtleMimic(unittest.TestCase):
    def test_second_turtle_follows_the_first(self):
        timeout = rospy.get_param("~timeout")
        mimic_type = rospy.get_param("~mimic_type")
        launch = subprocess.Popen(
            ["roslaunch", "beginner_tutorials", "turtlemimic.launch", "mimic_type:=" + mimic_type],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
            env=ENV,
        )
        first, second = "/turtlesim1/turtle1/pose", "/turtlesim2/turtle1/pose"
        poses = LastPoses([first, second])
        try:
            rospy.wait_for_service("/turtlesim1/spawn", timeout)
            rospy.wait_for_service("/turtlesim2/spawn", timeout)
            self.assertTrue(poses.wait_until(lambda p: p[first] and p[second], timeout), "no poses from the sims")
            # The mimic must be listening before the first turtle moves.
            rospy.wait_for_message("/turtlesim2/turtle1/cmd_vel", rospy.AnyMsg, timeout)
            # Tutorial 8's command: a twist once a second, the turtle goes round in circles until it stops.
            publisher = subprocess.Popen(
                shlex.split(
                    "rostopic pub /turtlesim1/turtle1/cmd_vel geometry_msgs/Twist -r 1 -- "
                    "'[2.0, 0.0, 0.0]' '[0.0, 0.0, -1.8]'"
                ),
                stdout=subprocess.DEVNULL,
                start_new_session=True,
                env=ENV,
            )
            try:
                circling = poses.wait_until(lambda p: sum(q.linear_velocity > 0 for q in p[first]) > 150, timeout)
                self.assertTrue(circling, "turtlesim1's turtle did not keep moving")
            finally:
                stop(publisher)
            both_done = poses.wait_until(
                lambda p: moved_then_stopped(p[first]) and moved_then_stopped(p[second]), timeout
            )
            self.assertTrue(both_done, "the turtles did not both move and stop")
            with poses.changed:
                a, b = poses.poses[first][-1], poses.poses[second][-1]
            self.assertGreater(max(abs(q.theta) for q in poses.poses[first]), 1.0, "turtlesim1's turtle did not turn")
            self.assertAlmostEqual(b.x, a.x, delta=rospy.get_param("~position_tolerance"))
            self.assertAlmostEqual(b.y, a.y, delta=rospy.get_param("~position_tolerance"))
            self.assertAlmostEqual(b.theta, a.theta, delta=rospy.get_param("~angle_tolerance"))
        finally:
            poses.close()
            stop(launch, grace=20.0)


if __name__ == "__main__":
    rospy.init_node("test_turtlemimic")
    rostest.rosrun("beginner_tutorials", "turtlemimic", TurtleMimic, sys.argv)
