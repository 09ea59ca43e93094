"""The model plugins this simulator knows, by library file name, as gazebo_plugins keeps them: one module per plugin
(or family) that reads its tags (gazebo_ros's names and defaults) and holds its per-step work without ROS. A module
offers ``MODEL_PLUGINS`` (its file names) and ``read(model_name, plugin, overrides)``; the ROS side of each config is
a module of ros.plugins; sensor plugins are in sensors.plugins. Adding a plugin is a module and a line in
``MODULES``."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Dict, List, Mapping, Optional, Protocol, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.sensors.config import SensorBlocks
from turtle_sim_ode.world.diff_drive import DiffDriveParams
from turtle_sim_ode.world.plugins import (
    diff_drive,
    elevator,
    f3d,
    force,
    ft_sensor,
    hector_gps,
    hector_imu,
    imu,
    joint_state_publisher,
    kobuki,
    odometry_source,
    p3d,
    planar_move,
    ros_control,
    skid_steer_drive,
    vacuum_gripper,
    tricycle_drive,
)
from turtle_sim_ode.world.plugins.diff_drive import DIFF_DRIVE, DiffDriveRobot, DriveConfig
from turtle_sim_ode.world.plugins.imu import IMU
from turtle_sim_ode.world.plugins.joint_state_publisher import JOINT_STATE_PUBLISHER, JointStatesConfig
from turtle_sim_ode.world.plugins.kobuki import KOBUKI
from turtle_sim_ode.world.plugins.p3d import P3D, GroundTruthConfig, find_body

__all__ = ["DIFF_DRIVE", "IMU", "JOINT_STATE_PUBLISHER", "KOBUKI", "P3D", "DRIVES", "MODEL_PLUGINS"]
__all__ += ["DiffDriveRobot", "DriveRobot", "DriveConfig", "GroundTruthConfig", "JointStatesConfig", "ModelPlugins"]
__all__ += ["find_body", "read_plugins", "unsupported_warning"]

MODULES = (
    kobuki,
    diff_drive,
    skid_steer_drive,
    planar_move,
    tricycle_drive,
    p3d,
    odometry_source,
    joint_state_publisher,
    imu,
    hector_imu,
    hector_gps,
    force,
    f3d,
    ft_sensor,
    vacuum_gripper,
    ros_control,
    elevator,
)
MODEL_PLUGINS: Dict[str, Callable[[str, GazeboPlugin, Mapping[str, object]], object]] = {
    name: module.read for module in MODULES for name in module.MODEL_PLUGINS
}
DRIVES = (KOBUKI, DIFF_DRIVE)
# The warning about unsupported plugins names at most this many file names (each cut to SHOWN_FILENAME_CHARS).
SHOWN_FILENAMES = 10
SHOWN_FILENAME_CHARS = 80


class Motors(Protocol):
    def update(self, now: float, dt: float) -> None:
        """Set the motors (or velocities) for the next step of ``dt`` s."""

    def stop(self) -> None:
        """Forget the command (a world reset)."""


class DriveRobot(Protocol):
    """What a drive plugin's ``make_robot`` gives: motors the simulation sets before each step (``drive``), the wheel
    joints they turn (none for a planar move), and the limits velocity commands are clamped to (``params``)."""

    model: BuiltModel
    config: object
    params: DiffDriveParams
    drive: Motors
    wheels: Tuple[JointHandle, ...]

    def reset_odometry(self, now: float) -> None:
        ...

    def wheels_moved(self, now: float) -> None:
        ...


@dataclass
class ModelPlugins(SensorBlocks):
    """The configs of a model's plugins, model plugins first, then those of its sensors (``configs``)."""

    @property
    def drives(self) -> List:
        """The drive plugins' configs: those that make a robot (``make_robot(model)``) the simulation steps."""
        return [config for config in self.configs if hasattr(config, "make_robot")]

    @property
    def ground_truths(self) -> List[GroundTruthConfig]:
        return self.of_type(GroundTruthConfig)

    @property
    def joint_states(self) -> List[JointStatesConfig]:
        return self.of_type(JointStatesConfig)


def read_plugins(
    model_name: str,
    plugins: List[GazeboPlugin],
    overrides: Mapping[str, object],
    joint_names: List[str],
    sensors: Optional[SensorBlocks] = None,
) -> ModelPlugins:
    """Configs of the known plugins of one model (then the configs of its ``sensors``); ModelError for a known plugin
    with bad values or joints the model does not have; one warning counting the unknown plugins by file name (those
    in ``sensors`` too)."""
    found = ModelPlugins()
    unsupported: Dict[str, int] = {}
    for plugin in plugins:
        read = MODEL_PLUGINS.get(plugin.filename)
        if read is None:
            unsupported[plugin.filename] = unsupported.get(plugin.filename, 0) + 1
        else:
            found.configs.append(read(model_name, plugin, overrides))
    if sensors is not None:
        found.configs += sensors.configs
        for name, count in sensors.unsupported.items():
            unsupported[name] = unsupported.get(name, 0) + count
    if unsupported:
        found.warnings.append(unsupported_warning(unsupported))
    wanted = [joint for config in found.configs for joint in getattr(config, "joints_needed", ())]
    missing = sorted(set(wanted) - set(joint_names))
    if missing:
        raise ModelError(f"model '{model_name}' has no movable joint(s) {missing} named by its plugins")
    return found


def unsupported_warning(counts: Mapping[str, int]) -> str:
    """One warning for every unsupported plugin: how many, of which file names (a bounded list)."""
    names = [
        (name if len(name) <= SHOWN_FILENAME_CHARS else f"{name[:SHOWN_FILENAME_CHARS]}... ({len(name)} characters)")
        + (f" x{count}" if count > 1 else "")
        for name, count in list(counts.items())[:SHOWN_FILENAMES]
    ]
    more = f" and {len(counts) - SHOWN_FILENAMES} other file names" if len(counts) > SHOWN_FILENAMES else ""
    total = sum(counts.values())
    return f"{total} plugin(s) not supported, ignored: {', '.join(names)}{more}"
