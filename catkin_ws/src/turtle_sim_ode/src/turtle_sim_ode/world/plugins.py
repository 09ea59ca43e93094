"""ROS-free reading of the gazebo_ros plugin tags this simulator implements: what each plugin drives or
publishes, with gazebo_ros's parameter names and defaults."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Mapping, Optional, Tuple

from turtle_sim_ode.models.text import ModelError, read_number
from turtle_sim_ode.models.urdf import GazeboPlugin
from turtle_sim_ode.sensors.config import CameraConfig, ContactConfig, ImuConfig, LaserConfig, imu_config
from turtle_sim_ode.sensors.kobuki import KOBUKI_CLIFF_THRESHOLD
from turtle_sim_ode.world.diff_drive import DiffDriveParams

KOBUKI = "libgazebo_ros_kobuki.so"
DIFF_DRIVE = "libgazebo_ros_diff_drive.so"
P3D = "libgazebo_ros_p3d.so"
JOINT_STATE_PUBLISHER = "libgazebo_ros_joint_state_publisher.so"
IMU = "libgazebo_ros_imu.so"
DRIVES = (KOBUKI, DIFF_DRIVE)
SUPPORTED = (KOBUKI, DIFF_DRIVE, P3D, JOINT_STATE_PUBLISHER, IMU)
# The warning about unsupported plugins names at most this many file names (each cut to SHOWN_FILENAME_CHARS).
SHOWN_FILENAMES = 10
SHOWN_FILENAME_CHARS = 80


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
    robot_namespace: str = ""
    cliff_threshold: float = KOBUKI_CLIFF_THRESHOLD  # the Kobuki's cliff sensors (m to the floor)


@dataclass
class GroundTruthConfig:
    """libgazebo_ros_p3d.so: a body's pose and velocity from the physics state, as nav_msgs/Odometry."""

    body: str
    topic: str
    frame: str
    update_rate: float
    gaussian_noise: float
    xyz_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    robot_namespace: str = ""


@dataclass
class JointStatesConfig:
    """libgazebo_ros_joint_state_publisher.so: positions and velocities of the named joints."""

    joints: List[str]
    update_rate: float
    robot_namespace: str = ""


@dataclass
class ModelPlugins:
    drives: List[DriveConfig] = field(default_factory=list)
    ground_truths: List[GroundTruthConfig] = field(default_factory=list)
    joint_states: List[JointStatesConfig] = field(default_factory=list)
    lasers: List[LaserConfig] = field(default_factory=list)  # <sensor type="ray"> blocks of a URDF
    imus: List[ImuConfig] = field(default_factory=list)  # IMU plugins, of the model or in <sensor type="imu">
    contacts: List[ContactConfig] = field(default_factory=list)  # <sensor type="contact"> + bumper plugin
    cameras: List[CameraConfig] = field(default_factory=list)  # <sensor type="camera"/"depth"> + ROS plugin
    warnings: List[str] = field(default_factory=list)


def _number(plugin: GazeboPlugin, tag: str, default: float, minimum: float = 0.0) -> float:
    return read_number(plugin.params.get(tag), f"{plugin.filename} <{tag}>", default, minimum)


def _flag(plugin: GazeboPlugin, tag: str, default: bool) -> bool:
    text = plugin.params.get(tag)
    if text is None:
        return default
    value = text.strip().lower()
    if value not in ("true", "false", "1", "0"):
        raise ModelError(f"{plugin.filename} <{tag}> must be true or false, got '{text}'")
    return value in ("true", "1")


def _text(plugin: GazeboPlugin, tag: str, default: str) -> str:
    text = plugin.params.get(tag)
    return text.strip() if text is not None and text.strip() else default


def _triple(plugin: GazeboPlugin, tag: str) -> Tuple[float, float, float]:
    text = plugin.params.get(tag, "0 0 0")
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise ModelError(f"{plugin.filename} <{tag}> must be 3 numbers, got '{text}'")
    return values  # type: ignore[return-value]


def kobuki_drive(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> DriveConfig:
    """kobuki_gazebo_plugins: topics under the model's name, as turtlebot_gazebo has them."""
    return DriveConfig(
        filename=plugin.filename,
        left_joint=_text(plugin, "left_wheel_joint_name", "wheel_left_joint"),
        right_joint=_text(plugin, "right_wheel_joint_name", "wheel_right_joint"),
        params=DiffDriveParams.from_kobuki_plugin(plugin.params, **overrides),
        command_topic=model_name + "/commands/velocity",
        reset_topic=model_name + "/commands/reset_odometry",
        odometry_topic="odom",
        odometry_frame="",
        base_frame="",
        odometry_source="encoder",
        publish_tf=_flag(plugin, "publish_tf", True),
        publish_joint_states=True,
        update_rate=0.0,
        robot_namespace=_text(plugin, "robotNamespace", ""),
        cliff_threshold=_number(plugin, "cliff_detection_threshold", KOBUKI_CLIFF_THRESHOLD, minimum=1e-6),
    )


def gazebo_ros_diff_drive(plugin: GazeboPlugin, overrides: Mapping[str, object]) -> DriveConfig:
    """gazebo_ros_diff_drive, with its parameter names and defaults (wheelAcceleration is in m/s^2 there)."""
    diameter = _number(plugin, "wheelDiameter", 0.15)
    fields: Dict[str, object] = {
        "wheel_separation": _number(plugin, "wheelSeparation", 0.34),
        "wheel_radius": diameter / 2,
        "max_wheel_torque": _number(plugin, "wheelTorque", 5.0),
        "max_wheel_acceleration": _number(plugin, "wheelAcceleration", 0.0) / (diameter / 2) if diameter else 0.0,
        # gazebo_ros_diff_drive has no watchdog and no velocity limits.
        "cmd_timeout": 0.0,
        "max_linear": math.inf,
        "max_angular": math.inf,
    }
    fields.update(overrides)
    params = DiffDriveParams(**fields)  # type: ignore[arg-type]
    try:
        params.validate()
    except ValueError as error:
        raise ModelError(f"{plugin.filename}: {error}") from None
    source = _text(plugin, "odometrySource", "world").lower()
    if source in ("0", "encoder"):
        source = "encoder"
    elif source in ("1", "world"):
        source = "world"
    else:
        raise ModelError(f"{plugin.filename} <odometrySource> must be encoder or world, got '{source}'")
    return DriveConfig(
        filename=plugin.filename,
        left_joint=_text(plugin, "leftJoint", "left_joint"),
        right_joint=_text(plugin, "rightJoint", "right_joint"),
        params=params,
        command_topic=_text(plugin, "commandTopic", "cmd_vel"),
        reset_topic="",
        odometry_topic=_text(plugin, "odometryTopic", "odom"),
        odometry_frame=_text(plugin, "odometryFrame", "odom"),
        base_frame=_text(plugin, "robotBaseFrame", "base_footprint"),
        odometry_source=source,
        publish_tf=_flag(plugin, "publishTf", _flag(plugin, "publishOdomTF", True)),
        publish_joint_states=_flag(plugin, "publishWheelJointState", False),
        update_rate=_number(plugin, "updateRate", 100.0),
        robot_namespace=_text(plugin, "robotNamespace", ""),
    )


def ground_truth(plugin: GazeboPlugin) -> GroundTruthConfig:
    body = _text(plugin, "bodyName", "")
    if not body:
        raise ModelError(f"{plugin.filename} needs <bodyName>")
    return GroundTruthConfig(
        body=body,
        topic=_text(plugin, "topicName", "ground_truth"),
        frame=_text(plugin, "frameName", "world"),
        update_rate=_number(plugin, "updateRate", 0.0),
        gaussian_noise=_number(plugin, "gaussianNoise", 0.0),
        xyz_offset=_triple(plugin, "xyzOffsets" if "xyzOffsets" in plugin.params else "xyzOffset"),
        rpy_offset=_triple(plugin, "rpyOffsets" if "rpyOffsets" in plugin.params else "rpyOffset"),
        robot_namespace=_text(plugin, "robotNamespace", ""),
    )


def joint_states(plugin: GazeboPlugin) -> JointStatesConfig:
    joints = [name.strip() for name in _text(plugin, "jointName", "").split(",") if name.strip()]
    if not joints:
        raise ModelError(f"{plugin.filename} needs <jointName> (comma-separated joint names)")
    return JointStatesConfig(
        joints=joints,
        update_rate=_number(plugin, "updateRate", 100.0),
        robot_namespace=_text(plugin, "robotNamespace", ""),
    )


def read_plugins(
    model_name: str, plugins: List[GazeboPlugin], overrides: Mapping[str, object], joint_names: List[str]
) -> ModelPlugins:
    """Configs of the supported plugins of one model; ModelError for a supported plugin with bad values or
    joints the model does not have, one warning counting the unsupported plugins by file name."""
    found = ModelPlugins()
    unsupported: Dict[str, int] = {}
    for plugin in plugins:
        if plugin.filename == KOBUKI:
            found.drives.append(kobuki_drive(model_name, plugin, overrides))
        elif plugin.filename == DIFF_DRIVE:
            # The node's ~diff_drive overrides are the TurtleBot's: a diff_drive plugin keeps its own tags.
            found.drives.append(gazebo_ros_diff_drive(plugin, {}))
        elif plugin.filename == P3D:
            found.ground_truths.append(ground_truth(plugin))
        elif plugin.filename == JOINT_STATE_PUBLISHER:
            found.joint_states.append(joint_states(plugin))
        elif plugin.filename == IMU:
            found.imus.append(imu_config(plugin.filename, plugin.params))
        else:
            unsupported[plugin.filename] = unsupported.get(plugin.filename, 0) + 1
    if unsupported:
        found.warnings.append(unsupported_warning(unsupported))
    wanted = [j for d in found.drives for j in (d.left_joint, d.right_joint)]
    wanted += [j for c in found.joint_states for j in c.joints]
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


def find_body(link_names: List[str], body: str) -> Optional[str]:
    """p3d's bodyName may be scoped ('model::link'): the link it names, if the model has it."""
    name = body.split("::")[-1]
    return name if name in link_names else None
