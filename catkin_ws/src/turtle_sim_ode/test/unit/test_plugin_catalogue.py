"""The plugin catalogue: every known library file name has a module that reads it and a ROS adapter for what it
reads, the README's tables name each, and a plugin not known is named in the one spawn warning, in a sensor too."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import hypothesis.strategies as st
import pytest
from hypothesis import given, settings
from conftest import PACKAGE_ROOT

from turtle_sim_ode.control.plugin import RosControlConfig
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.ros.plugins import ADAPTERS, GROUPED, plugin_namespace
from turtle_sim_ode.sensors.config import read_sdf_sensors
from turtle_sim_ode.sensors.plugins import SENSOR_PLUGINS
from turtle_sim_ode.world.plugins import MODEL_PLUGINS, P3D, read_plugins
from turtle_sim_ode.world.plugins.ros_control import ROS_CONTROL
from turtle_sim_ode.world.simulation import Simulation

README = (Path(PACKAGE_ROOT) / "README.md").read_text()
BURGER_URDF = (Path(PACKAGE_ROOT) / "test" / "models" / "burger.urdf").read_text()

RAY_SDF = """<sdf version="1.6"><model name="lidar"><link name="base">
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
  <sensor type="ray" name="{name}"><update_rate>10</update_rate>
    <ray><scan><horizontal><samples>8</samples><min_angle>-1</min_angle><max_angle>1</max_angle></horizontal></scan>
      <range><min>0.1</min><max>10</max></range></ray>
    <plugin name="p" filename="{filename}"><topicName>points</topicName></plugin>
  </sensor></link></model></sdf>"""


def test_every_known_plugin_is_in_the_readme() -> None:
    for filename in list(MODEL_PLUGINS) + list(SENSOR_PLUGINS):
        assert f"`{filename}`" in README, filename


def test_every_plugin_read_at_spawn_has_a_ros_adapter() -> None:
    sim = Simulation()
    sim.spawn_urdf("burger", BURGER_URDF)
    configs = sim.plugins["burger"].configs
    assert configs and all(type(config) in ADAPTERS or type(config) in GROUPED for config in configs), configs


def test_a_ray_sensor_with_an_unknown_plugin_is_named_in_the_one_warning() -> None:
    """Issue #23: a Velodyne-like sensor with an unknown plugin was dropped without a word."""
    sdf = RAY_SDF.format(name="top_lidar", filename="libmy_lidar_plugin.so")
    blocks = read_sdf_sensors(sdf)
    assert [laser.topic for laser in blocks.lasers] == [""]  # read and checked, published by no one
    warnings = Simulation().spawn_sdf("lidar", sdf)
    unsupported = [warning for warning in warnings if "not supported" in warning]
    assert unsupported == ["1 plugin(s) not supported, ignored: libmy_lidar_plugin.so (sensor 'top_lidar')"]


def test_a_laser_plugin_in_a_sensor_of_another_type_is_not_loaded() -> None:
    """gazebo_ros_laser's Load refuses a parent that is not a ray sensor."""
    sdf = RAY_SDF.format(name="cam", filename="libgazebo_ros_laser.so").replace('type="ray"', 'type="imu"')
    warnings = Simulation().spawn_sdf("lidar", sdf)
    assert any("libgazebo_ros_laser.so (sensor 'cam')" in warning for warning in warnings), warnings


def test_a_triggered_camera_reads_its_trigger_topic() -> None:
    """gazebo_ros_camera_utils.cpp: <triggerTopicName>, default image_trigger; the other tags as a camera's."""
    camera = """<sdf version="1.6"><model name="cam"><static>true</static><link name="link">
      <sensor type="camera" name="cam"><camera><image><width>8</width><height>6</height></image></camera>
        <plugin name="c" filename="libgazebo_ros_triggered_camera.so">{tags}<cameraName>front</cameraName></plugin>
      </sensor></link></model></sdf>"""
    (config,) = read_sdf_sensors(camera.format(tags="")).configs
    assert config.triggered and config.trigger_topic == "image_trigger" and config.camera_name == "front"
    (config,) = read_sdf_sensors(camera.format(tags="<triggerTopicName>shoot</triggerTopicName>")).configs
    assert config.trigger_topic == "shoot" and (config.width, config.height) == (8, 6)


@pytest.mark.parametrize(
    "own, spawn, expected",
    [
        ("own_ns", "spawned_ns", "own_ns"),
        ("/", "spawned_ns", "/"),
        ("", "spawned_ns", ""),
        (None, "spawned_ns", "spawned_ns"),
        (None, "", ""),
    ],
)
def test_a_plugins_own_robot_namespace_wins(own: Optional[str], spawn: str, expected: str) -> None:
    """gazebo_ros_api_plugin.cpp, walkChildAddRobotNamespace: the spawn's robot_namespace goes only to a <plugin>
    without a <robotNamespace> child; an empty child is the root namespace, as each plugin's Load reads
    _sdf->GetElement("robotNamespace")->Get<std::string>() whenever HasElement (issue #31: the SMB's plugins)."""
    tags = {"bodyName": "b"} if own is None else {"bodyName": "b", "robotNamespace": own}
    (config,) = read_plugins("m", [GazeboPlugin(P3D, "p", tags)], {}, []).configs
    assert plugin_namespace(spawn, config) == expected


@given(
    own=st.one_of(st.none(), st.from_regex(r"\A/?([a-z][a-z0-9_]{0,6}/?){0,3}\Z")),
    spawn=st.from_regex(r"\A/?([a-z][a-z0-9_]{0,6})?\Z"),
    filename=st.sampled_from(sorted(f for f in MODEL_PLUGINS if f != ROS_CONTROL)),
)
@settings(max_examples=60, deadline=None)
def test_every_model_plugin_takes_its_element_else_the_spawns(own: Optional[str], spawn: str, filename: str) -> None:
    """Each plugin's Load takes <robotNamespace> whenever the element exists, empty or not; without it the spawn's
    robot_namespace (walkChildAddRobotNamespace). Plugins that need more tags than given are skipped."""
    tags = {name: "base" for name in ("bodyName", "frameName", "jointName", "topicName")}
    if own is not None:
        tags["robotNamespace"] = own
    try:
        configs = read_plugins("m", [GazeboPlugin(filename, "p", tags)], {}, []).configs
    except ModelError:
        return
    for config in configs:
        assert plugin_namespace(spawn, config) == (spawn if own is None else own.strip())


@pytest.mark.parametrize(
    "element, expected",
    [("", ""), ("<robotNamespace></robotNamespace>", ""), ("<robotNamespace>r</robotNamespace>", "r")],
)
def test_a_sensor_plugins_empty_robot_namespace_is_the_root(element: str, expected: str) -> None:
    """gazebo_ros_block_laser.cpp / gazebo_ros_imu_sensor.cpp Load: the element's value where it exists."""
    sdf = RAY_SDF.format(name="lidar", filename="libgazebo_ros_laser.so").replace(
        "<topicName>", element + "<topicName>"
    )
    (laser,) = read_sdf_sensors(sdf).lasers
    assert plugin_namespace("spawned", laser) == (expected if element else "spawned")


def test_ros_control_takes_an_empty_robot_namespace_as_the_root() -> None:
    """gazebo_ros_control_plugin.cpp GazeboRosControlPlugin::Load: robot_namespace_ = the element's value when
    sdf_->HasElement("robotNamespace"), else parent_model_->GetName() (the SMB's URDF gives it empty)."""
    assert RosControlConfig.read({"robotNamespace": ""}, "smb", 0.001).robot_namespace == ""
    assert RosControlConfig.read({}, "smb", 0.001).robot_namespace == "smb"
