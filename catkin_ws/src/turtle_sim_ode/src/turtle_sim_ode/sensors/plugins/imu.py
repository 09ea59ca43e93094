"""gazebo_plugins' IMU (``libgazebo_ros_imu.so``, ``libgazebo_ros_imu_sensor.so``) inside an ``imu`` sensor: the tags;
the model-plugin form is read by world.plugins.imu with the same function. The reading is sensors.imu's ImuSensor."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Mapping, Optional
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, read_number, robot_namespace_tag
from turtle_sim_ode.sensors.sensor_element import rate_at, sensor_what

# gazebo_plugins' IMUs: the model plugin (also found inside <sensor type="imu">, as turtlebot3 has it) and the
# sensor plugin.
IMU_PLUGINS = ("libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so")
SENSOR_PLUGINS = {name: ("imu",) for name in IMU_PLUGINS}


@dataclass(frozen=True)
class ImuNoise:
    """Gaussian noise stddevs (rad, rad/s, m/s^2); 0 = exact."""

    orientation: float = 0.0
    angular_velocity: float = 0.0
    linear_acceleration: float = 0.0


@dataclass(frozen=True)
class ImuConfig:
    """An IMU plugin's settings (gazebo_plugins' names): on ``link``, published on ``topic`` in ``frame``
    ("" = the link) at ``update_rate`` Hz of sim time (0 = every step), with gaussian noise of ``noise``."""

    link: str
    topic: str = "imu"
    frame: str = ""
    update_rate: float = 0.0
    noise: ImuNoise = field(default_factory=ImuNoise)
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


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
        robot_namespace=robot_namespace_tag(params),
    )


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> ImuConfig:
    rate = rate_at(sensor, ("update_rate",), 0.0, sensor_what(sensor, "")[1])
    return imu_config(plugin.get("filename", ""), {c.tag: c.text or "" for c in plugin}, link, rate)
