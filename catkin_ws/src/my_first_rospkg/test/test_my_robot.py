#!/usr/bin/env python3
"""rostest node: our own robot, spawned beside the TurtleBot in namespace /my_robot, drives at the commanded
speed on /my_robot/cmd_vel, its tf tree hangs off odom, and the TurtleBot stays where it is."""
import math
import sys
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry


class MyRobot(unittest.TestCase):
    def test_drives_in_its_namespace(self):
        wanted = rospy.get_param("~speed")
        start = rospy.wait_for_message("/my_robot/odom", Odometry, timeout=60)
        turtlebot_before = rospy.wait_for_message("/ground_truth/odom", Odometry, timeout=30).pose.pose.position
        cmd = rospy.Publisher("/my_robot/cmd_vel", Twist, queue_size=1)
        rate = rospy.Rate(10)
        for tick in range(40):  # 4 s of sim time: 1 s to get up to speed, then 3 s measured
            cmd.publish(Twist(Vector3(wanted, 0, 0), Vector3()))
            if tick == 10:
                first = rospy.wait_for_message("/my_robot/odom", Odometry, timeout=10)
            rate.sleep()
        last = rospy.wait_for_message("/my_robot/odom", Odometry, timeout=10)
        cmd.publish(Twist())
        a, b = first.pose.pose.position, last.pose.pose.position
        speed = math.hypot(b.x - a.x, b.y - a.y) / (last.header.stamp - first.header.stamp).to_sec()
        self.assertAlmostEqual(speed, wanted, delta=wanted * 0.03)
        self.assertAlmostEqual(start.pose.pose.position.y, 1.0, delta=0.01)
        self.assertEqual(last.child_frame_id, "my_robot_base_footprint")

        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        wheel = buffer.lookup_transform("odom", "my_robot_left_wheel", rospy.Time(0), rospy.Duration(10))
        self.assertAlmostEqual(wheel.transform.translation.y, b.y + 0.125, delta=0.05)

        turtlebot_after = rospy.wait_for_message("/ground_truth/odom", Odometry, timeout=10).pose.pose.position
        moved = math.hypot(turtlebot_after.x - turtlebot_before.x, turtlebot_after.y - turtlebot_before.y)
        self.assertLess(moved, 0.005, "the TurtleBot must not move")


if __name__ == "__main__":
    rospy.init_node("test_my_robot")
    rostest.rosrun("my_first_rospkg", "my_robot", MyRobot, sys.argv)
