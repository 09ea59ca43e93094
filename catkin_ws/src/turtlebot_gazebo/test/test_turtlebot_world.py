#!/usr/bin/env python3
"""rostest node for turtlebot_world.launch as typed: a kobuki_msgs subscriber that is there before the robot spawns
does not stop the spawn; the description has 34 links; the multiplexer is idle, then lets navigation drive and
teleoperation take over; /scan comes from the depth image in camera_depth_frame and sees the bookshelf; driving on
into the bookshelf presses the CENTER bumper (an event, and the BUMPER_CENTRE bit of sensors/core); with motor power
off the robot does not move; driving off a 3 cm step gives cliff events (front first), both wheels' drop events and
the sensors/core bits. The robot is turned to face the bookshelf first. Expected behaviour from yujinrobot/
kobuki_desktop (melodic) kobuki_gazebo_plugins/src/gazebo_ros_kobuki_updates.cpp (updateBumper, updateCliffSensor,
updateWheelDrop, pubSensorState, propagateVelocityCommands) and gazebo_ros_kobuki.cpp (motorPowerCB)."""
import math
import struct
import sys
import threading
import time
import unittest
import xml.etree.ElementTree as ET

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetModelState, SetModelState
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from gazebo_msgs.srv import SpawnModel
from kobuki_msgs.msg import BumperEvent, CliffEvent, MotorPower, SensorState, WheelDropEvent
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan
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
        # where it stands (a pose at z 0 would press the wheels into the ground and make it bounce)
        standing = cls.get_state("mobile_base", "").pose.position
        facing_y = Pose(standing, Quaternion(0, 0, math.sqrt(0.5), math.sqrt(0.5)))
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
        # the connection follows the master's publisherUpdate, asynchronously: wait for it (wall clock)
        deadline = time.monotonic() + self.timeout
        while BUMPER.sub.get_num_connections() == 0 and time.monotonic() < deadline:
            rospy.rostime.wallsleep(0.05)
        self.assertEqual(BUMPER.sub.get_num_connections(), 1, "the early kobuki_msgs subscriber is not connected")
        # kobuki_gazebo_plugins stamps the gyro with the joint states' header: base_link (updateIMU)
        imu = rospy.wait_for_message("/mobile_base/sensors/imu_data", Imu, self.timeout)
        self.assertEqual(imu.header.frame_id, "base_link")
        # gravity at rest: the median of 21 readings, so that a contact transient of one step does not count
        readings = [
            rospy.wait_for_message("/mobile_base/sensors/imu_data", Imu, self.timeout).linear_acceleration.z
            for _ in range(21)
        ]
        self.assertAlmostEqual(sorted(readings)[10], 9.8, delta=0.3)

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

    def test_3b_the_scans_middle_beams_read_the_depth_images_centre(self):
        """depthimage_to_laserscan (DepthImageToLaserScan::convert) bins each column at -atan2(u - cx, fx) from
        camera_info's cx, which Gazebo reports as (width + 1) / 2 (gazebo_ros_camera_utils.cpp, Init): the middle
        beam and the beam straight ahead then hold a column at the image's centre, never NaN on a flat board."""
        info = rospy.wait_for_message("/camera/depth/camera_info", CameraInfo, self.timeout)
        self.assertEqual((info.K[2], info.K[5]), ((info.width + 1) / 2.0, (info.height + 1) / 2.0))
        image = rospy.wait_for_message("/camera/depth/image_raw", Image, self.timeout)
        centre = struct.unpack_from("<f", image.data, (image.height // 2) * image.step + (image.width // 2) * 4)[0]
        scan = rospy.wait_for_message("/scan", LaserScan, self.timeout)
        straight_ahead = int(-scan.angle_min / scan.angle_increment)
        tolerance = rospy.get_param("~centre_tolerance")
        for index in (len(scan.ranges) // 2, straight_ahead):
            self.assertAlmostEqual(scan.ranges[index], centre, delta=tolerance, msg="beam %d" % index)

    def place(self, x, y, z, yaw):
        pose = Pose(Point(x, y, z), Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)))
        result = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(
            ModelState("mobile_base", pose, Twist(), "")
        )
        self.assertTrue(result.success, result.status_message)
        rospy.sleep(0.5)  # sim time: settle

    def test_4_bumping_the_bookshelf_presses_center(self):
        core = Recorder("/mobile_base/sensors/core", SensorState)
        pressed = lambda: any(
            e.bumper == BumperEvent.CENTER and e.state == BumperEvent.PRESSED for e in BUMPER.messages
        )
        self.assertTrue(stream("/mobile_base/commands/velocity", 0.2, pressed, 20.0), (BUMPER.messages, self.pose()))
        self.assertAlmostEqual(self.pose().position.y, BOOKSHELF_FRONT_Y - KOBUKI_RADIUS, delta=0.05)
        self.assertTrue(core.wait_for(lambda m: m.bumper == SensorState.BUMPER_CENTRE, self.timeout))

    def test_5_motor_power_off_stops_the_wheels(self):
        self.place(0.0, 0.0, 0.0, -math.pi / 2)  # facing away from the bookshelf
        power = rospy.Publisher("/mobile_base/commands/motor_power", MotorPower, queue_size=1, latch=True)
        power.publish(MotorPower(MotorPower.OFF))
        start = self.pose().position
        moved = lambda: math.hypot(self.pose().position.x - start.x, self.pose().position.y - start.y) > 0.05
        # a latched message reaches the simulator once it has connected: wait for that, then drive for 2 s
        deadline = rospy.Time.now() + rospy.Duration(self.timeout)
        while power.get_num_connections() == 0 and rospy.Time.now() < deadline:
            rospy.sleep(0.05)
        self.assertFalse(stream("/mobile_base/commands/velocity", 0.2, moved, 2.0), "moved with the motors off")
        power.publish(MotorPower(MotorPower.ON))
        self.assertTrue(stream("/mobile_base/commands/velocity", 0.2, moved, 5.0), "did not move with the motors on")
        power.unregister()

    def test_6_driving_off_a_step_gives_cliff_and_wheel_drop_events(self):
        step = (
            '<sdf version="1.6"><model name="step"><static>true</static><link name="link"><collision name="c">'
            "<geometry><box><size>2 2 0.03</size></box></geometry></collision></link></model></sdf>"
        )
        spawn = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)
        result = spawn("step", step, "", Pose(Point(-2, -5, 0.015), Quaternion(0, 0, 0, 1)), "")
        self.assertTrue(result.success, result.status_message)
        self.place(-1.6, -5.0, 0.04, 0.0)  # on the step, 0.6 m from its edge at x = -1, facing it
        cliffs = Recorder("/mobile_base/events/cliff", CliffEvent)
        drops = Recorder("/mobile_base/events/wheel_drop", WheelDropEvent)
        core = Recorder("/mobile_base/sensors/core", SensorState)
        landed = lambda: sum(e.state == WheelDropEvent.RAISED for e in drops.messages) >= 2
        self.assertTrue(stream("/mobile_base/commands/velocity", 0.2, landed, 10.0), (cliffs.messages, drops.messages))
        events = [(e.sensor, e.state) for e in cliffs.messages]
        self.assertEqual(events[0], (CliffEvent.CENTER, CliffEvent.CLIFF), events)
        for sensor in (CliffEvent.LEFT, CliffEvent.CENTER, CliffEvent.RIGHT):
            self.assertIn((sensor, CliffEvent.CLIFF), events)
        self.assertTrue(cliffs.wait_for(lambda e: e.state == CliffEvent.FLOOR, self.timeout), events)
        wheels = {(e.wheel, e.state) for e in drops.messages}
        self.assertTrue(
            {(WheelDropEvent.LEFT, WheelDropEvent.DROPPED), (WheelDropEvent.RIGHT, WheelDropEvent.DROPPED)} <= wheels
        )
        self.assertTrue(any(m.cliff == 7 for m in core.messages), "no sensors/core with CLIFF_LEFT|CENTRE|RIGHT")
        self.assertTrue(any(m.wheel_drop == 3 for m in core.messages), "no sensors/core with both wheels dropped")
        self.assertLess(self.pose().position.z, 0.005)  # down on the floor


if __name__ == "__main__":
    rospy.init_node("test_turtlebot_world")
    BUMPER = Recorder("/mobile_base/events/bumper", BumperEvent)
    rostest.rosrun("turtlebot_gazebo", "turtlebot_world", TurtlebotWorld, sys.argv)
