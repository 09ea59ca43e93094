#!/usr/bin/env python3
"""rostest node: libgazebo_ros_vacuum_gripper.so on the gantry of models/vacuum_gripper_arm.urdf, whose plugin has
<robotNamespace>/arm/vacuum_gripper and <topicName>grasping: std_srvs/Empty /arm/vacuum_gripper/on and off, and
std_msgs/Bool /arm/vacuum_gripper/grasping at every step (GazeboRosVacuumGripper::Load, UpdateChild). A 0.04 m box
spawned under the end effector (its centre 0.032 m from the end effector's origin, within upstream's 0.05 m) is not
touched while off, is drawn up against it when on (grasping true), rides up with the boom lifted by
/gazebo/apply_joint_effort to its 0.2 m stop, and falls back to the ground when off (grasping false)."""
import os
import sys
import unittest

import rospy
import rostest
from std_msgs.msg import Bool
from std_srvs.srv import Empty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gazebo_clients import connect_gazebo_services, model_text, pose  # noqa: E402

NS = "/arm/vacuum_gripper"
WAIT = 60.0  # s of sim time (or wall time for the first messages)
BOX_AT = (0.45, 0.0, 0.02)  # on the ground under the end effector
TIP_DOWN, TIP_UP = 0.052, 0.252  # the end effector's origin at the lift's stops (0 and 0.2 m)
HELD_BELOW = 0.03  # a held box's centre under the end effector's origin: half the box + half the end effector


def wait_until(predicate, seconds, what):
    deadline = rospy.Time.now() + rospy.Duration(seconds)
    while not predicate():
        if rospy.Time.now() > deadline:
            raise AssertionError("timed out (sim time) waiting for " + what)
        rospy.sleep(0.05)


class VacuumGripper(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        connect_gazebo_services(cls)
        for name in ("on", "off"):
            rospy.wait_for_service(NS + "/" + name, timeout=WAIT)
        cls.on = rospy.ServiceProxy(NS + "/on", Empty)
        cls.off = rospy.ServiceProxy(NS + "/off", Empty)
        cls.tolerance = rospy.get_param("~height_tolerance")
        result = cls.spawn_sdf_model("box", model_text("small_box.sdf"), "", pose(*BOX_AT), "")
        assert result.success, result.status_message

    def grasping(self):
        return rospy.wait_for_message(NS + "/grasping", Bool, timeout=WAIT).data

    def wait_grasping(self, wanted):
        wait_until(lambda: self.grasping() == wanted, 10.0, "grasping %s" % wanted)

    def heights(self):
        tip = self.get_link_state("arm::vacuum_gripper", "").link_state.pose.position.z
        return tip, self.get_model_state("box", "").pose.position.z

    def lift(self):
        return self.get_joint_properties("lift").position[0]

    def test_1_off_leaves_the_box_alone(self):
        self.assertFalse(self.grasping())
        tip, box = self.heights()
        self.assertAlmostEqual(tip, TIP_DOWN, delta=self.tolerance)
        self.assertAlmostEqual(box, BOX_AT[2], delta=self.tolerance)

    def test_2_on_draws_the_box_up_and_grasps(self):
        self.on()
        self.wait_grasping(True)
        wait_until(lambda: self.heights()[1] > BOX_AT[2] + 0.001, 5.0, "the box drawn up")
        tip, box = self.heights()
        self.assertAlmostEqual(tip, TIP_DOWN, delta=self.tolerance)  # the heavy boom stays on its stop
        self.assertAlmostEqual(box, tip - HELD_BELOW, delta=self.tolerance)

    def near(self, tip, box):
        """Whether the end effector and the box are at these heights (within the tolerance)."""
        now = self.heights()
        rospy.loginfo("end effector at z %.4f m, box at z %.4f m (sim time %.3f s)", now[0], now[1], rospy.get_time())
        return abs(now[0] - tip) <= self.tolerance and abs(now[1] - box) <= self.tolerance

    def test_3_lifting_the_boom_carries_the_box(self):
        result = self.apply_joint_effort("lift", 40.0, rospy.Time(0), rospy.Duration(-1))
        self.assertTrue(result.success, result.status_message)
        wait_until(lambda: self.lift() > 0.195, 10.0, "the lift at its upper stop")
        wait_until(lambda: self.near(TIP_UP, TIP_UP - HELD_BELOW), 5.0, "the box held under the lifted end effector")
        self.assertTrue(self.grasping())

    def test_4_off_drops_the_box(self):
        self.off()
        self.wait_grasping(False)
        wait_until(lambda: self.near(TIP_UP, BOX_AT[2]), 10.0, "the box back on the ground, the boom still up")
        self.assertFalse(self.grasping())

    def test_5_bad_grippers_are_refused_or_left_out(self):
        """A second gripper on the same services is refused at spawn (success false, the services named); a gripper
        link lumped by a fixed joint leaves the model without the plugin (GazeboRosVacuumGripper::Load's fatal
        "link ... does not exist"), as upstream."""
        arm = model_text("vacuum_gripper_arm.urdf")
        result = self.spawn_urdf_model("arm2", arm, "", pose(y=1.0), "")
        self.assertFalse(result.success)
        self.assertIn(NS + "/on", result.status_message)
        self.assertFalse(self.get_model_state("arm2", "").success)  # nothing of it stays
        self.off()  # the first gripper's services and topic still serve
        self.assertFalse(self.grasping())
        lumped = arm.replace("<bodyName>vacuum_gripper<", "<bodyName>post<").replace(NS, "/arm3/vacuum_gripper")
        result = self.spawn_urdf_model("arm3", lumped, "", pose(y=-1.0), "")
        self.assertTrue(result.success, result.status_message)
        with self.assertRaises(rospy.ROSException):
            rospy.wait_for_service("/arm3/vacuum_gripper/on", timeout=1.0)


if __name__ == "__main__":
    rospy.init_node("test_vacuum_gripper")
    rostest.rosrun("turtle_sim_ode", "vacuum_gripper", VacuumGripper)
