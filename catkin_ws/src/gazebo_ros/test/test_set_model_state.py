#!/usr/bin/env python3
"""rostest node: what gazebo_plugins' set_model_state_test asserts (noetic-devel gazebo_plugins/test/
set_model_state_test/set_model_state_test.cpp, TEST(ModelStateTest, FrameTest)), on our own pioneer2dx-like robot
(turtle_sim_ode/test/worlds/caster_robot.world) started by gzserver: commands on the /gazebo/set_model_state topic
relative to the robot's own link `caster_bot::chassis`, first turns with the quaternion (0, 0, 0.04018, 1) (not unit
length) until the heading is pi/4 within 0.05 rad, then 0.1 m steps until 5 m out, where x and y are sqrt(25/2)
within 0.2 m; then (0, 0) in the world within 0.01 m. The upstream test sleeps 0.2 s of wall time between commands;
here each command is followed by 0.2 s of sim time (waited for on /clock)."""
import math
import threading
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelState, ModelStates
from geometry_msgs.msg import Pose, Quaternion
from rosgraph_msgs.msg import Clock

MODEL = "caster_bot"


class SetModelStateTopicTest(unittest.TestCase):
    def setUp(self) -> None:
        rospy.init_node("set_model_state_check")
        self.changed = threading.Condition()
        self.pose = None
        self.now = 0.0
        rospy.Subscriber("/gazebo/model_states", ModelStates, self.on_states, queue_size=1)
        rospy.Subscriber("/clock", Clock, self.on_clock, queue_size=1)
        self.publisher = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=5)
        with self.changed:
            self.assertTrue(self.changed.wait_for(lambda: self.pose is not None, 120), "no model_states with the robot")
        while self.publisher.get_num_connections() == 0:  # the simulator's subscriber is connected
            rospy.wait_for_message("/clock", Clock, timeout=60)

    def on_states(self, states: ModelStates) -> None:
        if MODEL in states.name:
            with self.changed:
                self.pose = states.pose[states.name.index(MODEL)]
                self.changed.notify_all()

    def on_clock(self, clock: Clock) -> None:
        with self.changed:
            self.now = clock.clock.to_sec()
            self.changed.notify_all()

    def command(self, state: ModelState):
        """Publish the state, let 0.2 s of sim time pass; the robot's (x, y, heading) then."""
        with self.changed:
            start = self.now
        self.publisher.publish(state)
        with self.changed:
            self.assertTrue(self.changed.wait_for(lambda: self.now >= start + 0.2, 30), "sim time stands still")
            pose = self.pose
        q = pose.orientation
        heading = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
        return pose.position.x, pose.position.y, heading

    def test_frame(self) -> None:
        state = ModelState(MODEL, Pose(), None, MODEL + "::chassis")
        state.pose.orientation = Quaternion(0, 0, 0.04018, 1)
        for _ in range(15):
            x, y, heading = self.command(state)
            if abs(heading - math.pi / 4) <= 0.05:
                break
        self.assertLessEqual(abs(heading - math.pi / 4), 0.05)
        state.pose.orientation = Quaternion(0, 0, 0, 1)
        state.pose.position.x = 0.1
        for _ in range(70):
            x, y, heading = self.command(state)
            if math.hypot(x, y) >= 5.0:
                break
        self.assertLess(abs(x - 3.535533906), 0.2)
        self.assertLess(abs(y - 3.535533906), 0.2)
        state.pose.position.x = 0
        state.reference_frame = "world"
        x, y, heading = self.command(state)
        self.assertLess(abs(x), 0.01)
        self.assertLess(abs(y), 0.01)


if __name__ == "__main__":
    rostest.rosrun("gazebo_ros", "set_model_state", SetModelStateTopicTest)
