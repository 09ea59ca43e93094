#!/usr/bin/env python3
"""Issue 23's acceptance, through ROS: the SMB-like robot of launch/smb_gazebo.launch publishes /rslidar_points (a
VelodyneLaser cloud in frame rslidar whose points on the pillar lie 1.0 m from its axis), /scan (from
pointcloud_to_laserscan), /imu0 (hector IMU) and /odom (skid steer), and drives on /cmd_vel: an exercise-style P
controller that reads the closest point of /scan reaches the pillar 20 m away."""
import math
import struct
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, LaserScan, PointCloud2

WAIT = 150.0  # s of wall time for the simulator, the spawn and the first messages on a loaded machine


def rotate(q, v):
    """v rotated by the unit quaternion q (x, y, z, w)."""
    x, y, z, w = q
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def points_of(cloud):
    offsets = {field.name: field.offset for field in cloud.fields}
    for index in range(cloud.width * cloud.height):
        base = index * cloud.point_step
        yield tuple(struct.unpack_from("<f", cloud.data, base + offsets[axis])[0] for axis in "xyz")


class Smb(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service("/gazebo/get_model_state", WAIT)
        cls.model_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        cls.axis = rospy.get_param("~pillar_axis")
        cls.radius = rospy.get_param("~pillar_radius")
        # spawn_model drops the robot from 0.4 m: the tests begin once it rests on its wheels.
        settled = rospy.get_param("~settled_after")
        while rospy.get_time() < settled and not rospy.is_shutdown():
            rospy.sleep(0.1)  # sim time

    def pose(self):
        state = self.model_state("smb", "world")
        self.assertTrue(state.success, state.status_message)
        p, q = state.pose.position, state.pose.orientation
        return (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)

    def test_1_velodyne_points_lie_on_the_pillar(self):
        cloud = rospy.wait_for_message("/rslidar_points", PointCloud2, WAIT)
        self.assertEqual(cloud.header.frame_id, "rslidar")
        self.assertEqual([f.name for f in cloud.fields], ["x", "y", "z", "intensity", "ring", "time"])
        self.assertEqual((cloud.point_step, cloud.height, cloud.is_dense), (22, 1, True))
        (px, py, pz), q = self.pose()  # the robot stands still until test_4 drives it
        lift = rospy.get_param("~lidar_height")
        tolerance = rospy.get_param("~cylinder_tolerance")
        on_pillar = 0
        for point in points_of(cloud):
            wx, wy, wz = rotate(q, (point[0], point[1], point[2] + lift))
            wx, wy, wz = wx + px, wy + py, wz + pz
            off_axis = math.hypot(wx - self.axis[0], wy - self.axis[1])
            if wz > 0.05 and off_axis < self.radius + 0.5:
                on_pillar += 1
                self.assertLess(abs(off_axis - self.radius), tolerance, (point, off_axis))
        self.assertGreater(on_pillar, 50)

    def test_2_imu0_reads_gravity(self):
        imu = rospy.wait_for_message("/imu0", Imu, WAIT)
        self.assertEqual(imu.header.frame_id, "imu_link")
        self.assertAlmostEqual(imu.linear_acceleration.z, 9.8, delta=0.5)

    def test_3_scan_sees_the_pillar(self):
        scan = rospy.wait_for_message("/scan", LaserScan, WAIT)
        self.assertEqual(scan.header.frame_id, "rslidar")
        closest = min(scan.ranges)
        (px, py, _), _ = self.pose()
        expected = math.hypot(self.axis[0] - px, self.axis[1] - py) - self.radius
        self.assertAlmostEqual(closest, expected, delta=0.1)

    def test_4_a_p_controller_reaches_the_pillar(self):
        """As the exercise's: turn towards the closest point of /scan, drive at a speed proportional to its distance."""
        commands = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        odometry = []
        rospy.Subscriber("/odom", Odometry, odometry.append)
        stop = rospy.get_param("~stop_distance")
        closest = [math.inf]

        def steer(scan):
            ranges = scan.ranges
            index = min(range(len(ranges)), key=lambda i: ranges[i])
            closest[0] = ranges[index]
            angle = scan.angle_min + index * scan.angle_increment
            twist = Twist()
            if ranges[index] > stop:
                twist.linear.x = min(1.0, 0.5 * (ranges[index] - stop) + 0.2)
                twist.angular.z = 1.5 * angle
            commands.publish(twist)

        rospy.Subscriber("/scan", LaserScan, steer, queue_size=1)
        start = rospy.get_time()
        limit = rospy.get_param("~sim_time_limit")
        while closest[0] > stop and rospy.get_time() - start < limit and not rospy.is_shutdown():
            rospy.sleep(0.1)  # sim time: the controller works in the subscriber's thread
        commands.publish(Twist())
        (px, py, _), _ = self.pose()
        gap = math.hypot(self.axis[0] - px, self.axis[1] - py) - self.radius
        self.assertLess(gap, stop + 0.6, "the robot stopped %.2f m from the pillar" % gap)
        self.assertGreater(gap, 0.5)
        self.assertTrue(odometry and odometry[-1].header.frame_id == "odom", "no /odom from the skid steer")
        self.assertGreater(odometry[-1].pose.pose.position.x, 15.0)


if __name__ == "__main__":
    rospy.init_node("test_smb")
    rostest.rosrun("turtle_sim_ode_smb", "smb", Smb)
