#!/usr/bin/env python3
"""rostest node for turtlebot_world.launch as typed: a kobuki_msgs subscriber that is there before the robot spawns
does not stop the spawn; the description has 34 links; the multiplexer is idle, then lets navigation drive and
teleoperation take over; /scan comes from the depth image in camera_depth_frame and sees the bookshelf; driving on
into the bookshelf presses the CENTER bumper. The robot is turned to face the bookshelf first."""
import math
import sys
import threading
import unittest
import xml.etree.ElementTree as ET

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetModelState, SetModelState
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from kobuki_msgs.msg import BumperEvent
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

# Where the playground's bookshelf stands (worlds/playground.world): its front board at y = 1.53 - 0.39, its back
# board's face at 1.53; between the bottom board and the lowest shelf, the scan's rows see the back board.
BOOKSHELF_FRONT_Y = 1.14
BOOKSHELF_BACK_Y = 1.53
KOBUKI_RADIUS = 0.176
# The depth image is taken from camera_link, as Gazebo's sensor sits on its link: 0.118 m behind base_link
# (turtlebot_description's Kinect: the RGB frame at x -0.087, the body 0.031 behind it).
CAMERA_BEHIND_BASE = 0.118


class Recorder:
    def __init__(self, topic, kind):
        self.messages = []
        self._cond = threading.Condition()
        self.sub = rospy.Subscriber(topic, kind, self._on, queue_size=50)

    def _on(self, msg):
        with self._cond:
            self.messages.append(msg)
            self._cond.notify_all()

    def wait_for(self, predicate, timeout):
        with self._cond:
            return self._cond.wait_for(lambda: any(predicate(m) for m in self.messages), timeout)


# Subscribed at import, before the launch's spawn_model can have spawned the robot.
BUMPER = None


def stream(topic, linear, until, timeout):
    """Publish a forward speed on `topic` at 10 Hz (sim time) until until() holds or timeout s of sim time pass."""
    pub = rospy.Publisher(topic, Twist, queue_size=1)
    rate = rospy.Rate(10)
    deadline = rospy.Time.now() + rospy.Duration(timeout)
    while not until() and rospy.Time.now() < deadline:
        pub.publish(Twist(Vector3(linear, 0, 0), Vector3()))
        rate.sleep()
    pub.publish(Twist())
    return until()


class TurtlebotWorld(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.timeout = rospy.get_param("~timeout")
        rospy.wait_for_service("/gazebo/get_model_state", cls.timeout)
        cls.get_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        # spawn_model unpauses once the robot is in: the first odometry means it is there
        rospy.wait_for_message("/odom", Odometry, cls.timeout)
        # turn the robot to face the bookshelf (+y)
        facing_y = Pose(Point(0, 0, 0), Quaternion(0, 0, math.sqrt(0.5), math.sqrt(0.5)))
        turn = ModelState("mobile_base", facing_y, Twist(), "")
        result = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(turn)
        assert result.success, result.status_message

    def pose(self):
        state = self.get_state("mobile_base", "")
        self.assertTrue(state.success, state.status_message)
        return state.pose

    def test_1_spawned_with_the_description_upstreams_launch_picks(self):
        self.assertTrue(self.get_state("mobile_base", "").success)
        links = ET.fromstring(rospy.get_param("/robot_description")).findall("link")
        self.assertEqual(len(links), 34)  # as turtlebot_description's kobuki_hexagons_kinect
        self.assertEqual(BUMPER.sub.get_num_connections(), 1, "the early kobuki_msgs subscriber is not connected")

    def test_2_mux_idle_then_navigation_then_teleop(self):
        active = rospy.wait_for_message("/cmd_vel_mux/active", String, self.timeout)
        self.assertEqual(active.data, "idle")
        actives = Recorder("/cmd_vel_mux/active", String)
        odom = Recorder("/odom", Odometry)
        start = self.pose().position
        moved = lambda: math.hypot(self.pose().position.x - start.x, self.pose().position.y - start.y) > 0.05
        self.assertTrue(stream("/cmd_vel_mux/input/navi", 0.1, moved, 10.0), "navigation did not move the robot")
        self.assertTrue(actives.wait_for(lambda m: m.data == "Navigation", self.timeout))
        stream("/cmd_vel_mux/input/teleop", 0.0, lambda: False, 0.5)
        self.assertTrue(actives.wait_for(lambda m: m.data == "Teleoperation", self.timeout))
        self.assertTrue(actives.wait_for(lambda m: m.data == "idle", self.timeout), "teleop never timed out")
        self.assertTrue(odom.messages, "no /odom")
        self.assertEqual(odom.messages[-1].child_frame_id, "base_footprint")

    def test_3_scan_from_the_depth_image_sees_the_bookshelf(self):
        scan = rospy.wait_for_message("/scan", LaserScan, self.timeout)
        self.assertEqual(scan.header.frame_id, "camera_depth_frame")
        self.assertEqual(len(scan.ranges), 640)
        self.assertAlmostEqual(scan.range_min, 0.45, places=5)
        self.assertAlmostEqual(scan.angle_max - scan.angle_min, math.radians(60), delta=0.01)
        ahead = scan.ranges[len(scan.ranges) // 2]
        expected = BOOKSHELF_BACK_Y - self.pose().position.y + CAMERA_BEHIND_BASE
        self.assertAlmostEqual(ahead, expected, delta=0.03)

    def test_4_bumping_the_bookshelf_presses_center(self):
        pressed = lambda: any(
            e.bumper == BumperEvent.CENTER and e.state == BumperEvent.PRESSED for e in BUMPER.messages
        )
        self.assertTrue(stream("/mobile_base/commands/velocity", 0.2, pressed, 20.0), (BUMPER.messages, self.pose()))
        self.assertAlmostEqual(self.pose().position.y, BOOKSHELF_FRONT_Y - KOBUKI_RADIUS, delta=0.05)


if __name__ == "__main__":
    rospy.init_node("test_turtlebot_world")
    BUMPER = Recorder("/mobile_base/events/bumper", BumperEvent)
    rostest.rosrun("turtlebot_gazebo", "turtlebot_world", TurtlebotWorld, sys.argv)
