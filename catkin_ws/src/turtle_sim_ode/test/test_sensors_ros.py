#!/usr/bin/env python3
"""rostest node: the TurtleBot's laser sees a box spawned at a known pose, beams past range are inf (REP 117),
its IMU reads gravity at rest and the commanded yaw rate on a spin, driving into a wall presses the CENTER
bumper and backing off releases it, and lifting the robot makes every cliff sensor see a cliff, then floor."""
import math
import os
import sys
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import DeleteModel, GetModelState, SetModelState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from kobuki_msgs.msg import BumperEvent, CliffEvent
from sensor_msgs.msg import Imu, LaserScan

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")
WALL_SDF = """<sdf version="1.6"><model name="wall"><static>true</static><link name="link">
<collision name="collision"><geometry><box><size>0.1 1.0 0.3</size></box></geometry></collision>
</link></model></sdf>"""


def drive_until(linear, events, wanted, timeout=15.0):
    """Stream a forward speed at 10 Hz until ``wanted`` is among ``events`` (or sim time runs out); then stop."""
    cmd = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=1)
    rate = rospy.Rate(10)
    deadline = rospy.Time.now() + rospy.Duration(timeout)
    while wanted not in events and rospy.Time.now() < deadline:
        cmd.publish(Twist(Vector3(linear, 0, 0), Vector3()))
        rate.sleep()
    cmd.publish(Twist())
    return wanted in events


class SensorsThroughRos(unittest.TestCase):
    def test_1_laser_measures_a_box(self):
        rospy.wait_for_service("/gazebo/spawn_urdf_model", timeout=60)
        with open(os.path.join(MODELS, "box.urdf")) as box_file:
            box = box_file.read()
        spawn = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)
        box_x = rospy.get_param("~box_x")
        result = spawn("scan_target", box, "", Pose(Point(box_x, 0, 0.1), Quaternion(0, 0, 0, 1)), "")
        self.assertTrue(result.success, result.status_message)
        try:
            rospy.sleep(0.5)  # sim time: let the box settle and a scan fall due
            scan = rospy.wait_for_message("/scan", LaserScan, timeout=30)
            self.assertEqual(scan.header.frame_id, "base_scan")
            self.assertEqual(len(scan.ranges), 360)
            expected = box_x - 0.1 - rospy.get_param("~laser_x")
            self.assertAlmostEqual(scan.ranges[0], expected, delta=0.01)
            self.assertTrue(math.isinf(scan.ranges[180]) and scan.ranges[180] > 0, "nothing behind: +inf")
        finally:
            rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)("scan_target")

    def test_2_imu_gravity_and_yaw_rate(self):
        rest = rospy.wait_for_message("/mobile_base/sensors/imu_data", Imu, timeout=30)
        self.assertAlmostEqual(rest.linear_acceleration.z, 9.81, delta=0.0981)
        cmd = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=1)
        rate = rospy.Rate(10)
        for tick in range(30):
            cmd.publish(Twist(Vector3(), Vector3(0, 0, 1.0)))
            if tick == 25:
                spinning = rospy.wait_for_message("/mobile_base/sensors/imu_data", Imu, timeout=10)
            rate.sleep()
        cmd.publish(Twist())
        self.assertAlmostEqual(spinning.angular_velocity.z, 1.0, delta=0.02)

    def test_3_wall_presses_then_releases_the_center_bumper(self):
        events = []
        rospy.Subscriber("/mobile_base/events/bumper", BumperEvent, lambda e: events.append((e.bumper, e.state)))
        robot = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("mobile_base", "world").pose
        q = robot.orientation
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
        ahead = 0.55  # the wall's near face 0.5 m from the base's centre, the bumper's front 0.18 m
        at = Pose(
            Point(robot.position.x + ahead * math.cos(yaw), robot.position.y + ahead * math.sin(yaw), 0.15),
            Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)),
        )
        result = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)("wall", WALL_SDF, "", at, "world")
        self.assertTrue(result.success, result.status_message)
        try:
            self.assertTrue(drive_until(0.2, events, (BumperEvent.CENTER, BumperEvent.PRESSED)), events)
            self.assertNotIn((BumperEvent.LEFT, BumperEvent.PRESSED), events)
            self.assertNotIn((BumperEvent.RIGHT, BumperEvent.PRESSED), events)
            self.assertTrue(drive_until(-0.2, events, (BumperEvent.CENTER, BumperEvent.RELEASED)), events)
            self.assertEqual(events[0], (BumperEvent.CENTER, BumperEvent.PRESSED), "the first event")
        finally:
            rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)("wall")

    def test_4_lifted_robot_sees_cliffs_then_floor(self):
        events = []
        rospy.Subscriber("/mobile_base/events/cliff", CliffEvent, events.append)
        lift = ModelState(model_name="mobile_base", reference_frame="world")
        lift.pose = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("mobile_base", "world").pose
        lift.pose.position.z = 0.3
        self.assertTrue(rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(lift).success)
        deadline = rospy.Time.now() + rospy.Duration(10)
        while sum(e.state == CliffEvent.FLOOR for e in events) < 3 and rospy.Time.now() < deadline:
            rospy.sleep(0.1)
        cliffs = sorted(e.sensor for e in events if e.state == CliffEvent.CLIFF)
        floors = sorted(e.sensor for e in events if e.state == CliffEvent.FLOOR)
        self.assertEqual(cliffs, [CliffEvent.LEFT, CliffEvent.CENTER, CliffEvent.RIGHT], events)
        self.assertEqual(floors, [CliffEvent.LEFT, CliffEvent.CENTER, CliffEvent.RIGHT], events)
        self.assertTrue(all(e.bottom > 4 for e in events if e.state == CliffEvent.CLIFF), events)


if __name__ == "__main__":
    rospy.init_node("test_sensors_ros")
    rostest.rosrun("turtle_sim_ode", "sensors_through_ros", SensorsThroughRos, sys.argv)
