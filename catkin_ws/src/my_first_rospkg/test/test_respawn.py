#!/usr/bin/env python3
"""rostest node: kill -9 the simulator mid-run; roslaunch respawns it, it spawns the robot again, and the nodes
that were never restarted (bounce, robot_state_publisher) drive and describe the robot again. Also: a client
killed while holding a persistent service connection does not disturb the simulator."""
import math
import os
import signal
import subprocess
import sys
import textwrap
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from gazebo_msgs.srv import GetModelState
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

from turtle_sim_ode.analysis.waiting import wait_for

# A client that opens a persistent connection to a /gazebo service, uses it, and then waits to be killed.
PERSISTENT_CLIENT = textwrap.dedent(
    """
    import sys, rospy
    from gazebo_msgs.srv import GetModelState
    rospy.init_node("persistent_client", anonymous=True)
    rospy.wait_for_service("/gazebo/get_model_state", timeout=30)
    proxy = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState, persistent=True)
    proxy("mobile_base", "world")
    print("connected", flush=True)
    sys.stdin.read()
    """
)


def node_pid(name):
    """The pid of a node, from its XML-RPC server (None while it is not registered or not answering)."""
    try:
        uri = rosgraph.Master("/test_respawn").lookupNode(name)
        return xmlrpc.client.ServerProxy(uri).getPid("/test_respawn")[2]
    except (rosgraph.MasterError, OSError, xmlrpc.client.Error):
        return None


def travelled(moved, timeout=60):
    """Wait until /odom shows the robot at least `moved` m from where it was first seen."""
    first = rospy.wait_for_message("/odom", Odometry, timeout=timeout).pose.pose.position
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        now = rospy.wait_for_message("/odom", Odometry, timeout=timeout).pose.pose.position
        if math.hypot(now.x - first.x, now.y - first.y) >= moved:
            return True
    return False


class Respawn(unittest.TestCase):
    def test_a_killed_client_with_a_persistent_connection(self):
        client = subprocess.Popen(
            [sys.executable, "-c", PERSISTENT_CLIENT], stdin=subprocess.PIPE, stdout=subprocess.PIPE
        )
        try:
            self.assertEqual(client.stdout.readline().strip(), b"connected")
        finally:
            client.kill()
            client.wait()
        before = rospy.wait_for_message("/clock", Clock, timeout=10).clock
        state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("mobile_base", "world")
        self.assertTrue(state.success, state.status_message)
        self.assertTrue(wait_for(lambda: rospy.wait_for_message("/clock", Clock, timeout=10).clock > before, 10))

    def test_b_simulator_respawns_and_the_graph_works_again(self):
        self.assertTrue(travelled(rospy.get_param("~moved")), "the robot did not drive before the kill")
        survivors = {name: node_pid(name) for name in ("/bounce", "/robot_state_publisher")}
        old = node_pid("/gazebo")
        self.assertTrue(old and all(survivors.values()), (old, survivors))
        os.kill(old, signal.SIGKILL)
        new = wait_for(lambda: (node_pid("/gazebo") or old) != old and node_pid("/gazebo"), 60)
        self.assertTrue(new, "the simulator was not respawned")
        self.assertTrue(travelled(rospy.get_param("~moved")), "the robot does not drive after the respawn")
        self.assertEqual({name: node_pid(name) for name in survivors}, survivors, "a node was restarted or died")
        wheel = wait_for(lambda: self._wheel_transform(), 30)
        self.assertTrue(wheel, "robot_state_publisher does not publish the wheels' tf again")

    @staticmethod
    def _wheel_transform():
        message = rospy.wait_for_message("/tf", TFMessage, timeout=10)
        return any(t.child_frame_id == "wheel_left_link" for t in message.transforms)


if __name__ == "__main__":
    rospy.init_node("test_respawn")
    rostest.rosrun("my_first_rospkg", "respawn", Respawn, sys.argv)
