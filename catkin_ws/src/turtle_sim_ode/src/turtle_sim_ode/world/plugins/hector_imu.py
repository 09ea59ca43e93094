"""hector_gazebo_plugins' IMU (``libhector_gazebo_ros_imu.so``, GazeboRosIMU of hector_gazebo_plugins/src/
gazebo_ros_imu.cpp): its tags and defaults, the sensor error model of sensor_model.h (offset, a first-order Gauss-
Markov drift with its frequency, white gaussian noise, scale error) for accelerations, rates and yaw, and its per-
update work (GazeboRosIMU::Update): proper acceleration from the change of the link's world velocity, rate from the
change of its orientation, and an orientation tilted by the accelerometer bias and turned by the yaw drift.

``xyzOffset`` is not read: GazeboRosIMU::Load reads it into offset_.Pos(), but Update never uses it (the line that
would add it to the position is commented out), so it changes nothing GazeboRosIMU publishes."""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from typing import Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Quat, quat_from_rpy, quat_multiply, quat_normalised, quat_rotate
from turtle_sim_ode.models.text import read_number, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.kinematics import conjugate
from turtle_sim_ode.world.plugins.hector_sensor_model import ErrorModel, SensorError, Vec3, error_model, vector_tag
from turtle_sim_ode.world.plugins.tags import text

HECTOR_IMU = "libhector_gazebo_ros_imu.so"
MODEL_PLUGINS = (HECTOR_IMU,)


@dataclass(frozen=True)
class HectorImuConfig:
    body: str  # "" = the model's canonical (root) link
    frame: str  # "" = the link's name
    topic: str = "imu"
    bias_topic: str = "imu/bias"  # "" = none
    service: str = "imu/calibrate"  # "" = none
    accel: ErrorModel = field(default_factory=ErrorModel)
    rate: ErrorModel = field(default_factory=ErrorModel)
    yaw: ErrorModel = field(default_factory=ErrorModel)
    rpy_offset: Vec3 = (0.0, 0.0, 0.0)
    update_rate: float = 0.0  # UpdateTimer: <updateRate>, or 1 / <updatePeriod>; 0 = every step
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> HectorImuConfig:
    topic = text(plugin, "topicName", "imu")
    accel, rate = error_model(plugin, "accel"), error_model(plugin, "rate")
    noise = read_number(plugin.params.get("gaussianNoise"), f"{plugin.filename} <gaussianNoise>", 0.0, 0.0)
    if noise:  # "also use old configuration variables from gazebo_ros_imu"
        accel = ErrorModel(accel.offset, accel.drift, accel.drift_frequency, (noise,) * 3, accel.scale_error)
        rate = ErrorModel(rate.offset, rate.drift, rate.drift_frequency, (noise,) * 3, rate.scale_error)
    period = read_number(plugin.params.get("updatePeriod"), f"{plugin.filename} <updatePeriod>", 0.0, 0.0)
    update_rate = read_number(plugin.params.get("updateRate"), f"{plugin.filename} <updateRate>", 0.0, 0.0)
    return HectorImuConfig(
        body=text(plugin, "bodyName", "").split("::")[-1],
        frame=text(plugin, "frameId", ""),
        topic=topic,
        bias_topic=text(plugin, "biasTopicName", topic + "/bias" if topic else ""),
        service=text(plugin, "serviceName", topic + "/calibrate"),
        accel=accel,
        rate=rate,
        yaw=error_model(plugin, "yaw"),
        rpy_offset=vector_tag(plugin, "rpyOffset", (0.0, 0.0, 0.0)),
        update_rate=1.0 / period if period > 0 else update_rate,
        robot_namespace=robot_namespace_tag(plugin.params),
    )


@dataclass(frozen=True)
class HectorImuReading:
    orientation: Quat  # (w, x, y, z), with the modelled errors
    angular_velocity: Vec3
    linear_acceleration: Vec3
    orientation_error: Quat  # (w, x, y, z): the bias topic's orientation
    rate_bias: Vec3
    accel_bias: Vec3


class HectorImu:
    """GazeboRosIMU's state on a model's link: ``update(now)`` at each of its updates."""

    def __init__(self, model: BuiltModel, link: str, config: HectorImuConfig, gravity: Vec3, rng=None) -> None:  # type: ignore[no-untyped-def]
        model.link_transform(link)  # KeyError now for a missing link
        self.model = model
        self.link = link
        self.config = config
        self.gravity = gravity
        rng = rng if rng is not None else random.Random()
        self.accel_error = SensorError(config.accel, rng)
        self.rate_error = SensorError(config.rate, rng)
        self.yaw_error = SensorError(config.yaw, rng)
        self._offset = quat_from_rpy(*config.rpy_offset)
        self.reset()

    def reset(self) -> None:
        """GazeboRosIMU::Reset."""
        self._last: Optional[float] = None
        self._orientation: Quat = (1.0, 0.0, 0.0, 0.0)
        self._velocity: Vec3 = (0.0, 0.0, 0.0)
        self._accel: Vec3 = (0.0, 0.0, 0.0)
        self._rate: Vec3 = (0.0, 0.0, 0.0)
        for error in (self.accel_error, self.rate_error, self.yaw_error):
            error.reset()

    def update(self, now: float) -> HectorImuReading:
        dt = now - self._last if self._last is not None else 0.0  # getTimeSinceLastUpdate: 0 at the first
        self._last = now
        _, pose_rotation = self.model.link_transform(self.link)
        rotation = quat_normalised(quat_multiply(self._offset, pose_rotation))
        velocity, _ = self.model.link_twist(self.link)
        if dt > 0.0:
            change = tuple((v - old) / dt - g for v, old, g in zip(velocity, self._velocity, self.gravity))
            self._accel = quat_rotate(conjugate(rotation), change)  # type: ignore[arg-type]
        self._velocity = tuple(velocity)  # type: ignore[assignment]
        delta = quat_multiply(conjugate(self._orientation), rotation)
        self._orientation = rotation
        if dt > 0.0:
            w = max(-1.0, min(1.0, delta[0]))
            axis_norm = math.sqrt(delta[1] ** 2 + delta[2] ** 2 + delta[3] ** 2)
            angle = 2.0 * math.acos(w)
            axis = tuple(c / axis_norm for c in delta[1:]) if axis_norm > 0 else (0.0, 0.0, 0.0)
            self._rate = quat_rotate(conjugate(self._offset), tuple(angle * c / dt for c in axis))  # type: ignore
        accel = self.accel_error.apply(self._accel, dt)
        rate = self.rate_error.apply(self._rate, dt)
        self.yaw_error.apply((0.0, 0.0, 0.0), dt)
        # A pseudo AHRS: the accelerometer bias tilts roll and pitch, the yaw drift turns yaw.
        g = math.sqrt(sum(c * c for c in self.gravity))
        accel_drift = quat_rotate(pose_rotation, self.accel_error.bias)
        yaw = self.yaw_error.bias[0]
        tilt = (1.0, 0.5 * accel_drift[1] / g, -0.5 * accel_drift[0] / g, 0.0) if g > 0 else (1.0, 0.0, 0.0, 0.0)
        error = quat_normalised(quat_multiply((math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)), tilt))
        return HectorImuReading(
            orientation=quat_multiply(error, rotation),
            angular_velocity=rate,
            linear_acceleration=accel,
            orientation_error=error,
            rate_bias=self.rate_error.bias,
            accel_bias=self.accel_error.bias,
        )

    def covariances(self) -> Tuple[Tuple[float, ...], Tuple[float, ...], Tuple[float, ...]]:
        """Orientation, angular velocity and linear acceleration covariances as Load and Update fill them: the
        orientation's from the accel and yaw noises of now (Update; dynamic_reconfigure may change them), the rate's
        and acceleration's from the tags (Load's constant matrices)."""
        accel, yaw = self.accel_error.model.gaussian_noise, self.yaw_error.model.gaussian_noise
        g2 = sum(c * c for c in self.gravity)
        tilt = (accel[0] ** 2 / g2, accel[1] ** 2 / g2) if g2 > 0 else (-1.0, -1.0)
        orientation = (tilt[0], 0.0, 0.0, 0.0, tilt[1], 0.0, 0.0, 0.0, yaw[0] ** 2)
        return orientation, _diagonal(self.config.rate.gaussian_noise), _diagonal(self.config.accel.gaussian_noise)


def _diagonal(stddevs: Vec3) -> Tuple[float, ...]:
    return (stddevs[0] ** 2, 0.0, 0.0, 0.0, stddevs[1] ** 2, 0.0, 0.0, 0.0, stddevs[2] ** 2)
