#!/usr/bin/env python3
"""rostest node: the tricycle of models/tricycle_bot.urdf (libgazebo_ros_tricycle_drive.so, odometrySource world,
updateRate 50, publishWheelTF and publishWheelJointState on) through ROS, with a tf_prefix parameter "trike" as
GazeboRos::resolveTF applies it. Straight, it moves at the commanded speed; with angular.z a steering angle d it
goes round a circle of radius wheelbase / tan(d); /odom and tf come in the configured frames at updateRate; a NaN
command is ignored and the simulation goes on."""
import math
import threading
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

WAIT = 90.0
JOINTS = ["front_steering_joint", "front_wheel_joint", "left_wheel_joint", "right_wheel_joint"]


class Odometries:
    """Every /odom message, and a wait until one stamped at or after a sim time has come."""

    def __init__(self):
        self.messages = []
        self._arrived = threading.Condition()
        self._subscriber = rospy.Subscriber("/odom", Odometry, self._on_odom)

    def _on_odom(self, message):
        with self._arrived:
            self.messages.append(message)
            self._arrived.notify_all()

    def at(self, seconds):
        """The first message stamped at or after ``seconds`` of sim time."""
        with self._arrived:
            found = self._arrived.wait_for(
                lambda: self.messages and self.messages[-1].header.stamp.to_sec() >= seconds, WAIT
            )
            if not found:
                raise AssertionError("no /odom stamped at %.3f s within %.0f s" % (seconds, WAIT))
            return next(m for m in self.messages if m.header.stamp.to_sec() >= seconds)


def command(publisher, speed, angle):
    publisher.publish(Twist(linear=Vector3(speed, 0, 0), angular=Vector3(0, 0, angle)))


def circumradius(a, b, c):
    area = abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2
    return math.dist(a, b) * math.dist(b, c) * math.dist(a, c) / (4 * area)


def planar(odom):
    return (odom.pose.pose.position.x, odom.pose.pose.position.y)


class TfPairs:
    """Every (parent, child) pair seen on /tf, and a wait until some have come."""

    def __init__(self):
        self.pairs = set()
        self._arrived = threading.Condition()
        self._subscriber = rospy.Subscriber("/tf", TFMessage, self._on_tf)

    def _on_tf(self, message):
        with self._arrived:
            self.pairs.update((t.header.frame_id, t.child_frame_id) for t in message.transforms)
            self._arrived.notify_all()

    def wait_for(self, wanted):
        with self._arrived:
            self._arrived.wait_for(lambda: set(wanted) <= self.pairs, WAIT)
            return set(self.pairs)


class TricycleDrive(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.odom = Odometries()
        cls.tf = TfPairs()
        cls.commands = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        first = rospy.wait_for_message("/odom", Odometry, WAIT)
        while cls.commands.get_num_connections() == 0 and not rospy.is_shutdown():
            rospy.wait_for_message("/clock", Clock, WAIT)
        cls.start = first.header.stamp.to_sec()

    def test_1_odometry_and_tf_in_the_configured_frames_at_the_update_rate(self):
        begin = self.odom.at(self.start + 0.5).header.stamp.to_sec()
        end = self.odom.at(begin + 2.0).header.stamp.to_sec()
        stamps = [m.header.stamp.to_sec() for m in self.odom.messages if begin <= m.header.stamp.to_sec() <= end]
        rate = (len(stamps) - 1) / (end - begin)
        wanted = rospy.get_param("~update_rate")
        rospy.loginfo("odometry rate %.2f Hz (wanted %.0f)", rate, wanted)
        self.assertAlmostEqual(rate, wanted, delta=wanted * rospy.get_param("~rate_tolerance"))
        last = self.odom.messages[-1]
        self.assertEqual((last.header.frame_id, last.child_frame_id), ("trike/odom", "trike/base_link"))
        diagonal = [last.pose.covariance[7 * i] for i in range(6)]
        self.assertEqual(diagonal, [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3])  # publishOdometry's
        self.assertEqual(list(last.twist.covariance), [0.0] * 36)
        self.assertAlmostEqual(last.pose.pose.position.z, 0.075, delta=0.005)  # world source: the model's z
        # publishOdometry's odom -> base, and publishWheelTF's parent link -> a frame named after each joint.
        wanted = {
            ("trike/odom", "trike/base_link"),
            ("trike/base_link", "trike/front_steering_joint"),
            ("trike/front_steering", "trike/front_wheel_joint"),
            ("trike/base_link", "trike/left_wheel_joint"),
            ("trike/base_link", "trike/right_wheel_joint"),
        }
        self.assertLessEqual(wanted, self.tf.wait_for(wanted))

    def test_2_joint_states_of_the_four_joints(self):
        joints = rospy.wait_for_message("/joint_states", JointState, WAIT)
        self.assertEqual(joints.name, JOINTS)  # publishWheelJointState's order
        self.assertEqual((len(joints.position), len(joints.velocity), list(joints.effort)), (4, 4, [0.0] * 4))

    def test_3_drives_straight_at_the_commanded_speed(self):
        speed = rospy.get_param("~speed")
        command(self.commands, speed, 0.0)
        now = self.odom.messages[-1].header.stamp.to_sec()
        first = self.odom.at(now + 1.0)  # up to speed
        last = self.odom.at(first.header.stamp.to_sec() + 3.0)
        elapsed = (last.header.stamp - first.header.stamp).to_sec()
        (x0, y0), (x1, y1) = planar(first), planar(last)
        measured = math.hypot(x1 - x0, y1 - y0) / elapsed
        rospy.loginfo("straight: %.4f m/s (commanded %.2f)", measured, speed)
        self.assertAlmostEqual(measured, speed, delta=speed * rospy.get_param("~speed_tolerance"))
        self.assertAlmostEqual(last.twist.twist.linear.x, speed, delta=speed * rospy.get_param("~speed_tolerance"))
        self.assertLess(abs(last.twist.twist.linear.y), 0.01)
        heading = math.atan2(y1 - y0, x1 - x0)
        self.assertLess(abs(heading), 0.02)

    def test_4_turns_on_the_circle_the_geometry_implies(self):
        speed, angle = rospy.get_param("~speed"), rospy.get_param("~steering_angle")
        wheelbase = rospy.get_param("~wheelbase")
        command(self.commands, speed, angle)
        now = self.odom.messages[-1].header.stamp.to_sec()
        points = [self.odom.at(now + 1.0)]
        for _ in range(2):
            points.append(self.odom.at(points[-1].header.stamp.to_sec() + 2.0))
        radius = circumradius(*(planar(p) for p in points))
        wanted = wheelbase / math.tan(angle)
        rospy.loginfo("turn: radius %.4f m (geometry %.4f)", radius, wanted)
        self.assertAlmostEqual(radius, wanted, delta=wanted * rospy.get_param("~radius_tolerance"))
        rate = speed * math.sin(angle) / wheelbase  # the yaw rate of that circle at the front wheel's speed
        self.assertAlmostEqual(points[-1].twist.twist.angular.z, rate, delta=rate * rospy.get_param("~speed_tolerance"))

    def test_5_a_nan_command_is_ignored_and_the_sim_goes_on(self):
        before = self.odom.messages[-1]
        turning = before.twist.twist.angular.z
        command(self.commands, float("nan"), 0.0)
        command(self.commands, 0.1, float("nan"))
        later = self.odom.at(before.header.stamp.to_sec() + 1.0)
        values = [later.pose.pose.position.x, later.pose.pose.position.y, later.twist.twist.angular.z]
        self.assertTrue(all(math.isfinite(v) for v in values), values)
        # The last good command (test_4's turn) holds.
        self.assertAlmostEqual(later.twist.twist.angular.z, turning, delta=abs(turning) * 0.05)
        command(self.commands, 0.0, 0.0)
        stopped = self.odom.at(later.header.stamp.to_sec() + 1.0)
        self.assertLess(math.hypot(stopped.twist.twist.linear.x, stopped.twist.twist.linear.y), 0.01)


if __name__ == "__main__":
    rospy.init_node("test_tricycle_drive")
    rostest.rosrun("turtle_sim_ode", "tricycle_drive", TricycleDrive)
