"""libgazebo_ros_planar_move.so: tags and defaults as GazeboRosPlanarMove::Load reads them, and the holonomic
motion its UpdateChild sets (gazebo_plugins/src/gazebo_ros_planar_move.cpp)."""
from __future__ import annotations

import math

import pytest
from conftest import yaw_of

from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.planar_move import PLANAR_MOVE, PlanarMoveRobot
from turtle_sim_ode.world.simulation import Simulation

# A round holonomic base as robots with planar_move write it: a cylinder body without wheels, slippery so that the
# ground's friction does not fight the velocities the plugin sets.
HOLONOMIC_URDF = """<robot name="holo"><link name="base_footprint">
  <collision><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.25" length="0.2"/></geometry></collision>
  <inertial><origin xyz="0 0 0.1"/><mass value="10"/><inertia ixx="0.2" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>
  </inertial></link>
  <gazebo reference="base_footprint"><mu1>0.0</mu1><mu2>0.0</mu2></gazebo>
  <gazebo><plugin name="planar" filename="libgazebo_ros_planar_move.so">
    <commandTopic>cmd_vel</commandTopic><odometryTopic>odom</odometryTopic><odometryFrame>odom</odometryFrame>
    <odometryRate>50.0</odometryRate><robotBaseFrame>base_footprint</robotBaseFrame>{extra}
  </plugin></gazebo></robot>"""


def test_defaults_are_load_s() -> None:
    (config,) = read_plugins("m", [GazeboPlugin(PLANAR_MOVE, "planar", {})], {}, []).drives
    assert (config.command_topic, config.odometry_topic, config.odometry_frame, config.base_frame) == (
        "cmd_vel",
        "odom",
        "odom",
        "base_footprint",
    )
    assert (config.odometry_rate, config.cmd_timeout) == (20.0, -1.0)


def run(sim: Simulation, seconds: float) -> None:
    for _ in range(int(round(seconds / sim.physics.time_step))):
        sim.step()


def test_moves_sideways_and_turns_as_commanded() -> None:
    sim = Simulation()
    sim.spawn_urdf("holo", HOLONOMIC_URDF.format(extra=""), (0, 0, 0.01, 0, 0, 0))
    robot = sim.robots["holo"]
    assert isinstance(robot, PlanarMoveRobot) and robot.wheels == ()
    run(sim, 0.2)
    robot.drive.set_command(0.0, 0.5, 0.0, sim.sim_time)  # straight to the left
    run(sim, 2.0)
    (x, y, _), orientation = sim.models["holo"].link_pose("base_footprint")
    assert (x, y) == pytest.approx((0.0, 1.0), abs=0.02) and abs(yaw_of(orientation)) < 0.01
    robot.drive.set_command(0.0, 0.0, 0.5, sim.sim_time)
    run(sim, 1.0)
    _, orientation = sim.models["holo"].link_pose("base_footprint")
    assert yaw_of(orientation) == pytest.approx(0.5, abs=0.02)
    robot.drive.set_command(1.0, 0.0, 0.0, sim.sim_time)  # forward in the turned frame
    run(sim, 1.0)
    (x2, y2, _), _ = sim.models["holo"].link_pose("base_footprint")
    assert (x2 - x, y2 - y) == pytest.approx((math.cos(0.5), math.sin(0.5)), abs=0.03)


def test_cmd_timeout_stops_it() -> None:
    sim = Simulation()
    sim.spawn_urdf("holo", HOLONOMIC_URDF.format(extra="<cmdTimeout>0.5</cmdTimeout>"), (0, 0, 0.01, 0, 0, 0))
    sim.robots["holo"].drive.set_command(1.0, 0.0, 0.0, sim.sim_time)
    run(sim, 2.0)
    (x, _, _), _ = sim.models["holo"].link_pose("base_footprint")
    assert x == pytest.approx(0.5, abs=0.1)  # moved for 0.5 s, then held
