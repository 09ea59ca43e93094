#!/usr/bin/env python3
"""rostest node (issue #31): the droid of models/droid rests upright on its four wheels after its drop, drives on
droid_diff_drive_controller/cmd_vel (ground truth and odometry), and its head and gripper go where
position_controllers' JointPositionController and JointGroupPositionController are told."""
import math
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray

WAIT = 120.0  # s of wall time for the simulator and the spawner on a loaded machine
CONTROLLERS = {
    "droid_joint_state_controller",
    "droid_head_controller",
    "droid_gripper_controller",
    "droid_diff_drive_controller",
}


def tilt(q):
    """Angle between the body's z axis and the world's."""
    return math.acos(max(-1.0, min(1.0, 1 - 2 * (q.x * q.x + q.y * q.y))))


class Droid(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service("/controller_manager/list_controllers", WAIT)
        listing = rospy.ServiceProxy("/controller_manager/list_controllers", ListControllers)
        while {c.name for c in listing().controller if c.state == "running"} != CONTROLLERS:
            rospy.sleep(0.1)  # sim time; the test's time-limit bounds it
        rospy.wait_for_service("/gazebo/get_model_state", WAIT)
        cls.model_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        deadline = rospy.get_time() + rospy.get_param("~settle_limit")
        state = cls.model_state("robot", "world")
        while rospy.get_time() < 2.0 or math.hypot(state.twist.linear.x, state.twist.linear.z) > 0.01:
            assert rospy.get_time() < deadline, "the droid never came to rest: %s" % (state,)
            rospy.sleep(0.1)  # sim time
            state = cls.model_state("robot", "world")

    def joint_positions(self):
        states = rospy.wait_for_message("/joint_states", JointState, WAIT)
        return dict(zip(states.name, states.position))

    def await_positions(self, targets):
        tolerance = rospy.get_param("~position_tolerance")
        deadline = rospy.get_time() + rospy.get_param("~settle_limit")
        positions = self.joint_positions()
        while any(abs(positions[joint] - target) > tolerance for joint, target in targets.items()):
            self.assertLess(rospy.get_time(), deadline, "joints %s never reached %s" % (positions, targets))
            positions = self.joint_positions()

    def test_1_rests_upright(self):
        state = self.model_state("robot", "world")
        self.assertLess(tilt(state.pose.orientation), 0.05)
        self.assertAlmostEqual(state.pose.position.z, rospy.get_param("~rest_height"), delta=0.02)  # on its wheels

    def test_2_drives_on_cmd_vel(self):
        speed, seconds = rospy.get_param("~speed"), rospy.get_param("~drive_time")
        start = self.model_state("robot", "world").pose.position
        odom_start = rospy.wait_for_message("/droid_diff_drive_controller/odom", Odometry, WAIT).pose.pose.position
        commands = rospy.Publisher("/droid_diff_drive_controller/cmd_vel", Twist, queue_size=1)
        rate = rospy.Rate(10)
        end_time = rospy.get_time() + seconds
        while rospy.get_time() < end_time:
            commands.publish(Twist(linear=Vector3(speed, 0, 0)))
            rate.sleep()
        end = self.model_state("robot", "world").pose.position
        odom = rospy.wait_for_message("/droid_diff_drive_controller/odom", Odometry, WAIT).pose.pose.position
        travelled = math.hypot(end.x - start.x, end.y - start.y)
        # max_acceleration 0.5 m/s^2: 0.4 s to reach 0.2 m/s, so at least speed * (seconds - 0.4) less slip
        self.assertGreater(travelled, 0.8 * speed * (seconds - 0.4))
        self.assertLess(travelled, speed * seconds + 0.05)
        odom_travelled = math.hypot(odom.x - odom_start.x, odom.y - odom_start.y)
        self.assertAlmostEqual(odom_travelled, travelled, delta=0.15 * travelled)

    def test_3_head_turns(self):
        target = rospy.get_param("~head_target")
        rospy.Publisher("/droid_head_controller/command", Float64, queue_size=1, latch=True).publish(Float64(target))
        self.await_positions({"head_swivel": target})

    def test_4_gripper_moves(self):
        targets = rospy.get_param("~gripper_targets")
        publisher = rospy.Publisher("/droid_gripper_controller/command", Float64MultiArray, queue_size=1, latch=True)
        publisher.publish(Float64MultiArray(data=targets))
        self.await_positions(dict(zip(("gripper_extension", "left_gripper_joint", "right_gripper_joint"), targets)))


if __name__ == "__main__":
    rospy.init_node("test_droid")
    rostest.rosrun("turtle_sim_ode", "droid", Droid)
