#!/usr/bin/env python3
"""The holonomic base of models/holonomic_bot.urdf through ROS: planar move on /cmd_vel and /odom
(GazeboRosPlanarMove), the downward sonar's sensor_msgs/Range (GazeboRosRange), the block laser's
sensor_msgs/PointCloud (GazeboRosBlockLaser), the hector GPS's NavSatFix, set_reference_geopose and dynamic_reconfigure
servers (GazeboRosGps), a triggered camera's one frame a trigger (GazeboRosTriggeredCamera) and a stereo head's pairs (GazeboRosMultiCamera)."""
import math
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image, NavSatFix, NavSatStatus, PointCloud, Range
from geographic_msgs.msg import GeoPoint, GeoPose
from hector_gazebo_plugins.srv import SetReferenceGeoPose
from std_msgs.msg import Empty
from tf2_msgs.msg import TFMessage

WAIT = 90.0


class MorePlugins(unittest.TestCase):
    def test_1_sonar_reads_the_mast_height(self):
        reading = rospy.wait_for_message("/sonar", Range, WAIT)
        self.assertEqual((reading.header.frame_id, reading.radiation_type), ("mast", Range.ULTRASOUND))
        self.assertAlmostEqual(reading.field_of_view, 0.1, places=6)
        self.assertAlmostEqual(reading.range, 0.5, delta=0.03)  # the mast 0.5 m above the floor, looking down
        self.assertAlmostEqual(reading.min_range, 0.02, places=6)  # float32
        self.assertEqual(reading.max_range, 3.0)

    def test_2_block_laser_cloud(self):
        cloud = rospy.wait_for_message("/block_cloud", PointCloud, WAIT)
        self.assertEqual(cloud.header.frame_id, "mast")
        self.assertEqual((len(cloud.points), len(cloud.channels), len(cloud.channels[0].values)), (8, 1, 8))
        for point in cloud.points:  # the floor, ~0.5 m along the sensor's x (pointing down)
            self.assertAlmostEqual(point.x, 0.5, delta=0.05)

    def test_3_gps_fix_near_the_reference(self):
        fix = rospy.wait_for_message("/fix", NavSatFix, WAIT)
        self.assertEqual(fix.header.frame_id, "base_footprint")
        self.assertAlmostEqual(fix.latitude, 47.0, delta=1e-4)
        self.assertAlmostEqual(fix.longitude, 8.5, delta=1e-4)
        self.assertEqual(fix.position_covariance_type, NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN)

    def test_3b_set_reference_geopose_moves_the_fix(self):
        """hector's setGeoposeCb: the GeoPose becomes the reference (yaw 0: x east); a non-finite one is refused
        (our choice: upstream takes it) and the GPS goes on publishing."""
        rospy.wait_for_service("/fix/set_reference_geopose", WAIT)
        set_reference = rospy.ServiceProxy("/fix/set_reference_geopose", SetReferenceGeoPose)
        pose = GeoPose(position=GeoPoint(latitude=-33.9, longitude=151.2, altitude=40.0))
        pose.orientation.w = 1.0
        set_reference(pose)
        fix = self._fix_after(rospy.Time.now())
        self.assertAlmostEqual(fix.latitude, -33.9, delta=1e-4)  # the base is within 10 m of the origin
        self.assertAlmostEqual(fix.longitude, 151.2, delta=1e-4)
        self.assertAlmostEqual(fix.altitude, 40.0, delta=0.5)
        pose.position.latitude = math.nan
        with self.assertRaises(rospy.ServiceException):
            set_reference(pose)
        fix = self._fix_after(rospy.Time.now())
        self.assertAlmostEqual(fix.latitude, -33.9, delta=1e-4)

    def test_3c_gps_status_reconfigure(self):
        """GazeboRosGps::dynamicReconfigureCallback on /fix/status (hector_gazebo_plugins/src/gazebo_ros_gps.cpp):
        the first configuration reports the loaded status (FIX) and service (0, no tag); a change sets the next
        fix's status (SBAS_FIX; NO_FIX without STATUS_FIX) and service mask (GPS | GALILEO = 9)."""
        client = Client("/fix/status", timeout=WAIT)
        first = client.get_configuration(timeout=WAIT)
        self.assertTrue(first["STATUS_FIX"])
        for name in ("STATUS_SBAS_FIX", "STATUS_GBAS_FIX", "SERVICE_GPS", "SERVICE_GLONASS", "SERVICE_COMPASS"):
            self.assertFalse(first[name], name)
        self.assertFalse(first["SERVICE_GALILEO"])  # GNSS.cfg's defaults (all services on) do not count
        flags = dict(STATUS_SBAS_FIX=True, SERVICE_GPS=True, SERVICE_GALILEO=True)
        answer = client.update_configuration(flags)
        self.assertTrue(all(answer[name] for name in flags))
        fix = self._fix_after(rospy.Time.now())
        self.assertEqual((fix.status.status, fix.status.service), (NavSatStatus.STATUS_SBAS_FIX, 9))
        client.update_configuration({"STATUS_FIX": False})
        fix = self._fix_after(rospy.Time.now())
        self.assertEqual((fix.status.status, fix.status.service), (NavSatStatus.STATUS_NO_FIX, 9))
        # A change leaves the flags as given (STATUS_GBAS_FIX stays off): a plain fix again, GALILEO alone.
        client.update_configuration(dict(STATUS_FIX=True, STATUS_SBAS_FIX=False, SERVICE_GPS=False))
        fix = self._fix_after(rospy.Time.now())
        self.assertEqual((fix.status.status, fix.status.service), (NavSatStatus.STATUS_FIX, 8))

    def test_3d_gps_position_noise_reconfigure(self):
        """SensorModel_::dynamicReconfigureCallback on /fix/position (include/hector_gazebo_plugins/sensor_model.h):
        the tags first (no noise: 0; driftFrequency 1/3600, SensorModel_()'s); gaussian_noise 0.5 on every axis
        makes GazeboRosGps::Update's covariance diagonal drift^2 + noise^2 = 0.25; NaN is refused, the noise
        kept. /fix/velocity reports its model too."""
        position = Client("/fix/position", timeout=WAIT)
        first = position.get_configuration(timeout=WAIT)
        self.assertEqual((first["gaussian_noise"], first["drift"], first["offset"]), (0.0, 0.0, 0.0))
        self.assertAlmostEqual(first["drift_frequency"], 1.0 / 3600.0, places=12)
        velocity = Client("/fix/velocity", timeout=WAIT).get_configuration(timeout=WAIT)
        self.assertEqual((velocity["gaussian_noise"], velocity["scale_error"]), (0.0, 1.0))
        try:
            self.assertAlmostEqual(position.update_configuration({"gaussian_noise": 0.5})["gaussian_noise"], 0.5)
            fix = self._fix_after(rospy.Time.now())
            for index, value in enumerate(fix.position_covariance):
                self.assertAlmostEqual(value, 0.25 if index % 4 == 0 else 0.0, places=12)
            self.assertAlmostEqual(position.update_configuration({"gaussian_noise": math.nan})["gaussian_noise"], 0.5)
            fix = self._fix_after(rospy.Time.now())
            self.assertAlmostEqual(fix.position_covariance[8], 0.25, places=12)
            self.assertTrue(math.isfinite(fix.latitude))
        finally:
            position.update_configuration({"gaussian_noise": 0.0})  # the other tests read exact positions

    @staticmethod
    def _fix_after(stamp):
        while True:
            fix = rospy.wait_for_message("/fix", NavSatFix, WAIT)
            if fix.header.stamp > stamp:
                return fix

    def test_7_a_plugins_own_namespace_wins_over_the_spawns(self):
        """GazeboRosApiPlugin::walkChildAddRobotNamespace adds the spawn's robot_namespace (spawned_ns) only to a
        plugin without a <robotNamespace>: truth_a stays in own_ns."""
        for topic in ("/own_ns/truth_a", "/spawned_ns/truth_b"):
            truth = rospy.wait_for_message(topic, Odometry, WAIT)
            self.assertAlmostEqual(truth.pose.pose.position.x, 5.0, delta=0.01)
        published = {name for name, _ in rospy.get_published_topics()}
        self.assertNotIn("/spawned_ns/truth_a", published)
        self.assertNotIn("/own_ns/truth_b", published)

    def test_5_triggered_camera_sends_a_frame_a_trigger(self):
        images = []
        rospy.Subscriber("/front/image_raw", Image, images.append)
        trigger = rospy.Publisher("/front/image_trigger", Empty, queue_size=10)
        began = rospy.get_time()
        while rospy.get_time() - began < 1.0 and not rospy.is_shutdown():
            rospy.sleep(0.1)  # sim time: untriggered, the camera sends nothing
        self.assertEqual(images, [])
        while trigger.get_num_connections() == 0 and not rospy.is_shutdown():
            rospy.sleep(0.1)
        trigger.publish(Empty())
        began = rospy.get_time()
        while rospy.get_time() - began < 2.0 and not rospy.is_shutdown():
            rospy.sleep(0.1)
        self.assertEqual(len(images), 1)
        self.assertEqual((images[0].width, images[0].height, images[0].header.frame_id), (8, 6, "mast"))

    def test_6_stereo_pairs_share_their_stamps(self):
        left, right = [], []
        rospy.Subscriber("/stereo/left/image_raw", Image, left.append)
        rospy.Subscriber("/stereo/right/image_raw", Image, right.append)
        info = rospy.wait_for_message("/stereo/right/camera_info", CameraInfo, WAIT)
        self.assertAlmostEqual(info.P[3], -info.P[0] * 0.07, places=6)  # the right camera's baseline
        began = rospy.get_time()
        while rospy.get_time() - began < 1.0 and not rospy.is_shutdown():
            rospy.sleep(0.1)
        common = {m.header.stamp for m in left} & {m.header.stamp for m in right}
        self.assertGreaterEqual(len(common), 5, "left and right frames with one stamp: %d" % len(common))

    def test_4_planar_move_goes_sideways(self):
        start = rospy.wait_for_message("/odom", Odometry, WAIT)
        self.assertEqual((start.header.frame_id, start.child_frame_id), ("odom", "base_footprint"))
        commands = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        twist = Twist()
        twist.linear.y = 0.5
        began = rospy.get_time()
        latest = start
        while rospy.get_time() - began < 2.0 and not rospy.is_shutdown():
            commands.publish(twist)
            latest = rospy.wait_for_message("/odom", Odometry, WAIT)
        commands.publish(Twist())
        moved_y = latest.pose.pose.position.y - start.pose.pose.position.y
        moved_x = latest.pose.pose.position.x - start.pose.pose.position.x
        self.assertGreater(moved_y, 0.5, "odom y moved %.3f m" % moved_y)
        self.assertLess(abs(moved_x), 0.05)
        self.assertAlmostEqual(latest.twist.twist.linear.y, 0.5, delta=0.1)
        self.assertLess(abs(math.atan2(latest.pose.pose.orientation.z, latest.pose.pose.orientation.w)), 0.02)

    def test_4b_planar_move_sends_odom_on_tf(self):
        """GazeboRosPlanarMove::publishOdometry sends odometryFrame -> robotBaseFrame with each odometry message."""
        deadline = rospy.get_time() + WAIT
        while rospy.get_time() < deadline:
            message = rospy.wait_for_message("/tf", TFMessage, WAIT)
            frames = {(t.header.frame_id, t.child_frame_id) for t in message.transforms}
            if ("odom", "base_footprint") in frames:
                return
        self.fail("no odom -> base_footprint on /tf")


if __name__ == "__main__":
    rospy.init_node("test_more_plugins")
    rostest.rosrun("turtle_sim_ode", "more_plugins", MorePlugins)
