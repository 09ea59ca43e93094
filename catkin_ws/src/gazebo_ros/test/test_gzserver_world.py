#!/usr/bin/env python3
"""rostest node: a world started with `gzserver --verbose -u -e ode -s PLUGIN WORLD` (gzserver_world.test), seen
through gazebo_ros's API. Expected values: gzserver's -u starts paused (gazebo-classic gazebo/Server.cc,
ParseArgs/ProcessParams); gazebo_ros's API plugin sets /use_sim_time when it is unset (gazebo_ros_api_plugin.cpp,
loadGazeboRosApiPlugin); the light services answer as getLightProperties/setLightProperties/deleteLight do; the
physics through dynamic_reconfigure as physicsReconfigureCallback; the sun of model://sun is gazebo_models'
sun/model.sdf (diffuse 0.8, attenuation constant 0.9, linear 0.01, quadratic 0.001). The ground plane of
model://ground_plane is a model (gazebo_models ground_plane/model.sdf, loaded as every <include>): listed by
getWorldProperties (every world_->ModelByIndex(i), in load order) and publishModelStates, answered by getModelState,
removed by deleteModel and spawned again by spawnSDFModel; without it nothing holds a box up."""
import math
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from gazebo_msgs import srv
from gazebo_msgs.msg import ModelState, ModelStates
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3, Wrench
from rosgraph_msgs.msg import Clock
from std_msgs.msg import ColorRGBA
from std_srvs.srv import Empty


def service(name, kind):
    rospy.wait_for_service("/gazebo/" + name, timeout=120)
    return rospy.ServiceProxy("/gazebo/" + name, kind)


class GzserverWorldTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("gzserver_world_check")
        cls.world = service("get_world_properties", srv.GetWorldProperties)
        cls.physics = service("get_physics_properties", srv.GetPhysicsProperties)
        cls.get_light = service("get_light_properties", srv.GetLightProperties)
        cls.set_light = service("set_light_properties", srv.SetLightProperties)
        cls.delete_light = service("delete_light", srv.DeleteLight)
        cls.model_state = service("get_model_state", srv.GetModelState)

    def assertColour(self, colour: ColorRGBA, expected) -> None:  # noqa: N802 (unittest style)
        """ColorRGBA holds float32s."""
        for value, wanted in zip((colour.r, colour.g, colour.b, colour.a), expected):
            self.assertAlmostEqual(value, wanted, places=6)

    def test_a_started_paused_with_the_worlds_models(self) -> None:
        world = self.world()
        self.assertEqual(world.model_names, ["ground_plane", "box_a", "box_b"])
        self.assertEqual(world.sim_time, 0.0)
        self.assertTrue(self.physics().pause)
        self.assertIs(rospy.get_param("/use_sim_time"), True)

    def test_b_the_suns_and_the_worlds_lights(self) -> None:
        sun = self.get_light("sun")
        self.assertTrue(sun.success)
        self.assertColour(sun.diffuse, (0.8, 0.8, 0.8, 1.0))
        self.assertEqual(
            (sun.attenuation_constant, sun.attenuation_linear, sun.attenuation_quadratic), (0.9, 0.01, 0.001)
        )
        lamp = self.get_light("lamp")
        self.assertColour(lamp.diffuse, (0.5, 0.4, 0.3, 1.0))
        self.assertEqual(
            (lamp.attenuation_constant, lamp.attenuation_linear, lamp.attenuation_quadratic), (0.5, 0.02, 0.003)
        )

    def test_c_set_and_delete_a_light(self) -> None:
        answer = self.set_light(
            "lamp",
            False,
            ColorRGBA(0.1, 0.2, 0.3, 1.0),
            ColorRGBA(0.0, 0.0, 0.0, 1.0),
            1.0,
            0.0,
            0.0,
            Vector3(0, 0, -1),
            Pose(Point(0, 0, 4), Quaternion(0, 0, 0, 1)),
        )
        self.assertTrue(answer.success, answer.status_message)
        lamp = self.get_light("lamp")
        self.assertColour(lamp.diffuse, (0.1, 0.2, 0.3, 1.0))
        self.assertEqual((lamp.attenuation_constant, lamp.attenuation_linear), (1.0, 0.0))
        self.assertTrue(self.delete_light("lamp").success)
        gone = self.get_light("lamp")
        self.assertFalse(gone.success)
        self.assertIn("lamp", gone.status_message)
        self.assertFalse(self.delete_light("lamp").success)
        self.assertTrue(self.get_light("sun").success)

    def test_d_physics_through_dynamic_reconfigure(self) -> None:
        client = Client("gazebo", timeout=60)
        config = client.get_configuration(timeout=60)
        physics = self.physics()
        self.assertEqual(config["time_step"], physics.time_step)
        self.assertEqual(config["sor_pgs_iters"], physics.ode_config.sor_pgs_iters)
        self.assertEqual(config["gravity_z"], physics.gravity.z)
        client.update_configuration({"gravity_z": -5.0, "sor_pgs_iters": 30})
        physics = self.physics()
        self.assertEqual((physics.gravity.z, physics.ode_config.sor_pgs_iters), (-5.0, 30))
        # a step the simulator refuses (0 s) leaves the physics as they were, and the config says so
        config = client.update_configuration({"time_step": 0.0})
        self.assertEqual(self.physics().time_step, physics.time_step)
        self.assertEqual(config["time_step"], physics.time_step)
        client.update_configuration({"gravity_z": -9.8})
        client.close()

    def test_e_clear_body_wrenches_then_run(self) -> None:
        apply = service("apply_body_wrench", srv.ApplyBodyWrench)
        clear = service("clear_body_wrenches", srv.BodyRequest)
        lifted = apply(
            "box_a::link", "", Point(), Wrench(Vector3(0, 0, 100), Vector3()), rospy.Time(), rospy.Duration(-1)
        )
        self.assertTrue(lifted.success, lifted.status_message)
        clear("box_a::link")
        service("unpause_physics", Empty)()
        rospy.wait_for_message("/clock", Clock, timeout=60)
        start = rospy.wait_for_message("/clock", Clock, timeout=60).clock.to_sec()
        while rospy.wait_for_message("/clock", Clock, timeout=60).clock.to_sec() < start + 0.5:
            pass
        z = self.model_state("box_a", "").pose.position.z
        self.assertLess(abs(z - 0.25), 0.01, "box_a should rest on the ground, the cleared wrench lifted it: z %g" % z)
        self.assertFalse(math.isnan(z))

    def test_f_the_ground_plane_is_a_model_that_can_be_deleted_and_spawned_again(self) -> None:
        states = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=60)
        self.assertEqual(states.name[0], "ground_plane")
        ground = self.model_state("ground_plane", "")
        self.assertTrue(ground.success, ground.status_message)
        self.assertEqual((ground.pose.position.z, ground.pose.orientation.w), (0.0, 1.0))
        deleted = service("delete_model", srv.DeleteModel)("ground_plane")
        self.assertTrue(deleted.success, deleted.status_message)
        self.assertNotIn("ground_plane", self.world().model_names)
        start = rospy.wait_for_message("/clock", Clock, timeout=60).clock.to_sec()
        while rospy.wait_for_message("/clock", Clock, timeout=60).clock.to_sec() < start + 0.5:
            pass
        self.assertLess(self.model_state("box_a", "").pose.position.z, 0.0, "box_a should fall without a ground")
        spawned = service("spawn_sdf_model", srv.SpawnModel)("ground_plane", GROUND_PLANE, "", Pose(), "")
        self.assertTrue(spawned.success, spawned.status_message)
        up = ModelState("box_a", Pose(Point(1, 0, 0.6), Quaternion(0, 0, 0, 1)), Twist(), "")
        self.assertTrue(service("set_model_state", srv.SetModelState)(up).success)
        start = rospy.wait_for_message("/clock", Clock, timeout=60).clock.to_sec()
        while rospy.wait_for_message("/clock", Clock, timeout=60).clock.to_sec() < start + 1.0:
            pass
        z = self.model_state("box_a", "").pose.position.z
        self.assertLess(abs(z - 0.25), 0.01, "box_a should rest on the spawned ground plane: z %g" % z)


# A ground plane as a user writes one for spawn_model -sdf: a static plane facing up.
GROUND_PLANE = """<sdf version="1.6"><model name="ground_plane"><static>true</static><link name="link">
  <collision name="collision"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
  </collision></link></model></sdf>"""


if __name__ == "__main__":
    rostest.rosrun("gazebo_ros", "gzserver_world", GzserverWorldTest)
