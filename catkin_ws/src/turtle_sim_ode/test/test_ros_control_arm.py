#!/usr/bin/env python3
"""rostest node: the two-link arm's effort JointPositionControllers bring it to commanded angles; switching to the
trajectory controller is refused while they hold its joints (STRICT) and done when they are stopped; a trajectory
goal succeeds, and a goal beyond the shoulder's limit is aborted with GOAL_TOLERANCE_VIOLATED."""
import sys
import unittest

import actionlib
import rospy
import rostest
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryGoal,
    FollowJointTrajectoryResult,
    GripperCommandAction,
    GripperCommandGoal,
    JointTolerance,
)
from controller_manager_msgs.srv import ListControllers, SwitchController, SwitchControllerRequest
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from trajectory_msgs.msg import JointTrajectoryPoint

NS = "/two_link_arm"
POSITION_CONTROLLERS = ["shoulder_position_controller", "elbow_position_controller"]


def states():
    listing = rospy.ServiceProxy(NS + "/controller_manager/list_controllers", ListControllers)()
    return {c.name: c.state for c in listing.controller}


def wait_until(predicate, seconds, what):
    deadline = rospy.Time.now() + rospy.Duration(seconds)
    while not predicate():
        if rospy.Time.now() > deadline:
            raise AssertionError("timed out (sim time) waiting for " + what)
        rospy.sleep(0.1)


def positions():
    message = rospy.wait_for_message(NS + "/joint_states", JointState, timeout=10)
    return dict(zip(message.name, message.position))


class ArmControl(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service(NS + "/controller_manager/list_controllers", timeout=60)
        cls.switch = rospy.ServiceProxy(NS + "/controller_manager/switch_controller", SwitchController)
        wait_until(
            lambda: [states().get(n) for n in POSITION_CONTROLLERS + ["arm_trajectory_controller"]]
            == ["running", "running", "initialized"],
            60,
            "the spawners",
        )

    def test_a_position_controllers_reach_commanded_angles(self):
        tolerance = rospy.get_param("~angle_tolerance")
        targets = {"shoulder": 0.7, "elbow": -0.9}
        publishers = {
            j: rospy.Publisher(f"{NS}/{j}_position_controller/command", Float64, queue_size=1, latch=True)
            for j in targets
        }
        for joint, angle in targets.items():
            publishers[joint].publish(Float64(angle))
        wait_until(
            lambda: all(abs(positions()[j] - a) < tolerance for j, a in targets.items()), 10, "the commanded angles"
        )

    def test_b_switch_strictness_and_conflicts(self):
        strict, best_effort = SwitchControllerRequest.STRICT, SwitchControllerRequest.BEST_EFFORT
        self.assertFalse(self.switch(["arm_trajectory_controller"], [], strict, False, 0.0).ok, "joints claimed twice")
        self.assertFalse(self.switch(["no_such_controller"], [], strict, False, 0.0).ok)
        self.assertTrue(self.switch(["no_such_controller"], [], best_effort, False, 0.0).ok)
        self.assertTrue(self.switch(["arm_trajectory_controller"], POSITION_CONTROLLERS, strict, False, 0.0).ok)
        self.assertEqual(
            [states()[n] for n in POSITION_CONTROLLERS + ["arm_trajectory_controller"]],
            ["stopped", "stopped", "running"],
        )

    def send(self, shoulder, elbow, seconds, path_tolerance=()):
        client = actionlib.SimpleActionClient(
            NS + "/arm_trajectory_controller/follow_joint_trajectory", FollowJointTrajectoryAction
        )
        self.assertTrue(client.wait_for_server(rospy.Duration(10)))
        goal = FollowJointTrajectoryGoal()
        goal.trajectory.joint_names = ["shoulder", "elbow"]
        goal.trajectory.points = [
            JointTrajectoryPoint(positions=[shoulder, elbow], time_from_start=rospy.Duration(seconds))
        ]
        goal.path_tolerance = list(path_tolerance)
        self.feedback = []
        client.send_goal(goal, feedback_cb=self.feedback.append)
        self.assertTrue(client.wait_for_result(rospy.Duration(seconds + 10)))
        return client.get_state(), client.get_result()

    def test_c_trajectory_goal_succeeds(self):
        state, result = self.send(-0.4, 1.0, 2.0)
        self.assertEqual(
            (state, result.error_code), (actionlib.GoalStatus.SUCCEEDED, FollowJointTrajectoryResult.SUCCESSFUL)
        )
        now = positions()
        self.assertAlmostEqual(now["shoulder"], -0.4, delta=0.05)
        self.assertAlmostEqual(now["elbow"], 1.0, delta=0.05)
        self.assertGreater(len(self.feedback), 10, "feedback at action_monitor_rate (20 Hz) over 2 s")
        self.assertEqual(self.feedback[-1].joint_names, ["shoulder", "elbow"])

    def test_d_goal_beyond_the_limit_is_aborted(self):
        # the shoulder stops at 2.0; its path tolerance is removed (< 0) so that the goal tolerance decides
        state, result = self.send(2.6, 0.0, 1.5, [JointTolerance("shoulder", -1.0, 0.0, 0.0)])
        self.assertEqual(state, actionlib.GoalStatus.ABORTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED)
        self.assertTrue(result.error_string.startswith("shoulder goal error"), result.error_string)

    def test_e_gripper_action(self):
        """gripper_action_controller on the elbow: the trajectory controller gives the elbow up in the same switch;
        a GripperCommand goal with enough effort is reached."""
        stop = ["arm_trajectory_controller"]
        self.assertTrue(self.switch(["elbow_gripper_controller"], stop, SwitchControllerRequest.STRICT, False, 0.0).ok)
        client = actionlib.SimpleActionClient(NS + "/elbow_gripper_controller/gripper_cmd", GripperCommandAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(10)))
        goal = GripperCommandGoal()
        goal.command.position, goal.command.max_effort = 0.6, 30.0
        client.send_goal(goal)
        self.assertTrue(client.wait_for_result(rospy.Duration(10)))
        self.assertEqual(client.get_state(), actionlib.GoalStatus.SUCCEEDED)
        self.assertTrue(client.get_result().reached_goal)
        self.assertAlmostEqual(client.get_result().position, 0.6, delta=0.02)


if __name__ == "__main__":
    rospy.init_node("test_ros_control_arm")
    rostest.rosrun("turtle_sim_ode", "ros_control_arm", ArmControl, sys.argv)
