"""gazebo_ros_range (``libgazebo_ros_range.so`` in a ``ray`` sensor, gazebo_plugins/src/gazebo_ros_range.cpp): a sonar
or infrared ranger, the nearest of its rays as sensor_msgs/Range. The tags with GazeboRosRange::Load's defaults; the
rays are sensors.lidar's."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, read_number
from turtle_sim_ode.sensors.sensor_element import RayGridConfig, gazebo_ray_tags, read_ray_grid_plugin, sensor_what

SENSOR_PLUGINS = {"libgazebo_ros_range.so": ("ray", "gpu_ray")}
MAX_RAYS = 10_000
ULTRASOUND, INFRARED = 0, 1  # sensor_msgs/Range radiation types


@dataclass(frozen=True)
class RangeConfig(RayGridConfig):
    topic: str = "/range"
    frame: str = "/world"
    radiation: int = ULTRASOUND  # "ultrasound", anything else infrared
    field_of_view: float = 0.05
    gaussian_noise: float = 0.0
    plugin_rate: float = 0.0  # <updateRate>: at most this often (0: every scan)
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> RangeConfig:
    def tags(params: Dict[str, str], plugin_what: str) -> Dict[str, object]:
        return {
            **gazebo_ray_tags(params, plugin_what, "/range"),
            "radiation": ULTRASOUND if (params.get("radiation") or "ultrasound") == "ultrasound" else INFRARED,
            "field_of_view": read_number(params.get("fov"), f"{plugin_what} <fov>", 0.05),
            "plugin_rate": read_number(params.get("updateRate"), f"{plugin_what} <updateRate>", 0.0, 0.0),
        }

    config = read_ray_grid_plugin(RangeConfig, link, sensor, plugin, "range", MAX_RAYS, tags)
    if not math.isfinite(config.range_max):
        raise ModelError(f"{sensor_what(sensor, 'range')[1]}: <range><max> must be finite")
    return config


def nearest(ranges, range_max: float, noise: float, gauss) -> float:  # type: ignore[no-untyped-def]
    """PutRangeData: the smallest of the rays' ranges; below range max, plus gaussian noise, at most range max."""
    found = float(min(ranges.min(), range_max)) if ranges.size else range_max
    if found < range_max:
        found = min(found + (gauss(0.0, noise) if noise else 0.0), range_max)
    return found
