"""gazebo_ros plugin tags read with gazebo_ros's names and defaults."""
import math
from pathlib import Path

import pytest
from conftest import TURTLEBOT_URDF

from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.sensors.config import ImuNoise
from turtle_sim_ode.world.plugins import DIFF_DRIVE, IMU, KOBUKI, P3D, find_body, read_plugins

BURGER_URDF = (Path(__file__).resolve().parents[1] / "models" / "burger.urdf").read_text()


def test_turtlebot3_diff_drive_tags():
    robot = parse_urdf(BURGER_URDF)
    plugins = read_plugins("burger", robot.plugins, {}, ["wheel_left_joint", "wheel_right_joint"])
    (drive,) = plugins.drives
    assert drive.filename == DIFF_DRIVE
    assert (drive.left_joint, drive.right_joint) == ("wheel_left_joint", "wheel_right_joint")
    assert drive.params.wheel_separation == pytest.approx(0.160)
    assert drive.params.wheel_radius == pytest.approx(0.033)
    assert drive.params.max_wheel_torque == 10.0
    assert drive.params.max_wheel_acceleration == pytest.approx(1 / 0.033)  # m/s^2 -> rad/s^2
    assert (drive.command_topic, drive.odometry_topic, drive.odometry_frame, drive.base_frame) == (
        "cmd_vel",
        "odom",
        "odom",
        "base_footprint",
    )
    assert drive.odometry_source == "world" and drive.publish_tf and drive.publish_joint_states
    assert drive.update_rate == 30.0
    (truth,) = plugins.ground_truths
    assert (truth.body, truth.topic, truth.frame, truth.update_rate) == (
        "base_footprint",
        "ground_truth/burger",
        "world",
        50.0,
    )


def test_kobuki_topics_follow_the_model_name():
    robot = parse_urdf(TURTLEBOT_URDF)
    (drive,) = read_plugins(
        "mobile_base", robot.plugins, {"cmd_timeout": 1.0}, ["wheel_left_joint", "wheel_right_joint"]
    ).drives
    assert drive.filename == KOBUKI
    assert drive.command_topic == "mobile_base/commands/velocity"
    assert drive.reset_topic == "mobile_base/commands/reset_odometry"
    assert drive.params.cmd_timeout == 1.0 and drive.odometry_source == "encoder"


def test_defaults_of_gazebo_ros_diff_drive():
    plugin = GazeboPlugin(DIFF_DRIVE, "drive", {})
    (drive,) = read_plugins("m", [plugin], {}, ["left_joint", "right_joint"]).drives
    assert drive.params.wheel_separation == 0.34 and drive.params.wheel_radius == 0.075
    assert drive.params.cmd_timeout == 0.0 and math.isinf(drive.params.max_linear)
    assert drive.command_topic == "cmd_vel" and drive.update_rate == 100.0


@pytest.mark.parametrize(
    "params, message",
    [
        ({"wheelSeparation": "wide"}, "<wheelSeparation> must be a number"),
        ({"wheelDiameter": "-1"}, "<wheelDiameter> must be a finite number >= 0"),
        ({"publishTf": "maybe"}, "<publishTf> must be true or false"),
        ({"odometrySource": "gps"}, "<odometrySource> must be encoder or world"),
        ({"leftJoint": "no_such_joint"}, "no movable joint(s) ['no_such_joint']"),
    ],
)
def test_bad_tags_are_named(params, message):
    plugin = GazeboPlugin(DIFF_DRIVE, "drive", params)
    with pytest.raises(ModelError) as error:
        read_plugins("m", [plugin], {}, ["left_joint", "right_joint"])
    assert message in str(error.value)


def test_p3d_needs_a_body_and_unknown_plugins_are_named():
    with pytest.raises(ModelError, match="bodyName"):
        read_plugins("m", [GazeboPlugin(P3D, "truth", {})], {}, [])
    plugins = read_plugins("m", [GazeboPlugin("libgazebo_ros_camera.so", "cam", {})], {}, [])
    assert plugins.warnings == ["1 plugin(s) not supported, ignored: libgazebo_ros_camera.so"]


def test_many_unsupported_plugins_give_one_bounded_warning():
    """Issue #16: 20,000 unsupported plugins gave 20,000 warnings (1.1 MB in the answer)."""
    plugins = [GazeboPlugin("lib_%d.so" % (i % 30), "p%d" % i, {}) for i in range(20000)]
    plugins.append(GazeboPlugin("x" * 100000, "long", {}))
    (warning,) = read_plugins("m", plugins, {}, []).warnings
    assert warning.startswith("20001 plugin(s) not supported, ignored: lib_0.so x667, lib_1.so x667")
    assert "and 21 other file names" in warning
    assert len(warning) < 500


def test_find_body_accepts_scoped_names():
    assert find_body(["base_link"], "robot::base_link") == "base_link"
    assert find_body(["base_link"], "base_link") == "base_link"
    assert find_body(["base_link"], "wheel") is None


def test_imu_model_plugin_as_turtlebot3_writes_it():
    params = {"bodyName": "imu_link", "frameName": "imu_link", "topicName": "imu", "updateRate": "200"}
    params["gaussianNoise"] = "0.01"
    (imu,) = read_plugins("m", [GazeboPlugin(IMU, "imu_plugin", params)], {}, []).imus
    assert (imu.link, imu.frame, imu.topic, imu.update_rate) == ("imu_link", "imu_link", "imu", 200.0)
    assert imu.noise == ImuNoise(0.01, 0.01, 0.01)
    with pytest.raises(ModelError, match="needs <bodyName>"):
        read_plugins("m", [GazeboPlugin(IMU, "imu_plugin", {"topicName": "imu"})], {}, [])
    with pytest.raises(ModelError, match="<updateRateHZ> must be a finite number >= 0"):
        read_plugins("m", [GazeboPlugin(IMU, "imu_plugin", {"bodyName": "b", "updateRateHZ": "-5"})], {}, [])


def test_kobuki_cliff_threshold_tag():
    robot = parse_urdf(TURTLEBOT_URDF)
    joints = ["wheel_left_joint", "wheel_right_joint"]
    assert read_plugins("mobile_base", robot.plugins, {}, joints).drives[0].cliff_threshold == 0.04
    (kobuki,) = robot.plugins
    bad = GazeboPlugin(kobuki.filename, kobuki.name, dict(kobuki.params, cliff_detection_threshold="-1"))
    with pytest.raises(ModelError, match="cliff_detection_threshold"):
        read_plugins("mobile_base", [bad], {}, joints)
