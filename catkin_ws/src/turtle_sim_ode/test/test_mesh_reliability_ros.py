#!/usr/bin/env python3
"""rostest node (issue #26): mesh files through the running simulator. The issue's broken meshes as collisions get
success: false naming the file and the fault; as visuals before a camera with a subscribed image they give a
warning naming model, link and file while the images keep coming; a 30 MB ASCII STL over the triangle limit is
refused from its count, about as fast as a small mesh is spawned, while sim time keeps its pace; then generated mesh
files (test/unit/test_mesh_fuzz.py's, fixed seed), each spawned as a collision and as a visual. After each input:
the spawn was answered within answer_time_ratio times a reference spawn of a small mesh (timed in the same run),
/clock moves on, the camera's images keep coming, every model's state is finite, and nothing is written but the
test's own scratch folder."""
import math
import os
import shutil
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from gazebo_clients import connect_gazebo_services, pose
from hypothesis import HealthCheck, given, settings
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import Image
from workspace_testing.timing import assert_within, best_seconds, timed

UNIT_TESTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "unit")
sys.path.insert(0, UNIT_TESTS)
from test_mesh_fuzz import meshes  # noqa: E402  (the generated mesh files of the unit suite)
from test_mesh_reliability import BROKEN  # noqa: E402

SMALL_STL = b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n"
CAMERA = """<robot name="cam"><link name="base"><inertial><mass value="1"/>
<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<gazebo reference="base"><sensor type="camera" name="cam"><update_rate>10</update_rate><pose>0 0 0.2 0 0 0</pose>
<camera><horizontal_fov>1.047</horizontal_fov><image><width>32</width><height>24</height></image>
<clip><near>0.05</near><far>10</far></clip></camera>
<plugin name="c" filename="libgazebo_ros_camera.so"><cameraName>fuzz_cam</cameraName></plugin>
</sensor></gazebo></robot>"""


def model_with(uri, as_visual, name="m"):
    mesh = "<mesh><uri>%s</uri></mesh>" % uri
    box = "<box><size>0.2 0.2 0.2</size></box>"
    collision = '<collision name="c"><geometry>%s</geometry></collision>' % (box if as_visual else mesh)
    visual = '<visual name="v"><geometry>%s</geometry></visual>' % mesh if as_visual else ""
    return '<sdf version="1.6"><model name="%s"><static>true</static><link name="l">%s%s</link></model></sdf>' % (
        name,
        collision,
        visual,
    )


class Arrivals:
    """A topic's messages and their wall arrival times; waiting for the next few."""

    def __init__(self, topic, msg_type):
        self.times, self.msgs = [], []
        self._changed = threading.Condition()
        self._sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=50)

    def _on_msg(self, _msg):
        with self._changed:
            self.times.append(time.monotonic())
            self.msgs.append(_msg)
            self._changed.notify_all()

    def wait_next(self, count, timeout):
        with self._changed:
            start = len(self.times)
            ok = self._changed.wait_for(lambda: len(self.times) >= start + count, timeout)
        assert ok, "%s stopped" % self._sub.name

    def sim_pace(self, since):
        """Sim seconds per wall second over the /clock messages that came after ``since``."""
        with self._changed:
            came = [(t, msg.clock.to_sec()) for t, msg in zip(self.times, self.msgs) if t >= since]
        (wall0, sim0), (wall1, sim1) = came[0], came[-1]
        return (sim1 - sim0) / (wall1 - wall0)


class MeshReliability(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        connect_gazebo_services(cls)
        cls.limit = rospy.get_param("~wait_limit")
        cls.ratio = rospy.get_param("~answer_time_ratio")
        cls.scratch = rospy.get_param("~scratch")
        cls.folder = os.path.join(cls.scratch, "fuzz_meshes")  # model://fuzz_meshes/NAME
        os.makedirs(cls.folder)
        cls.clock = Arrivals("/clock", Clock)
        cls.warnings = []
        rospy.Subscriber("/rosout", Log, lambda m: m.level == Log.WARN and cls.warnings.append(m.msg), queue_size=200)
        result = cls.spawn_urdf_model("fuzz_cam", CAMERA, "", pose(0, 0, 0.05), "")
        assert result.success, result.status_message
        topic = next(
            name
            for name, kind in rosgraph.Master(rospy.get_name()).getTopicTypes()
            if name.endswith("fuzz_cam/image_raw") and kind == "sensor_msgs/Image"
        )
        cls.images = Arrivals(topic, Image)
        cls.images.wait_next(2, 60)
        with open(os.path.join(cls.folder, "small.stl"), "wb") as mesh_file:
            mesh_file.write(SMALL_STL)

        def spawn_small():
            small = model_with("model://fuzz_meshes/small.stl", False, "small")
            assert cls.spawn_sdf_model("small", small, "", pose(2.0, 0, 0.2), "").success
            assert cls.delete_model("small").success

        cls.reference = best_seconds(spawn_small)  # a spawn and a delete: the unit for every answer's time
        cls.outside = cls.listing(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.scratch, ignore_errors=True)

    @staticmethod
    def listing(folder):
        return sorted(
            (os.path.join(root, name), os.path.getmtime(os.path.join(root, name)))
            for root, _, names in os.walk(folder)
            for name in names
            if "__pycache__" not in root
        )

    def alive(self):
        """/clock and the images move on, the node answers, every model's state is finite."""
        self.clock.wait_next(3, self.limit)
        self.images.wait_next(1, self.limit)
        properties, took = timed(self.get_world_properties)
        assert_within(took, self.reference, self.ratio, "get_world_properties")
        for name in properties.model_names:
            state, took = timed(lambda: self.get_model_state(name, ""))
            assert_within(took, self.reference, self.ratio, "get_model_state")
            values = [getattr(state.pose.position, a) for a in "xyz"] + [getattr(state.twist.linear, a) for a in "xyz"]
            self.assertTrue(state.success and all(math.isfinite(v) for v in values), (name, values))

    def spawn_file(self, name, data, as_visual, model="m"):
        with open(os.path.join(self.folder, name), "wb") as mesh_file:
            mesh_file.write(data)
        result, took = timed(
            lambda: self.spawn_sdf_model(
                model, model_with("model://fuzz_meshes/" + name, as_visual, model), "", pose(1.0, 0, 0.2), ""
            )
        )
        self.last_answer = took
        assert_within(took, self.reference, self.ratio, "spawning %s" % name)
        return result

    def removed(self, model):
        if model in self.get_world_properties().model_names:
            self.assertTrue(self.delete_model(model).success)

    def test_1_broken_collision_meshes_are_refused_naming_the_file_and_the_fault(self):
        for name, text, words in BROKEN:
            result = self.spawn_file(name, text.encode(), as_visual=False)
            self.assertFalse(result.success, name)
            self.assertIn(name, result.status_message)
            self.assertIn(words, result.status_message)
            self.alive()

    def test_2_broken_visual_meshes_warn_once_and_the_camera_goes_on(self):
        for index, (name, text, words) in enumerate(BROKEN):
            before = len(self.warnings)
            model = "v%d" % index
            self.assertTrue(self.spawn_file(name, text.encode(), as_visual=True, model=model).success)
            self.images.wait_next(3, self.limit)
            self.alive()
            named = [w for w in self.warnings[before:] if "model '%s'" % model in w and name in w and "link 'l'" in w]
            self.assertEqual(len(named), 1, self.warnings[before:])
            self.removed(model)

    def test_3_a_large_file_is_read_without_stopping_the_clock(self):
        facet = b"facet normal 0 0 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n"
        data = b"solid large\n" + facet * 320000 + b"endsolid large\n"
        quiet = time.monotonic()
        self.clock.wait_next(50, self.limit)
        pace = self.clock.sim_pace(quiet)
        since = time.monotonic()
        result = self.spawn_file("large.stl", data, as_visual=False)
        self.assertFalse(result.success)
        self.assertIn("320000 triangles", result.status_message)
        assert_within(self.last_answer, self.reference, rospy.get_param("~large_file_ratio"), "the 30 MB file")
        self.clock.wait_next(50, self.limit)
        # Read away from the world lock: sim time keeps its pace meanwhile (a stalled /clock would fall behind).
        self.assertGreater(self.clock.sim_pace(since), rospy.get_param("~kept_pace") * pace)
        self.alive()

    def test_4_generated_mesh_files(self):
        @settings(
            max_examples=rospy.get_param("~examples"),
            derandomize=True,
            deadline=None,
            database=None,
            suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
        )
        @given(mesh=meshes)
        def check(mesh):
            name, data = mesh
            for as_visual in (False, True):
                result = self.spawn_file(name, data, as_visual)
                if not result.success:
                    self.assertIn(name, result.status_message)
                self.images.wait_next(1, self.limit)
                self.alive()
                self.removed("m")

        check()
        self.assertEqual(self.listing(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), self.outside)


if __name__ == "__main__":
    rospy.init_node("mesh_reliability")
    rostest.rosrun("turtle_sim_ode", "mesh_reliability", MeshReliability, sys.argv)
