#!/usr/bin/env python3
"""rostest node (issue #31 bug 2): gazebo_ros_control at the root namespace reads the parameter server itself, not
rospy's cache, so root-level gazebo_ros_control/pid_gains make the wheels VELOCITY_PID joints.

default_robot_hw_sim.cpp, DefaultRobotHWSim::initSim: a velocity joint whose
<ns>/gazebo_ros_control/pid_gains/<joint> Pid::init finds becomes VELOCITY_PID; writeSim then SetForce()s the PID's
effort, and readSim reports joint_effort_ = GetForce(0), the force set. Without gains it is a VELOCITY joint
(SetParam("vel") with "fmax"), GetForce(0) stays 0: /joint_states' efforts tell the two apart."""
import math
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from geometry_msgs.msg import Twist, Vector3
from sensor_msgs.msg import JointState

from turtle_sim_ode.ros.plugins.ros_control import uncached_param

WHEELS = ("front_left_wheel", "rear_left_wheel", "front_right_wheel", "rear_right_wheel")


class RootParams(unittest.TestCase):
    def test_a_uncached_param_sees_the_whole_tree(self):
        """rospy.get_param("/") answers from the cache once one key is cached; uncached_param asks the master."""
        rospy.get_param_cached("/base_controller/publish_rate")
        self.assertNotIn("gazebo_ros_control", rospy.get_param("/"))  # rospy's cache: the pitfall
        tree = uncached_param("/", {})
        self.assertEqual(tree["gazebo_ros_control"]["pid_gains"]["front_left_wheel"]["p"], rospy.get_param("~p_gain"))
        self.assertEqual(uncached_param("/no/such/param", "default"), "default")

    def test_b_wheels_run_on_the_pid(self):
        listing = rospy.ServiceProxy("/controller_manager/list_controllers", ListControllers)
        rospy.wait_for_service("/controller_manager/list_controllers", timeout=60)
        deadline = rospy.Time.now() + rospy.Duration(60)
        while {c.name: c.state for c in listing().controller}.get("base_controller") != "running":
            self.assertLess(rospy.Time.now(), deadline, "base_controller never ran")
            rospy.sleep(0.1)
        efforts = []

        def record(states):
            named = dict(zip(states.name, states.effort))
            efforts.append([named[wheel] for wheel in WHEELS if wheel in named])

        rospy.Subscriber("/joint_states", JointState, record)
        commands = rospy.Publisher("/base_controller/cmd_vel", Twist, queue_size=1)
        rate = rospy.Rate(10)
        for _ in range(20):  # 2 s of sim time
            commands.publish(Twist(linear=Vector3(rospy.get_param("~speed"), 0, 0)))
            rate.sleep()
        strongest = max(abs(effort) for sample in efforts for effort in sample)
        # accelerating 50 kg at up to 3 m/s² (the YAML's limit) takes tens of N·m over the four wheels
        self.assertGreater(strongest, 1.0, "the wheels report no effort: velocity motors, not the PID")
        self.assertTrue(all(math.isfinite(effort) for sample in efforts for effort in sample))


if __name__ == "__main__":
    rospy.init_node("test_ros_control_root_params")
    rostest.rosrun("turtle_sim_ode", "ros_control_root_params", RootParams)
