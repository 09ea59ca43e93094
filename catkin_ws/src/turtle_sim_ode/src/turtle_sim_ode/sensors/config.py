"""Sensor settings read from model text: the <sensor> blocks of URDF <gazebo reference> and SDF <link> elements
and the plugin tags inside them (gazebo_plugins' names and defaults)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Mapping, Optional, Sequence, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.text import ModelError, child_text, read_number
from turtle_sim_ode.models.urdf import RobotModel, parse_urdf

LASER_PLUGINS = ("libgazebo_ros_laser.so", "libgazebo_ros_ray_sensor.so")
# gazebo_plugins' IMUs: the model plugin (also found inside <sensor type="imu">, as turtlebot3 has it) and the
# sensor plugin.
IMU_PLUGINS = ("libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so")
BUMPER_PLUGIN = "libgazebo_ros_bumper.so"


# --- configuration -----------------------------------------------------------------------
@dataclass
class LaserConfig:
    """A Gazebo ``<sensor type="ray">`` with its ROS laser plugin (gazebo_ros_laser names)."""

    link: str
    name: str = "laser"
    samples: int = 360
    resolution: float = 1.0  # Gazebo's rays per sample; rays are cast one per sample here
    min_angle: float = 0.0
    max_angle: float = math.tau
    range_min: float = 0.12
    range_max: float = 3.5
    range_resolution: float = 0.0
    update_rate: float = 5.0  # Hz of sim time
    frame: str = ""  # "" = the link
    topic: str = "scan"  # "" when the sensor has no ROS plugin
    noise_mean: float = 0.0
    noise_stddev: float = 0.0
    # <sensor><pose>: (x, y, z, roll, pitch, yaw) of the sensor in the link frame.
    pose: Tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    robot_namespace: str = ""

    @property
    def angle_increment(self) -> float:
        return (self.max_angle - self.min_angle) / (self.samples - 1) if self.samples > 1 else 0.0

    def validate(self) -> None:
        """Raise ModelError naming the first bad field."""
        what = f"sensor '{self.name}' on link '{self.link}'"
        if not isinstance(self.samples, int) or isinstance(self.samples, bool) or not 1 <= self.samples <= 100_000:
            raise ModelError(f"{what}: samples must be an integer in 1..100000, got {self.samples!r}")
        numbers = ("resolution", "min_angle", "max_angle", "range_min", "range_max", "range_resolution")
        for attr in numbers + ("update_rate", "noise_mean", "noise_stddev"):
            if not math.isfinite(getattr(self, attr)):
                raise ModelError(f"{what}: {attr} must be finite, got {getattr(self, attr)!r}")
        if self.max_angle < self.min_angle:
            raise ModelError(f"{what}: max_angle {self.max_angle} < min_angle {self.min_angle}")
        if not 0 <= self.range_min < self.range_max:
            raise ModelError(f"{what}: need 0 <= range min < range max, got {self.range_min}, {self.range_max}")
        for attr in ("update_rate", "noise_stddev", "range_resolution"):
            if getattr(self, attr) < 0:
                raise ModelError(f"{what}: {attr} must be >= 0, got {getattr(self, attr)!r}")
        if len(self.pose) != 6 or not all(math.isfinite(v) for v in self.pose):
            raise ModelError(f"{what}: pose must be 6 finite numbers, got {self.pose!r}")


@dataclass(frozen=True)
class ImuNoise:
    """Gaussian noise stddevs (rad, rad/s, m/s^2); 0 = exact."""

    orientation: float = 0.0
    angular_velocity: float = 0.0
    linear_acceleration: float = 0.0


def _float(element: Optional[Element], path: str, default: float, what: str) -> float:
    return read_number(child_text(element, path), f"{what} <{path}>", default)


def _laser_config(link: str, sensor: Element) -> LaserConfig:
    name = sensor.get("name", "laser")
    what = f"<sensor name='{name}'>"
    defaults = LaserConfig(link)
    ray = sensor.find("ray")
    horizontal = None if ray is None else ray.find("scan/horizontal")
    samples_text = child_text(horizontal, "samples")
    try:
        samples = defaults.samples if samples_text is None else int(samples_text)
    except ValueError:
        raise ModelError(f"{what} <samples> must be an integer, got '{samples_text}'") from None
    noise = None if ray is None else ray.find("noise")
    gaussian = noise is not None and (child_text(noise, "type") or "gaussian").lower() == "gaussian"
    plugin = next((p for p in sensor.findall("plugin") if p.get("filename") in LASER_PLUGINS), None)
    pose_text = child_text(sensor, "pose")
    pose = defaults.pose
    if pose_text is not None:
        try:
            pose = tuple(float(v) for v in pose_text.split())  # type: ignore[assignment]
        except ValueError:
            raise ModelError(f"{what} <pose> must be 6 numbers, got '{pose_text}'") from None
    config = LaserConfig(
        link=link,
        name=name,
        samples=samples,
        resolution=_float(horizontal, "resolution", defaults.resolution, what),
        min_angle=_float(horizontal, "min_angle", defaults.min_angle, what),
        max_angle=_float(horizontal, "max_angle", defaults.max_angle, what),
        range_min=_float(ray, "range/min", defaults.range_min, what),
        range_max=_float(ray, "range/max", defaults.range_max, what),
        range_resolution=_float(ray, "range/resolution", defaults.range_resolution, what),
        update_rate=_float(sensor, "update_rate", defaults.update_rate, what),
        frame=(child_text(plugin, "frameName") or "") if plugin is not None else "",
        topic=(child_text(plugin, "topicName") or defaults.topic) if plugin is not None else "",
        noise_mean=_float(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=_float(noise, "stddev", 0.0, what) if gaussian else 0.0,
        pose=pose,
        robot_namespace=(child_text(plugin, "robotNamespace") or "") if plugin is not None else "",
    )
    config.validate()
    return config


@dataclass(frozen=True)
class ImuConfig:
    """An IMU plugin's settings (gazebo_plugins' names): on ``link``, published on ``topic`` in ``frame``
    ("" = the link) at ``update_rate`` Hz of sim time (0 = every step), with gaussian noise of ``noise``."""

    link: str
    topic: str = "imu"
    frame: str = ""
    update_rate: float = 0.0
    noise: ImuNoise = field(default_factory=ImuNoise)
    robot_namespace: str = ""


@dataclass(frozen=True)
class ContactConfig:
    """A ``<sensor type="contact">`` with libgazebo_ros_bumper.so: contacts of ``link``'s collisions, published
    as gazebo_msgs/ContactsState on ``topic`` (frame ``frame``) at ``update_rate`` Hz (0 = every step)."""

    link: str
    name: str
    collisions: Tuple[str, ...]
    topic: str = "bumper_states"
    frame: str = "world"
    update_rate: float = 0.0
    robot_namespace: str = ""


@dataclass
class SensorBlocks:
    """The sensors a URDF's ``<gazebo reference="link"><sensor>`` blocks define (with a ROS plugin)."""

    lasers: List[LaserConfig] = field(default_factory=list)
    imus: List[ImuConfig] = field(default_factory=list)
    contacts: List[ContactConfig] = field(default_factory=list)


def _rate(element: Optional[Element], tags: Sequence[str], default: float, what: str) -> float:
    for tag in tags:
        if child_text(element, tag) is not None:
            value = _float(element, tag, default, what)
            if value < 0:
                raise ModelError(f"{what} <{tag}> must be >= 0, got {value}")
            return value
    return default


def imu_config(filename: str, params: Mapping[str, str], link: str = "", sensor_rate: float = 0.0) -> ImuConfig:
    """gazebo_plugins' IMU plugin tags (``params``: tag -> text), as a model plugin or inside a <sensor> on
    ``link``; <bodyName> wins over ``link``, and a model plugin must have it."""
    what = f"<plugin filename='{filename}'>"
    body = (params.get("bodyName") or link).strip().split("::")[-1]
    if not body:
        raise ModelError(f"{what} needs <bodyName> (the link the IMU is on)")
    noise = read_number(params.get("gaussianNoise"), f"{what} <gaussianNoise>", 0.0, minimum=0.0)
    rate_tag = "updateRateHZ" if "updateRateHZ" in params else "updateRate"
    return ImuConfig(
        link=body,
        topic=(params.get("topicName") or "imu").strip(),
        frame=(params.get("frameName") or "").strip(),
        update_rate=read_number(params.get(rate_tag), f"{what} <{rate_tag}>", sensor_rate, minimum=0.0),
        noise=ImuNoise(noise, noise, noise),
        robot_namespace=(params.get("robotNamespace") or "").strip(),
    )


def _contact_config(link: str, sensor: Element, plugin: Element) -> ContactConfig:
    name = sensor.get("name", "bumper")
    what = f"<sensor name='{name}'>"
    return ContactConfig(
        link=link,
        name=name,
        collisions=tuple(c.text.strip() for c in sensor.findall("contact/collision") if c.text and c.text.strip()),
        topic=child_text(plugin, "bumperTopicName") or "bumper_states",
        frame=child_text(plugin, "frameName") or "world",
        update_rate=_rate(sensor, ("update_rate",), 0.0, what),
        robot_namespace=child_text(plugin, "robotNamespace") or "",
    )


def _add_sensor(found: SensorBlocks, link: str, sensor: Element) -> None:
    """One <sensor> on ``link`` (URDF and SDF write them alike): ray (``gpu_ray`` too), imu or contact."""
    kind = sensor.get("type")
    plugins = sensor.findall("plugin")
    if kind in ("ray", "gpu_ray"):
        found.lasers.append(_laser_config(link, sensor))
    elif kind == "imu":
        what = f"<sensor name='{sensor.get('name', '')}'>"
        rate = _rate(sensor, ("update_rate",), 0.0, what)
        found.imus += [
            imu_config(p.get("filename"), {c.tag: c.text or "" for c in p}, link, rate)
            for p in plugins
            if p.get("filename") in IMU_PLUGINS
        ]
    elif kind == "contact":
        found.contacts += [_contact_config(link, sensor, p) for p in plugins if p.get("filename") == BUMPER_PLUGIN]


def model_sensors(robot: RobotModel) -> SensorBlocks:
    """The sensors the parsed model carries (``robot.sensors``): ray (``gpu_ray`` too), imu and contact, with a
    ROS plugin. ModelError for bad values, or a URDF sensor in a <gazebo> block that names no link of the model."""
    found = SensorBlocks()
    for block in robot.sensors:
        if block.element.get("type") not in ("ray", "gpu_ray", "imu", "contact"):
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
