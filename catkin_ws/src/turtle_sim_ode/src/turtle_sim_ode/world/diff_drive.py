"""ROS-free differential drive: velocity commands to wheel motors, encoders to odometry."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Dict, Mapping, Tuple

from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity

if TYPE_CHECKING:  # only for annotations: odometry needs no ODE
    import ode

INTEGRATIONS = ("midpoint", "exact")


@dataclass
class DiffDriveParams:
    """Geometry and limits; 0 disables max_wheel_acceleration and cmd_timeout."""

    wheel_separation: float = 0.230
    wheel_radius: float = 0.035
    max_wheel_torque: float = 1.0
    max_wheel_acceleration: float = 0.0
    max_linear: float = 0.7
    max_angular: float = 3.14
    cmd_timeout: float = 0.6
    odometry_integration: str = "midpoint"

    def validate(self) -> None:
        """Raise ValueError naming the bad field and its value."""
        for name in ("wheel_separation", "wheel_radius", "max_wheel_torque", "max_linear", "max_angular"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or math.isnan(value) or value <= 0:
                raise ValueError(f"{name} must be > 0, got {value!r}")
        # Finite and sane: an infinite separation made ODE abort, an infinite diameter gave NaN odometry.
        sanity.drive_length(self.wheel_separation, "wheel_separation")
        sanity.drive_length(2 * self.wheel_radius, "wheel diameter")
        sanity.number(self.max_wheel_torque, "max_wheel_torque (N m)", 0.0, sanity.MAX_FORCE)
        for name in ("max_wheel_acceleration", "cmd_timeout"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or math.isnan(value) or value < 0:
                raise ValueError(f"{name} must be >= 0, got {value!r}")
        if self.odometry_integration not in INTEGRATIONS:
            raise ValueError(
                f"odometry_integration must be one of {INTEGRATIONS}, " f"got {self.odometry_integration!r}"
            )

    @classmethod
    def from_kobuki_plugin(cls, params: Mapping[str, str], **overrides: object) -> "DiffDriveParams":
        """Read libgazebo_ros_kobuki.so's <plugin> parameters (wheel_diameter, torque, ...);
        keyword ``overrides`` win over them."""
        fields: Dict[str, object] = {}
        try:
            if "wheel_separation" in params:
                fields["wheel_separation"] = float(params["wheel_separation"])
            if "wheel_diameter" in params:
                fields["wheel_radius"] = float(params["wheel_diameter"]) / 2
            if "torque" in params:
                fields["max_wheel_torque"] = float(params["torque"])
            if "velocity_command_timeout" in params:
                fields["cmd_timeout"] = float(params["velocity_command_timeout"])
        except ValueError as error:
            raise ValueError(f"kobuki plugin parameter is not a number: {error}") from None
        fields.update(overrides)
        result = cls(**fields)  # type: ignore[arg-type]
        result.validate()
        return result


class DiffDriveController:
    """Turns (v, w) commands into velocity motors on two hinge joints.

    Both wheel joints must turn about the robot's +y axis (positive = forward), as in
    URDFs where left and right wheels share ``<axis xyz="0 1 0"/>``.
    """

    def __init__(self, left: ode.HingeJoint, right: ode.HingeJoint, params: DiffDriveParams) -> None:
        params.validate()
        self.params = params
        self._left = left
        self._right = right
        self._command = (0.0, 0.0)
        self._command_time = -math.inf
        self._wheel_speeds = (0.0, 0.0)
        # The Kobuki's motor power (kobuki_msgs/MotorPower): while off, commands are dropped and the wheels held.
        self.motors_enabled = True
        for joint in (left, right):
            joint.setParam(oc.PARAM_VEL, 0.0)
            joint.setParam(oc.PARAM_FMAX, params.max_wheel_torque)

    @property
    def command(self) -> Tuple[float, float]:
        """Last accepted (v, w) after clamping."""
        return self._command

    @property
    def wheel_speeds(self) -> Tuple[float, float]:
        """Motor target speeds (left, right) in rad/s set by the last update."""
        return self._wheel_speeds

    def set_command(self, linear: float, angular: float, now: float) -> bool:
        """Accept a command at sim time ``now``; False (and ignored) if not finite."""
        if not (math.isfinite(linear) and math.isfinite(angular)):
            return False
        p = self.params
        self._command = (
            max(-p.max_linear, min(p.max_linear, linear)),
            max(-p.max_angular, min(p.max_angular, angular)),
        )
        self._command_time = now
        return True

    def stop(self) -> None:
        """Forget the command and the wheel speed ramp (e.g. after a teleport)."""
        self._command = (0.0, 0.0)
        self._command_time = -math.inf
        self._wheel_speeds = (0.0, 0.0)
        self._left.setParam(oc.PARAM_VEL, 0.0)
        self._right.setParam(oc.PARAM_VEL, 0.0)

    def timed_out(self, now: float) -> bool:
        timeout = self.params.cmd_timeout
        return timeout > 0 and now - self._command_time > timeout

    def update(self, now: float, dt: float) -> None:
        """Set the motors for the next ``dt`` seconds; call before each physics step."""
        p = self.params
        if not self.motors_enabled:
            self._command = (0.0, 0.0)  # as kobuki_gazebo_plugins: after power-on, only a new command moves it
        linear, angular = (0.0, 0.0) if self.timed_out(now) else self._command
        half_turn = angular * p.wheel_separation / 2
        left = (linear - half_turn) / p.wheel_radius
        right = (linear + half_turn) / p.wheel_radius
        old_left, old_right = self._wheel_speeds
        if p.max_wheel_acceleration > 0:
            # Scale both changes by one factor so the commanded curvature is kept.
            largest = max(abs(left - old_left), abs(right - old_right))
            allowed = p.max_wheel_acceleration * dt
            if largest > allowed:
                scale = allowed / largest
                left = old_left + (left - old_left) * scale
                right = old_right + (right - old_right) * scale
        if left != old_left:
            self._left.setParam(oc.PARAM_VEL, left)
        if right != old_right:
            self._right.setParam(oc.PARAM_VEL, right)
        self._wheel_speeds = (left, right)


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


class WheelOdometry:
    """Dead reckoning from wheel joint angles (encoders), as the Kobuki base does."""

    def __init__(self, wheel_separation: float, wheel_radius: float, integration: str = "midpoint") -> None:
        if integration not in INTEGRATIONS:
            raise ValueError(f"integration must be one of {INTEGRATIONS}, got {integration!r}")
        if not wheel_separation > 0 or not wheel_radius > 0:
            raise ValueError(
                f"wheel_separation and wheel_radius must be > 0, got " f"{wheel_separation!r}, {wheel_radius!r}"
            )
        self.wheel_separation = wheel_separation
        self.wheel_radius = wheel_radius
        self.exact = integration == "exact"
        self.x = self.y = self.yaw = 0.0
        self.linear = self.angular = 0.0
        self._last: Tuple[float, float, float] = (math.nan, math.nan, math.nan)

    @classmethod
    def from_params(cls, params: DiffDriveParams) -> "WheelOdometry":
        return cls(params.wheel_separation, params.wheel_radius, params.odometry_integration)

    def reset(self, x: float = 0.0, y: float = 0.0, yaw: float = 0.0) -> None:
        """Set the pose; the next update only sets the encoder baseline."""
        self.x, self.y, self.yaw = x, y, yaw
        self.linear = self.angular = 0.0
        self._last = (math.nan, math.nan, math.nan)

    def update(self, left_angle: float, right_angle: float, now: float) -> None:
        """Integrate the increments of multi-turn wheel angles (``JointHandle.angle()``)
        since the previous call, made at sim time ``now``."""
        last_left, last_right, last_time = self._last
        self._last = (left_angle, right_angle, now)
        if math.isnan(last_time):
            return
        left = (left_angle - last_left) * self.wheel_radius
        right = (right_angle - last_right) * self.wheel_radius
        distance = (left + right) / 2
        turn = (right - left) / self.wheel_separation
        if self.exact and abs(turn) > 1e-9:
            radius = distance / turn
            self.x += radius * (math.sin(self.yaw + turn) - math.sin(self.yaw))
            self.y -= radius * (math.cos(self.yaw + turn) - math.cos(self.yaw))
        else:
            heading = self.yaw + turn / 2
            self.x += distance * math.cos(heading)
            self.y += distance * math.sin(heading)
        self.yaw = _wrap(self.yaw + turn)
        elapsed = now - last_time
        if elapsed > 0:
            self.linear = distance / elapsed
            self.angular = turn / elapsed

    @property
    def pose(self) -> Tuple[float, float, float]:
        return self.x, self.y, self.yaw
