"""The private parameters of ekf_localization_node as RosFilter::loadParams (ros_filter.cpp) reads them, without
ROS: defaults, the sensors odomN/poseN/twistN/imuN (counted from 0 until the first gap), their update vectors split
into pose, twist and acceleration parts. Values upstream cannot use raise ConfigError naming the parameter."""
from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from robot_localization.ekf import ACCELERATION_SLICE, DEFAULT_PROCESS_NOISE, POSE_SLICE, STATE_SIZE, TWIST_SLICE

SENSOR_KINDS = ("odom", "pose", "twist", "imu")
UNSUPPORTED = {  # upstream features this drop-in leaves out: a warning, the node still runs
    "use_control": "the control term (cmd_vel) is not used",
    "smooth_lagged_data": "old measurements are not replayed",
}


class ConfigError(ValueError):
    """A parameter with a value the filter cannot use; the message names it and the value."""


class Sensor:
    """One input: kind (odom, pose, twist, imu), name (odom0), topic and the update vectors of its parts."""

    def __init__(self, kind: str, name: str, params: Mapping[str, Any]) -> None:
        self.kind, self.name = kind, name
        self.topic = read_string(params, name, "")
        self.differential = read_bool(params, name + "_differential", False)
        self.relative = read_bool(params, name + "_relative", False)
        self.relative_overridden = self.relative and self.differential  # upstream: differential wins, warns
        if self.relative_overridden:
            self.relative = False
        self.pose_use_child_frame = read_bool(params, name + "_pose_use_child_frame", False)
        self.queue_size = read_int(params, name + "_queue_size", 1, minimum=1)
        self.nodelay = read_bool(params, name + "_nodelay", False)
        self.remove_gravitational_acceleration = read_bool(params, name + "_remove_gravitational_acceleration", False)
        update = read_update_vector(params, name + "_config")
        threshold = {
            "odom": (name + "_pose_rejection_threshold", name + "_twist_rejection_threshold", None),
            "pose": (name + "_rejection_threshold", None, None),
            "twist": (None, name + "_rejection_threshold", None),
            "imu": (
                name + "_pose_rejection_threshold",
                name + "_twist_rejection_threshold",
                name + "_linear_acceleration_rejection_threshold",
            ),
        }[kind]
        self.thresholds = [read_float(params, key, math.inf, minimum=0.0) if key else math.inf for key in threshold]
        self.pose_update = only(update, POSE_SLICE) if kind in ("odom", "pose", "imu") else [False] * STATE_SIZE
        self.twist_update = only(update, TWIST_SLICE) if kind in ("odom", "twist", "imu") else [False] * STATE_SIZE
        self.acceleration_update = only(update, ACCELERATION_SLICE) if kind == "imu" else [False] * STATE_SIZE
        if kind == "imu":  # an Imu has orientation, angular velocity and acceleration only
            self.pose_update[0:3] = [False] * 3
            self.twist_update[6:9] = [False] * 3
        self.ignored_imu_entries = kind == "imu" and any(update[0:3] + update[6:9])

    @property
    def used(self) -> bool:
        return any(self.pose_update + self.twist_update + self.acceleration_update)


class Config:
    """All parameters, with upstream's defaults."""

    def __init__(self, params: Mapping[str, Any]) -> None:
        self.frequency = read_float(params, "frequency", 30.0, minimum=0.0, exclusive=True)
        self.sensor_timeout = read_float(params, "sensor_timeout", 1.0 / self.frequency, minimum=0.0)
        self.two_d_mode = read_bool(params, "two_d_mode", False)
        self.map_frame = read_string(params, "map_frame", "map")
        self.odom_frame = read_string(params, "odom_frame", "odom")
        self.base_link_frame = read_string(params, "base_link_frame", "base_link")
        self.base_link_frame_output = read_string(params, "base_link_frame_output", self.base_link_frame)
        self.world_frame = read_string(params, "world_frame", self.odom_frame)
        frames = (self.map_frame, self.odom_frame, self.base_link_frame)
        if len(set(frames)) < 3 or self.base_link_frame_output in (self.map_frame, self.odom_frame):
            raise ConfigError(
                "map_frame [%s], odom_frame [%s] and base_link_frame [%s] must differ, and base_link_frame_output "
                "[%s] must be neither map_frame nor odom_frame" % (frames + (self.base_link_frame_output,))
            )
        if self.world_frame not in (self.map_frame, self.odom_frame):
            raise ConfigError(
                "world_frame [%s] must be map_frame [%s] or odom_frame [%s]"
                % (self.world_frame, self.map_frame, self.odom_frame)
            )
        self.publish_tf = read_bool(params, "publish_tf", True)
        self.invert_tf = read_bool(params, "invert_tf", False)
        self.publish_acceleration = read_bool(params, "publish_acceleration", False)
        self.permit_corrected_publication = read_bool(params, "permit_corrected_publication", False)
        self.transform_time_offset = read_float(params, "transform_time_offset", 0.0)
        self.transform_timeout = read_float(params, "transform_timeout", 0.0, minimum=0.0)
        self.print_diagnostics = read_bool(params, "print_diagnostics", True)
        self.gravitational_acceleration = read_float(params, "gravitational_acceleration", 9.80665)
        self.predict_to_current_time = read_bool(params, "predict_to_current_time", False)
        self.dynamic_process_noise_covariance = read_bool(params, "dynamic_process_noise_covariance", False)
        self.disabled_at_startup = read_bool(params, "disabled_at_startup", False)
        self.reset_on_time_jump = read_bool(params, "reset_on_time_jump", False)
        self.initial_state = read_vector(params, "initial_state", STATE_SIZE)
        self.process_noise_covariance = read_matrix(params, "process_noise_covariance")
        if self.process_noise_covariance is None:
            self.process_noise_covariance = DEFAULT_PROCESS_NOISE.copy()
        self.initial_estimate_covariance = read_matrix(params, "initial_estimate_covariance")
        self.unsupported = [
            "%s is true, but %s in this drop-in" % (key, why)
            for key, why in UNSUPPORTED.items()
            if read_bool(params, key, False)
        ]
        self.sensors: List[Sensor] = []
        for kind in SENSOR_KINDS:
            index = 0
            while kind + str(index) in params:
                self.sensors.append(Sensor(kind, kind + str(index), params))
                index += 1

    def warnings(self) -> List[str]:
        """What upstream warns about at start-up (and what this drop-in leaves out)."""
        found = list(self.unsupported)
        for sensor in self.sensors:
            if sensor.relative_overridden:
                found.append(
                    "Both %s_differential and %s_relative were set to true. Using differential mode."
                    % (sensor.name, sensor.name)
                )
            if sensor.ignored_imu_entries:
                found.append(
                    "Some position or linear velocity entries in %s_config are true, but sensor_msgs/Imu has no "
                    "position or linear velocity" % sensor.name
                )
            if not sensor.used:
                found.append(
                    "%s [%s] is listed as an input topic, but all its update variables are false"
                    % (sensor.name, sensor.topic)
                )
        return found


def only(update: Sequence[bool], part: slice) -> List[bool]:
    kept = [False] * STATE_SIZE
    kept[part] = update[part]
    return kept


def bad(name: str, value: Any, expected: str) -> ConfigError:
    return ConfigError("parameter ~%s is [%r]: expected %s" % (name, value, expected))


def read_bool(params: Mapping[str, Any], name: str, default: bool) -> bool:
    value = params.get(name, default)
    if isinstance(value, bool):
        return value
    raise bad(name, value, "true or false")


def read_float(
    params: Mapping[str, Any], name: str, default: float, minimum: Optional[float] = None, exclusive: bool = False
) -> float:
    value = params.get(name, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value):
        raise bad(name, value, "a number")
    if minimum is not None and (value < minimum or (exclusive and value == minimum)):
        raise bad(name, value, "a number %s %g" % (">" if exclusive else ">=", minimum))
    return float(value)


def read_int(params: Mapping[str, Any], name: str, default: int, minimum: int) -> int:
    value = params.get(name, default)
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise bad(name, value, "an integer >= %d" % minimum)
    return value


def read_string(params: Mapping[str, Any], name: str, default: str) -> str:
    value = params.get(name, default)
    if not isinstance(value, str):
        raise bad(name, value, "a string")
    return value


def read_update_vector(params: Mapping[str, Any], name: str) -> List[bool]:
    """loadUpdateConfig: up to 15 booleans (x, y, z, roll, pitch, yaw, vx, vy, vz, vroll, vpitch, vyaw, ax, ay,
    az); missing entries are false. Upstream reads the parameter as a list of booleans and stops otherwise."""
    value = params.get(name, [False] * STATE_SIZE)
    if not isinstance(value, (list, tuple)) or len(value) > STATE_SIZE:
        raise bad(name, value, "a list of at most 15 booleans")
    if not all(isinstance(entry, bool) for entry in value):
        raise bad(name, value, "a list of booleans (true/false)")
    return list(value) + [False] * (STATE_SIZE - len(value))


def read_vector(params: Mapping[str, Any], name: str, size: int) -> Optional[np.ndarray]:
    if name not in params:
        return None
    value = params[name]
    if not isinstance(value, (list, tuple)) or len(value) != size or not all(is_number(v) for v in value):
        raise bad(name, value, "a list of %d numbers" % size)
    return np.array(value, dtype=float)


def read_matrix(params: Mapping[str, Any], name: str) -> Optional[np.ndarray]:
    """A 15x15 matrix given row by row as 225 numbers (process_noise_covariance, initial_estimate_covariance)."""
    vector = read_vector(params, name, STATE_SIZE * STATE_SIZE)
    return None if vector is None else vector.reshape(STATE_SIZE, STATE_SIZE)


def is_number(value: Any) -> bool:
    return not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)


def defaults() -> Dict[str, Any]:
    """The scalar parameters' defaults (documented in config/ekf_localization_node.yaml)."""
    config = Config({})
    return {
        key: getattr(config, key)
        for key in vars(config)
        if isinstance(getattr(config, key), (bool, float, str)) and key != "unsupported"
    }
