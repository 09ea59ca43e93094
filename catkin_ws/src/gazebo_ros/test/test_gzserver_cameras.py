#!/usr/bin/env python3
"""rostest node: a camera and a depth camera of a world started by gzserver (gzserver_cameras.test). As
gazebo_ros_camera_utils and gazebo_ros_openni_kinect publish them: the L16 camera as mono16 (GazeboRosCameraUtils::
Init), and the depth camera's image, depth image and cloud of one rendering with one stamp (the sensor's update
time, GazeboRosOpenniKinect::OnNewDepthFrame / OnNewImageFrame); stamps fresh (not older than the /clock of the
moment by more than two frames, on the sensor's 10 Hz grid)."""
import threading
import unittest
from collections import defaultdict

import rospy
import rostest
from gazebo_msgs.msg import PerformanceMetrics
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image, PointCloud2

TOPICS = {
    "/grey_cam/image_raw": Image,
    "/depth_cam/rgb/image_raw": Image,
    "/depth_cam/depth/image_raw": Image,
    "/depth_cam/depth/points": PointCloud2,
}
DEPTH_CAMERA = ("/depth_cam/rgb/image_raw", "/depth_cam/depth/image_raw", "/depth_cam/depth/points")
PERIOD = 0.1  # s: the sensors' <update_rate> 10


class GzserverCamerasTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("gzserver_cameras_check")
        cls.changed = threading.Condition()
        cls.stamps = defaultdict(list)  # topic -> [(stamp, /clock when it arrived)]
        cls.first = {}
        cls.clock = 0.0
        rospy.Subscriber("/clock", Clock, cls.on_clock, queue_size=1)
        cls.subscribers = [
            rospy.Subscriber(topic, kind, cls.on_message, topic, queue_size=10) for topic, kind in TOPICS.items()
        ]
        # every topic heard, then a second of sim time more
        with cls.changed:
            assert cls.changed.wait_for(lambda: len(cls.stamps) == len(TOPICS), 120), sorted(cls.stamps)
            start = cls.clock
            assert cls.changed.wait_for(lambda: cls.clock >= start + 1.0, 60)
        for subscriber in cls.subscribers:
            subscriber.unregister()

    @classmethod
    def on_clock(cls, clock: Clock) -> None:
        with cls.changed:
            cls.clock = clock.clock.to_sec()
            cls.changed.notify_all()

    @classmethod
    def on_message(cls, message, topic: str) -> None:
        with cls.changed:
            cls.stamps[topic].append((message.header.stamp.to_sec(), cls.clock))
            cls.first.setdefault(topic, message)
            cls.changed.notify_all()

    def test_the_l16_camera_publishes_mono16(self) -> None:
        image = self.first["/grey_cam/image_raw"]
        self.assertEqual((image.encoding, image.step, image.width, image.height), ("mono16", 128, 64, 48))
        self.assertEqual(len(image.data), 128 * 48)

    def test_stamps_are_fresh_and_on_the_sensor_grid(self) -> None:
        for topic in TOPICS:
            for stamp, clock in self.stamps[topic]:
                # /clock comes on a connection of its own: the /clock of the same step may arrive a little later
                self.assertLessEqual(stamp, clock + PERIOD, topic)
                self.assertGreater(stamp, clock - 2 * PERIOD, "%s: stamp %.3f at /clock %.3f" % (topic, stamp, clock))
            # the first frame comes with the first step after start (sim time 0.001), the grid from there on
            times = [stamp for stamp, _ in self.stamps[topic]][1:]
            self.assertGreaterEqual(len(times), 5, topic)
            for earlier, later in zip(times, times[1:]):
                self.assertAlmostEqual(later - earlier, PERIOD, delta=1e-6, msg=topic)

    def test_image_depth_and_cloud_of_one_frame_share_one_stamp(self) -> None:
        sets = [set(round(stamp, 6) for stamp, _ in self.stamps[topic]) for topic in DEPTH_CAMERA]
        # all three were subscribed from the latest first message on: from there, every stamp is in all three
        start = max(min(stamps) for stamps in sets)
        end = min(max(stamps) for stamps in sets)
        window = [{stamp for stamp in stamps if start <= stamp <= end} for stamps in sets]
        self.assertGreaterEqual(len(window[0]), 5)
        self.assertEqual(window[0], window[1])
        self.assertEqual(window[0], window[2])

    def test_performance_metrics_name_the_cameras(self) -> None:
        """/gazebo/performance_metrics as gazebo_ros republishes Gazebo 11's (gazebo_ros_api_plugin.cpp,
        onPerformanceMetrics): the real-time factor, and per sensor its scoped name (world::model::link::sensor),
        its update rate in sim time (<update_rate> 10), and, cameras both, a frame rate (fps, not gazebo_ros's -1)."""
        metrics = rospy.wait_for_message("/gazebo/performance_metrics", PerformanceMetrics, timeout=30)
        self.assertGreater(metrics.real_time_factor, 0.0)
        sensors = {sensor.name: sensor for sensor in metrics.sensors}
        self.assertEqual(
            sorted(sensors),
            ["cameras::depth_camera_post::link::depth_camera", "cameras::grey_camera_post::link::grey_camera"],
        )
        for sensor in sensors.values():
            self.assertEqual(sensor.sim_update_rate, 10.0)
            self.assertAlmostEqual(sensor.real_update_rate, 10.0 * metrics.real_time_factor, places=6)
            self.assertGreater(sensor.fps, 0.0)


if __name__ == "__main__":
    rostest.rosrun("gazebo_ros", "gzserver_cameras", GzserverCamerasTest)
