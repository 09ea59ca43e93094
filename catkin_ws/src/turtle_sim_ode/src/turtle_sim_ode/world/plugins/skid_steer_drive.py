"""gazebo_ros_skid_steer_drive (``libgazebo_ros_skid_steer_drive.so``): four wheels, the two of a side at one speed,
as gazebo_plugins/src/gazebo_ros_skid_steer_drive.cpp has it: its tags and defaults, and its per-step work, velocity
motors of ``torque`` on the four wheel joints (no watchdog, no limits: a command holds until the next). Its odometry
is the model's pose from the physics state (ros.plugins.skid_steer_drive)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.diff_drive import DiffDriveController, DiffDriveParams
from turtle_sim_ode.world.plugins.tags import flag, number, text

SKID_STEER_DRIVE = "libgazebo_ros_skid_steer_drive.so"
MODEL_PLUGINS = (SKID_STEER_DRIVE,)


@dataclass
class SkidSteerConfig:
    """The plugin's tags (GazeboRosSkidSteerDrive::Load's names and defaults)."""

    filename: str
    left_front_joint: str
    right_front_joint: str
    left_rear_joint: str
    right_rear_joint: str
    params: DiffDriveParams  # wheelSeparation, wheelDiameter / 2, torque; no timeout or limits
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    base_frame: str = "base_footprint"
    broadcast_tf: bool = False
    update_rate: float = 100.0  # Hz of sim time; 0 = every step
    covariance_x: float = 0.0001
    covariance_y: float = 0.0001
    covariance_yaw: float = 0.01
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>

    @property
    def joints_needed(self) -> Tuple[str, ...]:
        return (self.left_front_joint, self.right_front_joint, self.left_rear_joint, self.right_rear_joint)

    def make_robot(self, model: BuiltModel) -> "SkidSteerRobot":
        return SkidSteerRobot(model, self)


class _Side:
    """The two wheel joints of one side, commanded as one (what DiffDriveController sets on a wheel)."""

    def __init__(self, front: JointHandle, rear: JointHandle) -> None:
        self._joints = (front.joint, rear.joint)

    def setParam(self, param: int, value: float) -> None:  # noqa: N802 (PyODE's name)
        for joint in self._joints:
            joint.setParam(param, value)


class SkidSteerRobot:
    """A model's skid steer plugin: each side's two wheels at (v -/+ w separation / 2) / radius."""

    def __init__(self, model: BuiltModel, config: SkidSteerConfig) -> None:
        self.model = model
        self.config = config
        self.params = config.params
        handles = [model.joint(name) for name in config.joints_needed]
        self.wheels: Tuple[JointHandle, ...] = tuple(handles)
        left_front, right_front, left_rear, right_rear = handles
        self.drive = DiffDriveController(
            _Side(left_front, left_rear), _Side(right_front, right_rear), self.params  # type: ignore[arg-type]
        )

    def reset_odometry(self, now: float) -> None:
        """Nothing to reset: the plugin's odometry is the physics state."""

    def wheels_moved(self, now: float) -> None:
        """Nothing to do: the plugin's odometry is the physics state."""


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> SkidSteerConfig:
    diameter = number(plugin, "wheelDiameter", 0.15)
    params = DiffDriveParams(
        wheel_separation=number(plugin, "wheelSeparation", 0.4),
        wheel_radius=diameter / 2,
        max_wheel_torque=number(plugin, "torque", 5.0),
        cmd_timeout=0.0,
        max_linear=math.inf,
        max_angular=math.inf,
    )
    try:
        params.validate()
    except ValueError as error:
        raise ModelError(f"{plugin.filename}: {error}") from None
    return SkidSteerConfig(
        filename=plugin.filename,
        left_front_joint=text(plugin, "leftFrontJoint", "left_front_joint"),
        right_front_joint=text(plugin, "rightFrontJoint", "right_front_joint"),
        left_rear_joint=text(plugin, "leftRearJoint", "left_rear_joint"),
        right_rear_joint=text(plugin, "rightRearJoint", "right_rear_joint"),
        params=params,
        command_topic=text(plugin, "commandTopic", "cmd_vel"),
        odometry_topic=text(plugin, "odometryTopic", "odom"),
        odometry_frame=text(plugin, "odometryFrame", "odom"),
        base_frame=text(plugin, "robotBaseFrame", "base_footprint"),
        broadcast_tf=flag(plugin, "broadcastTF", False),
        update_rate=number(plugin, "updateRate", 100.0),
        covariance_x=number(plugin, "covariance_x", 0.0001),
        covariance_y=number(plugin, "covariance_y", 0.0001),
        covariance_yaw=number(plugin, "covariance_yaw", 0.01),
        robot_namespace=robot_namespace_tag(plugin.params),
    )
