"""gazebo_ros_planar_move (``libgazebo_ros_planar_move.so``, gazebo_plugins/src/gazebo_ros_planar_move.cpp): a
holonomic base. Its tags and defaults, and its per-step work (UpdateChild): every link of the model gets the commanded
x, y velocity turned by the model's yaw (z 0) and the commanded yaw rate, until ``cmdTimeout`` s without a command
(-1: never)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.transforms import rpy_of
from turtle_sim_ode.models.text import ModelError, read_number, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.diff_drive import DiffDriveParams
from turtle_sim_ode.world.plugins.tags import number, text

PLANAR_MOVE = "libgazebo_ros_planar_move.so"
MODEL_PLUGINS = (PLANAR_MOVE,)


@dataclass
class PlanarMoveConfig:
    filename: str
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    base_frame: str = "base_footprint"
    odometry_rate: float = 20.0  # Hz of sim time; 0 = no odometry
    cmd_timeout: float = -1.0  # s of sim time; negative = none
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>

    @property
    def publish_tf(self) -> bool:
        """publishOdometry sends odometryFrame -> robotBaseFrame on tf with every odometry message (the node opens
        /tf for it); none without odometry (odometryRate 0)."""
        return self.odometry_rate > 0.0

    def make_robot(self, model: BuiltModel) -> "PlanarMoveRobot":
        return PlanarMoveRobot(model, self)


class PlanarMotion:
    """The commanded body-frame (x, y, yaw rate), set on every link of the model before each step."""

    def __init__(self, model: BuiltModel, cmd_timeout: float) -> None:
        self._model = model
        self._timeout = cmd_timeout
        self.command: Tuple[float, float, float] = (0.0, 0.0, 0.0)
        self._command_time = -math.inf

    def set_command(self, x: float, y: float, rotation: float, now: float) -> bool:
        """False (and ignored) if not finite."""
        if not all(math.isfinite(v) for v in (x, y, rotation)):
            return False
        self.command, self._command_time = (x, y, rotation), now
        return True

    def update(self, now: float, dt: float) -> None:
        if self._timeout >= 0 and now - self._command_time > self._timeout:
            self.command = (0.0, 0.0, 0.0)
        x, y, rotation = self.command
        model = self._model
        _, orientation = model.link_transform(model.root_link)
        yaw = rpy_of(orientation)[2]
        cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
        linear = (x * cos_yaw - y * sin_yaw, y * cos_yaw + x * sin_yaw, 0.0)
        for body in model.bodies:
            body.setLinearVel(linear)
            body.setAngularVel((0.0, 0.0, rotation))

    def stop(self) -> None:
        self.command, self._command_time = (0.0, 0.0, 0.0), -math.inf


class PlanarMoveRobot:
    """A model moved by the planar move plugin: no wheels; its odometry is the physics state."""

    wheels: Tuple[JointHandle, ...] = ()

    def __init__(self, model: BuiltModel, config: PlanarMoveConfig) -> None:
        self.model = model
        self.config = config
        self.params = DiffDriveParams(max_linear=math.inf, max_angular=math.inf, cmd_timeout=0.0)
        self.drive = PlanarMotion(model, config.cmd_timeout)

    def reset_odometry(self, now: float) -> None:
        """Nothing to reset: the odometry is the physics state."""

    def wheels_moved(self, now: float) -> None:
        """No wheels."""


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> PlanarMoveConfig:
    timeout = read_number(plugin.params.get("cmdTimeout"), f"{plugin.filename} <cmdTimeout>", -1.0)
    if not math.isfinite(timeout):
        raise ModelError(f"{plugin.filename} <cmdTimeout> must be finite, got {timeout}")
    return PlanarMoveConfig(
        filename=plugin.filename,
        command_topic=text(plugin, "commandTopic", "cmd_vel"),
        odometry_topic=text(plugin, "odometryTopic", "odom"),
        odometry_frame=text(plugin, "odometryFrame", "odom"),
        base_frame=text(plugin, "robotBaseFrame", "base_footprint"),
        odometry_rate=number(plugin, "odometryRate", 20.0),
        cmd_timeout=timeout,
        robot_namespace=robot_namespace_tag(plugin.params),
    )
