#!/usr/bin/env python3
"""rostest node: a listener on /gazebo/scene_markers that keeps what it is sent, as rviz's MarkerArray display keeps
it (DELETEALL clears, DELETE removes, ADD adds or replaces), sees after each generated spawn, move
(set_model_state) and delete exactly the models of /gazebo/model_states, each box at its model's pose, and the
ground plane. A second listener that joins late gets the whole scene at once."""
import math
import subprocess
import sys
import threading
import time
import unittest
from typing import Dict, Tuple

import rospy
import rostest
from gazebo_msgs.msg import ModelState, ModelStates
from geometry_msgs.msg import Point, Pose, Quaternion
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from visualization_msgs.msg import Marker, MarkerArray

from gazebo_clients import connect_gazebo_services

TOPIC = "/gazebo/scene_markers"
NAMES = ("box_a", "box_b", "box_c")
BOX = """<sdf version="1.6"><model name="{name}"><static>true</static><link name="body">
  <visual name="look"><geometry><box><size>0.4 0.3 0.2</size></box></geometry>
    <material><diffuse>1 0 0 1</diffuse></material></visual>
  <collision name="shape"><geometry><box><size>0.4 0.3 0.2</size></box></geometry></collision>
</link></model></sdf>"""


class SceneKeeper:
    """What a MarkerArray display keeps of the topic, and the latest /gazebo/model_states."""

    def __init__(self) -> None:
        self.changed = threading.Condition()
        self.markers: Dict[Tuple[str, int], Marker] = {}
        self.states: Dict[str, Pose] = {}
        self.subscriber = rospy.Subscriber(TOPIC, MarkerArray, self.on_markers, queue_size=100)

    def on_markers(self, message: MarkerArray) -> None:
        with self.changed:
            for marker in message.markers:
                if marker.action == Marker.DELETEALL:
                    self.markers.clear()
                elif marker.action == Marker.DELETE:
                    self.markers.pop((marker.ns, marker.id), None)
                else:
                    self.markers[(marker.ns, marker.id)] = marker
            self.changed.notify_all()

    def on_states(self, message: ModelStates) -> None:
        with self.changed:
            self.states = dict(zip(message.name, message.pose))
            self.changed.notify_all()

    def mismatch(self) -> str:
        """Why the kept scene differs from the model states ("" if it does not); call holding ``changed``."""
        shown = {ns for ns, _ in self.markers}
        if shown != set(self.states) | {"ground_plane"}:
            return "markers of %s, models %s" % (sorted(shown), sorted(self.states))
        for name, pose in self.states.items():
            marker = self.markers.get((name, 0))
            if marker is None or marker.type != Marker.CUBE or marker.header.frame_id != "world":
                return "model %s has no box marker in frame world: %s" % (name, marker)
            a, b = marker.pose, pose
            if math.dist((a.position.x, a.position.y, a.position.z), (b.position.x, b.position.y, b.position.z)) > 1e-3:
                return "model %s marker at %s, model at %s" % (name, a.position, b.position)
            dot = abs(sum(getattr(a.orientation, c) * getattr(b.orientation, c) for c in "xyzw"))
            if dot < 1 - 1e-5:
                return "model %s marker turned %s, model %s" % (name, a.orientation, b.orientation)
        return ""


def quaternion_of(yaw: float) -> Quaternion:
    return Quaternion(0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


# Rounded to a micrometre: no subnormal numbers, which the simulator refuses as poses (allow_subnormal needs
# Hypothesis 6; Ubuntu 20.04 has 5).
coordinates = st.floats(-4, 4).map(lambda v: round(v, 6))
operations = st.lists(
    st.tuples(
        st.sampled_from(["spawn", "move", "delete"]),
        st.sampled_from(NAMES),
        st.tuples(
            coordinates,
            coordinates,
            st.floats(0, 1).map(lambda v: round(v, 6)),
            st.floats(-3, 3).map(lambda v: round(v, 6)),
        ),
    ),
    min_size=1,
    max_size=6,
)


class SceneMarkersFollowTheWorld(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        connect_gazebo_services(cls, 120)
        cls.keeper = SceneKeeper()
        cls.states_sub = rospy.Subscriber("/gazebo/model_states", ModelStates, cls.keeper.on_states, queue_size=1)
        cls.timeout = rospy.get_param("~timeout", 10.0)
        cls.latencies = []

    def agree(self, what: str) -> None:
        """Wait until the kept scene matches the model states (both topics keep arriving)."""
        start = time.monotonic()
        with self.keeper.changed:
            agreed = self.keeper.changed.wait_for(lambda: not self.keeper.mismatch(), self.timeout)
            why = self.keeper.mismatch()
        self.assertTrue(agreed, "after %s: %s" % (what, why))
        self.latencies.append(time.monotonic() - start)

    @settings(max_examples=15, deadline=None, suppress_health_check=list(HealthCheck))
    @given(operations)
    def test_kept_scene_matches_model_states(self, steps) -> None:  # type: ignore[no-untyped-def]
        try:
            for action, name, (x, y, z, yaw) in steps:
                pose = Pose(Point(x, y, z), quaternion_of(yaw))
                if action == "spawn":
                    answer = self.spawn_sdf_model(name, BOX.format(name=name), "", pose, "world")
                elif action == "move":
                    answer = self.set_model_state(ModelState(model_name=name, pose=pose, reference_frame="world"))
                else:
                    answer = self.delete_model(name)
                what = "%s %s at (%.3f, %.3f, %.3f, yaw %.3f): %s" % (action, name, x, y, z, yaw, answer.status_message)
                self.agree(what)
        finally:
            for name in NAMES:
                self.delete_model(name)
            self.agree("clean-up")
        rospy.loginfo("scene agreed with model_states within %.3f s at worst", max(self.latencies))

    def test_late_listener_gets_the_whole_scene(self) -> None:
        """A listener in a process of its own (rospy shares one connection per topic in a process) gets, as its
        first message, a DELETEALL and every visual of the scene, though nothing changes meanwhile."""
        self.spawn_sdf_model("box_a", BOX.format(name="box_a"), "", Pose(Point(1, 2, 0), quaternion_of(0.5)), "world")
        try:
            self.agree("spawn box_a")
            first = subprocess.run(
                ["rostopic", "echo", "-n", "1", TOPIC], capture_output=True, text=True, timeout=self.timeout + 30
            ).stdout
            self.assertIn("action: 3", first)  # DELETEALL
            self.assertIn('ns: "box_a"', first)
            self.assertIn('ns: "ground_plane"', first)
        finally:
            self.delete_model("box_a")


if __name__ == "__main__":
    rospy.init_node("test_scene_markers")
    rostest.rosrun("turtle_sim_ode", "scene_markers_follow_the_world", SceneMarkersFollowTheWorld, sys.argv)
