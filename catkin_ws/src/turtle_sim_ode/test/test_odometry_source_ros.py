#!/usr/bin/env python3
"""smb_gazebo's OdometrySource (ETHZ-RobotX/smb_common, smb_gazebo/src/OdometrySource.cpp) through ROS, on the box
of models/odometry_sources.urdf: Load's topic in the robot namespace (NodeHandle(robotNamespace + "/")), an absolute
topic as it is; UpdateChild's messages (frames as written, the pose relative to where the link came to rest,
gaussianNoise squared on the covariance diagonals, one message per 1/updateRate of sim time) and its tf where
publishTf is true; a model moved with /gazebo/set_model_state read in the frame it settled in."""
import threading
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from nav_msgs.msg import Odometry
from tf2_msgs.msg import TFMessage

WAIT = 60.0
CAMERA_TOPIC = "/smb/tracking_camera/odom/sample"
BASE_TOPIC = "/base/ground_truth"
REST_TOLERANCE = 0.01  # m, rad: the box on the ground plane after settling
CAMERA_RATE = 50.0  # Hz, models/odometry_sources.urdf
CAMERA_NOISE = 0.001


def collect(topic, msg_type, enough, timeout=WAIT):
    """Messages on topic from now until enough(messages) holds (or timeout s of wall time pass)."""
    messages = []
    done = threading.Event()

    def received(message):
        messages.append(message)
        if enough(messages):
            done.set()

    subscriber = rospy.Subscriber(topic, msg_type, received, queue_size=100)
    done.wait(timeout)
    subscriber.unregister()
    return list(messages)


class OdometrySourceTest(unittest.TestCase):
    def test_1_camera_odometry_at_rest(self):
        odom = rospy.wait_for_message(CAMERA_TOPIC, Odometry, WAIT)
        self.assertEqual(
            (odom.header.frame_id, odom.child_frame_id), ("tracking_camera_odom_frame", "tracking_camera_pose_frame")
        )
        self.assertGreater(odom.header.stamp.to_sec(), 1.0)  # nothing before the first settle check
        position = odom.pose.pose.position
        for value in (position.x, position.y, position.z, odom.pose.pose.orientation.z):
            self.assertAlmostEqual(value, 0.0, delta=REST_TOLERANCE)
        for index in range(36):
            expected = CAMERA_NOISE**2 if index in (0, 7, 14, 21, 28, 35) else 0.0
            self.assertAlmostEqual(odom.pose.covariance[index], expected, places=12)
            self.assertAlmostEqual(odom.twist.covariance[index], expected, places=12)

    def test_2_one_message_per_period_of_sim_time(self):
        messages = collect(CAMERA_TOPIC, Odometry, lambda got: len(got) >= 11)
        self.assertGreaterEqual(len(messages), 11)
        stamps = [message.header.stamp.to_sec() for message in messages]
        for earlier, later in zip(stamps, stamps[1:]):
            self.assertAlmostEqual(later - earlier, 1.0 / CAMERA_RATE, delta=1e-6)

    def test_3_tf_only_where_publish_tf(self):
        def has_camera(got):
            return any(t.child_frame_id == "tracking_camera_pose_frame" for m in got for t in m.transforms)

        messages = collect("/tf", TFMessage, has_camera)
        transforms = [t for m in messages for t in m.transforms]
        camera = [t for t in transforms if t.child_frame_id == "tracking_camera_pose_frame"]
        self.assertTrue(camera, "no tf to tracking_camera_pose_frame")
        self.assertEqual(camera[0].header.frame_id, "tracking_camera_odom_frame")
        self.assertFalse([t for t in transforms if t.child_frame_id == "base"])  # publishTf false

    def test_4_moved_base_read_in_its_settled_frame(self):
        odom = rospy.wait_for_message(BASE_TOPIC, Odometry, WAIT)
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ("map", "base"))
        rospy.wait_for_service("/gazebo/set_model_state", WAIT)
        # spawned at the origin, it rests there (the settled frame's origin): 1 m along x from it, on the ground
        state = ModelState(model_name="odometry_box")
        state.pose.position.x, state.pose.position.z = 1.0, 0.1
        state.pose.orientation.w = 1.0
        moved_at = rospy.Time.now()
        self.assertTrue(rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(state).success)
        later = collect(BASE_TOPIC, Odometry, lambda got: got[-1].header.stamp > moved_at)
        self.assertTrue(later and later[-1].header.stamp > moved_at)
        self.assertAlmostEqual(later[-1].pose.pose.position.x, 1.0, delta=REST_TOLERANCE)


if __name__ == "__main__":
    rospy.init_node("test_odometry_source")
    rostest.rosrun("turtle_sim_ode", "odometry_source", OdometrySourceTest)
