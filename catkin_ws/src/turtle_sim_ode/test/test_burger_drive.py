#!/usr/bin/env python3
"""rostest node: a URDF written the way turtlebot3 writes its burger (libgazebo_ros_diff_drive.so tags) is
spawned with spawn_model and drives at the commanded speed; its p3d ground truth and world odometry agree."""
import math
import sys
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState


class BurgerDrive(unittest.TestCase):
    def test_drives_at_commanded_speed(self):
        wanted = rospy.get_param("~speed")
        truth = rospy.wait_for_message("/ground_truth/burger", Odometry, timeout=60)
        self.assertEqual(truth.header.frame_id, "world")
        cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        rate = rospy.Rate(10)
        start = None
        for tick in range(60):  # 6 s of sim time at 10 Hz: 2 s to get up to speed, 4 s measured
            cmd.publish(Twist(linear=type(Twist().linear)(wanted, 0, 0)))
            if tick == 20:
                start = (rospy.wait_for_message("/ground_truth/burger", Odometry, timeout=10), rospy.Time.now())
            rate.sleep()
        end = rospy.wait_for_message("/ground_truth/burger", Odometry, timeout=10)
        cmd.publish(Twist())
        first, last = start[0].pose.pose.position, end.pose.pose.position
        elapsed = (end.header.stamp - start[0].header.stamp).to_sec()
        speed = math.hypot(last.x - first.x, last.y - first.y) / elapsed
        self.assertAlmostEqual(speed, wanted, delta=wanted * rospy.get_param("~tolerance"))
        odom = rospy.wait_for_message("/odom", Odometry, timeout=10)
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ("odom", "base_footprint"))
        joints = rospy.wait_for_message("/joint_states", JointState, timeout=10)
        self.assertEqual(joints.name, ["wheel_left_joint", "wheel_right_joint"])


if __name__ == "__main__":
    rospy.init_node("test_burger_drive")
    rostest.rosrun("turtle_sim_ode", "burger_drive", BurgerDrive, sys.argv)
