#!/usr/bin/env python3
"""rostest node: camera plugins through ROS. A waffle-like depth camera (libgazebo_ros_openni_kinect.so, topics
under camera/) and a Kinect-like one spawned in namespace tb2 advertise gazebo_ros's topics and types; their images,
depth images and clouds come in their optical frames with gazebo_ros's encodings, and the depth at the image centre
is the distance to the face of a box spawned in front of the camera."""
import math
import struct
import sys
import unittest

import rospy
import rostest
from gazebo_clients import connect_gazebo_services, model_text, pose
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

# The waffle fixture's lens (camera_rgb_frame) in the world when its base_footprint is at the origin.
WAFFLE_LENS = (0.067, -0.054, 0.113)
RED_BOX_SDF = """<sdf version="1.6"><model name="red_box"><static>true</static><link name="link">
<collision name="c"><geometry><box><size>0.2 1.0 1.0</size></box></geometry></collision>
<visual name="v"><geometry><box><size>0.2 1.0 1.0</size></box></geometry>
<material><script><name>Gazebo/Red</name></script></material></visual></link></model></sdf>"""
WAFFLE_TOPICS = {
    "/camera/rgb/image_raw": "sensor_msgs/Image",
    "/camera/rgb/camera_info": "sensor_msgs/CameraInfo",
    "/camera/depth/image_raw": "sensor_msgs/Image",
    "/camera/depth/camera_info": "sensor_msgs/CameraInfo",
    "/camera/depth/points": "sensor_msgs/PointCloud2",
}


def centre_depth(image):
    row, column = image.height // 2, image.width // 2
    return struct.unpack_from("<f", image.data, (row * image.width + column) * 4)[0]


class CamerasThroughRos(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        connect_gazebo_services(cls)
        result = cls.spawn_urdf_model("waffle", model_text("waffle_depth_camera.urdf"), "", pose(), "world")
        assert result.success, result.status_message
        result = cls.spawn_urdf_model("kinect", model_text("kinect_camera.urdf"), "tb2", pose(y=5.0), "world")
        assert result.success, result.status_message
        assert "front_sonar" in result.status_message, result.status_message  # the unsupported sensor is named

    def test_1_topics_and_types_as_gazebo_ros(self):
        published = dict(rospy.get_published_topics())
        for topic, kind in WAFFLE_TOPICS.items():
            self.assertEqual(published.get(topic), kind, topic)
            self.assertEqual(published.get("/tb2" + topic), kind, "/tb2" + topic)

    def test_2_depth_colour_and_cloud_of_a_spawned_box(self):
        distance = rospy.get_param("~box_distance")
        tolerance = rospy.get_param("~depth_tolerance")
        x, y, _ = WAFFLE_LENS
        result = self.spawn_sdf_model("red_box", RED_BOX_SDF, "", pose(x + distance + 0.1, y, 0.5), "world")
        self.assertTrue(result.success, result.status_message)
        try:
            rospy.sleep(0.2)  # sim time: a frame after the spawn
            depth = rospy.wait_for_message("/camera/depth/image_raw", Image, timeout=30)
            self.assertEqual((depth.encoding, depth.header.frame_id), ("32FC1", "camera_rgb_optical_frame"))
            self.assertAlmostEqual(centre_depth(depth), distance, delta=tolerance)
            image = rospy.wait_for_message("/camera/rgb/image_raw", Image, timeout=30)
            self.assertEqual((image.encoding, image.width, image.height), ("rgb8", 160, 120))
            centre = (60 * 160 + 80) * 3
            r, g, b = bytearray(image.data[centre : centre + 3])
            self.assertGreater(r, 2 * max(g, b), "the box is red")
            cloud = rospy.wait_for_message("/camera/depth/points", PointCloud2, timeout=30)
            self.assertEqual((cloud.header.frame_id, cloud.height, cloud.width), ("camera_rgb_optical_frame", 120, 160))
            self.assertEqual([f.name for f in cloud.fields], ["x", "y", "z", "rgb"])
            z = struct.unpack_from("<f", cloud.data, (60 * 160 + 80) * cloud.point_step + 8)[0]
            self.assertAlmostEqual(z, distance, delta=tolerance)
            info = rospy.wait_for_message("/camera/rgb/camera_info", CameraInfo, timeout=30)
            self.assertAlmostEqual(info.K[0], 160 / (2 * math.tan(1.3439 / 2)), delta=1e-6)
            self.assertAlmostEqual(info.P[3], -info.K[0] * 0.07, delta=1e-9)  # the waffle's <hackBaseline>
        finally:
            self.delete_model("red_box")

    def test_3_kinect_in_its_namespace_with_its_frame_and_format(self):
        image = rospy.wait_for_message("/tb2/camera/rgb/image_raw", Image, timeout=30)
        self.assertEqual((image.encoding, image.header.frame_id), ("bgr8", "camera_depth_optical_frame"))
        depth = rospy.wait_for_message("/tb2/camera/depth/image_raw", Image, timeout=30)
        self.assertEqual(depth.header.stamp.to_sec() > 0, True)
        self.assertTrue(math.isnan(centre_depth(depth)), "nothing within 5 m ahead: NaN, as gazebo_ros")


if __name__ == "__main__":
    rospy.init_node("test_cameras_ros")
    rostest.rosrun("turtle_sim_ode", "cameras_through_ros", CamerasThroughRos, sys.argv)
