"""velodyne_simulator's plugins (``libgazebo_ros_velodyne_laser.so`` in a ``ray`` sensor,
``libgazebo_ros_velodyne_gpu_laser.so`` in a ``gpu_ray`` one; GazeboRosVelodyneLaser::Load of velodyne_gazebo_plugins
1.0.12, noetic): the sensor's horizontal and vertical scan, range and update rate, and the plugin's tags with their
defaults. The rays are sensors.lidar's; the cloud is built by ros.plugins.velodyne."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, child_text, plugin_params, read_number
from turtle_sim_ode.sensors.sensor_element import number_at, rate_at, sensor_pose

SENSOR_PLUGINS = {
    "libgazebo_ros_velodyne_laser.so": ("ray",),
    "libgazebo_ros_velodyne_gpu_laser.so": ("gpu_ray",),  # Load throws for a parent that is not a GpuRaySensor
}
# A point of the cloud (velodyne_gazebo_plugins 1.0.12): x, y, z, intensity float32, ring uint16, time float32.
POINT_STEP = 22
POINT = np.dtype(
    {
        "names": ["x", "y", "z", "intensity", "ring", "time"],
        "formats": ["<f4", "<f4", "<f4", "<f4", "<u2", "<f4"],
        "offsets": [0, 4, 8, 12, 16, 18],
        "itemsize": POINT_STEP,
    }
)
# At most this many rays a scan (a VLP-32C at 0.1 deg is 115,200; an HDL-64E at 0.08 deg 288,000).
MAX_RAYS = 300_000


@dataclass(frozen=True)
class VelodyneConfig:
    link: str
    name: str
    samples: int  # horizontal rays (rangeCount: <samples> x <resolution>)
    min_angle: float
    max_angle: float
    vertical_samples: int  # lasers (rings)
    vertical_min_angle: float
    vertical_max_angle: float
    range_min: float  # the sensor's <range>: where rays start and end
    range_max: float
    update_rate: float  # Hz of sim time; 0 = every step
    pose: Tuple[float, float, float, float, float, float]
    noise_mean: float  # the sensor's <noise> on every range
    noise_stddev: float
    topic: str = "/points"
    frame: str = "/world"
    min_range: float = 0.0  # the plugin's band: points with min_range < r < max_range only
    max_range: float = math.inf
    min_intensity: float = -math.inf
    gaussian_noise: float = 0.0
    organize_cloud: bool = False
    robot_namespace: str = "/"

    @property
    def rays(self) -> int:
        return self.samples * self.vertical_samples


def _count(element: Optional[Element], what: str) -> int:
    samples = int(number_at(element, "samples", 1, what))
    resolution = number_at(element, "resolution", 1.0, what)
    count = int(round(samples * resolution)) if resolution > 1 else samples  # Gazebo: resolution < 1 is samples
    if count < 1:
        raise ModelError(f"{what} <samples> x <resolution> must be at least 1, got {count}")
    return count


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> VelodyneConfig:
    name = sensor.get("name", "velodyne")
    what = f"<sensor name='{name}'>"
    ray = sensor.find("ray")
    horizontal = None if ray is None else ray.find("scan/horizontal")
    vertical = None if ray is None else ray.find("scan/vertical")
    noise = None if ray is None else ray.find("noise")
    gaussian = noise is not None and (child_text(noise, "type") or "gaussian").lower() == "gaussian"
    params = plugin_params(plugin)
    plugin_what = f"{what} <plugin filename='{plugin.get('filename')}'>"

    def tag(key: str, default: float, minimum: float = -math.inf) -> float:
        text = params.get(key)
        if text is not None and text.strip().lower() in ("inf", "infinity"):
            return math.inf
        return read_number(text, f"{plugin_what} <{key}>", default, minimum)

    organize = (params.get("organize_cloud") or "false").strip().lower()
    if organize not in ("true", "false", "1", "0"):
        raise ModelError(f"{plugin_what} <organize_cloud> must be true or false, got '{organize}'")
    config = VelodyneConfig(
        link=link,
        name=name,
        samples=_count(horizontal, what + " <horizontal>"),
        min_angle=number_at(horizontal, "min_angle", 0.0, what),
        max_angle=number_at(horizontal, "max_angle", 0.0, what),
        vertical_samples=_count(vertical, what + " <vertical>"),
        vertical_min_angle=number_at(vertical, "min_angle", 0.0, what),
        vertical_max_angle=number_at(vertical, "max_angle", 0.0, what),
        range_min=number_at(ray, "range/min", 0.0, what),
        range_max=number_at(ray, "range/max", 0.0, what),
        update_rate=rate_at(sensor, ("update_rate",), 0.0, what),
        pose=sensor_pose(sensor, what),
        noise_mean=number_at(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=number_at(noise, "stddev", 0.0, what) if gaussian else 0.0,
        topic=(params.get("topicName") or "/points").strip(),
        frame=(params.get("frameName") or "/world").strip(),
        min_range=tag("min_range", 0.0),
        max_range=tag("max_range", math.inf),
        min_intensity=tag("min_intensity", -math.inf),
        gaussian_noise=tag("gaussianNoise", 0.0, minimum=0.0),
        organize_cloud=organize in ("true", "1"),
        robot_namespace=(params.get("robotNamespace") or "/").strip(),
    )
    if not 0 <= config.range_min < config.range_max:
        raise ModelError(f"{what}: need 0 <= <range><min> < <max>, got {config.range_min}, {config.range_max}")
    if config.max_angle < config.min_angle or config.vertical_max_angle < config.vertical_min_angle:
        raise ModelError(f"{what}: a <max_angle> is below its <min_angle>")
    if config.rays > MAX_RAYS:
        raise ModelError(f"{what}: {config.rays} rays a scan, more than {MAX_RAYS}")
    if config.noise_stddev < 0:
        raise ModelError(f"{what} <noise><stddev> must be >= 0, got {config.noise_stddev}")
    return config


class VelodyneCloud:
    """GazeboRosVelodyneLaser::OnScan's cloud of one scan: ``points(ranges)`` (rings x azimuths, as the sensor
    reads them) -> (points as POINT records, height, width, is_dense)."""

    def __init__(self, config: VelodyneConfig, directions: np.ndarray, rng: np.random.Generator) -> None:
        """``directions``: the rays' unit vectors in the sensor frame, (rings, azimuths, 3)."""
        self._config = config
        self._rng = rng
        self._low = max(config.min_range, config.range_min)
        self._high = min(config.max_range, config.range_max)
        self._directions = np.ascontiguousarray(np.transpose(directions, (1, 0, 2)))  # (azimuths, rings, 3)
        self._rings = np.broadcast_to(np.arange(config.vertical_samples, dtype=np.uint16), self._directions.shape[:2])

    def points(self, ranges: np.ndarray) -> Tuple[np.ndarray, int, int, bool]:
        config = self._config
        measured = ranges.T  # (azimuths, rings): OnScan's loop order
        noisy = measured
        if config.gaussian_noise:
            noisy = measured + self._rng.normal(0.0, config.gaussian_noise, measured.shape)
        in_band = (noisy > self._low) & (noisy < self._high)
        intensity = 0.0  # Gazebo's laser_retro default; no retro-reflectors are simulated
        if not config.organize_cloud:
            in_band &= (measured > self._low) & (measured < self._high) & (intensity >= config.min_intensity)
            cloud = np.zeros(int(in_band.sum()), dtype=POINT)
            xyz = noisy[in_band][:, None] * self._directions[in_band]
            cloud["x"], cloud["y"], cloud["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
            cloud["ring"] = self._rings[in_band]
            return cloud, 1, len(cloud), True
        cloud = np.zeros(measured.shape, dtype=POINT)
        xyz = np.where(in_band[..., None], noisy[..., None] * self._directions, np.nan)
        cloud["x"], cloud["y"], cloud["z"] = xyz[..., 0], xyz[..., 1], xyz[..., 2]
        cloud["intensity"] = np.where(in_band, intensity, np.nan)
        cloud["ring"] = self._rings
        return cloud, measured.shape[0], measured.shape[1], False
