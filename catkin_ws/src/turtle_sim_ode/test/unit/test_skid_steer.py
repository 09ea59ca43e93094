"""libgazebo_ros_skid_steer_drive.so: tags and defaults as gazebo_plugins/src/gazebo_ros_skid_steer_drive.cpp
(GazeboRosSkidSteerDrive::Load) reads them, the four wheels driven as its getWheelVelocities sets them, and the
odometry covariance its publishOdometry reports."""
from __future__ import annotations

import math
from pathlib import Path

import pytest
from conftest import PACKAGE_ROOT, yaw_of

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.ros.plugins.skid_steer_drive import covariance
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.skid_steer_drive import SKID_STEER_DRIVE, SkidSteerRobot
from turtle_sim_ode.world.simulation import Simulation

SKID_BOT = (Path(PACKAGE_ROOT) / "test" / "models" / "skid_bot.urdf").read_text()
WHEEL_JOINTS = [f"{side}_WHEEL_JOINT" for side in ("LF", "RF", "LH", "RH")]
DEFAULT_JOINTS = ["left_front_joint", "right_front_joint", "left_rear_joint", "right_rear_joint"]


def test_defaults_are_load_s() -> None:
    (drive,) = read_plugins("m", [GazeboPlugin(SKID_STEER_DRIVE, "drive", {})], {}, DEFAULT_JOINTS).drives
    # GazeboRosSkidSteerDrive::Load: joint names, 0.4 m separation, 0.15 m diameter, torque 5, cmd_vel, odom,
    # odom, base_footprint, 100 Hz, covariances 0.0001, 0.0001, 0.01, no tf.
    assert list(drive.joints_needed) == DEFAULT_JOINTS
    assert (drive.params.wheel_separation, drive.params.wheel_radius, drive.params.max_wheel_torque) == (0.4, 0.075, 5)
    assert (drive.command_topic, drive.odometry_topic, drive.odometry_frame, drive.base_frame) == (
        "cmd_vel",
        "odom",
        "odom",
        "base_footprint",
    )
    assert drive.update_rate == 100.0 and not drive.broadcast_tf
    assert (drive.covariance_x, drive.covariance_y, drive.covariance_yaw) == (0.0001, 0.0001, 0.01)
    # No watchdog and no limits: a command holds until the next (cmdVelCallback only stores it).
    assert drive.params.cmd_timeout == 0 and math.isinf(drive.params.max_linear)


def test_missing_joints_and_bad_tags_refuse_the_model() -> None:
    with pytest.raises(ModelError, match="no movable joint"):
        read_plugins("m", [GazeboPlugin(SKID_STEER_DRIVE, "drive", {})], {}, DEFAULT_JOINTS[:3])
    with pytest.raises(ModelError, match="<torque>"):
        read_plugins("m", [GazeboPlugin(SKID_STEER_DRIVE, "drive", {"torque": "-1"})], {}, DEFAULT_JOINTS)
    with pytest.raises(ModelError, match="<broadcastTF> must be true or false"):
        read_plugins("m", [GazeboPlugin(SKID_STEER_DRIVE, "drive", {"broadcastTF": "yes"})], {}, DEFAULT_JOINTS)


def test_covariance_is_publish_odometry_s_diagonal() -> None:
    (drive,) = read_plugins("smb", parse_urdf(SKID_BOT).plugins, {}, WHEEL_JOINTS).drives
    matrix = covariance(drive)
    assert [matrix[7 * i] for i in range(6)] == [0.001, 0.001, 1e12, 1e12, 1e12, 0.01]
    assert sum(matrix) == sum(matrix[7 * i] for i in range(6))


def drive(sim: Simulation, linear: float, angular: float, seconds: float) -> None:
    sim.robots["smb"].drive.set_command(linear, angular, sim.sim_time)
    for _ in range(int(round(seconds / sim.physics.time_step))):
        sim.step()


def test_four_wheels_drive_straight_and_turn() -> None:
    sim = Simulation()
    sim.spawn_urdf("smb", SKID_BOT, (0, 0, 0.2, 0, 0, 0))
    robot = sim.robots["smb"]
    assert isinstance(robot, SkidSteerRobot) and len(robot.wheels) == 4
    drive(sim, 0.0, 0.0, 0.5)  # settle
    model = sim.models["smb"]
    (x0, y0, _), _ = model.link_pose("base_link")
    drive(sim, 0.5, 0.0, 2.0)
    (x1, y1, _), orientation = model.link_pose("base_link")
    assert x1 - x0 == pytest.approx(1.0, abs=0.1) and abs(y1 - y0) < 0.05
    # Every wheel at v / r (getWheelVelocities: both sides at vr, each wheel at speed / (diameter / 2)).
    for wheel in robot.wheels:
        assert wheel.rate() == pytest.approx(0.5 / 0.14, rel=0.02)
    yaw0 = yaw_of(orientation)
    drive(sim, 0.0, 0.5, 1.0)
    _, orientation = model.link_pose("base_link")
    turned = (yaw_of(orientation) - yaw0 + math.pi) % math.tau - math.pi
    assert 0.2 < turned < 0.6  # counter-clockwise, slowed by the wheels' scrub as a real skid steer is
    left_front, right_front, left_rear, right_rear = robot.wheels
    assert left_front.rate() < 0 < right_front.rate() and left_rear.rate() < 0 < right_rear.rate()
