"""gazebo_ros_tricycle_drive (``libgazebo_ros_tricycle_drive.so``, gazebo_plugins/src/gazebo_ros_tricycle_drive.cpp):
a steered, driven front wheel and two passive encoder wheels. Its tags and defaults (GazeboRosTricycleDrive::Load),
and its per-step work without ROS: the motor control at ``updateRate`` (UpdateChild, motorController) and the
odometry from the encoder wheels' speeds at every step (UpdateOdometryEncoder). The topics are in
ros.plugins.tricycle_drive.

As upstream, a command's ``linear.x`` is the actuated wheel's ground speed and its ``angular.z`` is the steering
angle itself (rad, held to +-pi/2), not a yaw rate; the steering joint is put at that angle each update (Gazebo's
Joint::SetPosition) unless ``steeringSpeed`` > 0, which turns it at that speed instead."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.joint_positions import move_joints
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.world.diff_drive import DiffDriveParams
from turtle_sim_ode.world.plugins.tags import flag, number, text

TRICYCLE_DRIVE = "libgazebo_ros_tricycle_drive.so"
MODEL_PLUGINS = (TRICYCLE_DRIVE,)
ODOMETRY_SOURCES = ("encoder", "world")
MAX_STEERING = math.pi / 2  # motorController truncates the target angle to +-pi/2
# Beyond upstream: the actuated wheel's speed is held to this (rad/s) so a huge command cannot break ODE.
MAX_WHEEL_SPEED = sanity.MAX_SPEED


@dataclass
class TricycleConfig:
    """The plugin's tags, with GazeboRosTricycleDrive::Load's names and defaults."""

    filename: str
    steering_joint: str = "front_steering_joint"
    actuated_wheel_joint: str = "front_wheel_joint"
    encoder_wheel_left_joint: str = "left_wheel_joint"
    encoder_wheel_right_joint: str = "right_wheel_joint"
    actuated_wheel_diameter: float = 0.15  # m
    encoder_wheel_diameter: float = 0.15  # m
    encoder_wheel_separation: float = 0.5  # m
    wheel_torque: float = 5.0  # N m, on the actuated wheel and the steering joint
    wheel_acceleration: float = 0.0  # rad/s^2 of the actuated wheel; 0: no limit
    wheel_deceleration: float = 0.0  # rad/s^2; defaults to wheelAcceleration
    wheel_speed_tolerance: float = 0.01  # rad/s
    steering_speed: float = 0.0  # rad/s; 0: the steering joint is put at the angle (position control)
    steering_angle_tolerance: float = 0.01  # rad
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    base_frame: str = "base_link"
    odometry_source: str = "world"
    publish_wheel_tf: bool = False
    publish_wheel_joint_state: bool = False
    update_rate: float = 100.0  # Hz of sim time; 0 = every step
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>

    @property
    def joints_needed(self) -> Tuple[str, ...]:
        """In publishWheelTF's and publishWheelJointState's order."""
        return (
            self.steering_joint,
            self.actuated_wheel_joint,
            self.encoder_wheel_left_joint,
            self.encoder_wheel_right_joint,
        )

    @property
    def publish_tf(self) -> bool:
        """publishOdometry always sends odometryFrame -> robotBaseFrame on tf (the node opens /tf for it)."""
        return True

    def make_robot(self, model: BuiltModel) -> "TricycleRobot":
        return TricycleRobot(model, self)


# --- motorController, as pure functions --------------------------------------------------------------------------
def target_wheel_speed(speed: float, actuated_wheel_diameter: float) -> float:
    """UpdateChild: the actuated wheel's rotation speed (rad/s) for a ground speed (m/s), speed / (diameter / 2)."""
    return speed / (actuated_wheel_diameter / 2.0)


def target_steering_angle(angle: float) -> float:
    """motorController: the commanded angle (angular.z) truncated to +-pi/2."""
    return max(-MAX_STEERING, min(MAX_STEERING, angle))


def applied_wheel_speed(
    current: float, target: float, dt: float, acceleration: float, deceleration: float, tolerance: float
) -> float:
    """motorController's actuated wheel speed: the target where ``acceleration`` is 0; else the current speed within
    ``tolerance`` of the target, the target within ``acceleration * dt`` of it, otherwise one step from the current
    speed towards it: down by ``acceleration * dt``, up by ``deceleration * dt`` (upstream's naming)."""
    if acceleration <= 0:
        return target
    difference = current - target
    if abs(difference) < tolerance:
        return current
    if abs(difference) > acceleration * dt:
        return current - acceleration * dt if difference > 0 else current + deceleration * dt
    return target


def steering_velocity(
    current: float, target: float, target_wheel: float, steering_speed: float, tolerance: float
) -> float:
    """motorController with ``steeringSpeed`` > 0: 0 within ``tolerance`` of the (truncated) target, else
    +steering_speed where current - target is below ``target_wheel`` (the wheel's target speed: upstream compares the
    angle difference with it, not with 0) and -steering_speed otherwise."""
    difference = current - target
    if abs(difference) < tolerance:
        return 0.0
    return steering_speed if difference < target_wheel else -steering_speed


class EncoderOdometry:
    """UpdateOdometryEncoder: the pose from the encoder wheels' speeds over the time since the last call, with its
    signs: the yaw grows by (sl - sr) / separation, the heading of a step is yaw + (sl - sr) / (2 separation), and
    the twist is (dx, dy) / dt in the odometry frame with yaw rate dyaw / dt."""

    def __init__(self, wheel_radius: float, separation: float) -> None:
        self.wheel_radius = wheel_radius
        self.separation = separation
        self.x = self.y = self.yaw = 0.0
        self.linear: Tuple[float, float] = (0.0, 0.0)
        self.angular = 0.0
        self._last = math.nan

    def reset(self, now: float) -> None:
        self.x = self.y = self.yaw = 0.0
        self.linear, self.angular = (0.0, 0.0), 0.0
        self._last = now

    def update(self, left_rate: float, right_rate: float, now: float) -> None:
        """Integrate the wheels' joint speeds (rad/s) over the time since the last call."""
        elapsed = now - self._last if math.isfinite(self._last) else 0.0
        self._last = now
        if not elapsed > 0 or not (math.isfinite(left_rate) and math.isfinite(right_rate)):
            return  # upstream divides by a zero step here
        left = left_rate * self.wheel_radius * elapsed
        right = right_rate * self.wheel_radius * elapsed
        half = (left + right) / 2.0
        heading = self.yaw + (left - right) / (2.0 * self.separation)
        dx, dy = half * math.cos(heading), half * math.sin(heading)
        turn = (left - right) / self.separation
        self.x += dx
        self.y += dy
        self.yaw += turn
        self.linear = (dx / elapsed, dy / elapsed)
        self.angular = turn / elapsed


class TricycleMotors:
    """UpdateChild's schedule: encoder odometry every step (odometrySource encoder); the motors when more than a
    period has passed since the last motor update, with that time as the step (the last update then moves on by one
    period, so ``updateRate`` 0 passes the time since the start)."""

    def __init__(self, model: BuiltModel, config: TricycleConfig, odometry: EncoderOdometry) -> None:
        self._model = model
        self._config = config
        self._odometry = odometry
        self._encoder = config.odometry_source == "encoder"
        self.steering, self.wheel, self.left, self.right = (model.joint(name) for name in config.joints_needed)
        self._period = 1.0 / config.update_rate if config.update_rate > 0 else 0.0
        self._last_update = math.nan
        self.command: Tuple[float, float] = (0.0, 0.0)  # speed (m/s), steering angle (rad)
        self.applied: Tuple[float, float] = (0.0, 0.0)  # the wheel's speed, the steering's angle or speed
        for handle in (self.wheel, self.steering):  # Load: SetParam("fmax", wheelTorque) on both
            handle.joint.setParam(oc.PARAM_VEL, 0.0)
            handle.joint.setParam(oc.PARAM_FMAX, config.wheel_torque)

    def set_command(self, speed: float, angle: float, now: float) -> bool:
        """cmdVelCallback: False (and ignored) if not finite; held until the next one (no watchdog)."""
        if not (math.isfinite(speed) and math.isfinite(angle)):
            return False
        self.command = (speed, angle)
        return True

    def start(self, now: float) -> None:
        """Load: the motor schedule counts from now."""
        self._last_update = now

    def update(self, now: float, dt: float) -> None:
        if self._encoder:
            self._odometry.update(self.left.rate(), self.right.rate(), now)
        if not math.isfinite(self._last_update):
            self._last_update = now
        elapsed = now - self._last_update
        if elapsed > self._period:
            self.control(elapsed)
            self._last_update += self._period

    def control(self, dt: float) -> None:
        """motorController for the command, over ``dt`` s."""
        config = self._config
        speed, angle = self.command
        target = target_wheel_speed(speed, config.actuated_wheel_diameter)
        target = max(-MAX_WHEEL_SPEED, min(MAX_WHEEL_SPEED, target))
        wheel = applied_wheel_speed(
            self.wheel.rate(),
            target,
            dt,
            config.wheel_acceleration,
            config.wheel_deceleration,
            config.wheel_speed_tolerance,
        )
        wheel = max(-MAX_WHEEL_SPEED, min(MAX_WHEEL_SPEED, wheel))
        self.wheel.joint.setParam(oc.PARAM_VEL, wheel)
        angle = target_steering_angle(angle)
        if config.steering_speed > 0:
            steering = steering_velocity(
                self.steering.angle(), angle, target, config.steering_speed, config.steering_angle_tolerance
            )
            self.steering.joint.setParam(oc.PARAM_VEL, steering)
        else:
            steering = self._within_limits(angle)
            move_joints(self._model, {self.steering.name: steering})
        self.applied = (wheel, steering)

    def _within_limits(self, angle: float) -> float:
        """Joint::SetPosition holds the position to the joint's limits where it has some."""
        if self.steering.type == "continuous":
            return angle
        low = self.steering.joint.getParam(oc.PARAM_LO_STOP)
        high = self.steering.joint.getParam(oc.PARAM_HI_STOP)
        return max(low, min(high, angle)) if low < high else angle

    def stop(self) -> None:
        """A world reset: the command forgotten, the wheel's motor at 0 (upstream keeps the command)."""
        self.command = (0.0, 0.0)
        self.wheel.joint.setParam(oc.PARAM_VEL, 0.0)
        if self._config.steering_speed > 0:
            self.steering.joint.setParam(oc.PARAM_VEL, 0.0)


class TricycleRobot:
    """A model's tricycle drive plugin: the motors, the encoder odometry and the four joints it names."""

    def __init__(self, model: BuiltModel, config: TricycleConfig) -> None:
        self.model = model
        self.config = config
        # What the simulation's drive protocol asks for; the plugin itself has no limits to clamp commands to.
        self.params = DiffDriveParams(
            wheel_separation=config.encoder_wheel_separation,
            wheel_radius=config.actuated_wheel_diameter / 2,
            max_wheel_torque=config.wheel_torque,
            max_linear=math.inf,
            max_angular=math.inf,
            cmd_timeout=0.0,
        )
        self.odometry = EncoderOdometry(config.encoder_wheel_diameter / 2, config.encoder_wheel_separation)
        self.drive = TricycleMotors(model, config, self.odometry)
        self.wheels: Tuple[JointHandle, ...] = tuple(model.joint(name) for name in config.joints_needed)

    def reset_odometry(self, now: float) -> None:
        """At spawn and on a world reset: the encoder pose back at 0, the motor schedule from now."""
        self.odometry.reset(now)
        self.drive.start(now)

    def wheels_moved(self, now: float) -> None:
        """The odometry integrates wheel speeds, not angles: a jump of the wheels does not count."""


def _bounded(plugin: GazeboPlugin, tag: str, default: float, high: float) -> float:
    """A tag that must be a finite number in [0, high]."""
    return sanity.number(number(plugin, tag, default), f"{plugin.filename} <{tag}>", 0.0, high, ModelError)


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> TricycleConfig:
    """GazeboRosTricycleDrive::Load's tags. Beyond upstream, bad values refuse the model: lengths must be in
    (0, 100] m; the torque, accelerations, speeds, tolerances and rate finite, >= 0 and sane; odometrySource encoder
    or world (upstream warns and keeps world)."""
    what = plugin.filename
    lengths = {}
    for tag, default in (
        ("actuatedWheelDiameter", 0.15),
        ("encoderWheelDiameter", 0.15),
        ("encoderWheelSeparation", 0.5),
    ):
        lengths[tag] = sanity.drive_length(number(plugin, tag, default), f"{what} <{tag}>", ModelError)
    acceleration = _bounded(plugin, "wheelAcceleration", 0.0, sanity.MAX_JOINT_ACCELERATION)
    source = text(plugin, "odometrySource", "world")
    if source not in ODOMETRY_SOURCES:
        raise ModelError(f"{what} <odometrySource> must be encoder or world, got '{source}'")
    return TricycleConfig(
        filename=plugin.filename,
        steering_joint=text(plugin, "steeringJoint", "front_steering_joint"),
        actuated_wheel_joint=text(plugin, "actuatedWheelJoint", "front_wheel_joint"),
        encoder_wheel_left_joint=text(plugin, "encoderWheelLeftJoint", "left_wheel_joint"),
        encoder_wheel_right_joint=text(plugin, "encoderWheelRightJoint", "right_wheel_joint"),
        actuated_wheel_diameter=lengths["actuatedWheelDiameter"],
        encoder_wheel_diameter=lengths["encoderWheelDiameter"],
        encoder_wheel_separation=lengths["encoderWheelSeparation"],
        wheel_torque=_bounded(plugin, "wheelTorque", 5.0, sanity.MAX_FORCE),
        wheel_acceleration=acceleration,
        wheel_deceleration=_bounded(plugin, "wheelDeceleration", acceleration, sanity.MAX_JOINT_ACCELERATION),
        wheel_speed_tolerance=_bounded(plugin, "wheelSpeedTolerance", 0.01, sanity.MAX_SPEED),
        steering_speed=_bounded(plugin, "steeringSpeed", 0.0, sanity.MAX_SPEED),
        steering_angle_tolerance=_bounded(plugin, "steeringAngleTolerance", 0.01, math.tau),
        command_topic=text(plugin, "commandTopic", "cmd_vel"),
        odometry_topic=text(plugin, "odometryTopic", "odom"),
        odometry_frame=text(plugin, "odometryFrame", "odom"),
        base_frame=text(plugin, "robotBaseFrame", "base_link"),
        odometry_source=source,
        publish_wheel_tf=flag(plugin, "publishWheelTF", False),
        publish_wheel_joint_state=flag(plugin, "publishWheelJointState", False),
        update_rate=_bounded(plugin, "updateRate", 100.0, sanity.MAX_UPDATE_RATE),
        robot_namespace=robot_namespace_tag(plugin.params),
    )
