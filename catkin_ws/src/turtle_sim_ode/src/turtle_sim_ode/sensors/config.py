"""Sensor settings read from model text: the <sensor> blocks of URDF <gazebo reference> and SDF <link> elements and the
plugins inside them, each read by its module in sensors.plugins (gazebo_plugins' names and defaults)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import RobotModel
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.sensors.plugins import SENSOR_PLUGINS, SIMULATED_TYPES, WITHOUT_PLUGIN
from turtle_sim_ode.sensors.plugins.bumper import ContactConfig
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.plugins.imu import ImuConfig, ImuNoise
from turtle_sim_ode.sensors.plugins.laser import LaserConfig

# The configs of the sensor plugins are defined in their modules; these names are also read from here.
__all__ = ["ContactConfig", "CameraConfig", "ImuConfig", "ImuNoise", "LaserConfig"]
__all__ += ["SensorBlocks", "model_sensors", "read_sensors", "read_sdf_sensors"]


@dataclass
class SensorBlocks:
    """What a model's ``<sensor>`` blocks define: the configs of their plugins (``configs``, in document order), the
    sensors read but publishing nothing (``unpublished``: a ray sensor without a laser plugin), warnings naming the
    sensors not simulated, and the plugins not known, counted by name (``unsupported``)."""

    configs: List[object] = field(default_factory=list)
    unpublished: List[object] = field(default_factory=list)
    warnings: List[str] = field(default_factory=list)
    unsupported: Dict[str, int] = field(default_factory=dict)

    def of_type(self, kind: type) -> List:
        return [config for config in self.configs + self.unpublished if isinstance(config, kind)]

    @property
    def lasers(self) -> List[LaserConfig]:
        return self.of_type(LaserConfig)

    @property
    def imus(self) -> List[ImuConfig]:
        return self.of_type(ImuConfig)

    @property
    def contacts(self) -> List[ContactConfig]:
        return self.of_type(ContactConfig)

    @property
    def cameras(self) -> List[CameraConfig]:
        return self.of_type(CameraConfig)


def _add_sensor(found: SensorBlocks, link: str, sensor: Element) -> None:
    """One <sensor> on ``link`` (URDF and SDF write them alike): each plugin in it that loads in its type is read by
    its module; a plugin not known is counted in ``found.unsupported`` with the sensor's name."""
    kind = sensor.get("type", "")
    known = 0
    for plugin in sensor.findall("plugin"):
        filename = plugin.get("filename", "")
        entry = SENSOR_PLUGINS.get(filename)
        if entry is None or kind not in entry.sensor_types:
            label = f"{filename} (sensor '{sensor.get('name', '')}')"
            found.unsupported[label] = found.unsupported.get(label, 0) + 1
            continue
        known += 1
        found.configs.append(entry.read(link, sensor, plugin, found.warnings))
    if not known and kind in WITHOUT_PLUGIN:
        config = WITHOUT_PLUGIN[kind](link, sensor, found.warnings)
        if config is not None:
            found.unpublished.append(config)


def model_sensors(robot: RobotModel) -> SensorBlocks:
    """The sensors the parsed model carries (``robot.sensors``): ray (``gpu_ray`` too), imu, contact, camera and
    depth, with a ROS plugin; a warning names each sensor of another type (not simulated). ModelError for bad
    values, or a URDF sensor in a <gazebo> block that names no link of the model."""
    found = SensorBlocks()
    for block in robot.sensors:
        kind = block.element.get("type")
        if kind not in SIMULATED_TYPES:
            found.warnings.append(
                f"<sensor name='{block.element.get('name', '')}' type='{kind}'> on link '{block.link}' is not "
                f"simulated: no topics"
            )
            continue
        if block.link is None or block.link not in robot.links:
            raise ModelError(f"<sensor name='{block.element.get('name', '')}'> must be in a <gazebo reference=link>")
        _add_sensor(found, block.link, block.element)
    return found


def read_sensors(urdf: str) -> SensorBlocks:
    """The sensors of a URDF's ``<gazebo reference="link"><sensor>`` blocks (ModelError as parse_urdf's)."""
    return model_sensors(parse_urdf(urdf))


def read_sdf_sensors(sdf: str) -> SensorBlocks:
    """The ``<link><sensor>`` elements of an SDF model; a sensor's <pose> is in its link's frame, as in Gazebo."""
    return model_sensors(parse_sdf_model(sdf))
