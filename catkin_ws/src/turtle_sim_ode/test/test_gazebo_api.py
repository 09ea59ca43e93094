#!/usr/bin/env python3
"""rostest node: every /gazebo service on its happy path and its error paths, through gazebo_msgs clients, as
code written for Gazebo calls them."""
import math
import sys
import unittest

import rosgraph
import rospy
import rostest
from gazebo_clients import connect_gazebo_services, model_text, pose
from gazebo_msgs import srv as gz
from gazebo_msgs.msg import LinkState, ModelState, ModelStates, ODEJointProperties
from geometry_msgs.msg import Point, Twist, Vector3, Wrench
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log

NAN = float("nan")


class GazeboApi(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        connect_gazebo_services(cls)
        cls.box = model_text("box.urdf")

    def spawn(self, name, xml=None, at=None, reference_frame="", sdf=False):
        service = self.spawn_sdf_model if sdf else self.spawn_urdf_model
        return service(name, xml if xml is not None else self.box, "", at or pose(0, 3, 0.1), reference_frame)

    def spawned(self, name, **kwargs):
        result = self.spawn(name, **kwargs)
        self.assertTrue(result.success, result.status_message)
        self.addCleanup(lambda: self.delete_model(name))
        return result

    def refused(self, result, *words):
        self.assertFalse(result.success)
        for word in words:
            self.assertIn(word, result.status_message)

    def position(self, name, frame=""):
        state = self.get_model_state(name, frame)
        self.assertTrue(state.success, state.status_message)
        return state.pose.position

    # --- spawning and deleting ---------------------------------------------------------------------------------
    def test_spawn_urdf_and_sdf_appear_in_world_properties(self):
        self.spawned("api_box", at=pose(1, 3, 0.1))
        self.spawned("api_sdf_box", xml=model_text("box.sdf"), sdf=True, at=pose(-1, 3, 0.1))
        names = self.get_world_properties().model_names
        self.assertIn("mobile_base", names)
        self.assertIn("api_box", names)
        self.assertIn("api_sdf_box", names)

    def test_five_spawned_one_deleted_live_name_refused(self):
        for i in range(5):
            self.assertTrue(self.spawn("crate_%d" % i, at=pose(i, -3, 0.1)).success)
        try:
            self.assertTrue(self.delete_model("crate_2").success)
            names = self.get_world_properties().model_names
            self.assertNotIn("crate_2", names)
            self.refused(self.spawn("crate_1", at=pose(5, -3, 0.1)), "crate_1", "already exists")
            self.assertTrue(self.spawn("crate_2", at=pose(2, -3, 0.1)).success, "a deleted name can be re-used")
        finally:
            for i in range(5):
                self.delete_model("crate_%d" % i)

    def test_spawn_relative_to_a_model(self):
        self.spawned("beside_robot", at=pose(1.0, 0, 0.1), reference_frame="mobile_base")
        robot, box = self.position("mobile_base"), self.position("beside_robot")
        self.assertAlmostEqual(math.hypot(box.x - robot.x, box.y - robot.y), 1.0, delta=0.02)

    def test_spawn_errors(self):
        self.refused(self.spawn(""), "empty")
        self.refused(self.spawn("mobile_base"), "already exists")
        self.refused(self.spawn("truncated", xml=self.box[:120]), "line")
        self.refused(self.spawn("not_xml", xml="hello world"), "neither URDF")
        self.refused(self.spawn("wrong_root", xml="<html><body/></html>"), "neither URDF")
        self.refused(self.spawn("far", reference_frame="no_such_model"), "no_such_model")
        laughs = (
            '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;&a;&a;">]>'
            '<robot name="r">&b;</robot>'
        )
        self.refused(self.spawn("laughs", xml=laughs))
        external = (
            '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]><robot name="r">&x;</robot>'
        )
        self.refused(self.spawn("external", xml=external))
        self.assertNotIn("truncated", self.get_world_properties().model_names)

    def test_mesh_outside_the_package_path_is_refused_naming_it(self):
        # Issue 14: meshes are read, from under the ROS package path and model path only (it was a 1 cm box).
        mesh = self.box.replace(
            '<box size="0.2 0.2 0.2"/></geometry></collision>',
            '<mesh filename="file:///etc/passwd"/></geometry></collision>',
        )
        self.refused(
            self.spawn("mesh_box", xml=mesh, at=pose(2, 2, 0.1)), "/etc/passwd", "outside the ROS package path"
        )

    def test_delete_unknown_model(self):
        self.refused(self.delete_model("no_such_model"), "no_such_model")

    def test_spawn_while_paused_returns_at_once(self):
        self.pause_physics()
        try:
            started = self.get_world_properties().sim_time
            self.spawned("paused_box", at=pose(3, 3, 0.1))
            self.assertIn("paused_box", self.get_world_properties().model_names)
            self.assertEqual(self.get_world_properties().sim_time, started, "sim time must stand still while paused")
        finally:
            self.unpause_physics()

    # --- model state -------------------------------------------------------------------------------------------
    def test_set_and_get_model_state(self):
        self.spawned("teleported", at=pose(0, 4, 0.1))
        target = pose(2.5, 4.0, 0.1, 0, 0, math.sin(0.4), math.cos(0.4))
        result = self.set_model_state(ModelState("teleported", target, Twist(), "world"))
        self.assertTrue(result.success, result.status_message)
        state = self.get_model_state("teleported", "world")
        self.assertAlmostEqual(state.pose.position.x, 2.5, delta=0.01)
        self.assertAlmostEqual(state.pose.orientation.z, math.sin(0.4), delta=0.01)

    def test_state_relative_to_another_model(self):
        self.spawned("reference_box", at=pose(0, -4, 0.1))
        self.spawned("other_box", at=pose(1, -4, 0.1))
        relative = self.get_model_state("other_box", "reference_box")
        self.assertTrue(relative.success, relative.status_message)
        self.assertAlmostEqual(relative.pose.position.x, 1.0, delta=0.02)
        self.assertAlmostEqual(relative.pose.position.y, 0.0, delta=0.02)
        self.assertEqual(relative.header.frame_id, "reference_box")

    def test_quaternions_are_normalised(self):
        self.spawned("twisted_box", at=pose(-2, 4, 0.1))
        self.assertTrue(
            self.set_model_state(ModelState("twisted_box", pose(-2, 4, 0.1, 0, 0, 2, 2), Twist(), "")).success
        )
        q = self.get_model_state("twisted_box", "").pose.orientation
        self.assertAlmostEqual(math.sqrt(q.x**2 + q.y**2 + q.z**2 + q.w**2), 1.0, places=6)
        self.assertTrue(
            self.set_model_state(ModelState("twisted_box", pose(-2, 4, 0.1, 0, 0, 0, 0), Twist(), "")).success
        )
        q = self.get_model_state("twisted_box", "").pose.orientation
        self.assertAlmostEqual(abs(q.w), 1.0, places=3)

    def test_set_model_state_twist_moves_the_model(self):
        self.spawned("sliding_box", at=pose(-3, -3, 0.1))
        self.set_model_state(ModelState("sliding_box", pose(-3, -3, 0.3), Twist(Vector3(1.0, 0, 0), Vector3()), ""))
        rospy.sleep(0.3)
        self.assertGreater(self.position("sliding_box").x, -2.95)

    def test_model_state_errors(self):
        self.refused(self.get_model_state("no_such_model", ""), "no_such_model")
        self.refused(self.get_model_state("mobile_base", "no_such_frame"), "no_such_frame")
        self.refused(self.set_model_state(ModelState("no_such_model", pose(), Twist(), "")), "no_such_model")
        self.refused(self.set_model_state(ModelState("mobile_base", pose(NAN, 0, 0), Twist(), "")))
        self.refused(self.set_model_state(ModelState("mobile_base", pose(), Twist(), "no_such_frame")), "no_such_frame")

    def test_set_model_state_topic(self):
        self.spawned("topic_box", at=pose(4, 0, 0.1))
        publisher = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=1, latch=True)
        publisher.publish(ModelState("topic_box", pose(4, 1.5, 0.1), Twist(), "world"))
        deadline = rospy.Time.now() + rospy.Duration(5)
        while rospy.Time.now() < deadline and self.position("topic_box").y < 1.4:
            rospy.sleep(0.05)
        self.assertAlmostEqual(self.position("topic_box").y, 1.5, delta=0.02)
        publisher.unregister()

    def test_model_states_lists_every_model(self):
        self.spawned("listed_box", at=pose(-4, 0, 0.1))
        states = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=10)
        self.assertIn("mobile_base", states.name)
        self.assertIn("listed_box", states.name)
        self.assertEqual(len(states.name), len(states.pose))

    # --- properties --------------------------------------------------------------------------------------------
    def test_model_properties(self):
        properties = self.get_model_properties("mobile_base")
        self.assertTrue(properties.success, properties.status_message)
        self.assertIn("wheel_left_joint", properties.joint_names)
        self.assertIn("wheel_left_link", properties.body_names)
        self.assertFalse(properties.is_static)
        self.refused(self.get_model_properties("no_such_model"), "no_such_model")

    def test_link_state_and_properties(self):
        state = self.get_link_state("mobile_base::wheel_left_link", "")
        self.assertTrue(state.success, state.status_message)
        self.assertAlmostEqual(state.link_state.pose.position.z, 0.035, delta=0.005)
        properties = self.get_link_properties("mobile_base::wheel_left_link")
        self.assertAlmostEqual(properties.mass, 0.1, places=6)
        self.refused(self.get_link_state("mobile_base::no_such_link", ""), "no_such_link")
        self.refused(self.get_link_properties("nobody::base_link"), "nobody")

    def test_set_link_state_and_properties(self):
        self.spawned("link_box", at=pose(0, -2, 0.1))
        result = self.set_link_state(LinkState("link_box::box_link", pose(0.5, -2, 0.1), Twist(), "world"))
        self.assertTrue(result.success, result.status_message)
        self.assertAlmostEqual(
            self.get_link_state("link_box::box_link", "").link_state.pose.position.x, 0.5, delta=0.01
        )
        result = self.set_link_properties("link_box::box_link", pose(), True, 3.0, 0.02, 0, 0, 0.02, 0, 0.02)
        self.assertTrue(result.success, result.status_message)
        self.assertAlmostEqual(self.get_link_properties("link_box::box_link").mass, 3.0, places=6)
        self.refused(self.set_link_properties("link_box::box_link", pose(), True, -1.0, 0.02, 0, 0, 0.02, 0, 0.02))

    def test_joint_properties(self):
        properties = self.get_joint_properties("wheel_left_joint")
        self.assertTrue(properties.success, properties.status_message)
        self.assertEqual(properties.type, gz.GetJointPropertiesResponse.CONTINUOUS)
        self.assertEqual(len(properties.position), 1)
        config = ODEJointProperties(damping=[0.01])
        self.assertTrue(self.set_joint_properties("wheel_left_joint", config).success)
        self.refused(self.get_joint_properties("no_such_joint"), "no_such_joint")
        self.refused(self.set_joint_properties("no_such_joint", config), "no_such_joint")

    def test_set_model_configuration(self):
        self.spawned("pendulum", xml=model_text("pendulum.urdf"), at=pose(-4, -4, 0.05))
        result = self.set_model_configuration("pendulum", "", ["arm_joint"], [1.0])
        self.assertTrue(result.success, result.status_message)
        self.assertAlmostEqual(self.get_joint_properties("arm_joint").position[0], 1.0, delta=0.02)
        self.refused(self.set_model_configuration("pendulum", "", ["no_such_joint"], [1.0]), "no_such_joint")
        self.refused(self.set_model_configuration("pendulum", "", ["arm_joint"], []))

    # --- physics -----------------------------------------------------------------------------------------------
    def test_physics_properties_round_trip_and_errors(self):
        physics = self.get_physics_properties()
        self.assertAlmostEqual(physics.time_step, 0.001)
        self.assertAlmostEqual(physics.gravity.z, -9.81)
        self.assertEqual(physics.ode_config.sor_pgs_iters, 50)
        moon = Vector3(0, 0, -1.62)
        result = self.set_physics_properties(physics.time_step, physics.max_update_rate, moon, physics.ode_config)
        self.assertTrue(result.success, result.status_message)
        self.assertAlmostEqual(self.get_physics_properties().gravity.z, -1.62)
        try:
            self.refused(
                self.set_physics_properties(0.0, physics.max_update_rate, physics.gravity, physics.ode_config),
                "time_step",
            )
            self.refused(
                self.set_physics_properties(
                    physics.time_step, physics.max_update_rate, Vector3(0, 0, NAN), physics.ode_config
                ),
                "gravity",
            )
            huge = physics.ode_config
            huge.sor_pgs_iters = 10**6
            self.refused(
                self.set_physics_properties(physics.time_step, physics.max_update_rate, physics.gravity, huge),
                "iterations",
            )
            self.assertAlmostEqual(self.get_physics_properties().gravity.z, -1.62, msg="refused calls change nothing")
        finally:
            physics = self.get_physics_properties()
            physics.ode_config.sor_pgs_iters = 50
            self.set_physics_properties(
                physics.time_step, physics.max_update_rate, Vector3(0, 0, -9.81), physics.ode_config
            )

    def test_pause_stops_the_clock(self):
        self.pause_physics()
        try:
            self.assertTrue(self.get_physics_properties().pause)
            before = self.get_world_properties().sim_time
            rospy.rostime.wallsleep(0.3)
            self.assertEqual(self.get_world_properties().sim_time, before)
        finally:
            self.unpause_physics()
        self.assertFalse(self.get_physics_properties().pause)

    def test_odom_and_clock_come_on_their_exact_sim_times_when_unpaced(self):
        """Unpaced, the loop runs the steps at which nothing is due back to back: no message may come a step late."""
        physics = self.get_physics_properties()
        unpaced = self.set_physics_properties(physics.time_step, 0.0, physics.gravity, physics.ode_config)
        self.assertTrue(unpaced.success, unpaced.status_message)
        self.addCleanup(
            self.set_physics_properties,
            physics.time_step,
            physics.max_update_rate,
            physics.gravity,
            physics.ode_config,
        )
        stamps = {"/odom": [], "/clock": []}
        subscribers = [
            rospy.Subscriber("/odom", Odometry, lambda m: stamps["/odom"].append(m.header.stamp.to_nsec())),
            rospy.Subscriber("/clock", Clock, lambda m: stamps["/clock"].append(m.clock.to_nsec())),
        ]
        for subscriber in subscribers:
            self.addCleanup(subscriber.unregister)
        deadline = rospy.get_rostime() + rospy.Duration(300)
        while min(len(s) for s in stamps.values()) < 60 and rospy.get_rostime() < deadline:
            rospy.rostime.wallsleep(0.05)
        received = stamps["/odom"][1:]  # the first may be from before the subscription settled
        gaps = {later - earlier for earlier, later in zip(received, received[1:])}
        self.assertEqual(gaps, {20000000}, "odom (50 Hz) stamps %s" % received[:20])
        # /clock counts from sim time 0 at 100 Hz: a message a step late would be off its grid ever after. (Gaps
        # prove nothing here: rospy's own /clock subscriber in this node keeps only the newest message.)
        self.assertEqual({stamp % 10000000 for stamp in stamps["/clock"]}, {0}, stamps["/clock"][:20])

    def test_simulator_keeps_sim_time_without_hearing_its_own_clock(self):
        """rospy subscribes every node to /clock under /use_sim_time; the simulator, its source, drops that
        subscriber and sets its ROS time as it publishes: its log messages carry the sim time."""
        _, subscribers, _ = rosgraph.Master("/test_gazebo_api").getSystemState()
        self.assertNotIn("/gazebo", dict(subscribers).get("/clock", []))
        warnings = []
        logs = rospy.Subscriber(
            "/rosout", Log, lambda log: warnings.append(log) if "no_clock_model" in log.msg else None
        )
        self.addCleanup(logs.unregister)
        deadline = rospy.get_rostime() + rospy.Duration(30)
        while not warnings and rospy.get_rostime() < deadline:  # each refusal logs: repeat until one arrives
            self.refused(self.delete_model("no_clock_model"), "no_clock_model")
            rospy.sleep(0.2)
        self.assertTrue(warnings, "no warning of the refused delete on /rosout")
        sim_time = self.get_world_properties().sim_time
        stamp = warnings[0].header.stamp.to_sec()
        self.assertTrue(sim_time - 2.0 < stamp <= sim_time, "log stamp %.3f, sim time %.3f" % (stamp, sim_time))

    # --- forces ------------------------------------------------------------------------------------------------
    def test_body_wrench_pushes_for_its_duration(self):
        self.spawned("pushed_box", at=pose(2, -2, 0.1))
        rospy.sleep(0.2)
        start = self.position("pushed_box")
        wrench = Wrench(Vector3(0, 30.0, 0), Vector3())
        result = self.apply_body_wrench("pushed_box::box_link", "", Point(), wrench, rospy.Time(0), rospy.Duration(0.5))
        self.assertTrue(result.success, result.status_message)
        rospy.sleep(1.5)
        moved = self.position("pushed_box")
        self.assertGreater(moved.y - start.y, 0.1)
        self.clear_body_wrenches("pushed_box::box_link")

    def test_wrench_errors(self):
        wrench = Wrench(Vector3(1, 0, 0), Vector3())
        self.refused(
            self.apply_body_wrench("nobody::link", "", Point(), wrench, rospy.Time(0), rospy.Duration(1)), "nobody"
        )
        self.refused(
            self.apply_body_wrench(
                "mobile_base::base_link", "no_such_frame", Point(), wrench, rospy.Time(0), rospy.Duration(1)
            ),
            "no_such_frame",
        )
        self.refused(
            self.apply_body_wrench(
                "mobile_base::base_link",
                "",
                Point(),
                Wrench(Vector3(NAN, 0, 0), Vector3()),
                rospy.Time(0),
                rospy.Duration(1),
            )
        )
        self.clear_body_wrenches("nobody::link")  # an empty response, as in gazebo_ros: it logs, and goes on
        self.assertTrue(self.get_world_properties().success)

    def test_joint_effort(self):
        self.spawned("spun_pendulum", xml=model_text("pendulum.urdf"), at=pose(4, -4, 0.05))
        # 0.05 N m on ~0.015 kg m^2 for 0.3 s: the arm spins up to ~1 rad/s, then coasts (no friction).
        result = self.apply_joint_effort("spun_pendulum::arm_joint", 0.05, rospy.Time(0), rospy.Duration(0.3))
        self.assertTrue(result.success, result.status_message)
        rospy.sleep(0.6)
        joint = self.get_joint_properties("spun_pendulum::arm_joint")
        self.assertGreater(joint.position[0], 0.05)
        self.assertAlmostEqual(joint.rate[0], 0.05 * 0.3 / 0.01525, delta=0.15)
        self.clear_joint_forces("spun_pendulum::arm_joint")
        self.refused(self.apply_joint_effort("no_such_joint", 1.0, rospy.Time(0), rospy.Duration(1)), "no_such_joint")
        self.refused(self.apply_joint_effort("spun_pendulum::arm_joint", NAN, rospy.Time(0), rospy.Duration(1)))

    # --- resets (last: they move every model back) -------------------------------------------------------------
    def test_zz_reset_world_restores_poses_and_odometry(self):
        cmd = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=1)
        end = rospy.Time.now() + rospy.Duration(1.5)
        while rospy.Time.now() < end:
            cmd.publish(Twist(Vector3(0.3, 0, 0), Vector3(0, 0, 0.3)))
            rospy.sleep(0.1)
        cmd.publish(Twist())
        self.assertGreater(self.position("mobile_base").x, 0.2)
        self.reset_world()
        robot = self.position("mobile_base")
        self.assertLess(math.hypot(robot.x, robot.y), 0.005)
        odom = rospy.wait_for_message("/odom", Odometry, timeout=10)
        self.assertLess(math.hypot(odom.pose.pose.position.x, odom.pose.pose.position.y), 0.005)

    def test_zzz_reset_simulation_restarts_time(self):
        self.assertGreater(self.get_world_properties().sim_time, 1.0)
        self.reset_simulation()
        self.assertLess(self.get_world_properties().sim_time, 1.0)

    # --- lights ------------------------------------------------------------------------------------------------
    def test_an_unknown_light_is_refused_clearly(self):
        # no world file: no lights (gzserver_world.test in gazebo_ros has a world's lights)
        self.refused(self.delete_light("sun"), "light 'sun' does not exist", "none")
        self.refused(self.get_light_properties("sun"), "light 'sun' does not exist", "none")


if __name__ == "__main__":
    rospy.init_node("test_gazebo_api")
    rostest.rosrun("turtle_sim_ode", "gazebo_api", GazeboApi, sys.argv)
