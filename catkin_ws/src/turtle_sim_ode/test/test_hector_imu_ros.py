#!/usr/bin/env python3
"""hector_gazebo_plugins' IMU (models/hector_imu_box.urdf) through ROS: sensor_msgs/Imu on raw_imu, and the
dynamic_reconfigure servers raw_imu/accel, raw_imu/rate and raw_imu/yaw that GazeboRosIMU::Load sets up
(hector_gazebo_plugins/src/gazebo_ros_imu.cpp), with SensorModel_::dynamicReconfigureCallback's semantics
(include/hector_gazebo_plugins/sensor_model.h): the first configuration reports the tags (a vector's as the mean
of its axes), a change sets every axis of the model, and the next readings follow it."""
import math
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from sensor_msgs.msg import Imu

WAIT = 90.0


class HectorImuRos(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        cls.gravity = float(rospy.get_param("~gravity"))
        cls.tolerance = float(rospy.get_param("~accel_tolerance"))

    def client(self, name: str) -> Client:
        return Client("/raw_imu/" + name, timeout=WAIT)

    def test_1_reads_gravity_with_the_tag_offsets(self) -> None:
        imu = rospy.wait_for_message("/raw_imu", Imu, WAIT)
        self.assertEqual(imu.header.frame_id, "base_link")
        # accelGaussianNoise 0.3: Load's constant covariance 0.09; Update's tilt covariance 0.09 / g^2
        self.assertAlmostEqual(imu.linear_acceleration_covariance[0], 0.09, places=9)
        self.assertAlmostEqual(imu.orientation_covariance[0], 0.09 / self.gravity**2, places=9)

    def test_2_first_configuration_reports_the_tags(self) -> None:
        accel = self.client("accel").get_configuration(timeout=WAIT)
        # accelOffset 0.1 0.2 0.6: scalar_value is the mean of the axes
        self.assertAlmostEqual(accel["offset"], 0.3, places=9)
        self.assertAlmostEqual(accel["gaussian_noise"], 0.3, places=9)
        self.assertAlmostEqual(accel["drift_frequency"], 1.0 / 3600.0, places=12)  # SensorModel_()'s default
        self.assertAlmostEqual(accel["scale_error"], 1.0, places=9)
        yaw = self.client("yaw").get_configuration(timeout=WAIT)
        self.assertAlmostEqual(yaw["offset"], 0.05, places=9)
        rate = self.client("rate").get_configuration(timeout=WAIT)
        self.assertEqual((rate["offset"], rate["drift"], rate["gaussian_noise"]), (0.0, 0.0, 0.0))

    def test_3_a_change_sets_every_axis_and_the_readings_follow(self) -> None:
        values = {"gaussian_noise": 0.0, "offset": 1.0, "drift": 0.0, "drift_frequency": 0.0, "scale_error": 1.0}
        answer = self.client("accel").update_configuration(values)
        for name, value in values.items():
            self.assertAlmostEqual(answer[name], value, places=9)
        imu = rospy.wait_for_message("/raw_imu", Imu, WAIT)
        measured = imu.linear_acceleration
        for got, expected in zip((measured.x, measured.y, measured.z), (1.0, 1.0, self.gravity + 1.0)):
            self.assertAlmostEqual(got, expected, delta=self.tolerance)
        self.assertEqual(imu.orientation_covariance[0], 0.0)  # Update: from the accel noise of now
        self.assertAlmostEqual(imu.linear_acceleration_covariance[0], 0.09, places=9)  # Load: constant
        bias = rospy.wait_for_message("/raw_imu/bias", Imu, WAIT).linear_acceleration
        self.assertEqual((bias.x, bias.y, bias.z), (1.0, 1.0, 1.0))

    def test_4_a_non_finite_value_is_refused(self) -> None:
        client = self.client("accel")
        before = client.get_configuration(timeout=WAIT)
        answer = client.update_configuration({"offset": math.nan})
        self.assertEqual(answer["offset"], before["offset"])
        imu = rospy.wait_for_message("/raw_imu", Imu, WAIT)  # the simulator goes on
        self.assertTrue(math.isfinite(imu.linear_acceleration.x))


if __name__ == "__main__":
    rospy.init_node("test_hector_imu_ros")
    rostest.rosrun("turtle_sim_ode", "hector_imu", HectorImuRos)
