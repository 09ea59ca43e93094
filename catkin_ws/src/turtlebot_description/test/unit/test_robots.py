"""The robot files expand (xacro) to TurtleBot 2 descriptions with the names the TurtleBot 2 software expects.

Expected names from turtlebot/turtlebot (melodic) turtlebot_description: robots/kobuki_hexagons_*.urdf.xacro (the
file names turtlebot_gazebo's includes/kobuki.launch.xml builds from base, stacks and 3d_sensor), urdf/stacks/
hexagons.urdf.xacro (pole and plate links), urdf/sensors/kinect.urdf.xacro (camera frames), urdf/
turtlebot_gazebo.urdf.xacro (the openni_kinect plugin's tags); and yujinrobot/kobuki (melodic) kobuki_description
urdf/kobuki.urdf.xacro (base, wheel, caster, gyro and cliff links) and urdf/kobuki_gazebo.urdf.xacro (the sensors
and the libgazebo_ros_kobuki.so tags). Upstream's kobuki_hexagons_kinect has 34 links.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
SRC = PACKAGE_ROOT.parent
ROBOTS = sorted((PACKAGE_ROOT / "robots").glob("*.urdf.xacro"))

KOBUKI_LINKS = {
    "base_footprint", "base_link", "wheel_left_link", "wheel_right_link", "caster_front_link", "caster_back_link",
    "gyro_link", "cliff_sensor_left_link", "cliff_sensor_right_link", "cliff_sensor_front_link",
}  # fmt: skip
STACK_LINKS = (
    {"pole_bottom_%d_link" % i for i in range(6)}
    | {"pole_middle_%d_link" % i for i in range(4)}
    | {"pole_top_%d_link" % i for i in range(4)}
    | {"pole_kinect_%d_link" % i for i in range(2)}
    | {"plate_bottom_link", "plate_middle_link", "plate_top_link"}
)
CAMERA_LINKS = {
    "camera_rgb_frame", "camera_rgb_optical_frame", "camera_link", "camera_depth_frame", "camera_depth_optical_frame",
}  # fmt: skip
KOBUKI_PLUGIN = {
    "publish_tf": "1",
    "left_wheel_joint_name": "wheel_left_joint",
    "right_wheel_joint_name": "wheel_right_joint",
    "wheel_separation": "0.230",
    "wheel_diameter": "0.070",
    "torque": "1.0",
    "velocity_command_timeout": "0.6",
    "cliff_sensor_left_name": "cliff_sensor_left",
    "cliff_sensor_center_name": "cliff_sensor_front",
    "cliff_sensor_right_name": "cliff_sensor_right",
    "cliff_detection_threshold": "0.04",
    "bumper_name": "bumpers",
    "imu_name": "imu",
    "wheel_drop_left_sensor_name": "wheel_drop_left",
    "wheel_drop_right_sensor_name": "wheel_drop_right",
}


def xacro_command() -> list:
    if shutil.which("xacro"):
        return ["xacro"]
    dropin = SRC / "xacro"
    if not (dropin / "CATKIN_IGNORE").exists():
        return ["/usr/bin/python3", str(dropin / "xacro")]
    pytest.skip("no xacro command")


def expand(robot: Path) -> ET.Element:
    env = dict(os.environ, ROS_PACKAGE_PATH=str(SRC), PYTHONPATH=str(SRC / "xacro" / "src"))
    result = subprocess.run(
        xacro_command() + [str(robot)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, env=env
    )
    assert result.returncode == 0, result.stderr
    return ET.fromstring(result.stdout)


def test_the_robot_files_upstreams_launch_picks():
    assert [r.name for r in ROBOTS] == [
        "kobuki_hexagons_asus_xtion_pro.urdf.xacro",
        "kobuki_hexagons_asus_xtion_pro_offset.urdf.xacro",
        "kobuki_hexagons_kinect.urdf.xacro",
    ]


@pytest.mark.parametrize("robot", ROBOTS, ids=lambda r: r.name)
def test_links_sensors_and_plugins(robot: Path):
    urdf = expand(robot)
    links = [link.get("name") for link in urdf.findall("link")]
    assert len(links) == 34 and set(links) == KOBUKI_LINKS | STACK_LINKS | CAMERA_LINKS
    plugins = [p for g in urdf.findall("gazebo") for p in g.findall("plugin")]
    kobuki = [p for p in plugins if p.get("filename") == "libgazebo_ros_kobuki.so"]
    assert len(kobuki) == 1 and {c.tag: c.text for c in kobuki[0]} == KOBUKI_PLUGIN
    sensors = {
        s.get("name"): (g.get("reference"), s.get("type")) for g in urdf.findall("gazebo") for s in g.findall("sensor")
    }
    assert sensors == {
        "bumpers": ("base_link", "contact"),
        "wheel_drop_left": ("wheel_left_link", "contact"),
        "wheel_drop_right": ("wheel_right_link", "contact"),
        "cliff_sensor_left": ("cliff_sensor_left_link", "ray"),
        "cliff_sensor_right": ("cliff_sensor_right_link", "ray"),
        "cliff_sensor_front": ("cliff_sensor_front_link", "ray"),
        "imu": ("gyro_link", "imu"),
        "camera": ("camera_link", "depth"),
    }
    camera = [p for p in urdf.iter("plugin") if p.get("filename") == "libgazebo_ros_openni_kinect.so"]
    assert len(camera) == 1
    tags = {c.tag: c.text for c in camera[0]}
    assert tags["cameraName"] == "camera" and tags["frameName"] == "camera_depth_optical_frame"
    assert tags["depthImageTopicName"] == "depth/image_raw" and tags["pointCloudTopicName"] == "depth/points"
    assert tags["imageTopicName"] == "rgb/image_raw" and tags["depthImageCameraInfoTopicName"] == "depth/camera_info"
    joints = {j.get("name"): j.get("type") for j in urdf.findall("joint")}
    assert joints["wheel_left_joint"] == joints["wheel_right_joint"] == "continuous"
    assert sum(t == "fixed" for t in joints.values()) == 31
