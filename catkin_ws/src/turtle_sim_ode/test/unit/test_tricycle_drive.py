"""libgazebo_ros_tricycle_drive.so: the tags and defaults of GazeboRosTricycleDrive::Load, the motor control of
UpdateChild and motorController (the actuated wheel at speed / (diameter / 2), the steering at angular.z held to
+-pi/2, the wheel acceleration limits, the steering speed), the encoder odometry of UpdateOdometryEncoder and the
odometry publishOdometry reports (gazebo_plugins/src/gazebo_ros_tricycle_drive.cpp); then the tricycle of
models/tricycle_bot.urdf driven in the simulation."""
from __future__ import annotations

import math
from pathlib import Path

import pytest
from conftest import PACKAGE_ROOT, yaw_of
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.ros.plugins.tricycle_drive import POSE_COVARIANCE, encoder_odometry
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.tricycle_drive import (
    TRICYCLE_DRIVE,
    EncoderOdometry,
    TricycleRobot,
    applied_wheel_speed,
    steering_velocity,
    target_steering_angle,
    target_wheel_speed,
)
from turtle_sim_ode.world.simulation import Simulation

TRICYCLE = (Path(PACKAGE_ROOT) / "test" / "models" / "tricycle_bot.urdf").read_text()
DEFAULT_JOINTS = ["front_steering_joint", "front_wheel_joint", "left_wheel_joint", "right_wheel_joint"]
WHEELBASE = 0.5  # models/tricycle_bot.urdf: the steering axis 0.5 m ahead of the rear axle
SPEED_TOLERANCE = 0.02  # relative, of a speed measured over seconds of steady driving
RADIUS_TOLERANCE = 0.05  # relative


def config_of(tags):
    (config,) = read_plugins("m", [GazeboPlugin(TRICYCLE_DRIVE, "drive", tags)], {}, DEFAULT_JOINTS).drives
    return config


# --- Load --------------------------------------------------------------------------------------------------------
def test_defaults_are_load_s() -> None:
    """GazeboRosTricycleDrive::Load: the getParameter / getParameterBoolean / getJoint defaults."""
    config = config_of({})
    assert list(config.joints_needed) == DEFAULT_JOINTS
    assert (config.actuated_wheel_diameter, config.encoder_wheel_diameter, config.encoder_wheel_separation) == (
        0.15,
        0.15,
        0.5,
    )
    assert (config.wheel_torque, config.update_rate) == (5.0, 100.0)
    assert (config.wheel_acceleration, config.wheel_deceleration, config.wheel_speed_tolerance) == (0.0, 0.0, 0.01)
    assert (config.steering_speed, config.steering_angle_tolerance) == (0.0, 0.01)
    assert (config.command_topic, config.odometry_topic, config.odometry_frame, config.base_frame) == (
        "cmd_vel",
        "odom",
        "odom",
        "base_link",
    )
    assert config.odometry_source == "world"  # odomOptions' default WORLD
    assert not config.publish_wheel_tf and not config.publish_wheel_joint_state


def test_deceleration_defaults_to_the_acceleration() -> None:
    """Load: getParameter(wheel_deceleration_, "wheelDeceleration", wheel_acceleration_)."""
    assert config_of({"wheelAcceleration": "2.5"}).wheel_deceleration == 2.5
    config = config_of({"wheelAcceleration": "2.5", "wheelDeceleration": "1"})
    assert (config.wheel_acceleration, config.wheel_deceleration) == (2.5, 1.0)


def test_tags_are_read() -> None:
    config = config_of(
        {
            "odometrySource": "encoder",
            "publishWheelTF": "1",
            "publishWheelJointState": "true",
            "robotBaseFrame": "base_footprint",
            "steeringSpeed": "0.5",
        }
    )
    assert config.odometry_source == "encoder" and config.publish_wheel_tf and config.publish_wheel_joint_state
    assert (config.base_frame, config.steering_speed) == ("base_footprint", 0.5)


@pytest.mark.parametrize(
    "tags, message",
    [
        ({"odometrySource": "gps"}, "<odometrySource> must be encoder or world"),
        ({"wheelTorque": "-1"}, "<wheelTorque>"),
        ({"actuatedWheelDiameter": "0"}, "<actuatedWheelDiameter>"),
        ({"encoderWheelSeparation": "inf"}, "<encoderWheelSeparation>"),
        ({"steeringSpeed": "fast"}, "<steeringSpeed> must be a number"),
        ({"publishWheelTF": "yes"}, "<publishWheelTF> must be true or false"),
    ],
)
def test_bad_tags_refuse_the_model(tags, message) -> None:
    with pytest.raises(ModelError, match=message):
        config_of(tags)


def test_missing_joints_refuse_the_model() -> None:
    """Load: getJoint throws for a joint the model does not have."""
    with pytest.raises(ModelError, match="no movable joint"):
        read_plugins("m", [GazeboPlugin(TRICYCLE_DRIVE, "drive", {})], {}, DEFAULT_JOINTS[:3])


# --- UpdateChild / motorController -------------------------------------------------------------------------------
def test_wheel_speed_and_steering_angle_for_a_command() -> None:
    """UpdateChild: target_wheel_roation_speed = cmd_.speed / (diameter_actuated_wheel_ / 2), target_steering_angle
    = cmd_.angle (angular.z); motorController truncates the angle to +-M_PI / 2."""
    assert target_wheel_speed(0.3, 0.15) == pytest.approx(4.0)
    assert target_wheel_speed(-0.5, 0.2) == pytest.approx(-5.0)
    assert target_steering_angle(0.4) == 0.4
    assert target_steering_angle(2.0) == math.pi / 2 and target_steering_angle(-3.0) == -math.pi / 2


def test_acceleration_limit_per_update() -> None:
    """motorController: with wheel_acceleration_ > 0, diff = current - target; |diff| < tolerance keeps the current
    speed; |diff| > acceleration * dt moves by acceleration * dt down (diff > 0) or deceleration * dt up; else the
    target."""
    # No limit: the target at once.
    assert applied_wheel_speed(0.0, 4.0, 0.02, 0.0, 0.0, 0.01) == 4.0
    # Speeding up from 0 to 4 rad/s at 2 rad/s^2 (deceleration 3) over 0.02 s: up by deceleration * dt.
    assert applied_wheel_speed(0.0, 4.0, 0.02, 2.0, 3.0, 0.01) == pytest.approx(0.06)
    # Slowing down from 4 to 0: down by acceleration * dt.
    assert applied_wheel_speed(4.0, 0.0, 0.02, 2.0, 3.0, 0.01) == pytest.approx(3.96)
    # Within the tolerance: the current speed; within one step: the target.
    assert applied_wheel_speed(3.995, 4.0, 0.02, 2.0, 3.0, 0.01) == 3.995
    assert applied_wheel_speed(3.98, 4.0, 0.02, 2.0, 3.0, 0.01) == 4.0


def test_steering_speed_control() -> None:
    """motorController with steering_speed_ > 0: 0 within steering_angle_tolerance_ of the target; +steering_speed_
    where diff_angle (current - target) < target_speed (the wheel's target speed, as upstream compares), else
    -steering_speed_."""
    assert steering_velocity(0.0, 0.4, 0.0, 0.5, 0.01) == 0.5  # diff -0.4 < 0
    assert steering_velocity(0.4, 0.0, 0.0, 0.5, 0.01) == -0.5  # diff 0.4 >= 0
    assert steering_velocity(0.395, 0.4, 4.0, 0.5, 0.01) == 0.0  # within the tolerance
    # Upstream's comparison with the wheel speed: diff 0.4 < 4 rad/s turns the steering further up.
    assert steering_velocity(0.4, 0.0, 4.0, 0.5, 0.01) == 0.5


# --- UpdateOdometryEncoder ---------------------------------------------------------------------------------------
def test_encoder_odometry_straight() -> None:
    """UpdateOdometryEncoder: sl = vl * (diameter / 2) * dt, sr likewise; both wheels at 2 rad/s with 0.075 m radius
    for 1 s: 0.15 m ahead, no turn."""
    odometry = EncoderOdometry(0.075, 0.5)
    odometry.reset(0.0)
    for step in range(1, 1001):
        odometry.update(2.0, 2.0, step * 0.001)
    assert (odometry.x, odometry.y, odometry.yaw) == (pytest.approx(0.15), pytest.approx(0.0), 0.0)
    assert odometry.linear == (pytest.approx(0.15), pytest.approx(0.0)) and odometry.angular == 0.0


def test_encoder_odometry_of_a_known_step() -> None:
    """UpdateOdometryEncoder, one step of 0.5 s with vl 2, vr 1 rad/s, radius 0.075, b 0.5: sl 0.075, sr 0.0375,
    dtheta = (sl - sr) / b = 0.075, dx = (sl + sr) / 2 cos(theta + (sl - sr) / (2 b)), dy with sin; twist dx / dt,
    dy / dt (odometry frame), w = dtheta / dt."""
    odometry = EncoderOdometry(0.075, 0.5)
    odometry.reset(1.0)
    odometry.update(2.0, 1.0, 1.5)
    half = (0.075 + 0.0375) / 2
    assert odometry.yaw == pytest.approx(0.075)
    assert odometry.x == pytest.approx(half * math.cos(0.0375))
    assert odometry.y == pytest.approx(half * math.sin(0.0375))
    assert odometry.linear == (pytest.approx(odometry.x / 0.5), pytest.approx(odometry.y / 0.5))
    assert odometry.angular == pytest.approx(0.15)


def test_odometry_message_fields() -> None:
    """publishOdometry: pose covariance 1e-5, 1e-5, 1e12 x3, 1e-3 (the twist's stays 0); with the encoder source
    the pose of UpdateOdometryEncoder (z 0, yaw only)."""
    assert [POSE_COVARIANCE[7 * i] for i in range(6)] == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
    assert sum(POSE_COVARIANCE) == sum(POSE_COVARIANCE[7 * i] for i in range(6))
    sim = Simulation()
    sim.spawn_urdf("t", TRICYCLE.replace(">world<", ">encoder<"), (0, 0, 0.08, 0, 0, 0))
    robot = sim.robots["t"]
    robot.odometry.x, robot.odometry.yaw, robot.odometry.angular = 1.0, 0.5, 0.2
    position, orientation, _, angular = encoder_odometry(robot)
    assert position == (1.0, 0.0, 0.0) and yaw_of(orientation) == pytest.approx(0.5) and angular[2] == 0.2


# --- hypothesis: the pure functions ------------------------------------------------------------------------------
numbers = st.floats(-1e4, 1e4, allow_nan=False)
rates = st.floats(0.0, 1e3, allow_nan=False)


@given(current=numbers, target=numbers, dt=st.floats(1e-4, 1.0), acceleration=rates, deceleration=rates, tol=rates)
def test_wheel_speed_respects_the_limits(current, target, dt, acceleration, deceleration, tol) -> None:
    applied = applied_wheel_speed(current, target, dt, acceleration, deceleration, tol)
    assert math.isfinite(applied)
    if acceleration > 0:
        # Either the target, the current speed (within tolerance) or one limited step from the current speed.
        step = max(acceleration, deceleration) * dt
        assert applied == target or abs(applied - current) <= step * (1 + 1e-12) + 1e-12


@given(angle=st.floats(allow_nan=False), speed=numbers, steering=st.floats(1e-3, 10.0), current=numbers)
def test_steering_stays_within_its_limits(angle, speed, steering, current) -> None:
    target = target_steering_angle(angle)
    assert -math.pi / 2 <= target <= math.pi / 2
    assert steering_velocity(current, target, speed, steering, 0.01) in (0.0, steering, -steering)


@given(left=numbers, right=numbers, dt=st.floats(1e-4, 1.0), radius=st.floats(1e-3, 1.0), b=st.floats(1e-2, 10.0))
def test_encoder_odometry_is_finite(left, right, dt, radius, b) -> None:
    odometry = EncoderOdometry(radius, b)
    odometry.reset(0.0)
    odometry.update(left, right, dt)
    odometry.update(math.nan, right, 2 * dt)  # a NaN speed is skipped
    values = (odometry.x, odometry.y, odometry.yaw, *odometry.linear, odometry.angular)
    assert all(math.isfinite(value) for value in values)


# --- in the simulation -------------------------------------------------------------------------------------------
def spawn(urdf: str = TRICYCLE):
    sim = Simulation()
    assert sim.spawn_urdf("t", urdf, (0, 0, 0.08, 0, 0, 0)) == []
    robot = sim.robots["t"]
    assert isinstance(robot, TricycleRobot)
    run(sim, 0.5)  # settle on the wheels
    return sim, robot, sim.models["t"]


def run(sim: Simulation, seconds: float) -> None:
    for _ in range(int(round(seconds / sim.physics.time_step))):
        sim.step()


def circumradius(a, b, c) -> float:
    area = abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2
    return math.dist(a, b) * math.dist(b, c) * math.dist(a, c) / (4 * area)


def test_drives_straight_at_the_commanded_speed() -> None:
    sim, robot, model = spawn()
    robot.drive.set_command(0.3, 0.0, sim.sim_time)
    run(sim, 1.0)
    (x0, y0, _), _ = model.link_pose("base_link")
    run(sim, 2.0)
    (x1, y1, _), _ = model.link_pose("base_link")
    assert (x1 - x0) / 2.0 == pytest.approx(0.3, rel=SPEED_TOLERANCE) and abs(y1 - y0) < 0.01
    assert robot.drive.wheel.rate() == pytest.approx(0.3 / 0.075, rel=SPEED_TOLERANCE)


@pytest.mark.parametrize("angle", [0.4, -0.25])
def test_turns_on_the_circle_the_geometry_implies(angle) -> None:
    """A steering angle d with the front wheel L ahead of the rear axle: the rear axle's centre (base_link) goes
    round a circle of radius L / tan(d) at yaw rate v sin(d) / L."""
    sim, robot, model = spawn()
    robot.drive.set_command(0.3, angle, sim.sim_time)
    run(sim, 1.0)
    assert robot.drive.steering.angle() == pytest.approx(angle, abs=1e-3)  # put there (Joint::SetPosition)
    points = []
    for _ in range(3):
        points.append(model.link_pose("base_link")[0][:2])
        run(sim, 2.0)
    assert circumradius(*points) == pytest.approx(WHEELBASE / math.tan(abs(angle)), rel=RADIUS_TOLERANCE)
    _, angular = model.link_twist("base_link")
    assert angular[2] == pytest.approx(0.3 * math.sin(angle) / WHEELBASE, rel=SPEED_TOLERANCE)


def test_wheel_acceleration_limits_the_ramp() -> None:
    """motorController with wheelAcceleration 2 rad/s^2 (deceleration the same) at 50 Hz and 1 ms steps: UpdateChild
    runs it when more than 20 ms have passed (at 21 ms, with dt 0.021) and moves its last update on by 20 ms, so
    the wheel gains 2 x 0.021 rad/s every 20 ms: 2.1 rad/s a second, 4 rad/s in about 1.9 s."""
    sim, robot, _ = spawn(TRICYCLE.replace("<wheelAcceleration>0<", "<wheelAcceleration>2<"))
    robot.drive.set_command(0.3, 0.0, sim.sim_time)
    run(sim, 1.0)
    assert robot.drive.wheel.rate() == pytest.approx(2.1, abs=0.15)
    run(sim, 1.5)
    assert robot.drive.wheel.rate() == pytest.approx(4.0, abs=0.02)


def test_steering_speed_turns_the_steering_at_that_speed() -> None:
    sim, robot, _ = spawn(TRICYCLE.replace("<steeringSpeed>0<", "<steeringSpeed>0.5<"))
    robot.drive.set_command(0.0, 0.4, sim.sim_time)
    run(sim, 0.4)
    assert robot.drive.steering.angle() == pytest.approx(0.2, abs=0.03)  # 0.5 rad/s for 0.4 s
    run(sim, 1.0)
    assert robot.drive.steering.angle() == pytest.approx(0.4, abs=0.02)  # held within the tolerance


def test_encoder_odometry_follows_the_wheels() -> None:
    """odometrySource encoder: straight, the encoder x matches the distance driven; turning left, the encoder yaw
    goes the other way, by upstream's (sl - sr) / b with the left wheel inside."""
    sim, robot, model = spawn(TRICYCLE.replace(">world<", ">encoder<"))
    (x0, _, _), _ = model.link_pose("base_link")
    robot.drive.set_command(0.3, 0.0, sim.sim_time)
    run(sim, 2.0)
    (x1, _, _), _ = model.link_pose("base_link")
    assert robot.odometry.x == pytest.approx(x1 - x0, rel=0.02) and abs(robot.odometry.yaw) < 0.01
    _, start = model.link_pose("base_link")
    robot.drive.set_command(0.3, 0.4, sim.sim_time)
    run(sim, 2.0)
    _, end = model.link_pose("base_link")
    turned = yaw_of(end) - yaw_of(start)
    assert turned > 0.3 and robot.odometry.yaw == pytest.approx(-turned, rel=0.05)


def test_a_command_not_finite_is_ignored_and_a_reset_stops() -> None:
    sim, robot, _ = spawn()
    assert robot.drive.set_command(0.2, 0.1, sim.sim_time)
    assert not robot.drive.set_command(math.nan, 0.0, sim.sim_time)
    assert not robot.drive.set_command(0.1, math.inf, sim.sim_time)
    assert robot.drive.command == (0.2, 0.1)
    run(sim, 0.5)
    sim.reset_world()
    assert robot.drive.command == (0.0, 0.0) and robot.odometry.x == 0.0
    run(sim, 0.5)
    assert abs(robot.drive.wheel.rate()) < 0.05


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    commands=st.lists(st.tuples(st.floats(width=32), st.floats(width=32)), min_size=1, max_size=3),
    acceleration=st.floats(0.0, 100.0, allow_subnormal=False),
    steering_speed=st.floats(0.0, 5.0, allow_subnormal=False),
)
def test_any_commands_keep_the_sim_alive(commands, acceleration, steering_speed) -> None:
    urdf = TRICYCLE.replace("<wheelAcceleration>0<", f"<wheelAcceleration>{acceleration!r}<")
    urdf = urdf.replace("<steeringSpeed>0<", f"<steeringSpeed>{steering_speed!r}<")
    sim = Simulation()
    sim.spawn_urdf("t", urdf, (0, 0, 0.08, 0, 0, 0))
    robot, model = sim.robots["t"], sim.models["t"]
    for speed, angle in commands:
        robot.drive.set_command(speed, angle, sim.sim_time)
        run(sim, 0.05)
    position, orientation = model.link_pose("base_link")
    assert all(math.isfinite(value) for value in position + orientation)
    assert abs(robot.drive.applied[0]) <= 1e4  # the wheel speed held to MAX_WHEEL_SPEED
    # the joint's limits, as ODE holds them (softly, by its ERP: a hair past either side, e.g. -1.2000009 rad)
    assert abs(robot.drive.steering.angle()) <= 1.2 + 0.05
