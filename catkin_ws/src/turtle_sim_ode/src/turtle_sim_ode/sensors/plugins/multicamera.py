"""gazebo_ros_multicamera (``libgazebo_ros_multicamera.so`` in a ``multicamera`` sensor, gazebo_plugins/src/
gazebo_ros_multicamera.cpp): a stereo head. As GazeboRosMultiCamera::Load, each <camera> whose name holds "left" is
a camera under cameraName/left (no baseline), one whose name holds "right" under cameraName/right with the plugin's
hackBaseline; others are not published. Each is read as a camera (sensors.plugins.camera) with its <camera><pose>
on the sensor's <pose>; they share the sensor's rate, so their frames carry identical stamps."""
from __future__ import annotations

from dataclasses import dataclass
from typing import List, Tuple
from xml.etree.ElementTree import Element, SubElement

from turtle_sim_ode.models.transforms import compose, quat_from_rpy, rpy_of
from turtle_sim_ode.models.text import child_text
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.plugins.camera import read as read_camera
from turtle_sim_ode.sensors.sensor_element import sensor_pose, sensor_what

SENSOR_PLUGINS = {"libgazebo_ros_multicamera.so": ("multicamera",)}


@dataclass(frozen=True)
class MultiCameraConfig:
    cameras: Tuple[CameraConfig, ...]  # left, right, in the sensor's order


def _pose_text(outer: Tuple[float, ...], inner: Tuple[float, ...]) -> str:
    position, rotation = compose((outer[:3], quat_from_rpy(*outer[3:])), (inner[:3], quat_from_rpy(*inner[3:])))
    return " ".join(repr(v) for v in tuple(position) + tuple(rpy_of(rotation)))


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> MultiCameraConfig:
    name, what = sensor_what(sensor, "multicamera")
    outer = sensor_pose(sensor, what)
    base_name = (child_text(plugin, "cameraName") or "").strip("/")
    found = []
    for element in sensor.findall("camera"):
        camera_name = element.get("name", "")
        side = "left" if "left" in camera_name else "right" if "right" in camera_name else None
        if side is None:
            warnings.append(f"{what}: <camera name='{camera_name}'> is neither left nor right: not published")
            continue
        single = Element("sensor", {"type": "camera", "name": f"{name}/{camera_name}"})
        for tag in ("update_rate",):
            if sensor.find(tag) is not None:
                single.append(sensor.find(tag))  # type: ignore[arg-type]
        SubElement(single, "pose").text = _pose_text(
            outer, sensor_pose(element, f"{what} <camera name='{camera_name}'>")
        )
        single.append(element)
        per_camera = Element("plugin", plugin.attrib)
        for child in plugin:
            if child.tag not in ("cameraName", "hackBaseline"):
                per_camera.append(child)
        SubElement(per_camera, "cameraName").text = f"{base_name}/{side}" if base_name else side
        SubElement(per_camera, "hackBaseline").text = child_text(plugin, "hackBaseline") if side == "right" else "0"
        found.append(read_camera(link, single, per_camera, warnings))
    return MultiCameraConfig(tuple(found))
