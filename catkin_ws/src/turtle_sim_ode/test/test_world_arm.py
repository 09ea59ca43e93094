#!/usr/bin/env python3
"""rostest node (issue #31): the column of models/world_arm.urdf stays where it was spawned (its URDF "world" link
welds it, as Gazebo's URDF to SDF conversion does) while the arm moves, and the arm rests where the position
controllers' P gain and gravity put it (world_arm_statics.resting_angles, from the URDF's masses and lengths)."""
import math
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetLinkState
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from world_arm_statics import JOINTS, resting_angles

WAIT = 120.0  # s of wall time for the simulator and the spawner on a loaded machine


class WorldArm(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service("/rrbot/controller_manager/list_controllers", WAIT)
        listing = rospy.ServiceProxy("/rrbot/controller_manager/list_controllers", ListControllers)
        wanted = {f"{joint}_position_controller" for joint in JOINTS} | {"joint_state_controller"}
        while {c.name for c in listing().controller if c.state == "running"} != wanted:
            rospy.sleep(0.1)  # sim time; the test's time-limit bounds it
        rospy.wait_for_service("/gazebo/get_link_state", WAIT)
        cls.link_state = rospy.ServiceProxy("/gazebo/get_link_state", GetLinkState)

    def column(self):
        state = self.link_state("rrbot::column", "world")
        self.assertTrue(state.success, state.status_message)
        p, q = state.link_state.pose.position, state.link_state.pose.orientation
        return (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)

    def test_column_welded_and_arm_at_rest_where_gain_and_gravity_put_it(self):
        start, orientation = self.column()
        targets = rospy.get_param("~targets")
        commands = [
            rospy.Publisher(f"/rrbot/{joint}_position_controller/command", Float64, queue_size=1, latch=True)
            for joint in JOINTS
        ]
        for joint, command in zip(JOINTS, commands):
            command.publish(Float64(targets[joint]))
        deadline = rospy.get_time() + rospy.get_param("~settle_limit")
        states = rospy.wait_for_message("/rrbot/joint_states", JointState, WAIT)
        while max(abs(v) for v in states.velocity) > 1e-3 or rospy.get_time() < 2.0:
            self.assertLess(rospy.get_time(), deadline, "the arm never came to rest: %s" % (states,))
            states = rospy.wait_for_message("/rrbot/joint_states", JointState, WAIT)
        gain = rospy.get_param("/rrbot/shoulder_position_controller/pid/p")
        self.assertEqual(gain, rospy.get_param("/rrbot/elbow_position_controller/pid/p"))
        expected = resting_angles([targets[joint] for joint in JOINTS], gain)
        positions = dict(zip(states.name, states.position))
        tolerance = rospy.get_param("~angle_tolerance")
        for joint, angle in zip(JOINTS, expected):
            self.assertAlmostEqual(positions[joint], angle, delta=tolerance, msg=joint)
        # the offsets gravity leaves are several tolerances: a stiffer hold would fail above
        self.assertGreater(abs(expected[0] - targets["shoulder"]), 10 * tolerance)
        weld = rospy.get_param("~weld_tolerance")
        position, now = self.column()
        self.assertLess(math.dist(position, start), weld)
        self.assertLess(math.dist(now, orientation), weld)
        self.assertLess(math.dist(position, (0.0, 0.0, 0.0)), weld)


if __name__ == "__main__":
    rospy.init_node("test_world_arm")
    rostest.rosrun("turtle_sim_ode", "world_arm", WorldArm)
