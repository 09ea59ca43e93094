#!/usr/bin/env python3
"""rostest node: /gazebo/step_simulation on two paused simulators (namespaces in ~runs).

Both get the same spawns and the same command sequence, stepped in lockstep; their poses must then be bitwise
identical. The commands go through services (wrenches, a model state), which answer once they are applied: a
velocity command on a topic has no acknowledgement in ROS 1, so under load it may reach one simulator a step
later than the other, and two runs would then differ because their inputs did."""
import sys
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import ApplyBodyWrench, GetModelState, GetPhysicsProperties, SetModelState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3, Wrench
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty
from turtle_sim_ode_msgs.srv import StepSimulation

from turtle_sim_ode.analysis.waiting import wait_for

# (body, force x N, torque z N m, duration s, steps): push the box into the robot, turn the robot, push it back.
WRENCHES = [
    ("box::box_link", -15.0, 0.0, 0.6, 800),
    ("mobile_base::base_footprint", 0.0, 2.0, 0.3, 500),
    ("mobile_base::base_footprint", 40.0, 0.0, 0.4, 700),
]


def service(run, name, kind):
    full = "/%s/gazebo/%s" % (run, name)
    rospy.wait_for_service(full, timeout=60)
    return rospy.ServiceProxy(full, kind)


def pose_tuple(state):
    p, q = state.pose.position, state.pose.orientation
    return (p.x, p.y, p.z, q.x, q.y, q.z, q.w)


class Run:
    """One simulator: its services and what it published."""

    def __init__(self, name):
        self.name = name
        self.step = service(name, "step_simulation", StepSimulation)
        self.spawn = service(name, "spawn_urdf_model", SpawnModel)
        self.wrench = service(name, "apply_body_wrench", ApplyBodyWrench)
        self.set_state = service(name, "set_model_state", SetModelState)
        self.get_state = service(name, "get_model_state", GetModelState)
        self.pause = service(name, "pause_physics", Empty)
        self.unpause = service(name, "unpause_physics", Empty)
        self.time_step = service(name, "get_physics_properties", GetPhysicsProperties)().time_step
        self.odom_stamps, self.clock_stamps = [], []
        rospy.Subscriber("/%s/odom" % name, Odometry, lambda m: self.odom_stamps.append(m.header.stamp))
        rospy.Subscriber("/%s/clock" % name, Clock, lambda m: self.clock_stamps.append(m.clock))


class Lockstep(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.runs = [Run(name) for name in rospy.get_param("~runs")]
        with open(rospy.get_param("~model")) as box:
            cls.box = box.read()

    def test_a_same_commands_give_identical_poses(self):
        urdf = rospy.get_param("/robot_description")
        for run in self.runs:
            at = Pose(Point(0.0, 0.0, 0.0), Quaternion(0, 0, 0, 1))
            self.assertTrue(run.spawn("mobile_base", urdf, "", at, "world").success)
            box_at = Pose(Point(0.6, 0.05, 0.1), Quaternion(0, 0, 0, 1))
            self.assertTrue(run.spawn("box", self.box, "", box_at, "world").success)
        for run in self.runs:  # a model state set while paused: the robot starts rolling towards the box
            twist = Twist(Vector3(0.2, 0, 0), Vector3())
            self.assertTrue(run.set_state(ModelState("mobile_base", at, twist, "world")).success)
        for body, force, torque, duration, steps in WRENCHES:
            for run in self.runs:
                wrench = Wrench(Vector3(force, 0, 0), Vector3(0, 0, torque))
                answer = run.wrench(body, "", Point(), wrench, rospy.Time(0), rospy.Duration(duration))
                self.assertTrue(answer.success, answer.status_message)
                answer = run.step(steps)
                self.assertTrue(answer.success, answer.status_message)
        final = {}
        for run in self.runs:
            final[run.name] = [pose_tuple(run.get_state(model, "world")) for model in ("mobile_base", "box")]
        first, second = final.values()
        self.assertEqual(first, second, "runs differ: %s" % final)
        robot, box = first
        self.assertGreater(abs(robot[0]) + abs(robot[1]), 0.1, "the robot did not move: %s" % (robot,))
        self.assertLess(box[0], 0.6 - 0.1, "the box was not pushed: %s" % (box,))

    def test_b_steps_advance_time_exactly_and_publish_what_falls_due(self):
        run = self.runs[0]
        before = run.step(0).sim_time.to_sec()
        clocks, odoms = len(run.clock_stamps), len(run.odom_stamps)
        answer = run.step(200)
        self.assertTrue(answer.success, answer.status_message)
        self.assertAlmostEqual(answer.sim_time.to_sec() - before, 200 * run.time_step, delta=1e-6)
        # 0.2 s of sim time: /clock at 100 Hz and odometry at 50 Hz fall due 20 and 10 times.
        self.assertTrue(wait_for(lambda: len(run.clock_stamps) >= clocks + 20, 30.0), len(run.clock_stamps) - clocks)
        self.assertTrue(wait_for(lambda: len(run.odom_stamps) >= odoms + 10, 30.0), len(run.odom_stamps) - odoms)
        self.assertLessEqual(run.clock_stamps[-1].to_sec(), answer.sim_time.to_sec() + 1e-9)

    def test_c_refused_while_running_and_past_the_limit(self):
        run = self.runs[0]
        too_many = run.step(10**7)
        self.assertFalse(too_many.success)
        self.assertIn("split", too_many.status_message)
        run.unpause()
        try:
            running = run.step(10)
            self.assertFalse(running.success)
            self.assertIn("pause", running.status_message)
        finally:
            run.pause()


if __name__ == "__main__":
    rospy.init_node("test_lockstep")
    rostest.rosrun("turtle_sim_ode", "lockstep", Lockstep, sys.argv)
