"""Values of an SDF ``<sensor>`` element (URDF ``<gazebo><sensor>`` blocks are the same), with the one number reader
and a message naming the sensor and the tag."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Dict, NamedTuple, Optional, Sequence, Tuple, Type, TypeVar
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, child_text, plugin_params, read_number, robot_namespace_tag
from turtle_sim_ode.physics import sanity


def sensor_what(sensor: Element, default_name: str) -> Tuple[str, str]:
    """The sensor's name (``default_name`` where it has none) and the ``<sensor name='...'>`` its errors start with."""
    name = sensor.get("name", default_name)
    return name, f"<sensor name='{name}'>"


class SensorPlugin(NamedTuple):
    """What a sensor plugin's reader starts from (``sensor_plugin``)."""

    name: str  # the sensor's
    what: str  # "<sensor name='...'>": where the sensor's errors point
    params: Dict[str, str]  # the plugin's tags (models.text.plugin_params)
    plugin_what: str  # "<sensor name='...'> <plugin filename='...'>": where the plugin's tag errors point


def sensor_plugin(sensor: Element, plugin: Element, default_name: str) -> SensorPlugin:
    """The sensor's name and error prefix, with its plugin's tags and error prefix."""
    name, what = sensor_what(sensor, default_name)
    return SensorPlugin(name, what, plugin_params(plugin), f"{what} <plugin filename='{plugin.get('filename')}'>")


def number_at(element: Optional[Element], path: str, default: float, what: str) -> float:
    return read_number(child_text(element, path), f"{what} <{path}>", default)


def rate_at(element: Optional[Element], tags: Sequence[str], default: float, what: str) -> float:
    for tag in tags:
        if child_text(element, tag) is not None:
            value = number_at(element, tag, default, what)
            if value < 0:
                raise ModelError(f"{what} <{tag}> must be >= 0, got {value}")
            return value
    return default


def sensor_pose(sensor: Element, what: str) -> Tuple[float, float, float, float, float, float]:
    pose_text = child_text(sensor, "pose")
    if pose_text is None:
        return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    try:
        pose = tuple(float(v) for v in pose_text.split())
    except ValueError:
        pose = ()
    if len(pose) != 6 or not all(math.isfinite(v) for v in pose):
        raise ModelError(f"{what} <pose> must be 6 finite numbers, got '{pose_text}'")
    for value in pose:  # within the world's lengths, not subnormal (physics.sanity)
        sanity.number(value, f"{what} <pose>", -sanity.MAX_LENGTH, sanity.MAX_LENGTH, ModelError)
    return pose  # type: ignore[return-value]


def int_at(element: Optional[Element], path: str, default: int, what: str) -> int:
    text = child_text(element, path)
    try:
        value = default if text is None else int(text)
    except ValueError:
        raise ModelError(f"{what} <{path}> must be an integer, got '{text}'") from None
    if not 1 <= value <= 8192:
        raise ModelError(f"{what} <{path}> must be in 1..8192, got {value}")
    return value


@dataclass(frozen=True)
class RayGridConfig:
    """A ray sensor on ``link`` with its grid of rays (``ray_grid``'s fields): the base of the multi-beam plugins'
    configs, and what sensors.lidar casts."""

    link: str
    name: str
    samples: int  # horizontal rays
    min_angle: float
    max_angle: float
    vertical_samples: int
    vertical_min_angle: float
    vertical_max_angle: float
    range_min: float  # where rays start and end
    range_max: float
    update_rate: float  # Hz of sim time; 0 = every step
    pose: Tuple[float, float, float, float, float, float]
    noise_mean: float  # the sensor's <noise> on every range
    noise_stddev: float

    @property
    def rays(self) -> int:
        return self.samples * self.vertical_samples


def ray_count(element: Optional[Element], what: str) -> int:
    """A <horizontal> or <vertical> scan's rays: <samples> x <resolution> (Gazebo: a resolution below 1 counts 1)."""
    samples = int(number_at(element, "samples", 1, what))
    resolution = number_at(element, "resolution", 1.0, what)
    count = int(round(samples * resolution)) if resolution > 1 else samples
    if count < 1:
        raise ModelError(f"{what} <samples> x <resolution> must be at least 1, got {count}")
    return count


def ray_grid(sensor: Element, what: str) -> Dict[str, object]:
    """A ray sensor's grid of rays as Gazebo's MultiRayShape reads it, the fields of a multi-beam config (see
    sensors.lidar): samples, min/max angle, vertical samples, min/max angle, range min/max, update rate, pose, and
    the <noise> gaussian mean and stddev on every range. ModelError for values no grid can have."""
    ray = sensor.find("ray")
    horizontal = None if ray is None else ray.find("scan/horizontal")
    vertical = None if ray is None else ray.find("scan/vertical")
    noise = None if ray is None else ray.find("noise")
    gaussian = noise is not None and (child_text(noise, "type") or "gaussian").lower() == "gaussian"
    grid: Dict[str, object] = {
        "samples": ray_count(horizontal, what + " <horizontal>"),
        "min_angle": number_at(horizontal, "min_angle", 0.0, what),
        "max_angle": number_at(horizontal, "max_angle", 0.0, what),
        "vertical_samples": ray_count(vertical, what + " <vertical>"),
        "vertical_min_angle": number_at(vertical, "min_angle", 0.0, what),
        "vertical_max_angle": number_at(vertical, "max_angle", 0.0, what),
        "range_min": number_at(ray, "range/min", 0.0, what),
        "range_max": number_at(ray, "range/max", 0.0, what),
        "update_rate": rate_at(sensor, ("update_rate",), 0.0, what),
        "pose": sensor_pose(sensor, what),
        "noise_mean": number_at(noise, "mean", 0.0, what) if gaussian else 0.0,
        "noise_stddev": number_at(noise, "stddev", 0.0, what) if gaussian else 0.0,
    }
    if not 0 <= grid["range_min"] < grid["range_max"]:  # type: ignore[operator]
        raise ModelError(f"{what}: need 0 <= <range><min> < <max>, got {grid['range_min']}, {grid['range_max']}")
    if grid["max_angle"] < grid["min_angle"] or grid["vertical_max_angle"] < grid["vertical_min_angle"]:  # type: ignore
        raise ModelError(f"{what}: a <max_angle> is below its <min_angle>")
    if grid["noise_stddev"] < 0:  # type: ignore[operator]
        raise ModelError(f"{what} <noise><stddev> must be >= 0, got {grid['noise_stddev']}")
    return grid


GridConfig = TypeVar("GridConfig", bound=RayGridConfig)


def read_ray_grid_plugin(
    config_type: Type[GridConfig],
    link: str,
    sensor: Element,
    plugin: Element,
    default_name: str,
    max_rays: int,
    read_tags: Callable[[Dict[str, str], str], Dict[str, object]],
) -> GridConfig:
    """What the multi-beam plugins' readers share: the sensor's grid (``ray_grid``) and the plugin's tags
    (``read_tags(params, plugin_what)``: the config's remaining fields) as a ``config_type``; ModelError beyond
    ``max_rays`` rays a scan."""
    name, what, params, plugin_what = sensor_plugin(sensor, plugin, default_name)
    grid = ray_grid(sensor, what)
    config = config_type(link=link, name=name, **grid, **read_tags(params, plugin_what))  # type: ignore[arg-type]
    if config.rays > max_rays:
        raise ModelError(f"{what}: {config.rays} rays a scan, more than {max_rays}")
    return config


def gazebo_ray_tags(params: Dict[str, str], plugin_what: str, topic: str) -> Dict[str, object]:
    """The tags gazebo_plugins' block laser and range plugins read alike (their Load): topicName (``topic`` where not
    given), frameName (/world), gaussianNoise (0, >= 0) and robotNamespace."""
    return {
        "topic": params.get("topicName") or topic,
        "frame": params.get("frameName") or "/world",
        "gaussian_noise": read_number(params.get("gaussianNoise"), f"{plugin_what} <gaussianNoise>", 0.0, 0.0),
        "robot_namespace": robot_namespace_tag(params),
    }
