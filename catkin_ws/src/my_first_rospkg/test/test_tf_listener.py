#!/usr/bin/env python3
"""rostest node: drive the TurtleBot and compare tf_listener's distance_from_start with /odom."""
import math
import sys
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64


class TfListenerTest(unittest.TestCase):
    def test_distance_agrees_with_odom(self):
        tolerance = rospy.get_param("~tolerance")
        rospy.wait_for_message("distance_from_start", Float64, timeout=60)  # the start point is taken
        start = rospy.wait_for_message("odom", Odometry, timeout=30).pose.pose.position
        cmd = rospy.Publisher("mobile_base/commands/velocity", Twist, queue_size=1)
        twist = Twist()
        twist.linear.x, twist.angular.z = 0.4, 0.3
        end = rospy.Time.now() + rospy.Duration(4.0)
        rate = rospy.Rate(10)
        while rospy.Time.now() < end:
            cmd.publish(twist)
            rate.sleep()
        cmd.publish(Twist())
        rospy.sleep(1.0)  # sim time: let the robot come to rest and tf_listener look up the resting pose
        odom = rospy.wait_for_message("odom", Odometry, timeout=10).pose.pose.position
        reported = rospy.wait_for_message("distance_from_start", Float64, timeout=10).data
        expected = math.hypot(odom.x - start.x, odom.y - start.y)
        rospy.loginfo("tf_listener: reported [%.4f] m, odom [%.4f] m", reported, expected)
        self.assertGreater(expected, 1.0)
        self.assertAlmostEqual(reported, expected, delta=tolerance)


if __name__ == "__main__":
    rospy.init_node("test_tf_listener")
    rostest.rosrun("my_first_rospkg", "tf_listener", TfListenerTest, sys.argv)
