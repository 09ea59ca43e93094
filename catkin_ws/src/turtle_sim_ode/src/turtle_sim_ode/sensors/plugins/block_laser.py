"""gazebo_ros_block_laser (``libgazebo_ros_block_laser.so`` in a ``ray`` sensor, gazebo_plugins/src/
gazebo_ros_block_laser.cpp): a ray sensor's grid as sensor_msgs/PointCloud. The tags with GazeboRosBlockLaser::Load's
defaults, and PutLaserData's points; the rays are sensors.lidar's (one ray per sample: resolution 1)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Dict, List, Optional, Tuple
from xml.etree.ElementTree import Element

import numpy as np

from turtle_sim_ode.sensors.sensor_element import RayGridConfig, gazebo_ray_tags, read_ray_grid_plugin

SENSOR_PLUGINS = {"libgazebo_ros_block_laser.so": ("ray", "gpu_ray")}
MAX_RAYS = 100_000
EPSILON_DIFF = 0.000001  # gazebo_ros_block_laser.h: a range this close to the maximum gets no noise


@dataclass(frozen=True)
class BlockLaserConfig(RayGridConfig):
    topic: str = "/world"  # sic: Load's default
    frame: str = "/world"
    gaussian_noise: float = 0.0
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> BlockLaserConfig:
    def tags(params: Dict[str, str], plugin_what: str) -> Dict[str, object]:
        return gazebo_ray_tags(params, plugin_what, "/world")

    return read_ray_grid_plugin(BlockLaserConfig, link, sensor, plugin, "block_laser", MAX_RAYS, tags)


def _half_step_angles(count: int, low: float, high: float) -> np.ndarray:
    """PutLaserData's angle of sample i: the mean of rays i and min(i + 1, count - 1), as it aims its points."""
    if count == 1:
        return np.array([low])
    index = np.arange(count)
    return 0.5 * (index + np.minimum(index + 1, count - 1)) * (high - low) / (count - 1) + low


def block_points(
    ranges: np.ndarray, config: BlockLaserConfig, gauss: Callable[[float, float, Tuple[int, ...]], np.ndarray]
) -> Tuple[np.ndarray, np.ndarray]:
    """PutLaserData: (points (N, 3) row by row of the vertical samples, intensities (N,)) of one scan ``ranges``
    (vertical_samples x samples): -inf below range min and +inf beyond range max (REP 117); noise on the points not
    at the maximum and on every intensity (0: no retro-reflectors)."""
    r = np.array(ranges, dtype=float)
    with np.errstate(invalid="ignore"):
        r[r < config.range_min] = -np.inf
        r[r > config.range_max] = np.inf
    yaw = _half_step_angles(config.samples, config.min_angle, config.max_angle)[None, :]
    pitch = _half_step_angles(config.vertical_samples, config.vertical_min_angle, config.vertical_max_angle)[:, None]
    with np.errstate(invalid="ignore"):
        points = np.stack((r * np.cos(pitch) * np.cos(yaw), r * np.cos(pitch) * np.sin(yaw), r * np.sin(pitch)), -1)
    points = points.reshape(-1, 3)
    intensities = np.zeros(len(points))
    if config.gaussian_noise:
        noisy = (np.abs(config.range_max - r) > EPSILON_DIFF).reshape(-1)
        points[noisy] += gauss(0.0, config.gaussian_noise, (int(noisy.sum()), 3))
        intensities += gauss(0.0, config.gaussian_noise, intensities.shape)
    return points, intensities
