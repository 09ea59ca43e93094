#!/usr/bin/env python3
"""rostest node (issue #16, the node's half of bad input): inputs that once killed, froze or corrupted the simulator
through its ROS layer: pacing across rate changes, pause and lockstep; spawns that failed half-way; plugin topics
colliding with other types; non-ASCII and huge names; reset while paused; models asking for too many rays;
thousands of unsupported plugins; a <world> sent as a model. After each, as in test_bad_input.py: /clock still
advances, the reference models have not moved and every node answers."""
import threading
import unittest
from xmlrpc.client import ServerProxy

import rosgraph
import rospy
import rostest
from gazebo_clients import connect_gazebo_services, model_text, pose
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import LaserScan
from test_bad_input import NODES, STATIC_BOX, Latest
from turtle_sim_ode_msgs.srv import StepSimulation
from workspace_testing.timing import assert_within, best_seconds, timed

LASER = (
    '<gazebo reference="{link}"><sensor type="ray" name="{name}"><update_rate>{rate}</update_rate><ray><scan>'
    "<horizontal><samples>{samples}</samples><min_angle>0</min_angle><max_angle>6.28</max_angle></horizontal>"
    "</scan><range><min>0.1</min><max>3.5</max></range></ray>"
    '<plugin name="{name}_plugin" filename="libgazebo_ros_laser.so"><topicName>{topic}</topicName></plugin>'
    "</sensor></gazebo>"
)
P3D = (
    '<gazebo><plugin name="truth" filename="libgazebo_ros_p3d.so"><bodyName>box_link</bodyName>'
    "<topicName>{topic}</topicName><updateRate>10</updateRate></plugin></gazebo>"
)


def box_with(*extras):
    """box.urdf (one link, box_link) with extra <gazebo> blocks."""
    return model_text("box.urdf").replace("</robot>", "".join(extras) + "</robot>")


def rss_mb(pid):
    with open("/proc/%d/status" % pid) as status:
        return int(status.read().split("VmRSS:")[1].split()[0]) / 1024.0


class BadInputNode(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        connect_gazebo_services(cls)
        rospy.wait_for_service("/gazebo/step_simulation", timeout=60)
        cls.step_simulation = staticmethod(rospy.ServiceProxy("/gazebo/step_simulation", StepSimulation))
        cls.clock = Latest("/clock", Clock)
        cls.rosout = Latest("/rosout", Log, keep=True)
        cls.master = rosgraph.Master(rospy.get_name())
        cls.answer_ratio = rospy.get_param("~answer_time_ratio")
        for name, xml, at, sdf in (
            ("reference_static", STATIC_BOX, pose(-3, 3, 0.2), True),
            ("reference_box", model_text("box.urdf"), pose(-3, -3, 0.1), False),
        ):
            result = (cls.spawn_sdf_model if sdf else cls.spawn_urdf_model)(name, xml, "", at, "")
            assert result.success, result.status_message
        cls.wait_sim(1.0)
        cls.references = {name: cls.state(name) for name in ("reference_static", "reference_box")}
        cls.physics = cls.get_physics_properties()

        def spawn_and_delete():
            assert cls.spawn_urdf_model("timing_box", model_text("box.urdf"), "", pose(3, -3, 0.1), "").success
            assert cls.delete_model("timing_box").success

        cls.reference = best_seconds(spawn_and_delete)  # the unit of every answer's time

    @classmethod
    def wait_sim(cls, seconds, timeout=20.0):
        start = cls.clock.wait_for(lambda msg: True).clock
        cls.clock.wait_for(lambda msg: (msg.clock - start).to_sec() >= seconds, timeout)

    @classmethod
    def state(cls, name):
        result = cls.get_model_state(name, "")
        assert result.success, result.status_message
        return result.pose

    def tearDown(self):
        """After every input: running, /clock advances, the references stay, every node answers."""
        self.unpause_physics()
        now = self.clock.wait_for(lambda msg: True).clock
        self.clock.wait_for(lambda msg: msg.clock > now, timeout=10)
        tolerance = rospy.get_param("~pose_tolerance")
        for name, before in self.references.items():
            after = self.state(name)
            for axis in "xyz":
                self.assertAlmostEqual(getattr(after.position, axis), getattr(before.position, axis), delta=tolerance)
        for node in NODES[:1]:
            code, message, _ = ServerProxy(self.master.lookupNode(node)).getPid(rospy.get_name())
            self.assertEqual(code, 1, "%s does not answer: %s" % (node, message))

    def timed(self, call, *args):
        """``call(*args)``, which must answer within ~answer_time_ratio times a spawn and delete of a box."""
        result, took = timed(lambda: call(*args))
        assert_within(took, self.reference, self.answer_ratio, "the answer")
        return result

    def refused(self, result, *words):
        self.assertFalse(result.success, "accepted, but should have been refused")
        for word in words:
            self.assertIn(word, result.status_message)

    def spawn(self, name, xml, sdf=False, at=None):
        service = self.spawn_sdf_model if sdf else self.spawn_urdf_model
        return self.timed(service, name, xml, "", at or pose(3, 3, 0.1), "")

    def gone(self, name):
        self.assertFalse(self.get_model_properties(name).success, "model %s is still there" % name)

    def set_rate(self, rate, time_step=None):
        p = self.physics
        return self.timed(self.set_physics_properties, time_step or p.time_step, rate, p.gravity, p.ode_config)

    def restore_physics(self):
        result = self.set_rate(self.physics.max_update_rate, self.physics.time_step)
        self.assertTrue(result.success, result.status_message)

    def assert_clock_runs(self, sim_seconds=0.3, wall_seconds=3.0):
        """/clock advances by ``sim_seconds`` within ``wall_seconds`` (at real time factor 1: with room to spare)."""
        start = self.clock.wait_for(lambda msg: True, wall_seconds).clock
        self.clock.wait_for(lambda msg: (msg.clock - start).to_sec() >= sim_seconds, wall_seconds)

    # --- 1: pacing and freezes ------------------------------------------------------------------------------------
    def test_a01_paced_again_after_running_unpaced(self):
        self.addCleanup(self.restore_physics)
        self.assertTrue(self.set_rate(0.0).success)
        rospy.rostime.wallsleep(3.0)  # unpaced for a while: sim time runs far ahead of the wall
        self.restore_physics()
        self.assert_clock_runs()

    def test_a02_unpause_during_a_long_step_call(self):
        self.pause_physics()
        start = self.get_world_properties().sim_time
        answer = {}
        caller = threading.Thread(target=lambda: answer.update(result=self.step_simulation(20000)))
        caller.start()
        self.wait_sim(0.01)  # the call is stepping
        self.unpause_physics()
        caller.join(120)
        self.assertFalse(caller.is_alive(), "step_simulation did not answer")
        result = answer["result"]
        self.assertTrue(result.success, result.message if hasattr(result, "message") else result)
        self.assertAlmostEqual(result.sim_time.to_sec() - start, 20000 * self.physics.time_step, delta=1e-6)
        self.assert_clock_runs()

    def test_a03_rates_without_clock_are_refused(self):
        self.addCleanup(self.restore_physics)
        self.refused(self.set_rate(1e-12), "max_update_rate [1e-12]", "steps/s")
        self.refused(self.set_rate(1e-3), "max_update_rate [0.001]", ">= 1 steps/s")
        self.refused(self.set_rate(1e9, 1e-9), "time_step [1e-09] s is too small", ">= 1e-07 s")
        self.assertEqual(self.get_physics_properties().max_update_rate, self.physics.max_update_rate)

    def test_a04_a_slow_rate_is_left_at_once(self):
        self.addCleanup(self.restore_physics)
        self.assertTrue(self.set_rate(1.0).success)  # one step per wall second, /clock every 10 s
        rospy.rostime.wallsleep(1.5)
        self.restore_physics()
        self.assert_clock_runs()

    # --- 2: spawn is all or nothing -------------------------------------------------------------------------------
    def test_b01_laser_update_rate_0_is_every_step(self):
        scans = Latest("/every_step_scan", LaserScan)
        result = self.spawn(
            "laser_rate_0",
            box_with(LASER.format(link="box_link", name="l", rate=0, samples=36, topic="/every_step_scan")),
        )
        self.assertTrue(result.success, result.status_message)
        self.addCleanup(lambda: self.delete_model("laser_rate_0"))
        first = scans.wait_for(lambda msg: True).header.stamp
        later = scans.wait_for(lambda msg: msg.header.stamp > first).header.stamp
        self.assertLess((later - first).to_sec(), 0.1, "update_rate 0: a scan every step")

    def test_b02_failed_spawn_leaves_nothing_and_a_retry_works(self):
        self.refused(self.spawn("half_spawned", box_with(P3D.format(topic="/clock"))), "/clock")
        self.gone("half_spawned")
        result = self.spawn("half_spawned", box_with(P3D.format(topic="half_spawned_truth")))
        self.assertTrue(result.success, result.status_message)
        self.delete_model("half_spawned")

    # --- 3: topic collisions --------------------------------------------------------------------------------------
    def test_c01_plugin_topic_of_another_type_is_refused(self):
        self.refused(
            self.spawn("p3d_on_clock", box_with(P3D.format(topic="/clock"))),
            "/clock",
            "rosgraph_msgs/Clock",
            "nav_msgs/Odometry",
        )
        self.refused(
            self.spawn(
                "laser_on_rosout",
                box_with(LASER.format(link="box_link", name="l", rate=5, samples=10, topic="/rosout")),
            ),
            "/rosout",
            "sensor_msgs/LaserScan",
        )
        self.gone("p3d_on_clock")
        self.gone("laser_on_rosout")
        clocks = Latest("/clock", Clock, keep=True)
        self.wait_sim(0.2)
        times = [msg.clock.to_sec() for msg in clocks.matching(lambda msg: True)]
        self.assertEqual(times, sorted(times), "/clock went back")

    def test_c02_a_topic_no_node_uses_any_more_is_free(self):
        result = self.spawn("odometry_first", box_with(P3D.format(topic="/reused_topic")))
        self.assertTrue(result.success, result.status_message)
        self.assertTrue(self.delete_model("odometry_first").success)
        laser = LASER.format(link="box_link", name="l", rate=5, samples=10, topic="/reused_topic")
        result = self.spawn("laser_after", box_with(laser))
        self.assertTrue(result.success, result.status_message)
        self.assertTrue(self.delete_model("laser_after").success)

    # --- 4: names -------------------------------------------------------------------------------------------------
    def test_d01_non_ascii_model_name(self):
        self.refused(self.spawn("tb_\u00e9", model_text("box.urdf")), "not a legal ROS name", "ASCII")
        self.refused(
            self.timed(self.spawn_urdf_model, "ok_name", model_text("box.urdf"), "/\u00e9", pose(), ""),
            "robot_namespace",
        )

    def test_d02_huge_names_are_shortened_in_answers(self):
        huge = "n" * 100000
        for result in (
            self.timed(self.get_model_state, huge, ""),
            self.timed(self.get_model_state, "reference_box", huge),
            self.timed(self.delete_model, huge),
            self.timed(self.get_link_state, huge, ""),
            self.timed(self.get_joint_properties, huge),
            self.spawn(huge, model_text("box.urdf")),
            self.timed(self.spawn_urdf_model, "long_frame", model_text("box.urdf"), "", pose(), huge),
        ):
            self.assertFalse(result.success)
            self.assertLess(len(result.status_message), 400, result.status_message[:300])
            self.assertIn("(100000 characters)", result.status_message)

    # --- 5: reset while paused ------------------------------------------------------------------------------------
    def test_e01_reset_simulation_while_paused_publishes_the_new_time(self):
        self.wait_sim(0.5)
        self.pause_physics()
        self.assertGreater(self.clock.wait_for(lambda msg: True).clock.to_sec(), 0.5)
        self.reset_simulation()
        self.clock.wait_for(lambda msg: msg.clock.to_sec() < 0.01, timeout=2.0)
        self.assertLess(self.get_world_properties().sim_time, 0.01)

    # --- 6: big models --------------------------------------------------------------------------------------------
    def test_f01_too_many_rays_are_refused_with_the_limit(self):
        lasers = "".join(
            LASER.format(link="box_link", name="l%d" % i, rate=5, samples=100000, topic="big_scan_%d" % i)
            for i in range(8)
        )
        self.refused(self.spawn("many_rays", box_with(lasers)), "800000 rays", "at most 20000 per model")
        self.gone("many_rays")

    def test_f02_delete_gives_the_memory_back(self):
        """Eight models at the ray limit (160,000 rays, ~100 MB), all deleted: the node's RSS comes back."""
        pid = ServerProxy(self.master.lookupNode("/gazebo")).getPid(rospy.get_name())[2]
        lasers = "".join(
            LASER.format(link="box_link", name="l%d" % i, rate=5, samples=5000, topic="mem_scan_%d" % i)
            for i in range(4)
        )
        before = rss_mb(pid)
        names = ["memory_%d" % i for i in range(8)]
        for i, name in enumerate(names):
            result = self.spawn(name, box_with(lasers), at=pose(3 + i, 3, 0.1))
            self.assertTrue(result.success, result.status_message)
        peak = rss_mb(pid)
        for name in names:
            self.assertTrue(self.delete_model(name).success)
        after = rss_mb(pid)
        rospy.loginfo(
            "RSS of /gazebo: %.0f MB before, %.0f MB with 8 models of 20000 rays, %.0f MB after deleting them",
            before,
            peak,
            after,
        )
        self.assertGreater(peak - before, 50, "8 models of 20000 rays cost less than 50 MB: the test measures nothing")
        self.assertLess(after - before, rospy.get_param("~rss_kept_fraction") * (peak - before))

    # --- 7: unhelpful output --------------------------------------------------------------------------------------
    def test_g01_many_unsupported_plugins_give_one_short_warning(self):
        plugins = "".join(
            '<gazebo><plugin name="p%d" filename="libunknown_%d.so"/></gazebo>' % (i, i % 3) for i in range(20000)
        )
        already = len(self.rosout.matching(lambda msg: "not supported" in msg.msg))
        result = self.spawn("many_plugins", box_with(plugins))
        self.assertTrue(result.success, result.status_message[:300])
        self.addCleanup(lambda: self.delete_model("many_plugins"))
        self.assertIn("20000 plugin(s) not supported", result.status_message)
        self.assertLess(len(result.status_message), 1000)
        self.wait_sim(0.5)
        warnings = self.rosout.matching(lambda msg: "not supported" in msg.msg)
        self.assertEqual(len(warnings) - already, 1, [msg.msg[:200] for msg in warnings[already:]])

    def test_g02_world_sent_as_a_model_says_what_to_do(self):
        world = '<sdf version="1.6"><world name="w"><model name="m"><link name="l"/></model></world></sdf>'
        result = self.spawn("a_world", world, sdf=True)
        self.refused(result, "world_name")
        self.assertNotIn("parse_sdf_world", result.status_message)


if __name__ == "__main__":
    rospy.init_node("test_bad_input_node")
    rostest.rosrun("turtle_sim_ode", "bad_input_node", BadInputNode)
