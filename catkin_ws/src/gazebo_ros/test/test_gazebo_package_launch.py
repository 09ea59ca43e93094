#!/usr/bin/env python3
"""rostest node: `roslaunch sim_fixture_gazebo fixture_empty_world.launch` comes up unchanged and its robot drives.

The launch file is started here as a user would start it, against the test's master. The robot's description
must be xacro's expansion (no xacro left, the macro's links there), spawned by gazebo_ros's spawn_model at the
launch file's pose; driven at `speed` on cmd_vel (the diff-drive plugin's commandTopic) for `drive_time` s of sim
time, it must cover `distance` +- `distance_tolerance` m, measured by /gazebo/get_model_state (ground truth).
"""
import math
import os
import shlex
import sys
import time
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import GetModelProperties, GetModelState
from geometry_msgs.msg import Twist
from workspace_testing.processes import LoggedProcess
from workspace_testing.sim_clock import SimClock


class GazeboPackageLaunch(unittest.TestCase):
    launch = None

    @classmethod
    def setUpClass(cls) -> None:
        command = ["roslaunch"] + shlex.split(rospy.get_param("~launch"))
        cls.launch = LoggedProcess(command, env=dict(os.environ, PYTHONUNBUFFERED="1"), grace=10.0)
        cls.model = rospy.get_param("~model")
        cls.startup_timeout = float(rospy.get_param("~startup_timeout", 180.0))
        cls.deadline = time.monotonic() + cls.startup_timeout
        # rostest ends a test node that overruns its time-limit with a signal: the launch must not outlive it
        rospy.on_shutdown(cls.launch.stop)

    @classmethod
    def tearDownClass(cls) -> None:
        cls.launch.close()

    def wait_for_model(self) -> None:
        """Until the launch file's spawn_model has spawned the robot (model_states lists it)."""
        try:
            rospy.wait_for_service("/gazebo/get_model_state", timeout=max(1.0, self.deadline - time.monotonic()))
        except rospy.ROSException:
            self.fail("no /gazebo/get_model_state within %g s:\n%s" % (self.startup_timeout, self.launch.output()))
        while not rospy.is_shutdown():
            self.assertIsNone(self.launch.process.poll(), "roslaunch ended:\n" + self.launch.output())
            states = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=self.startup_timeout)
            if self.model in states.name:
                return
            self.assertLess(time.monotonic(), self.deadline, "model never spawned:\n" + self.launch.output())

    def model_pose(self):
        state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)(self.model, "world")
        self.assertTrue(state.success, state.status_message)
        return state.pose

    def test_a_spawned_from_xacro_description(self) -> None:
        self.wait_for_model()
        description = rospy.get_param("/robot_description")
        self.assertIn('<robot name="sim_fixture_bot">', description)
        self.assertNotIn("xacro:", description)
        self.assertNotIn("$(", description)
        self.assertIn("libgazebo_ros_diff_drive.so", description)
        properties = rospy.ServiceProxy("/gazebo/get_model_properties", GetModelProperties)(self.model)
        self.assertTrue(properties.success, properties.status_message)
        # the wheel macro's two expansions; fixed-joint children are merged into base_link as Gazebo merges them
        for link in ("wheel_left_link", "wheel_right_link"):
            self.assertTrue(any(body.endswith(link) for body in properties.body_names), properties.body_names)
        self.assertEqual(sorted(properties.child_model_names), [])
        pose = self.model_pose()
        self.assertAlmostEqual(pose.position.x, rospy.get_param("~spawn_x"), delta=0.01)
        self.assertAlmostEqual(pose.position.y, rospy.get_param("~spawn_y"), delta=0.01)

    def test_b_drives_the_commanded_distance(self) -> None:
        self.wait_for_model()
        speed, drive_time = float(rospy.get_param("~speed")), float(rospy.get_param("~drive_time"))
        clock = SimClock()
        command = rospy.Publisher("/cmd_vel", Twist, queue_size=1, latch=True)
        self.assertTrue(clock.wait_until(0.0, 30.0), "no /clock")
        # at rest first: the robot was dropped onto the ground at spawn
        self.assertTrue(clock.wait_until(clock.now + 1.0, 30.0))
        start = self.model_pose().position
        twist = Twist()
        twist.linear.x = speed
        command.publish(twist)
        started = clock.now
        self.assertTrue(clock.wait_until(started + drive_time, 10 * drive_time + 30), "sim time stalled")
        command.publish(Twist())
        self.assertTrue(clock.wait_until(started + drive_time + 1.0, 60.0), "sim time stalled")
        end = self.model_pose().position
        travelled = math.hypot(end.x - start.x, end.y - start.y)
        rospy.loginfo("travelled %.4f m in %.1f s of sim time at %.2f m/s", travelled, drive_time, speed)
        self.assertAlmostEqual(
            travelled, float(rospy.get_param("~distance")), delta=float(rospy.get_param("~distance_tolerance"))
        )
        self.assertLess(abs(end.y - start.y), 0.05, "drifted sideways")


if __name__ == "__main__":
    rospy.init_node("gazebo_package_launch")
    rostest.rosrun("gazebo_ros", "gazebo_package_launch", GazeboPackageLaunch, sys.argv)
