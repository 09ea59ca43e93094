#!/usr/bin/env python3
"""rostest node: the TurtleBot's laser sees a box spawned at a known pose, beams past range are inf (REP 117),
and its IMU reads gravity at rest and the commanded yaw rate on a spin."""
import math
import os
import sys
import unittest

import rospy
import rostest
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from sensor_msgs.msg import Imu, LaserScan

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")


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


if __name__ == "__main__":
    rospy.init_node("test_sensors_ros")
    rostest.rosrun("turtle_sim_ode", "sensors_through_ros", SensorsThroughRos, sys.argv)
