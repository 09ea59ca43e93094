#!/usr/bin/env python3
"""rostest node: drive the simulated TurtleBot through /mobile_base/commands/velocity and check what it did
against the simulator's ground truth, with sim time (the simulator runs faster than real time)."""
import math
import sys
import threading
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Empty


def planar(odom: Odometry):
    p, q = odom.pose.pose.position, odom.pose.pose.orientation
    return p.x, p.y, math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


class Latest:
    """The newest message of a topic, with a way to wait for one newer than a given stamp."""

    def __init__(self, topic, msg_type):
        self.msg = None
        self._changed = threading.Condition()
        self._sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=1)

    def _on_msg(self, msg):
        with self._changed:
            self.msg = msg
            self._changed.notify_all()

    def wait_newer(self, stamp=rospy.Time(0), timeout=30.0):
        with self._changed:
            ok = self._changed.wait_for(lambda: self.msg is not None and self._stamp(self.msg) > stamp, timeout)
        assert ok, "no message on %s newer than %s within %s s (wall)" % (self._sub.name, stamp.to_sec(), timeout)
        return self.msg

    @staticmethod
    def _stamp(msg):
        return msg.clock if isinstance(msg, Clock) else msg.header.stamp


class DriveThroughRos(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cmd = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=1)
        cls.reset = rospy.Publisher("/mobile_base/commands/reset_odometry", Empty, queue_size=1)
        cls.truth = Latest("/ground_truth/odom", Odometry)
        cls.odom = Latest("/odom", Odometry)
        cls.joints = Latest("/joint_states", JointState)
        cls.clock = Latest("/clock", Clock)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        cls.truth.wait_newer()

    def drive(self, linear, angular, seconds):
        """Send a command at 10 Hz of sim time for `seconds` of sim time, then a stop, as a well-behaved node does.
        Returns the last ground truth received while the command was still being sent."""
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        end = rospy.Time.now() + rospy.Duration(seconds)
        rate = rospy.Rate(10)
        while rospy.Time.now() < end:
            self.cmd.publish(twist)
            truth_while_driving = self.truth.msg
            rate.sleep()
        self.cmd.publish(Twist())
        return truth_while_driving

    def rest(self, seconds=1.0):
        rospy.sleep(seconds)
        return planar(self.truth.wait_newer(rospy.Time.now()))

    def test_1_clock_advances_and_stamps_agree(self):
        first = self.clock.wait_newer().clock
        later = self.clock.wait_newer(first + rospy.Duration(0.5)).clock
        self.assertGreater(later, first)
        odom = self.odom.wait_newer(later)
        joints = self.joints.wait_newer(odom.header.stamp - rospy.Duration(0.001))
        self.assertEqual(joints.name, ["wheel_left_joint", "wheel_right_joint"])
        self.assertEqual(joints.header.frame_id, "base_link")  # kobuki_gazebo_plugins: resolveTF("base_link")
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ("odom", "base_footprint"))
        transform = self.tf_buffer.lookup_transform("odom", "base_footprint", odom.header.stamp, rospy.Duration(5))
        self.assertAlmostEqual(transform.transform.translation.x, odom.pose.pose.position.x, places=9)

    def test_2_straight_line(self):
        start = self.rest()
        self.drive(0.3, 0.0, 5.0)
        end = self.rest()
        distance = math.hypot(end[0] - start[0], end[1] - start[1])
        self.assertAlmostEqual(distance, 1.5, delta=rospy.get_param("~distance_tolerance"))

    def test_3_timeout_stops_the_robot(self):
        twist = Twist()
        twist.linear.x = 0.3
        self.cmd.publish(twist)  # once, and no stop: the watchdog must stop it
        rospy.sleep(rospy.get_param("~cmd_timeout") + 0.5)
        stopped = planar(self.truth.wait_newer(rospy.Time.now()))
        later = self.rest(2.0)
        self.assertLess(math.hypot(later[0] - stopped[0], later[1] - stopped[1]), 0.001)

    def test_4_nan_ignored_and_clamped(self):
        self.drive(float("nan"), 0.0, 1.0)
        pose = planar(self.truth.wait_newer(rospy.Time.now()))
        self.assertTrue(all(math.isfinite(v) for v in pose))
        speed = self.drive(50.0, 0.0, 3.0).twist.twist.linear.x
        self.assertAlmostEqual(speed, rospy.get_param("~max_linear"), delta=0.03)
        self.rest()

    def test_5_reset_odometry(self):
        self.drive(0.3, 0.5, 2.0)
        self.rest()
        self.reset.publish(Empty())
        rospy.sleep(0.5)
        x, y, yaw = planar(self.odom.wait_newer(rospy.Time.now()))
        self.assertLess(math.hypot(x, y), 1e-3)
        self.assertLess(abs(yaw), 1e-3)


if __name__ == "__main__":
    rospy.init_node("test_drive")
    rostest.rosrun("turtle_sim_ode", "drive_through_ros", DriveThroughRos, sys.argv)
