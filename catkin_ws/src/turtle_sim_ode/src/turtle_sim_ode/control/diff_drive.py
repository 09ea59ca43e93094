"""diff_drive_controller/DiffDriveController (ros_controllers noetic) on velocity-controlled wheel joints.

Parameters as DiffDriveController::init reads them: left_wheel / right_wheel (a name or a list), wheel_separation
and wheel_radius (from the URDF when absent: the distance between the two first wheels' joint origins, and the
left wheel link's cylinder or sphere collision radius), wheel_separation_multiplier, wheel_radius_multiplier
(or left_/right_wheel_radius_multiplier), publish_rate (50), open_loop, velocity_rolling_window_size (10),
cmd_vel_timeout (0.5 s), base_frame_id (base_link), odom_frame_id (odom), enable_odom_tf (true),
pose/twist_covariance_diagonal (six numbers each), publish_cmd, linear/x/* and angular/z/* limits
(has_velocity_limits, max_velocity, min_velocity = -max_velocity, and the same for acceleration and jerk).
Topics: cmd_vel in, odom and /tf out (and cmd_vel_out with publish_cmd).
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from typing import Deque, List, Optional

from turtle_sim_ode.control.controller import Controller, Throttle
from turtle_sim_ode.control.hardware import JointData, RobotHW, clamp
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.transmissions import VELOCITY
from turtle_sim_ode.models.description import Cylinder, RobotModel, Sphere


@dataclass
class SpeedLimiter:
    """diff_drive_controller's SpeedLimiter: jerk, then acceleration, then velocity."""

    has_velocity_limits: bool = False
    has_acceleration_limits: bool = False
    has_jerk_limits: bool = False
    min_velocity: float = 0.0
    max_velocity: float = 0.0
    min_acceleration: float = 0.0
    max_acceleration: float = 0.0
    min_jerk: float = 0.0
    max_jerk: float = 0.0

    @classmethod
    def read(cls, params: Params) -> "SpeedLimiter":
        limiter = cls()
        for kind in ("velocity", "acceleration", "jerk"):
            setattr(limiter, f"has_{kind}_limits", params.flag(f"has_{kind}_limits", False))
            high = params.number(f"max_{kind}", 0.0)
            setattr(limiter, f"max_{kind}", high)
            setattr(limiter, f"min_{kind}", params.number(f"min_{kind}", -high))
        return limiter

    def limit(self, v: float, v0: float, v1: float, dt: float) -> float:
        if self.has_jerk_limits:
            dv, dv0, dt2 = v - v0, v0 - v1, 2.0 * dt * dt
            v = v0 + dv0 + clamp(dv - dv0, self.min_jerk * dt2, self.max_jerk * dt2)
        if self.has_acceleration_limits:
            v = v0 + clamp(v - v0, self.min_acceleration * dt, self.max_acceleration * dt)
        if self.has_velocity_limits:
            v = clamp(v, self.min_velocity, self.max_velocity)
        return v


class Odometry:
    """diff_drive_controller's Odometry: exact integration of the wheel displacements (Runge-Kutta 2 when the
    heading change is below 1e-6), velocities as rolling means of the last ``window`` estimates (worked out when
    read, at the publish rate, rather than at every control update)."""

    def __init__(self, window: int) -> None:
        self.window = window
        self.reset(0.0)

    def reset(self, time: float) -> None:
        self.x = self.y = self.heading = 0.0
        self._open_loop_twist = (0.0, 0.0)  # the velocities of open-loop updates, which estimate none
        self.timestamp = time
        self.left_old = self.right_old = None
        self.linear_acc: Deque[float] = deque(maxlen=self.window)
        self.angular_acc: Deque[float] = deque(maxlen=self.window)

    @property
    def linear(self) -> float:
        estimates = self.linear_acc
        return sum(estimates) / len(estimates) if estimates else self._open_loop_twist[0]

    @property
    def angular(self) -> float:
        estimates = self.angular_acc
        return sum(estimates) / len(estimates) if estimates else self._open_loop_twist[1]

    def integrate(self, linear: float, angular: float) -> None:
        if abs(angular) < 1e-6:
            direction = self.heading + angular * 0.5
            self.x += linear * math.cos(direction)
            self.y += linear * math.sin(direction)
            self.heading += angular
        else:
            old, r = self.heading, linear / angular
            self.heading += angular
            self.x += r * (math.sin(self.heading) - math.sin(old))
            self.y += -r * (math.cos(self.heading) - math.cos(old))

    def update(self, left: float, right: float, separation: float, time: float) -> None:
        """left, right: wheel travel (m) since start."""
        if self.left_old is None:  # Odometry::init is at the wheels' positions of the first update
            self.left_old, self.right_old = left, right
        d_left, d_right = left - self.left_old, right - self.right_old
        self.left_old, self.right_old = left, right
        linear, angular = (d_right + d_left) * 0.5, (d_right - d_left) / separation
        self.integrate(linear, angular)
        dt = time - self.timestamp
        if dt < 0.0001:
            return
        self.timestamp = time
        self.linear_acc.append(linear / dt)
        self.angular_acc.append(angular / dt)

    def update_open_loop(self, linear: float, angular: float, time: float) -> None:
        self._open_loop_twist = (linear, angular)
        dt, self.timestamp = time - self.timestamp, time
        self.integrate(linear * dt, angular * dt)


def mean_position(joints: List[JointData]) -> float:
    """The joints' mean position, summed in order from 0 as sum() does (a loop costs less than a generator)."""
    total = 0
    for joint in joints:
        total += joint.position
    return total / len(joints)


def _wheel_names(params: Params, name: str) -> List[str]:
    return params.strings(name, allow_single=True)


def _from_urdf(robot: Optional[RobotModel], left: str, right: str, separation: bool, radius: bool) -> tuple:
    """(separation, radius) looked up in the URDF where not given, as setOdomParamsFromUrdf does."""
    if robot is None:
        raise ControllerError("Robot description couldn't be retrieved from param server.")
    for name in (left, right):
        if name not in robot.joints:
            raise ControllerError(f"{name} couldn't be retrieved from model description")
    found_separation = found_radius = None
    if separation:
        a, b = robot.joints[left].origin.xyz, robot.joints[right].origin.xyz
        found_separation = math.dist(a, b)
    if radius:
        link = robot.links.get(robot.joints[left].child)
        shapes = [c.geometry for c in link.collisions] if link else []
        if not shapes or not isinstance(shapes[0], (Cylinder, Sphere)):
            raise ControllerError(f"Couldn't retrieve {left} wheel radius")
        found_radius = shapes[0].radius
    return found_separation, found_radius


class DiffDriveController(Controller):
    interface = VELOCITY

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        left, right = _wheel_names(params, "left_wheel"), _wheel_names(params, "right_wheel")
        if len(left) != len(right):
            raise ControllerError(f"#left wheels ({len(left)}) != #right wheels ({len(right)}).")
        self.left = [self.claim(hw, name) for name in left]
        self.right = [self.claim(hw, name) for name in right]
        self.throttle = Throttle(params.number("publish_rate", 50.0))
        self.open_loop = params.flag("open_loop", False)
        self.separation_multiplier = params.number("wheel_separation_multiplier", 1.0)
        radius_multiplier = params.number("wheel_radius_multiplier", 1.0)
        self.left_radius_multiplier = params.number("left_wheel_radius_multiplier", radius_multiplier)
        self.right_radius_multiplier = params.number("right_wheel_radius_multiplier", radius_multiplier)
        window = int(params.number("velocity_rolling_window_size", 10.0, minimum=1.0))
        self.cmd_vel_timeout = params.number("cmd_vel_timeout", 0.5)
        self.base_frame_id = params.string("base_frame_id", "base_link")
        self.odom_frame_id = params.string("odom_frame_id", "odom")
        self.enable_odom_tf = params.flag("enable_odom_tf", True)
        self.publish_cmd = params.flag("publish_cmd", False)
        self.limiter_linear = SpeedLimiter.read(params.child("linear").child("x"))
        self.limiter_angular = SpeedLimiter.read(params.child("angular").child("z"))
        self.pose_covariance = params.numbers("pose_covariance_diagonal", 6)
        self.twist_covariance = params.numbers("twist_covariance_diagonal", 6)
        separation = params.number("wheel_separation", 0.0) if params.has("wheel_separation") else None
        radius = params.number("wheel_radius", 0.0) if params.has("wheel_radius") else None
        if separation is None or radius is None:
            found = _from_urdf(robot, left[0], right[0], separation is None, radius is None)
            separation = found[0] if separation is None else separation
            radius = found[1] if radius is None else radius
        if separation <= 0 or radius <= 0:
            raise ControllerError(f"wheel_separation ({separation}) and wheel_radius ({radius}) must be > 0")
        self.separation, self.radius = separation, radius
        self.odometry = Odometry(window)
        self.command = (0.0, 0.0, -math.inf)  # linear, angular, stamp
        self.last0 = self.last1 = (0.0, 0.0)
        self.inputs["cmd_vel"] = ("twist", self._on_cmd_vel)
        self.outputs["odom"] = "odometry"
        if self.enable_odom_tf:
            self.outputs["/tf"] = "tf"
        if self.publish_cmd:
            self.outputs["cmd_vel_out"] = "twist_stamped"
        self.now = 0.0

    def _on_cmd_vel(self, twist: tuple) -> None:
        """twist: (linear.x, angular.z), stamped with the time of the last update (ros::Time::now in sim)."""
        linear, angular = twist
        if not self.running or not (math.isfinite(linear) and math.isfinite(angular)):
            return
        self.command = (float(linear), float(angular), self.now)

    def starting(self, time: float) -> None:
        self._brake()
        self.throttle.start(time, publish_first=False)
        self.odometry.reset(time)
        self.now = time

    def stopping(self, time: float) -> None:
        self._brake()

    def _brake(self) -> None:
        for joint in self.left + self.right:
            joint.command = 0.0

    def update(self, time: float, period: float) -> None:
        self.now = time
        separation = self.separation_multiplier * self.separation
        left_radius = self.left_radius_multiplier * self.radius
        right_radius = self.right_radius_multiplier * self.radius
        if self.open_loop:
            self.odometry.update_open_loop(self.last0[0], self.last0[1], time)
        else:
            left = mean_position(self.left) * left_radius
            right = mean_position(self.right) * right_radius
            if not (math.isfinite(left) and math.isfinite(right)):
                return
            self.odometry.update(left, right, separation, time)
        if self.throttle.due(time):
            self._publish_odometry(time)
        linear, angular, stamp = self.command
        if time - stamp > self.cmd_vel_timeout:
            linear = angular = 0.0
        last0, last1 = self.last0, self.last1
        linear = self.limiter_linear.limit(linear, last0[0], last1[0], period)
        angular = self.limiter_angular.limit(angular, last0[1], last1[1], period)
        self.last1, self.last0 = last0, (linear, angular)
        if self.publish_cmd:
            self.publish("cmd_vel_out", "twist_stamped", {"stamp": time, "linear": linear, "angular": angular})
        left_speed = (linear - angular * separation / 2.0) / left_radius
        right_speed = (linear + angular * separation / 2.0) / right_radius
        for joint in self.left:
            joint.command = left_speed
        for joint in self.right:
            joint.command = right_speed

    def _publish_odometry(self, time: float) -> None:
        odom = self.odometry
        pose = {"x": odom.x, "y": odom.y, "yaw": odom.heading}
        self.publish(
            "odom",
            "odometry",
            dict(
                pose,
                stamp=time,
                frame_id=self.odom_frame_id,
                child_frame_id=self.base_frame_id,
                linear=odom.linear,
                angular=odom.angular,
                pose_covariance=self.pose_covariance,
                twist_covariance=self.twist_covariance,
            ),
        )
        if self.enable_odom_tf:
            self.publish(
                "/tf", "tf", dict(pose, stamp=time, frame_id=self.odom_frame_id, child_frame_id=self.base_frame_id)
            )
