#!/usr/bin/env python3
"""The force plugins through ROS (test/models/ft_gantry.urdf, push_box.urdf). Expected values from upstream:
gazebo_ros_ft_sensor.cpp GazeboRosFT::UpdateChild (body2 of ODEJoint::GetForceTorque: what the child pulls on the
joint with, in the child link's frame, stamped with its name, at updateRate), gazebo_ros_f3d.cpp
GazeboRosF3D::UpdateChild (ODELink's force and torque: the total on the body, gravity and constraints included,
gazebo-classic deps/opende quickstep; stamped with frameName) and gazebo_ros_force.cpp GazeboRosForce::UpdateChild
(the last wrench added every step, in the world frame)."""
import math
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Wrench, WrenchStamped
from rosgraph_msgs.msg import Clock

WAIT = 90.0
G = 9.81
RATE = 50.0  # the wrist sensor's <updateRate>
STEP = 0.001  # the empty world's physics step


def vector(v):
    return (v.x, v.y, v.z)


def wait_sim(seconds):
    """Until /clock has gone ``seconds`` on (sim time, waited for on /clock)."""
    start = rospy.wait_for_message("/clock", Clock, WAIT).clock.to_sec()
    while rospy.wait_for_message("/clock", Clock, WAIT).clock.to_sec() < start + seconds:
        pass
    return start


def collect(topic, count, after=0.0):
    """``count`` messages of ``topic`` stamped after sim time ``after``."""
    got = []
    subscriber = rospy.Subscriber(
        topic, WrenchStamped, lambda m: got.append(m) if m.header.stamp.to_sec() > after else 0
    )
    try:
        while len(got) < count and not rospy.is_shutdown():
            rospy.wait_for_message("/clock", Clock, WAIT)
    finally:
        subscriber.unregister()
    return got[:count]


class Forces(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.payload_mass = rospy.get_param("~payload_mass")
        cls.box_mass = rospy.get_param("~box_mass")
        cls.tolerance = rospy.get_param("~force_tolerance")
        cls.relative = rospy.get_param("~acceleration_tolerance")

    def assertVector(self, got, expected, delta, what):
        for axis, (g, e) in enumerate(zip(got, expected)):
            self.assertAlmostEqual(g, e, delta=delta, msg="%s[%d]: %r, expected %r" % (what, axis, got, expected))

    def test_1_ft_sensor_reads_the_payload_weight_at_its_rate(self):
        messages = collect("/wrist_ft", 11, after=1.0)  # the gantry settled on the floor
        for message in messages:
            self.assertEqual(message.header.frame_id, "payload")
            self.assertVector(vector(message.wrench.force), (0, 0, -self.payload_mass * G), self.tolerance, "force")
            self.assertVector(vector(message.wrench.torque), (0, 0, 0), self.tolerance, "torque")
        rospy.loginfo(
            "wrist ft force %s torque %s", vector(messages[-1].wrench.force), vector(messages[-1].wrench.torque)
        )
        stamps = [m.header.stamp.to_sec() for m in messages]
        for earlier, later in zip(stamps, stamps[1:]):
            self.assertAlmostEqual(later - earlier, 1.0 / RATE, delta=STEP * 1.1)
        published = {name for name, _ in rospy.get_published_topics()}
        self.assertIn("/wrist_ft", published)
        self.assertNotIn("/beam_ft", published)  # beam_joint is fixed: merged, as Gazebo lumps it

    def test_2_f3d_payload_at_rest_is_balanced(self):
        (message,) = collect("/payload_force", 1, after=1.0)
        self.assertEqual(message.header.frame_id, "world")
        self.assertVector(vector(message.wrench.force), (0, 0, 0), self.tolerance, "force")

    def test_3_force_moves_the_box_and_f3d_reads_it(self):
        state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        rospy.wait_for_service("/gazebo/get_model_state", WAIT)
        push = rospy.Publisher("/box_wrench", Wrench, queue_size=1, latch=True)
        wrench = Wrench()
        wrench.force.x, wrench.force.z = 2.0, 19.81  # 1 kg: (2, 0, 10) m/s² with gravity
        wrench.torque.z = 0.05
        push.publish(wrench)
        expected = (2.0, 0.0, 19.81 - self.box_mass * G)
        lifted = []
        subscriber = rospy.Subscriber(
            "/box_force", WrenchStamped, lambda m: lifted.append(m) if m.wrench.force.z > 5 else 0
        )
        while len(lifted) < 5 and not rospy.is_shutdown():
            rospy.wait_for_message("/clock", Clock, WAIT)
        subscriber.unregister()
        for message in lifted[1:5]:  # the first may still be the step the box left the floor
            self.assertEqual(message.header.frame_id, "map")
            self.assertVector(vector(message.wrench.force), expected, 1e-3, "f3d force")
            self.assertVector(vector(message.wrench.torque), (0, 0, 0.05), 1e-3, "f3d torque")
        first = state("push_box", "")
        wait_sim(0.5)
        second = state("push_box", "")
        span = (second.header.stamp - first.header.stamp).to_sec()
        self.assertGreater(span, 0.4)
        acceleration = [(b - a) / span for a, b in zip(vector(first.twist.linear), vector(second.twist.linear))]
        rospy.loginfo("box acceleration %s over %.3f s; f3d %s", acceleration, span, vector(lifted[-1].wrench.force))
        for got, want in zip(acceleration, [f / self.box_mass for f in expected]):
            self.assertAlmostEqual(got, want, delta=self.relative * 10.0, msg="acceleration %r" % acceleration)
        Forces.push = push

    def test_4_non_finite_wrench_is_ignored(self):
        bad = Wrench()
        bad.force.x, bad.torque.y = float("nan"), float("inf")
        Forces.push.publish(bad)
        start = wait_sim(0.3)
        (message,) = collect("/box_force", 1, after=start + 0.3)
        self.assertVector(vector(message.wrench.force), (2.0, 0.0, 19.81 - self.box_mass * G), 1e-3, "kept force")
        self.assertTrue(all(math.isfinite(v) for v in vector(message.wrench.torque)))


if __name__ == "__main__":
    rospy.init_node("test_forces")
    rostest.rosrun("turtle_sim_ode", "forces", Forces)
