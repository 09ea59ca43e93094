"""ROS-free motion planning for the TurtleBot exercises (twin of include/my_first_rospkg/motion.h)."""
import enum
import math
from typing import NamedTuple


class Velocity(NamedTuple):
    """A unicycle command: forward speed [m/s] and yaw rate [rad/s]."""

    linear: float = 0.0
    angular: float = 0.0


class Pose2D(NamedTuple):
    """A planar pose: position [m] and heading [rad]."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0


STOP = Velocity()


def normalize_angle(angle: float) -> float:
    """The angle in (-pi, pi]."""
    angle = math.fmod(angle + math.pi, 2.0 * math.pi)
    if angle <= 0.0:
        angle += 2.0 * math.pi
    return angle - math.pi


def yaw_from_quaternion(x: float, y: float, z: float, w: float) -> float:
    """Heading of the unit quaternion (x, y, z, w) about z."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class TimedTrajectory:
    """A velocity profile over time, zero from duration() on."""

    def velocity_at(self, t: float) -> Velocity:
        raise NotImplementedError

    def duration(self) -> float:
        raise NotImplementedError


class CircleTrajectory(TimedTrajectory):
    """A circle of `radius` [m] driven at `speed` [m/s], `laps` times, turning left."""

    def __init__(self, radius: float, speed: float, laps: float):
        self._radius, self._speed, self._laps = radius, speed, laps

    def velocity_at(self, t: float) -> Velocity:
        if 0.0 <= t < self.duration():
            return Velocity(self._speed, self._speed / self._radius)
        return STOP

    def duration(self) -> float:
        return self._laps * 2.0 * math.pi * self._radius / self._speed


class SpiralTrajectory(TimedTrajectory):
    """An Archimedean spiral: the radius of curvature grows by `growth_rate` [m/rad] with the heading turned,
    r(theta) = initial_radius + growth_rate * theta, at a constant yaw rate `angular_speed` [rad/s], until it
    reaches `max_radius` [m]."""

    def __init__(self, initial_radius: float, growth_rate: float, angular_speed: float, max_radius: float):
        self._initial_radius, self._growth_rate = initial_radius, growth_rate
        self._angular_speed, self._max_radius = angular_speed, max_radius

    def radius_at(self, t: float) -> float:
        """Radius of curvature `t` seconds after the start."""
        return self._initial_radius + self._growth_rate * self._angular_speed * t

    def velocity_at(self, t: float) -> Velocity:
        if 0.0 <= t < self.duration():
            return Velocity(self._angular_speed * self.radius_at(t), self._angular_speed)
        return STOP

    def duration(self) -> float:
        return max(0.0, (self._max_radius - self._initial_radius) / (self._growth_rate * self._angular_speed))


class Bouncer:
    """Drives straight at `speed` and reverses whenever the robot is beyond |x| > limit_x or |y| > limit_y and
    still moving outwards."""

    def __init__(self, speed: float, limit_x: float, limit_y: float):
        self._speed, self._limit_x, self._limit_y = speed, limit_x, limit_y
        self.direction = 1

    def update(self, pose: Pose2D) -> Velocity:
        heading_x = self.direction * math.cos(pose.yaw)
        heading_y = self.direction * math.sin(pose.yaw)
        leaving_x = abs(pose.x) > self._limit_x and pose.x * heading_x > 0.0
        leaving_y = abs(pose.y) > self._limit_y and pose.y * heading_y > 0.0
        if leaving_x or leaving_y:
            self.direction = -self.direction
        return Velocity(self.direction * self._speed, 0.0)


class SquareParams(NamedTuple):
    """Settings of SquareController (units as in motion.h)."""

    side: float = 1.0
    linear_speed: float = 0.3
    angular_speed: float = 0.6
    settle_time: float = 0.5
    distance_tolerance: float = 0.005
    angle_tolerance: float = 0.01
    gain: float = 2.0
    min_linear_speed: float = 0.03
    min_angular_speed: float = 0.05


class SquareState(enum.Enum):
    START = "start"
    DRIVE = "drive"
    STOP_AFTER_DRIVE = "stop after drive"
    TURN = "turn"
    STOP_AFTER_TURN = "stop after turn"
    DONE = "done"


class SquareController:
    """Closed-loop square on odometry: drive a side, stop, turn 90 degrees left, stop; four times."""

    SIDES = 4

    def __init__(self, params: SquareParams):
        self._params = params
        self.state = SquareState.START
        self._side_start = Pose2D()
        self._target_yaw = 0.0
        self._stop_since = 0.0
        self.sides_done = 0

    def done(self) -> bool:
        return self.state == SquareState.DONE

    def _clamped_speed(self, error: float, min_speed: float, max_speed: float) -> float:
        speed = min(max_speed, max(min_speed, self._params.gain * abs(error)))
        return -speed if error < 0.0 else speed

    def update(self, pose: Pose2D, now: float) -> Velocity:
        """The command for the robot at `pose` at time `now` [s]."""
        p = self._params
        if self.state == SquareState.START:
            self._side_start = pose
            self._target_yaw = pose.yaw
            self.state = SquareState.DRIVE
            return self.update(pose, now)
        if self.state == SquareState.DRIVE:
            travelled = (pose.x - self._side_start.x) * math.cos(self._target_yaw) + (
                pose.y - self._side_start.y
            ) * math.sin(self._target_yaw)
            remaining = p.side - travelled
            if remaining <= p.distance_tolerance:
                self.state = SquareState.STOP_AFTER_DRIVE
                self._stop_since = now
                return STOP
            heading_error = normalize_angle(self._target_yaw - pose.yaw)
            angular = max(-p.angular_speed, min(p.angular_speed, p.gain * heading_error))
            return Velocity(self._clamped_speed(remaining, p.min_linear_speed, p.linear_speed), angular)
        if self.state == SquareState.STOP_AFTER_DRIVE:
            if now - self._stop_since >= p.settle_time:
                self.sides_done += 1
                if self.sides_done == self.SIDES:
                    self.state = SquareState.DONE
                    return STOP
                self._target_yaw = normalize_angle(self._target_yaw + math.pi / 2.0)
                self.state = SquareState.TURN
                return self.update(pose, now)
            return STOP
        if self.state == SquareState.TURN:
            error = normalize_angle(self._target_yaw - pose.yaw)
            if abs(error) <= p.angle_tolerance:
                self.state = SquareState.STOP_AFTER_TURN
                self._stop_since = now
                return STOP
            return Velocity(0.0, self._clamped_speed(error, p.min_angular_speed, p.angular_speed))
        if self.state == SquareState.STOP_AFTER_TURN:
            if now - self._stop_since >= p.settle_time:
                self._side_start = pose
                self.state = SquareState.DRIVE
                return self.update(pose, now)
            return STOP
        return STOP
