"""gazebo_ros_diff_drive (``libgazebo_ros_diff_drive.so``): its tags with gazebo_ros's names and defaults, and its
per-step work, velocity motors on two wheel joints and encoder odometry (world.diff_drive)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.diff_drive import DiffDriveController, DiffDriveParams, WheelOdometry
from turtle_sim_ode.world.plugins.tags import flag, number, text

DIFF_DRIVE = "libgazebo_ros_diff_drive.so"
MODEL_PLUGINS = (DIFF_DRIVE,)


@dataclass
class DriveConfig:
    """A differential drive plugin: its joints and geometry, and the names of its ROS interface."""

    filename: str
    left_joint: str
    right_joint: str
    params: DiffDriveParams
    command_topic: str
    reset_topic: str  # "" when the plugin has none
    odometry_topic: str
    odometry_frame: str  # "" = the node's odom_frame
    base_frame: str  # "" = the node's base_frame
    odometry_source: str  # "encoder" or "world"
    publish_tf: bool
    publish_joint_states: bool
    update_rate: float  # Hz of sim time; 0 = the node's publish_rate
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>

    @property
    def joints_needed(self) -> Tuple[str, ...]:
        return (self.left_joint, self.right_joint)

    def make_robot(self, model: BuiltModel) -> "DiffDriveRobot":
        return DiffDriveRobot(model, self)


class DiffDriveRobot:
    """A model's differential drive plugin: velocity motors on two wheel joints and encoder odometry."""

    def __init__(self, model: BuiltModel, config: DriveConfig) -> None:
        self.model = model
        self.config = config
        self.params = config.params
        self.left = model.joint(config.left_joint)
        self.right = model.joint(config.right_joint)
        self.drive = DiffDriveController(self.left.joint, self.right.joint, self.params)
        self.odometry = WheelOdometry.from_params(self.params)

    @property
    def wheels(self) -> Tuple[JointHandle, ...]:
        return (self.left, self.right)

    def update_odometry(self, now: float) -> None:
        """Read the encoders (call at the odometry rate, after a step)."""
        self.odometry.update(self.left.angle(), self.right.angle(), now)

    def reset_odometry(self, now: float) -> None:
        self.odometry.reset()
        self.update_odometry(now)

    def wheels_moved(self, now: float) -> None:
        """The wheels were set to new positions (set_model_configuration): the odometry keeps its pose."""
        self.odometry.reset(*self.odometry.pose)
        self.update_odometry(now)


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> DriveConfig:
    """gazebo_ros_diff_drive, with its parameter names and defaults (wheelAcceleration is in m/s^2 there). The
    node's ~diff_drive overrides are the TurtleBot's: a diff_drive plugin keeps its own tags."""
    diameter = number(plugin, "wheelDiameter", 0.15)
    fields: Dict[str, object] = {
        "wheel_separation": number(plugin, "wheelSeparation", 0.34),
        "wheel_radius": diameter / 2,
        "max_wheel_torque": number(plugin, "wheelTorque", 5.0),
        "max_wheel_acceleration": number(plugin, "wheelAcceleration", 0.0) / (diameter / 2) if diameter else 0.0,
        # gazebo_ros_diff_drive has no watchdog and no velocity limits.
        "cmd_timeout": 0.0,
        "max_linear": math.inf,
        "max_angular": math.inf,
    }
    params = DiffDriveParams(**fields)  # type: ignore[arg-type]
    try:
        params.validate()
    except ValueError as error:
        raise ModelError(f"{plugin.filename}: {error}") from None
    source = text(plugin, "odometrySource", "world").lower()
    if source in ("0", "encoder"):
        source = "encoder"
    elif source in ("1", "world"):
        source = "world"
    else:
        raise ModelError(f"{plugin.filename} <odometrySource> must be encoder or world, got '{source}'")
    return DriveConfig(
        filename=plugin.filename,
        left_joint=text(plugin, "leftJoint", "left_joint"),
        right_joint=text(plugin, "rightJoint", "right_joint"),
        params=params,
        command_topic=text(plugin, "commandTopic", "cmd_vel"),
        reset_topic="",
        odometry_topic=text(plugin, "odometryTopic", "odom"),
        odometry_frame=text(plugin, "odometryFrame", "odom"),
        base_frame=text(plugin, "robotBaseFrame", "base_footprint"),
        odometry_source=source,
        publish_tf=flag(plugin, "publishTf", flag(plugin, "publishOdomTF", True)),
        publish_joint_states=flag(plugin, "publishWheelJointState", False),
        update_rate=number(plugin, "updateRate", 100.0),
        robot_namespace=robot_namespace_tag(plugin.params),
    )
