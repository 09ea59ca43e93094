#!/usr/bin/env python3
"""rostest node (issue #9, bad input): throws malformed, hostile and absurd input at the running simulator and at a
tutorial node, one test per input. Each gets success: false with a status_message naming the problem, or a
throttled warning on /rosout; after each, /clock still advances, the reference models have not moved and every
node of the graph still answers."""
import contextlib
import math
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from xmlrpc.client import ServerProxy

import rosgraph
import rospy
import rostest
from gazebo_clients import connect_gazebo_services, model_text, pose
from gazebo_msgs.msg import LinkState, ModelState, ODEJointProperties
from geometry_msgs.msg import Point, Twist, Vector3, Wrench
from rosgraph_msgs.msg import Clock, Log
from std_msgs.msg import String
from workspace_testing.timing import assert_within, best_seconds, timed

NAN, INF = float("nan"), float("inf")
NODES = ("/gazebo", "/robot_state_publisher", "/listener")
INERTIAL = '<inertial><mass value="{mass}"/><inertia ixx="{i}" iyy="{i}" izz="{i}"/></inertial>'
COLLISION = '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
STATIC_BOX = (
    '<sdf version="1.6"><model name="m"><static>true</static><link name="link"><collision name="c"><geometry>'
    "<box><size>0.4 0.4 0.4</size></box></geometry></collision></link></model></sdf>"
)
LAUGHS = (
    '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaaaaaaaa">'
    + "".join('<!ENTITY %s "%s">' % (chr(98 + i), ("&%s;" % chr(97 + i)) * 10) for i in range(8))
    + "]>"
)
EXTERNAL = '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>'


def link(name, mass=1.0, inertia=0.01, collision=COLLISION):
    return '<link name="%s">%s%s</link>' % (name, INERTIAL.format(mass=mass, i=inertia), collision)


def joint(name, parent, child):
    return '<joint name="%s" type="fixed"><parent link="%s"/><child link="%s"/></joint>' % (name, parent, child)


def robot(*parts):
    return '<robot name="r">%s</robot>' % "".join(parts)


def twist(linear, angular=0.0):
    return Twist(Vector3(linear, 0, 0), Vector3(0, 0, angular))


class Latest:
    """The newest message of a topic, and a way to wait for one that satisfies a condition."""

    def __init__(self, topic, msg_type, keep=False):
        self.msg, self.all = None, []
        self._keep = keep
        self._changed = threading.Condition()
        self._sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=100)

    def _on_msg(self, msg):
        with self._changed:
            self.msg = msg
            if self._keep:
                self.all.append(msg)
            self._changed.notify_all()

    def wait_for(self, condition, timeout=20.0):
        with self._changed:
            ok = self._changed.wait_for(lambda: self.msg is not None and condition(self.msg), timeout)
        assert ok, "nothing on %s within %s s (wall)" % (self._sub.name, timeout)
        return self.msg

    def matching(self, condition):
        with self._changed:
            return [msg for msg in self.all if condition(msg)]


class BadInput(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        connect_gazebo_services(cls)
        cls.clock = Latest("/clock", Clock)
        cls.rosout = Latest("/rosout", Log, keep=True)
        cls.cmd = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=10)
        cls.state_topic = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=10)
        cls.box = model_text("box.urdf")
        cls.master = rosgraph.Master(rospy.get_name())
        for name, xml, at, sdf in (
            ("reference_static", STATIC_BOX, pose(-3, 3, 0.2), True),
            ("reference_box", cls.box, pose(-3, -3, 0.1), False),
            ("scratch_box", cls.box, pose(3, -3, 0.1), False),
        ):
            result = (cls.spawn_sdf_model if sdf else cls.spawn_urdf_model)(name, xml, "", at, "")
            assert result.success, result.status_message
        cls.wait_sim(1.0)  # the dynamic boxes settle
        cls.references = {name: cls.state(name) for name in ("reference_static", "reference_box")}
        for publisher in (cls.cmd, cls.state_topic):
            cls.wait_connected(publisher)

    @classmethod
    def wait_sim(cls, seconds):
        """Let ``seconds`` of sim time pass (wall-clock independent)."""
        start = cls.clock.wait_for(lambda msg: True).clock
        cls.clock.wait_for(lambda msg: (msg.clock - start).to_sec() >= seconds)

    @staticmethod
    def wait_connected(publisher):
        deadline = time.monotonic() + 20
        while publisher.get_num_connections() == 0 and time.monotonic() < deadline:
            rospy.rostime.wallsleep(0.02)  # rospy offers no event for a new subscriber

    @classmethod
    def state(cls, name):
        result = cls.get_model_state(name, "")
        assert result.success, result.status_message
        return result.pose, result.twist

    def tearDown(self):
        """After every bad input: the simulation steps, the references have not moved, every node answers."""
        now = self.clock.wait_for(lambda msg: True).clock
        self.clock.wait_for(lambda msg: msg.clock > now, timeout=10)
        tolerance = rospy.get_param("~pose_tolerance")
        for name, (before, _) in self.references.items():
            after, _ = self.state(name)
            for axis in "xyz":
                self.assertAlmostEqual(getattr(after.position, axis), getattr(before.position, axis), delta=tolerance)
            for axis in "xyzw":
                self.assertAlmostEqual(
                    getattr(after.orientation, axis), getattr(before.orientation, axis), delta=tolerance
                )
        for node in NODES:
            code, message, _ = ServerProxy(self.master.lookupNode(node)).getPid(rospy.get_name())
            self.assertEqual(code, 1, "%s does not answer: %s" % (node, message))

    def refused(self, result, *words):
        self.assertFalse(result.success, "accepted, but should have been refused")
        for word in words:
            self.assertIn(word, result.status_message)

    def spawn(self, name, xml, at=None, frame="", namespace="", sdf=False):
        service = self.spawn_sdf_model if sdf else self.spawn_urdf_model
        return service(name, xml, namespace, at or pose(3, 3, 0.1), frame)

    def spawned(self, name, xml, **kwargs):
        result = self.spawn(name, xml, **kwargs)
        self.assertTrue(result.success, result.status_message)
        self.addCleanup(lambda: self.delete_model(name))
        return result

    def warnings(self, text):
        return self.rosout.matching(lambda msg: msg.name == "/gazebo" and msg.level == Log.WARN and text in msg.msg)

    @contextlib.contextmanager
    def another_publisher(self, topic, msg_type, value):
        """``rostopic pub`` of ``value`` at 10 Hz on ``topic``, from its own node (a rospy node cannot publish two
        types on one topic), while the block runs; once the master lists it and 0.5 s of sim time have passed."""
        command = ["rostopic", "pub", "-r", "10", topic, msg_type, value]
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            deadline = time.monotonic() + 30
            while not any(
                topic == name and any(node.startswith("/rostopic_") for node in nodes)
                for name, nodes in self.master.getSystemState()[0]
            ):
                self.assertLess(time.monotonic(), deadline, "rostopic pub did not come up")
                self.assertIsNone(process.poll(), "rostopic pub ended early")
                rospy.rostime.wallsleep(0.05)  # the master announces no registration
            self.wait_sim(0.5)
            yield
        finally:
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()

    def assert_robot_stays(self, command):
        """Send ``command`` for 0.5 s of sim time: the robot must not move, its state must stay finite."""
        before, _ = self.state("mobile_base")
        for _ in range(10):
            self.cmd.publish(command)
            self.wait_sim(0.05)
        after, velocity = self.state("mobile_base")
        values = [getattr(v, a) for v in (after.position, after.orientation, velocity.linear) for a in "xyz"]
        self.assertTrue(all(math.isfinite(v) for v in values), values)
        self.assertLess(math.hypot(after.position.x - before.position.x, after.position.y - before.position.y), 1e-3)

    def drive_briefly(self, command):
        """Send ``command`` for 0.3 s of sim time, then stop; return the distance and the top speed seen."""
        before, _ = self.state("mobile_base")
        top = 0.0
        for _ in range(6):
            self.cmd.publish(command)
            self.wait_sim(0.05)
            _, velocity = self.state("mobile_base")
            top = max(top, math.hypot(velocity.linear.x, velocity.linear.y))
        self.cmd.publish(Twist())
        self.wait_sim(0.5)
        after, velocity = self.state("mobile_base")
        self.assertLess(math.hypot(velocity.linear.x, velocity.linear.y), 0.01, "the robot did not stop")
        return math.hypot(after.position.x - before.position.x, after.position.y - before.position.y), top

    # --- a: the robot's velocity topic --------------------------------------------------------------------------
    def test_a01_nan_velocity_is_ignored_with_one_throttled_warning(self):
        already = len(self.warnings("not finite"))
        self.assert_robot_stays(twist(NAN, 0.0))
        self.rosout.wait_for(lambda msg: len(self.warnings("not finite")) > already)
        for _ in range(40):
            self.cmd.publish(twist(NAN, NAN))
        self.wait_sim(0.2)
        self.assertEqual(len(self.warnings("not finite")), already + 1, "50 bad commands within the throttle period")

    def test_a02_inf_velocity_is_ignored(self):
        self.assert_robot_stays(twist(INF, -INF))

    def test_a03_1e308_velocity_is_clamped_and_stays_finite(self):
        distance, top = self.drive_briefly(twist(1e308, 1e308))
        self.assertLessEqual(top, rospy.get_param("~max_linear") + 0.05)
        self.assertTrue(math.isfinite(distance))

    def test_a04_wrong_message_type_leaves_the_node_working(self):
        with self.another_publisher("/mobile_base/commands/velocity", "std_msgs/String", "data: forward, fast"):
            self.assert_robot_stays(Twist())
        distance, _ = self.drive_briefly(twist(0.3))
        self.assertGreater(distance, 0.02, "a Twist after the String must still drive the robot")

    # --- b: spawn_urdf_model / spawn_sdf_model --------------------------------------------------------------
    def test_b01_empty_xml(self):
        self.refused(self.spawn("empty_xml", ""), "model_xml of 'empty_xml' is empty")

    def test_b02_truncated_xml(self):
        self.refused(self.spawn("truncated", self.box[:120]), "not well-formed XML at line")

    def test_b03_not_xml(self):
        self.refused(self.spawn("not_xml", "hello world"), "neither URDF (<robot>) nor SDF")

    def test_b04_wrong_root(self):
        self.refused(self.spawn("wrong_root", "<html><body/></html>", sdf=True), "neither URDF (<robot>) nor SDF")

    def test_b05_billion_laughs(self):
        self.refused(self.spawn("laughs", LAUGHS + '<robot name="r">&i;</robot>'), "XML guard", "EntitiesForbidden")
        self.refused(self.spawn("laughs", LAUGHS + '<sdf version="1.6">&i;</sdf>', sdf=True), "SDF rejected")

    def test_b06_external_entity(self):
        self.refused(self.spawn("external", EXTERNAL + '<robot name="r">&x;</robot>'), "XML guard")
        self.refused(self.spawn("external", EXTERNAL + '<sdf version="1.6">&x;</sdf>', sdf=True), "XML guard")

    def test_b07_zero_mass(self):
        self.refused(self.spawn("zero_mass", robot(link("a", mass=0))), "mass must be > 0, got 0")

    def test_b08_negative_mass(self):
        self.refused(self.spawn("negative_mass", robot(link("a", mass=-1))), "mass must be > 0, got -1")

    def test_b09_inertia_not_positive_definite(self):
        self.refused(self.spawn("flat", robot(link("a", inertia=-0.01))), "inertia matrix is not positive definite")

    def test_b10_joint_parent_missing(self):
        xml = robot(link("a"), link("b"), joint("j", "ghost", "b"))
        self.refused(self.spawn("orphan", xml), "joint 'j': parent link 'ghost' does not exist")

    def test_b11_joint_cycle(self):
        xml = robot(link("a"), link("b"), joint("ab", "a", "b"), joint("ba", "b", "a"))
        self.refused(self.spawn("cycle", xml), "cycle")

    def test_b12_two_root_links(self):
        self.refused(self.spawn("two_roots", robot(link("a"), link("b"))), "2 root links")

    def refused_quickly(self, xml, *words):
        """``xml`` refused with ``words`` within ~refusal_time_ratio times the refusal of the same text for its
        namespace, which is checked before the text is read (both timed here: the same bytes sent and answered)."""
        unread = best_seconds(lambda: self.spawn("fast", xml, namespace="bad namespace"))
        result, took = timed(lambda: self.spawn("slow", xml))
        self.refused(result, *words)
        assert_within(took, unread, rospy.get_param("~refusal_time_ratio"), "the refusal")

    def test_b13_10000_links_refused_quickly_with_the_limit(self):
        xml = robot(
            *(link("l%d" % i) for i in range(10000)), *(joint("j%d" % i, "l0", "l%d" % i) for i in range(1, 10000))
        )
        self.refused_quickly(xml, "too large: 10000 links, 9999 joints", "(limits 1000, 1000, 1000)")

    def test_b14_mesh_files_outside_the_roots_are_never_opened(self):
        folder = tempfile.mkdtemp()
        fifo = os.path.join(folder, "mesh.stl")
        os.mkfifo(fifo)  # reading it would block until a writer comes: an open() hangs the spawn
        self.addCleanup(os.rmdir, folder)
        self.addCleanup(os.unlink, fifo)
        collisions = "".join(
            '<collision><geometry><mesh filename="%s"/></geometry></collision>' % path
            for path in ("file://" + fifo, "file:///proc/self/mem", "file:///dev/zero")
        )
        result = []
        call = threading.Thread(
            target=lambda: result.append(self.spawn("meshy", robot(link("a", collision=collisions))))
        )
        call.start()
        call.join(rospy.get_param("~hang_wait"))
        self.assertFalse(call.is_alive(), "spawning a model with a mesh on a FIFO hangs")
        # Issue 14: meshes are read, but only from under the ROS package path and model path: refused, not hung.
        self.assertFalse(result[0].success, result[0].status_message)
        self.assertIn("mesh.stl", result[0].status_message)
        self.assertIn("outside the ROS package path", result[0].status_message)

    def test_b15_duplicate_model_name(self):
        self.refused(self.spawn("reference_box", self.box), "a model named 'reference_box' already exists")

    def test_b16_empty_model_name(self):
        self.refused(self.spawn("", self.box), "model name is empty")

    def test_b17_model_name_not_a_ros_name(self):
        self.refused(self.spawn("tb\x00e", model_text("box.urdf")), "is not a legal ROS name")
        self.refused(self.spawn("my box", self.box), "is not a legal ROS name")

    def test_b18_robot_namespace_not_a_ros_name(self):
        self.refused(self.spawn("spaced", self.box, namespace="bad namespace"), "not a legal ROS namespace")

    def test_b19_unknown_reference_frame(self):
        self.refused(self.spawn("lost", self.box, frame="nowhere"), "reference frame 'nowhere' is not a model or link")

    def test_b20_quaternions_in_initial_pose_are_normalised(self):
        self.spawned("turned", self.box, at=pose(3, 2, 0.1, 0, 0, 3, 3))
        q = self.state("turned")[0].orientation
        self.assertAlmostEqual(math.atan2(2 * q.w * q.z, 1 - 2 * q.z * q.z), math.pi / 2, delta=0.01)
        self.spawned("zero_turn", self.box, at=pose(3, 1, 0.1, 0, 0, 0, 0))  # Pose() as clients send it
        self.assertAlmostEqual(abs(self.state("zero_turn")[0].orientation.w), 1.0, delta=0.01)

    def test_b21_position_beyond_the_world(self):
        self.refused(self.spawn("far", self.box, at=pose(1e308, 0, 0)), "position must be at most 1e+06")

    def test_b22_absurd_numbers_in_the_model(self):
        self.refused(self.spawn("dense", robot(link("a", inertia=1e300))), "ixx (kg m^2) must be at most 1e+12")
        offset = '<collision><origin xyz="1e12 0 0"/><geometry><sphere radius="1"/></geometry></collision>'
        self.refused(self.spawn("offset", robot(link("a", collision=offset))), "origin xyz (m) must be at most 1e+06")

    def test_b23_too_many_collisions(self):
        self.refused(self.spawn("spiky", robot(link("a", collision=COLLISION * 1001))), "1001 collisions")

    def test_b24_hostile_prolog_is_refused_quickly(self):
        self.refused_quickly("<!--" * 1000000, "neither URDF (<robot>) nor SDF")

    # --- c: model states ---------------------------------------------------------------------------------------
    def test_c01_get_model_state_unknown_frame(self):
        self.refused(self.get_model_state("scratch_box", "nowhere"), "reference frame 'nowhere'")

    def test_c02_set_model_state_unknown_frame(self):
        state = ModelState("scratch_box", pose(3, -3, 0.1), Twist(), "nowhere")
        self.refused(self.set_model_state(state), "reference frame 'nowhere'")

    def test_c03_set_model_state_normalises_quaternions(self):
        result = self.set_model_state(ModelState("scratch_box", pose(3, -3, 0.1, 0, 0, 2, 2), Twist(), ""))
        self.assertTrue(result.success, result.status_message)
        q = self.state("scratch_box")[0].orientation
        self.assertAlmostEqual(math.sqrt(q.x**2 + q.y**2 + q.z**2 + q.w**2), 1.0, places=6)
        result = self.set_model_state(ModelState("scratch_box", pose(3, -3, 0.1, 0, 0, 0, 0), Twist(), ""))
        self.assertTrue(result.success, result.status_message)
        self.assertAlmostEqual(abs(self.state("scratch_box")[0].orientation.w), 1.0, places=3)

    def test_c04_set_model_state_huge_values(self):
        self.refused(
            self.set_model_state(ModelState("scratch_box", pose(1e308, 0, 0.1), Twist(), "")), "position must be"
        )
        huge_spin = Twist(Vector3(), Vector3(0, 0, 1e300))
        self.refused(
            self.set_model_state(ModelState("scratch_box", pose(3, -3, 0.1), huge_spin, "")), "angular velocity"
        )
        result = self.set_model_state(ModelState("scratch_box", pose(3, -3, 0.1, 0, 0, 1e308, 1e308), Twist(), ""))
        self.assertTrue(result.success, result.status_message)
        q = self.state("scratch_box")[0].orientation
        self.assertAlmostEqual(q.z, math.sqrt(0.5), places=6)

    def test_c05_set_model_state_topic_nan_is_a_throttled_warning(self):
        # Only this test's warnings: the refusals of c04's service calls may still be on their way to /rosout.
        nan_warnings = "/gazebo/set_model_state: position must be 3 finite numbers"
        already = len(self.warnings(nan_warnings))
        for _ in range(20):
            self.state_topic.publish(ModelState("scratch_box", pose(NAN, 0, 0), Twist(), ""))
        self.rosout.wait_for(lambda msg: len(self.warnings(nan_warnings)) > already)
        self.wait_sim(0.2)
        self.assertEqual(len(self.warnings(nan_warnings)), already + 1)
        self.assertTrue(all(math.isfinite(getattr(self.state("scratch_box")[0].position, a)) for a in "xyz"))

    # --- d: forces ---------------------------------------------------------------------------------------------
    def apply(self, force=(0, 0, 0.1), torque=(0, 0, 0), duration=1.0, body="scratch_box::box_link"):
        wrench = Wrench(Vector3(*force), Vector3(*torque))
        return self.apply_body_wrench(body, "", Point(), wrench, rospy.Time(0), rospy.Duration(duration))

    def test_d01_negative_duration_lasts_until_cleared(self):
        result = self.apply(duration=-5.0)
        self.assertTrue(result.success, result.status_message)
        self.clear_body_wrenches("scratch_box::box_link")

    def test_d02_huge_duration_is_accepted_and_cleared(self):
        result = self.apply(duration=2**31 - 1)
        self.assertTrue(result.success, result.status_message)
        self.clear_body_wrenches("scratch_box::box_link")

    def test_d03_huge_or_nan_force(self):
        self.refused(self.apply(force=(1e308, 0, 0)), "force must be at most 1e+06")
        self.refused(self.apply(torque=(0, NAN, 0)), "torque must be 3 finite numbers")
        self.refused(self.apply_joint_effort("wheel_left_joint", 1e308, rospy.Time(0), rospy.Duration(1)), "effort")

    # --- e: physics ---------------------------------------------------------------------------------------------
    def test_e01_bad_physics_properties_change_nothing(self):
        physics = self.get_physics_properties()
        rate, gravity, ode = physics.max_update_rate, physics.gravity, physics.ode_config
        for time_step in (0.0, -0.001):
            self.refused(self.set_physics_properties(time_step, rate, gravity, ode), "time_step must be in (0, 0.1]")
        self.refused(self.set_physics_properties(0.001, rate, Vector3(0, NAN, -9.81), ode), "gravity")
        self.refused(self.set_physics_properties(0.001, rate, Vector3(0, 0, -1e9), ode), "gravity must be at most")
        ode.sor_pgs_iters = 10**6
        self.refused(self.set_physics_properties(0.001, rate, gravity, ode), "iterations must be an integer in 1..1000")
        after = self.get_physics_properties()
        self.assertEqual((after.time_step, after.gravity.z, after.ode_config.sor_pgs_iters), (0.001, -9.81, 50))

    # --- f: unknown names --------------------------------------------------------------------------------------
    def test_f01_unknown_model(self):
        self.refused(self.get_model_state("ghost", ""), "model 'ghost' does not exist")
        self.refused(self.set_model_state(ModelState("ghost", pose(), Twist(), "")), "model 'ghost' does not exist")
        self.refused(self.get_model_properties("ghost"), "model 'ghost' does not exist")
        self.refused(self.delete_model("ghost"), "model 'ghost' does not exist")
        self.refused(self.set_model_configuration("ghost", "", ["j"], [0.0]), "model 'ghost' does not exist")

    def test_f02_unknown_link(self):
        self.refused(self.get_link_state("scratch_box::ghost", ""), "link 'scratch_box::ghost' does not exist")
        state = LinkState("ghost::link", pose(), Twist(), "")
        self.refused(self.set_link_state(state), "link 'ghost::link' does not exist")
        self.refused(self.get_link_properties("ghost"), "link 'ghost' does not exist")
        self.refused(self.set_link_properties("ghost::link", pose(), True, 1.0, 1, 0, 0, 1, 0, 1), "link 'ghost::link'")
        self.refused(self.apply(body="ghost::link"), "link 'ghost::link' does not exist")
        self.clear_body_wrenches("ghost::link")  # an empty response: logged, nothing else

    def test_f03_unknown_joint(self):
        self.refused(self.get_joint_properties("ghost_joint"), "joint 'ghost_joint' does not exist")
        config = ODEJointProperties(damping=[0.1])
        self.refused(self.set_joint_properties("ghost_joint", config), "joint 'ghost_joint' does not exist")
        effort = self.apply_joint_effort("ghost_joint", 1.0, rospy.Time(0), rospy.Duration(1))
        self.refused(effort, "joint 'ghost_joint' does not exist")
        self.refused(self.set_model_configuration("mobile_base", "", ["ghost_joint"], [0.0]), "no joint 'ghost_joint'")
        self.clear_joint_forces("ghost_joint")

    # --- g: a tutorial node ------------------------------------------------------------------------------------
    def test_g01_listener_survives_a_wrong_message_type(self):
        with self.another_publisher("/chatter", "std_msgs/Int32", "data: 42"):
            pass
        right = rospy.Publisher("/chatter", String, queue_size=1)
        try:
            self.wait_connected(right)
            right.publish(String("still listening"))
            heard = lambda msg: msg.name == "/listener" and msg.msg == "I heard: [still listening]"  # noqa: E731
            self.rosout.wait_for(lambda _: bool(self.rosout.matching(heard)))
        finally:
            right.unregister()


if __name__ == "__main__":
    rospy.init_node("test_bad_input")
    rostest.rosrun("turtle_sim_ode", "bad_input", BadInput, sys.argv)
