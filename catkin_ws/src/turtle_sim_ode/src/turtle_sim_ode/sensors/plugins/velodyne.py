"""velodyne_simulator's plugins (``libgazebo_ros_velodyne_laser.so`` in a ``ray`` sensor,
``libgazebo_ros_velodyne_gpu_laser.so`` in a ``gpu_ray`` one; GazeboRosVelodyneLaser::Load of velodyne_gazebo_plugins
1.0.12, noetic): the sensor's horizontal and vertical scan, range and update rate, and the plugin's tags with their
defaults; the cloud of a scan as OnScan builds it (VelodyneCloud), made on the lidar's thread (VelodyneScans). The
rays are sensors.lidar's; the message is ros.plugins.velodyne's."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, read_number, robot_namespace_tag
from turtle_sim_ode.sensors.lidar import MultiBeamLidar
from turtle_sim_ode.sensors.ray_kernel import library as ray_kernel_library
from turtle_sim_ode.sensors.ray_kernel import velodyne_cloud
from turtle_sim_ode.sensors.scan_thread import ScanThread
from turtle_sim_ode.sensors.sensor_element import RayGridConfig, read_ray_grid_plugin

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
INTENSITY = 0.0  # of every point: Gazebo's laser_retro default; no retro-reflectors are simulated
# At most this many rays a scan (a VLP-32C at 0.1 deg is 115,200; an HDL-64E at 0.08 deg 288,000).
MAX_RAYS = 300_000


@dataclass(frozen=True)
class VelodyneConfig(RayGridConfig):
    topic: str = "/points"
    frame: str = "/world"
    min_range: float = 0.0  # the plugin's band: points with min_range < r < max_range only
    max_range: float = math.inf
    min_intensity: float = -math.inf
    gaussian_noise: float = 0.0
    organize_cloud: bool = False
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>, the spawn's


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> VelodyneConfig:
    def tags(params: Dict[str, str], plugin_what: str) -> Dict[str, object]:
        def number(key: str, default: float, minimum: float = -math.inf) -> float:
            text = params.get(key)
            if text is not None and text.strip().lower() in ("inf", "infinity"):
                return math.inf
            return read_number(text, f"{plugin_what} <{key}>", default, minimum)

        organize = (params.get("organize_cloud") or "false").strip().lower()
        if organize not in ("true", "false", "1", "0"):
            raise ModelError(f"{plugin_what} <organize_cloud> must be true or false, got '{organize}'")
        return {
            "topic": (params.get("topicName") or "/points").strip(),
            "frame": (params.get("frameName") or "/world").strip(),
            "min_range": number("min_range", 0.0),
            "max_range": number("max_range", math.inf),
            "min_intensity": number("min_intensity", -math.inf),
            "gaussian_noise": number("gaussianNoise", 0.0, minimum=0.0),
            "organize_cloud": organize in ("true", "1"),
            "robot_namespace": robot_namespace_tag(params),
        }

    return read_ray_grid_plugin(VelodyneConfig, link, sensor, plugin, "velodyne", MAX_RAYS, tags)


class VelodyneCloud:
    """GazeboRosVelodyneLaser::OnScan's cloud of one scan: ``points(ranges)`` (rings x azimuths, as the sensor
    reads them) -> (points as POINT records, height, width, is_dense). In C (tso_velodyne_cloud: one call that lets
    go of the GIL, where numpy's dozen calls would take it back a dozen times from a thread stepping beside it), or
    where the ray library is not built or ``kernel`` is False, in numpy: the same bytes."""

    def __init__(
        self, config: VelodyneConfig, directions: np.ndarray, rng: np.random.Generator, kernel: bool = True
    ) -> None:
        """``directions``: the rays' unit vectors in the sensor frame, (rings, azimuths, 3)."""
        self._config = config
        self._rng = rng
        self._lib = ray_kernel_library() if kernel else None
        self._low = max(config.min_range, config.range_min)
        self._high = min(config.max_range, config.range_max)
        self._directions = np.ascontiguousarray(np.transpose(directions, (1, 0, 2)))  # (azimuths, rings, 3)
        # Each axis apart, contiguous, in OnScan's order: picking from these is a tenth of the cost of picking rows.
        self._axes = [np.ascontiguousarray(self._directions[..., axis]).ravel() for axis in range(3)]
        self._rings = np.broadcast_to(np.arange(config.vertical_samples, dtype=np.uint16), self._directions.shape[:2])
        self._ray_rings = np.ascontiguousarray(self._rings).ravel()
        # Scratch of a scan in OnScan's order, reused scan after scan (a VLP-16's rays are 28,800).
        shape = self._directions.shape[:2]
        self._measured, self._noise, self._noisy = np.empty(shape), np.empty(shape), np.empty(shape)
        self._in_band, self._also = np.empty(shape, dtype=bool), np.empty(shape, dtype=bool)

    def _normals(self) -> Optional[np.ndarray]:
        """A standard normal for every ray in OnScan's order, None without gaussianNoise: times gaussianNoise, the
        numbers rng.normal(0, gaussianNoise) draws."""
        return self._rng.standard_normal(out=self._noise) if self._config.gaussian_noise else None

    def _noisy_in_band(self, ranges: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(measured, measured + gaussianNoise, the rays whose noisy range is within the band), in OnScan's order."""
        measured = self._measured
        np.copyto(measured, ranges.T)
        noisy = measured
        noise = self._normals()
        if noise is not None:
            noise *= self._config.gaussian_noise
            noisy = np.add(measured, noise, out=self._noisy)
        in_band = np.greater(noisy, self._low, out=self._in_band)
        in_band &= np.less(noisy, self._high, out=self._also)
        return measured, noisy, in_band

    def points(self, ranges: np.ndarray) -> Tuple[np.ndarray, int, int, bool]:
        config = self._config
        if self._lib is not None:
            azimuths, rings = self._directions.shape[:2]
            cloud = np.empty(azimuths * rings, dtype=POINT)
            band, kept = (self._low, self._high), INTENSITY >= config.min_intensity
            noise = (self._normals(), config.gaussian_noise)
            count = velodyne_cloud(self._lib, ranges, noise, band, config.organize_cloud, kept, self._directions, cloud)
            if config.organize_cloud:
                return cloud.reshape(azimuths, rings), azimuths, rings, False
            return cloud[:count], 1, count, True
        measured, noisy, in_band = self._noisy_in_band(ranges)
        if not config.organize_cloud:
            in_band &= np.greater(measured, self._low, out=self._also)
            in_band &= np.less(measured, self._high, out=self._also)
            picked = np.flatnonzero(in_band) if INTENSITY >= config.min_intensity else np.empty(0, dtype=np.intp)
            cloud = np.zeros(len(picked), dtype=POINT)
            distance = noisy.take(picked)
            for field, axis in zip("xyz", self._axes):
                cloud[field] = distance * axis.take(picked)
            cloud["ring"] = self._ray_rings.take(picked)
            return cloud, 1, len(cloud), True
        cloud = np.zeros(measured.shape, dtype=POINT)
        xyz = np.where(in_band[..., None], noisy[..., None] * self._directions, np.nan)
        cloud["x"], cloud["y"], cloud["z"] = xyz[..., 0], xyz[..., 1], xyz[..., 2]
        cloud["intensity"] = np.where(in_band, INTENSITY, np.nan)
        cloud["ring"] = self._rings
        return cloud, measured.shape[0], measured.shape[1], False


# Takes a scan's cloud on the lidar's thread: points, height, width, is_dense, and the stamp the scan was asked with.
CloudSink = Callable[[np.ndarray, int, int, bool, Any], None]


class VelodyneScans:
    """A lidar's clouds made on a thread of its own (sensors.scan_thread): ``scan(stamp)`` takes the geometry from
    the world now, on the stepping thread; the rays, the noise and the cloud follow on the lidar's thread, which
    hands the cloud with ``stamp`` to ``sink`` as soon as it is made. Number for number the cloud that
    ``VelodyneCloud(config, lidar.directions, rng).points(lidar.ranges())`` would give at that time."""

    def __init__(self, lidar: MultiBeamLidar, rng: np.random.Generator, sink: CloudSink) -> None:
        self.lidar = lidar
        self._cloud = VelodyneCloud(lidar.config, lidar.directions, rng, kernel=lidar.uses_ray_kernel)
        self._sink = sink
        self._thread = ScanThread("lidar %s" % lidar.config.name)

    def scan(self, stamp: Any) -> None:
        """Start a scan of the world as it is now (after the scan before it is done: waits only if it is not)."""
        geometry = self.lidar.geometry()
        self._thread.submit(lambda: self._sink(*self._cloud.points(self.lidar.cast(geometry)), stamp))

    def wait(self) -> None:
        """Return once the last scan is in the sink (ScanError if it failed)."""
        self._thread.wait()

    def close(self) -> None:
        """Wait for the last scan and end the thread."""
        self._thread.close()
