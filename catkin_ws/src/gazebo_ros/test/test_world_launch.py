#!/usr/bin/env python3
"""rostest node: one of gazebo_ros's world launch files (the Gazebo tutorial "Using roslaunch" types them) is up:
its world's models are listed by /gazebo/get_world_properties (gazebo_ros_api_plugin.cpp, getWorldProperties: every
model in load order), sim time runs on /clock, and a TurtleBot spawned into it (turtle_sim_ode's urdf/turtlebot.urdf,
by /gazebo/spawn_urdf_model) drives forward on mobile_base/commands/velocity. With ~elevator, the elevator of
elevator_world.launch rides to floor 1 when asked on /elevator (gazebo_ros_elevator.cpp, OnElevator; ElevatorPlugin:
the car at floor * floor_height within the lift's 0.15 m, the door then opened to 1 m within 0.05 m)."""
import math
import os
import unittest

import rospkg
import rospy
import rostest
from gazebo_msgs.srv import GetJointProperties, GetModelState, GetWorldProperties, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion, Twist
from std_msgs.msg import String
from workspace_testing.sim_clock import SimClock


def service(name, kind, timeout):
    rospy.wait_for_service("/gazebo/" + name, timeout=timeout)
    return rospy.ServiceProxy("/gazebo/" + name, kind)


class WorldLaunch(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("world_launch_check")
        cls.timeout = float(rospy.get_param("~timeout"))
        cls.clock = SimClock()
        cls.world = service("get_world_properties", GetWorldProperties, cls.timeout)
        cls.model_state = service("get_model_state", GetModelState, cls.timeout)

    def position(self, model: str) -> Point:
        state = self.model_state(model, "")
        self.assertTrue(state.success, state.status_message)
        return state.pose.position

    def test_1_the_worlds_models_are_listed(self) -> None:
        names = self.world().model_names
        expected = rospy.get_param("~models")
        self.assertEqual(names[: len(expected)], expected)
        self.assertEqual(len(names), int(rospy.get_param("~model_count", len(expected))))

    def test_2_sim_time_runs(self) -> None:
        self.assertTrue(self.clock.wait_for(1.0, self.timeout), "/clock did not run 1 s")

    def test_3_a_spawned_robot_drives(self) -> None:
        x, y, z, yaw = (float(v) for v in rospy.get_param("~spawn").split())
        path = os.path.join(rospkg.RosPack().get_path("turtle_sim_ode"), "urdf", "turtlebot.urdf")
        with open(path) as urdf:
            pose = Pose(Point(x, y, z), Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)))
            # named as TurtleBot launch files name it: its Kobuki plugin listens on <model>/commands/velocity
            answer = service("spawn_urdf_model", SpawnModel, self.timeout)("mobile_base", urdf.read(), "", pose, "")
        self.assertTrue(answer.success, answer.status_message)
        self.assertTrue(self.clock.wait_for(1.0, self.timeout))  # settle
        start = self.position("mobile_base")
        command = rospy.Publisher("mobile_base/commands/velocity", Twist, queue_size=1)
        speed, seconds = float(rospy.get_param("~speed")), float(rospy.get_param("~drive_time"))
        end = self.clock.now + seconds
        rate = rospy.Rate(20)  # sim time: within the plugin's 0.6 s command timeout
        while not rospy.is_shutdown() and self.clock.now < end:
            command.publish(Twist(linear=Point(speed, 0, 0)))
            rate.sleep()
        command.publish(Twist())
        moved = self.position("mobile_base")
        distance = math.hypot(moved.x - start.x, moved.y - start.y)
        self.assertAlmostEqual(distance, speed * seconds, delta=float(rospy.get_param("~distance_tolerance")))
        heading = math.atan2(moved.y - start.y, moved.x - start.x)
        self.assertAlmostEqual(math.remainder(heading - yaw, 2 * math.pi), 0.0, delta=0.1)

    def test_4_the_elevator_rides_to_floor_1(self) -> None:
        if not rospy.get_param("~elevator", False):
            return
        floor_height = float(rospy.get_param("~floor_height"))
        ground = self.position("elevator").z
        asked = rospy.Publisher("/elevator", String, queue_size=1, latch=True)
        asked.publish(String("1"))
        deadline = self.clock.now + float(rospy.get_param("~ride_time"))
        while self.clock.now < deadline and self.position("elevator").z < ground + floor_height - 0.15:
            self.clock.wait_for(0.5, self.timeout)
        self.assertGreater(self.position("elevator").z, ground + floor_height - 0.15)
        door = service("get_joint_properties", GetJointProperties, self.timeout)
        while self.clock.now < deadline and door("door").position[0] < 0.95:
            self.clock.wait_for(0.5, self.timeout)
        self.assertGreater(door("door").position[0], 0.95, "the door did not open at floor 1")


if __name__ == "__main__":
    rostest.rosrun("gazebo_ros", "world_launch", WorldLaunch)
