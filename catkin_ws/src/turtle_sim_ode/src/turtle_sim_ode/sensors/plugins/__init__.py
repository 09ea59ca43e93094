"""The sensor plugins this simulator knows, by library file name, as gazebo_plugins keeps them: one module per plugin
(or family) that reads its tags into a config. A module offers ``SENSOR_PLUGINS`` (file name -> the ``<sensor>``
types it loads in, as the plugin's Load refuses other parents) and ``read(link, sensor, plugin, warnings)``; the ROS
side of each config is a module of ros.plugins. Adding a plugin is a module and a line in ``MODULES``."""
from __future__ import annotations

from typing import Callable, Dict, List, NamedTuple, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.sensors.plugins import (
    block_laser,
    bumper,
    camera,
    imu,
    laser,
    multicamera,
    range_finder,
    velodyne,
)

SIMULATED_TYPES = ("ray", "gpu_ray", "imu", "contact", "camera", "depth", "multicamera")
MODULES = (laser, velodyne, range_finder, block_laser, imu, bumper, camera, multicamera)


class SensorPlugin(NamedTuple):
    sensor_types: Tuple[str, ...]
    read: Callable[[str, Element, Element, List[str]], object]


SENSOR_PLUGINS: Dict[str, SensorPlugin] = {
    name: SensorPlugin(types, module.read) for module in MODULES for name, types in module.SENSOR_PLUGINS.items()
}
# A sensor with none of its type's known plugins: what is read of it (its checked config, which publishes nothing),
# or None after a warning.
WITHOUT_PLUGIN: Dict[str, Callable[[str, Element, List[str]], Optional[object]]] = {
    "ray": laser.without_plugin,
    "gpu_ray": laser.without_plugin,
    "camera": camera.without_plugin,
    "depth": camera.without_plugin,
}
