"""The IMU: orientation, body rates and proper acceleration of a link, with gaussian noise."""
from __future__ import annotations

import random
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Vec3, quat_from_rpy, quat_multiply, quat_rotate
from turtle_sim_ode.sensors.plugins.imu import ImuNoise


@dataclass(frozen=True)
class ImuReading:
    """sensor_msgs/Imu contents: quaternion (x, y, z, w), body-frame rates and proper acceleration."""

    stamp: float
    orientation: Tuple[float, float, float, float]
    angular_velocity: Vec3
    linear_acceleration: Vec3
    orientation_covariance: List[float] = field(default_factory=lambda: [0.0] * 9)
    angular_velocity_covariance: List[float] = field(default_factory=lambda: [0.0] * 9)
    linear_acceleration_covariance: List[float] = field(default_factory=lambda: [0.0] * 9)


def _diagonal(stddev: float) -> List[float]:
    variance = stddev * stddev
    return [variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance]


class ImuSensor:
    """An IMU on a model's link.

    ``read(now)`` gives the orientation in the world, the angular velocity in the link frame
    and the proper acceleration in the link frame: the change of the link origin's world
    velocity since the previous ``read`` divided by the time between them, minus gravity
    (at rest: +9.81 up). The first reading, or one at the same time as the previous, takes
    the acceleration of the previous reading (0 at first).
    """

    def __init__(
        self,
        model: BuiltModel,
        link: str,
        gravity: Vec3 = (0.0, 0.0, -9.81),
        noise: Optional[ImuNoise] = None,
        rng: Optional[random.Random] = None,
    ) -> None:
        model.link_transform(link)  # KeyError now for a missing link
        self.model = model
        self.link = link
        self.gravity = tuple(gravity)
        self.noise = noise if noise is not None else ImuNoise()
        self.rng = rng if rng is not None else random.Random()
        self._last: Optional[Tuple[float, Vec3]] = None
        self._acceleration: Vec3 = (0.0, 0.0, 0.0)
        self._covariances = (
            _diagonal(self.noise.orientation),
            _diagonal(self.noise.angular_velocity),
            _diagonal(self.noise.linear_acceleration),
        )
        # Without noise (the Kobuki's gyro) an exact reading is already this IMU's: zero covariances, nothing added.
        self._noiseless = self.noise == ImuNoise()

    def reset(self) -> None:
        """Forget the velocity history (after a teleport or world reset)."""
        self._last = None
        self._acceleration = (0.0, 0.0, 0.0)

    def _noisy(self, values: Vec3, stddev: float) -> Vec3:
        if stddev <= 0:
            return values
        gauss = self.rng.gauss
        return (values[0] + gauss(0.0, stddev), values[1] + gauss(0.0, stddev), values[2] + gauss(0.0, stddev))

    def read(self, now: float) -> ImuReading:
        """The IMU's reading at sim time ``now`` (call after steps, e.g. at the publish rate)."""
        return self.with_noise(self.exact(now))

    def exact(self, now: float) -> ImuReading:
        """``read`` without noise (covariances left out): what every IMU on the link reads, shared by ImuGroup."""
        _, (w, x, y, z) = self.model.link_transform(self.link)
        velocity, angular = self.model.link_twist(self.link)
        if self._last is not None and now > self._last[0]:
            dt = now - self._last[0]
            previous = self._last[1]
            self._acceleration = (
                (velocity[0] - previous[0]) / dt,
                (velocity[1] - previous[1]) / dt,
                (velocity[2] - previous[2]) / dt,
            )
        self._last = (now, tuple(velocity))  # type: ignore[assignment]
        to_link = (w, -x, -y, -z)
        g = self.gravity
        a = self._acceleration
        proper = quat_rotate(to_link, (a[0] - g[0], a[1] - g[1], a[2] - g[2]))
        return ImuReading(now, (x, y, z, w), quat_rotate(to_link, angular), proper)

    def with_noise(self, exact: ImuReading) -> ImuReading:
        """An exact reading with this IMU's noise and covariances."""
        if self._noiseless:
            return exact
        orientation = exact.orientation
        noise = self.noise
        if noise.orientation > 0:
            x, y, z, w = orientation
            roll, pitch, yaw = self._noisy((0.0, 0.0, 0.0), noise.orientation)
            nw, nx, ny, nz = quat_multiply((w, x, y, z), quat_from_rpy(roll, pitch, yaw))
            orientation = (nx, ny, nz, nw)
        return ImuReading(
            exact.stamp,
            orientation,
            self._noisy(exact.angular_velocity, noise.angular_velocity),
            self._noisy(exact.linear_acceleration, noise.linear_acceleration),
            list(self._covariances[0]),
            list(self._covariances[1]),
            list(self._covariances[2]),
        )
