"""The simulator node's private parameters, checked without ROS: a bad value raises SettingsError naming it."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Tuple

from rosgraph.names import is_legal_base_name

from turtle_sim_ode.models.urdf import MAX_LENGTH
from turtle_sim_ode.physics.settings import MAX_GRAVITY, PhysicsParams
from turtle_sim_ode.ros.pacing import pacing_problem
from turtle_sim_ode.world.diff_drive import DiffDriveParams

# Parameters of physics.yaml, read into PhysicsParams (checked again by PhysicsParams.validate()).
PHYSICS_PARAMS = (
    "time_step",
    "solver",
    "solver_iterations",
    "gravity",
    "erp",
    "cfm",
    "max_contacts",
    "contact_max_correcting_vel",
    "contact_surface_layer",
)
# Overrides of the drive plugin's values, under ~diff_drive/ (names of DiffDriveParams).
DRIVE_OVERRIDES = (
    "max_wheel_torque",
    "max_wheel_acceleration",
    "max_linear",
    "max_angular",
    "cmd_timeout",
    "odometry_integration",
)

# ~spawn_<axis> and its range: a position within the world's extent (m), any angle (rad).
SPAWN_AXES = (
    ("x", MAX_LENGTH),
    ("y", MAX_LENGTH),
    ("z", MAX_LENGTH),
    ("roll", math.inf),
    ("pitch", math.inf),
    ("yaw", math.inf),
)
# ~write_batch_period's limit (wall s): longer would hold messages a subscriber would see as late.
MAX_WRITE_BATCH_PERIOD_S = 0.1


class SettingsError(ValueError):
    """A parameter is of the wrong type or out of range."""


@dataclass
class SimulatorSettings:
    real_time_factor: float = 1.0  # 0 = as fast as possible
    paused: bool = False
    pub_clock_frequency: float = 100.0  # Hz of sim time
    publish_rate: float = 50.0  # odom, tf, joint_states, ground truth: Hz of sim time
    model_states_rate: float = 50.0  # /gazebo/model_states and link_states (while subscribed): Hz of sim time
    write_batch_period: float = 0.001  # wall s a step-rate message may wait to go out with others (ros.wire)
    world_name: str = ""  # an SDF world file loaded at start-up
    odom_frame: str = "odom"
    base_frame: str = "base_footprint"
    publish_tf: bool = True
    # gazebo_ros's ~enable_ros_network: false offers none of the /gazebo services and topics (/clock and the
    # plugins' topics stay).
    enable_ros_network: bool = True
    # /gazebo/step_simulation (turtle_sim_ode_msgs/StepSimulation): not part of Gazebo's API, so off unless asked.
    step_simulation_service: bool = False
    ground_truth_topic: str = "ground_truth/odom"
    ground_truth_frame: str = "world"
    # A model spawned at start-up from a URDF parameter (none when spawn_model_name is empty).
    spawn_model_name: str = ""
    spawn_robot_description: str = "robot_description"
    spawn_pose: Tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    physics: PhysicsParams = field(default_factory=PhysicsParams)
    drive_overrides: Dict[str, Any] = field(default_factory=dict)


def number_param(
    params: Mapping[str, Any],
    name: str,
    default: float,
    minimum: float = -math.inf,
    exclusive: bool = False,
    maximum: float = math.inf,
) -> float:
    """Private parameter ``name`` from ``params`` (``default`` when absent): a finite number within the bounds, or
    SettingsError naming the parameter and its value."""
    value = params.get(name, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SettingsError(f"parameter ~{name} must be a finite number, got [{value!r}]")
    if value < minimum or (exclusive and value == minimum):
        raise SettingsError(f"parameter ~{name} must be {'>' if exclusive else '>='} {minimum}, got [{value!r}]")
    if value > maximum:
        raise SettingsError(f"parameter ~{name} must be <= {maximum:g}, got [{value!r}]")
    return float(value)


def typed_param(params: Mapping[str, Any], name: str, default: Any, kind: type) -> Any:
    """Private parameter ``name`` of type ``kind`` (``default`` when absent), or SettingsError naming it."""
    value = params.get(name, default)
    if not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
        raise SettingsError(f"parameter ~{name} must be of type {kind.__name__}, got [{value!r}]")
    return value


def _physics(params: Mapping[str, Any]) -> PhysicsParams:
    defaults = PhysicsParams()
    values: Dict[str, Any] = {}
    for name in PHYSICS_PARAMS:
        if name not in params:
            continue
        default = getattr(defaults, name)
        if name == "gravity":
            gravity = params[name]
            if not isinstance(gravity, (list, tuple)) or len(gravity) != 3:
                raise SettingsError(f"parameter ~gravity must be a list of 3 numbers, got [{gravity!r}]")
            values[name] = tuple(
                number_param({"gravity": g}, "gravity", 0.0, -MAX_GRAVITY, maximum=MAX_GRAVITY) for g in gravity
            )
        elif name == "solver":
            values[name] = typed_param(params, name, default, str)
        elif isinstance(default, int):
            values[name] = typed_param(params, name, default, int)
        else:
            values[name] = number_param(params, name, default)
    physics = PhysicsParams(**values)
    try:
        physics.validate()
    except ValueError as error:
        raise SettingsError(f"parameter ~{error}") from None
    return physics


def _drive_overrides(params: Mapping[str, Any]) -> Dict[str, Any]:
    overrides = params.get("diff_drive", {})
    if not isinstance(overrides, dict):
        raise SettingsError(f"parameter ~diff_drive must be a dictionary, got [{overrides!r}]")
    unknown = sorted(set(overrides) - set(DRIVE_OVERRIDES))
    if unknown:
        raise SettingsError(f"parameter ~diff_drive has unknown keys {unknown}; known: {list(DRIVE_OVERRIDES)}")
    checked: Dict[str, Any] = {}
    for name, value in overrides.items():
        key = "diff_drive/" + name
        if name == "odometry_integration":
            checked[name] = typed_param({key: value}, key, "midpoint", str)
        else:
            checked[name] = number_param({key: value}, key, 0.0, minimum=0.0)
    try:
        DiffDriveParams(**checked).validate()
    except ValueError as error:
        raise SettingsError(f"parameter ~diff_drive/{error}") from None
    return checked


def settings_from_params(params: Mapping[str, Any]) -> SimulatorSettings:
    """Build settings from the node's private parameter dictionary (rospy.get_param("~"))."""
    defaults = SimulatorSettings()
    settings = SimulatorSettings(
        real_time_factor=number_param(params, "real_time_factor", defaults.real_time_factor, minimum=0.0),
        paused=typed_param(params, "paused", defaults.paused, bool),
        pub_clock_frequency=number_param(params, "pub_clock_frequency", defaults.pub_clock_frequency, 0.0, True),
        publish_rate=number_param(params, "publish_rate", defaults.publish_rate, 0.0, True),
        model_states_rate=number_param(params, "model_states_rate", defaults.model_states_rate, 0.0, True),
        write_batch_period=number_param(
            params, "write_batch_period", defaults.write_batch_period, 0.0, maximum=MAX_WRITE_BATCH_PERIOD_S
        ),
        publish_tf=typed_param(params, "publish_tf", defaults.publish_tf, bool),
        enable_ros_network=typed_param(params, "enable_ros_network", defaults.enable_ros_network, bool),
        step_simulation_service=typed_param(params, "step_simulation_service", defaults.step_simulation_service, bool),
        spawn_pose=tuple(
            number_param(params, "spawn_" + axis, 0.0, -limit, maximum=limit) for axis, limit in SPAWN_AXES
        ),
        physics=_physics(params),
        drive_overrides=_drive_overrides(params),
    )
    for name in (
        "world_name",
        "odom_frame",
        "base_frame",
        "ground_truth_topic",
        "ground_truth_frame",
        "spawn_model_name",
        "spawn_robot_description",
    ):
        setattr(settings, name, typed_param(params, name, getattr(defaults, name), str))
    for name in ("odom_frame", "base_frame", "ground_truth_topic", "ground_truth_frame"):
        if not getattr(settings, name):
            raise SettingsError(f"parameter ~{name} must not be empty")
    time_step = settings.physics.time_step
    problem = pacing_problem(time_step, settings.real_time_factor / time_step, settings.pub_clock_frequency)
    if problem:
        raise SettingsError(
            f"parameters ~real_time_factor [{settings.real_time_factor!r}] and ~time_step [{time_step!r}]: {problem}"
        )
    if settings.spawn_model_name and not is_legal_base_name(settings.spawn_model_name):
        raise SettingsError(
            f"parameter ~spawn_model_name must be a legal ROS name (a letter, then letters, digits or '_'), "
            f"got [{settings.spawn_model_name!r}]"
        )
    return settings
