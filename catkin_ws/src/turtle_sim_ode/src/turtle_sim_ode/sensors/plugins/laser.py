"""gazebo_ros_laser (``libgazebo_ros_laser.so``, and ``libgazebo_ros_ray_sensor.so`` of the same tags): a ``ray`` or
``gpu_ray`` sensor published as sensor_msgs/LaserScan; its scan is sensors.laser's LaserScanner."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, child_text, plugin_params, robot_namespace_tag
from turtle_sim_ode.sensors.sensor_element import number_at, sensor_what

LASER_PLUGINS = ("libgazebo_ros_laser.so", "libgazebo_ros_ray_sensor.so")
SENSOR_PLUGINS = {name: ("ray", "gpu_ray") for name in LASER_PLUGINS}


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
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>

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


def laser_config(link: str, sensor: Element, plugin: Optional[Element]) -> LaserConfig:
    """The ray sensor's tags and its laser plugin's (``plugin``; None: the sensor publishes nothing)."""
    name, what = sensor_what(sensor, "laser")
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
        resolution=number_at(horizontal, "resolution", defaults.resolution, what),
        min_angle=number_at(horizontal, "min_angle", defaults.min_angle, what),
        max_angle=number_at(horizontal, "max_angle", defaults.max_angle, what),
        range_min=number_at(ray, "range/min", defaults.range_min, what),
        range_max=number_at(ray, "range/max", defaults.range_max, what),
        range_resolution=number_at(ray, "range/resolution", defaults.range_resolution, what),
        update_rate=number_at(sensor, "update_rate", defaults.update_rate, what),
        frame=(child_text(plugin, "frameName") or "") if plugin is not None else "",
        topic=(child_text(plugin, "topicName") or defaults.topic) if plugin is not None else "",
        noise_mean=number_at(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=number_at(noise, "stddev", 0.0, what) if gaussian else 0.0,
        pose=pose,
        robot_namespace=robot_namespace_tag(plugin_params(plugin)) if plugin is not None else None,
    )
    config.validate()
    return config


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> LaserConfig:
    return laser_config(link, sensor, plugin)


def without_plugin(link: str, sensor: Element, warnings: List[str]) -> LaserConfig:
    """A ray sensor without a laser plugin: its tags are checked, and nothing is published (topic "")."""
    return laser_config(link, sensor, None)
