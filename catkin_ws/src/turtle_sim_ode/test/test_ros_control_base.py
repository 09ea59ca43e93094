#!/usr/bin/env python3
"""rostest node: the four-wheeled base under diff_drive_controller drives at the commanded speed, its odometry
agrees with the ground truth, its velocity limit holds (max_velocity 1.0 with 3 m/s asked) and it stops once the
commands stop for longer than cmd_vel_timeout."""
import math
import sys
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry


def truth():
    state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("base", "world")
    return state.pose.position, state.twist.linear


def drive(speed, seconds):
    """cmd_vel at 10 Hz for ``seconds`` of sim time."""
    publisher = rospy.Publisher("/base_controller/cmd_vel", Twist, queue_size=1)
    rate = rospy.Rate(10)
    for _ in range(int(seconds * 10)):
        publisher.publish(Twist(linear=Vector3(speed, 0, 0)))
        rate.sleep()


class BaseControl(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service("/controller_manager/list_controllers", timeout=60)
        listing = rospy.ServiceProxy("/controller_manager/list_controllers", ListControllers)
        deadline = rospy.Time.now() + rospy.Duration(60)
        while {c.name: c.state for c in listing().controller}.get("base_controller") != "running":
            assert rospy.Time.now() < deadline, "base_controller never ran"
            rospy.sleep(0.1)
        while math.hypot(*[getattr(truth()[1], axis) for axis in "xyz"]) > 0.01:  # settled on its wheels
            assert rospy.Time.now() < deadline, "the base never came to rest"
            rospy.sleep(0.1)

    def test_a_odometry_against_ground_truth(self):
        """From rest to rest, so that the odometry and the ground truth are compared at the same places."""
        speed = rospy.get_param("~speed")
        start, _ = truth()
        odom_start = rospy.wait_for_message("/base_controller/odom", Odometry, timeout=10).pose.pose.position
        drive(speed, 4.0)
        _, velocity = truth()
        self.assertAlmostEqual(velocity.x, speed, delta=0.05)
        rospy.sleep(1.5)  # sim time: cmd_vel_timeout 0.25 s, then it brakes
        end, _ = truth()
        odom = rospy.wait_for_message("/base_controller/odom", Odometry, timeout=10)
        travelled = math.hypot(end.x - start.x, end.y - start.y)
        odom_travelled = math.hypot(odom.pose.pose.position.x - odom_start.x, odom.pose.pose.position.y - odom_start.y)
        self.assertGreater(travelled, 0.5 * speed * 4.0)
        self.assertAlmostEqual(odom_travelled, travelled, delta=rospy.get_param("~odometry_tolerance") * travelled)
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ("odom", "base_link"))
        self.assertEqual(odom.pose.covariance[0], 0.001)  # pose_covariance_diagonal of the YAML

    def test_b_velocity_limit_holds(self):
        drive(3.0, 3.0)
        _, velocity = truth()
        self.assertLess(velocity.x, 1.0 + 0.05)
        self.assertGreater(velocity.x, 0.9)

    def test_c_cmd_vel_timeout_stops_it(self):
        drive(0.8, 1.0)
        rospy.sleep(1.0)  # sim time: the timeout is 0.25 s, deceleration at most 3 m/s^2 takes another 0.27 s
        _, velocity = truth()
        self.assertLess(abs(velocity.x), 0.05)


if __name__ == "__main__":
    rospy.init_node("test_ros_control_base")
    rostest.rosrun("turtle_sim_ode", "ros_control_base", BaseControl, sys.argv)
