"""Sensor settings read from model text: the <sensor> blocks of URDF <gazebo reference> and SDF <link> elements
and the plugin tags inside them (gazebo_plugins' names and defaults)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Mapping, Optional, Sequence, Tuple
from xml.etree.ElementTree import Element, ParseError

import defusedxml
import defusedxml.ElementTree as SafeET

from turtle_sim_ode.models.urdf import ModelError

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


def _child_text(element: Optional[Element], path: str) -> Optional[str]:
    found = None if element is None else element.find(path)
    if found is None or found.text is None or not found.text.strip():
        return None
    return found.text.strip()


def _float(element: Optional[Element], path: str, default: float, what: str) -> float:
    text = _child_text(element, path)
    if text is None:
        return default
    try:
        value = float(text)
    except ValueError:
        raise ModelError(f"{what} <{path}> must be a number, got '{text}'") from None
    if not math.isfinite(value):
        raise ModelError(f"{what} <{path}> must be finite, got '{text}'")
    return value


def _laser_config(link: str, sensor: Element) -> LaserConfig:
    name = sensor.get("name", "laser")
    what = f"<sensor name='{name}'>"
    defaults = LaserConfig(link)
    ray = sensor.find("ray")
    horizontal = None if ray is None else ray.find("scan/horizontal")
    samples_text = _child_text(horizontal, "samples")
    try:
        samples = defaults.samples if samples_text is None else int(samples_text)
    except ValueError:
        raise ModelError(f"{what} <samples> must be an integer, got '{samples_text}'") from None
    noise = None if ray is None else ray.find("noise")
    gaussian = noise is not None and (_child_text(noise, "type") or "gaussian").lower() == "gaussian"
    plugin = next((p for p in sensor.findall("plugin") if p.get("filename") in LASER_PLUGINS), None)
    pose_text = _child_text(sensor, "pose")
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
        frame=(_child_text(plugin, "frameName") or "") if plugin is not None else "",
        topic=(_child_text(plugin, "topicName") or defaults.topic) if plugin is not None else "",
        noise_mean=_float(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=_float(noise, "stddev", 0.0, what) if gaussian else 0.0,
        pose=pose,
        robot_namespace=(_child_text(plugin, "robotNamespace") or "") if plugin is not None else "",
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
        if _child_text(element, tag) is not None:
            value = _float(element, tag, default, what)
            if value < 0:
                raise ModelError(f"{what} <{tag}> must be >= 0, got {value}")
            return value
    return default


def _param_number(params: Mapping[str, str], tag: str, default: float, what: str) -> float:
    text = params.get(tag)
    if text is None or not text.strip():
        return default
    try:
        value = float(text)
    except ValueError:
        raise ModelError(f"{what} <{tag}> must be a number, got '{text}'") from None
    if not math.isfinite(value) or value < 0:
        raise ModelError(f"{what} <{tag}> must be a finite number >= 0, got '{text}'")
    return value


def imu_config(filename: str, params: Mapping[str, str], link: str = "", sensor_rate: float = 0.0) -> ImuConfig:
    """gazebo_plugins' IMU plugin tags (``params``: tag -> text), as a model plugin or inside a <sensor> on
    ``link``; <bodyName> wins over ``link``, and a model plugin must have it."""
    what = f"<plugin filename='{filename}'>"
    body = (params.get("bodyName") or link).strip().split("::")[-1]
    if not body:
        raise ModelError(f"{what} needs <bodyName> (the link the IMU is on)")
    noise = _param_number(params, "gaussianNoise", 0.0, what)
    rate_tag = "updateRateHZ" if "updateRateHZ" in params else "updateRate"
    return ImuConfig(
        link=body,
        topic=(params.get("topicName") or "imu").strip(),
        frame=(params.get("frameName") or "").strip(),
        update_rate=_param_number(params, rate_tag, sensor_rate, what),
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
        topic=_child_text(plugin, "bumperTopicName") or "bumper_states",
        frame=_child_text(plugin, "frameName") or "world",
        update_rate=_rate(sensor, ("update_rate",), 0.0, what),
        robot_namespace=_child_text(plugin, "robotNamespace") or "",
    )


def _safe_xml(text: str, kind: str) -> Element:
    try:
        return SafeET.fromstring(text)
    except ParseError as error:
        raise ModelError(f"{kind} is not well-formed XML: {error}") from None
    except defusedxml.DefusedXmlException as error:
        raise ModelError(f"{kind} rejected by the XML guard: {error}") from None


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


def read_sensors(urdf: str) -> SensorBlocks:
    """The ``<gazebo reference="link"><sensor>`` blocks of a URDF: ray (``gpu_ray`` too), imu and contact.

    urdf_model keeps only contact tags of referenced ``<gazebo>`` blocks, so the raw text is
    read again here. ModelError for malformed XML or bad values, or a sensor on no link.
    """
    robot = _safe_xml(urdf, "URDF")
    links = {link.get("name") for link in robot.findall("link")}
    found = SensorBlocks()
    for gazebo in robot.findall("gazebo"):
        reference = gazebo.get("reference")
        for sensor in gazebo.findall("sensor"):
            if sensor.get("type") not in ("ray", "gpu_ray", "imu", "contact"):
                continue
            if reference is None or reference not in links:
                raise ModelError(f"<sensor name='{sensor.get('name', '')}'> must be in a <gazebo reference=link>")
            _add_sensor(found, reference, sensor)
    return found


def read_sdf_sensors(sdf: str) -> SensorBlocks:
    """The ``<link><sensor>`` elements of an SDF model (``<sdf><model>`` or a bare ``<model>``); a sensor's
    <pose> is in its link's frame, as in Gazebo. ModelError for malformed XML or bad values."""
    root = _safe_xml(sdf, "SDF")
    model = root if root.tag == "model" else root.find("model")
    found = SensorBlocks()
    for link in [] if model is None else model.findall("link"):
        for sensor in link.findall("sensor"):
            _add_sensor(found, link.get("name", ""), sensor)
    return found
