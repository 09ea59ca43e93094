"""Sensor data to measurements and the periodic update, as ros_filter.cpp does them (RosFilter::preparePose,
::prepareTwist, ::prepareAcceleration, ::forceTwoD, ::integrateMeasurements, ::periodicUpdate), worked by hand."""
from __future__ import annotations

import math
from typing import Dict, Tuple

import numpy as np
import pytest

from robot_localization.ekf import AX, AZ, PITCH, ROLL, VROLL, VX, VY, VYAW, X, Y, YAW, Z
from robot_localization.localizer import Localizer
from robot_localization.params import Config
from robot_localization.prepare import ImuData, PoseData, TwistData, force_two_d
from robot_localization.rotations import rpy_to_matrix, rpy_to_quaternion

IDENTITY_Q = (0.0, 0.0, 0.0, 1.0)


def flags(*indices: int) -> list:
    return [i in indices for i in range(15)]


def diagonal(values) -> list:
    return np.diag(values).flatten().tolist()


class Tf:
    """A static tf tree: {(target, source): (R, t)}, the inverse looked up too."""

    def __init__(self, transforms: Dict[Tuple[str, str], Tuple[np.ndarray, np.ndarray]]) -> None:
        self.transforms = dict(transforms)
        for (target, source), (r, t) in transforms.items():
            self.transforms[(source, target)] = (r.T, -r.T @ t)

    def __call__(self, target: str, source: str, stamp: float):
        return self.transforms.get((target, source))


def localizer(params: dict, tf: Tf = Tf({})) -> Localizer:
    return Localizer(Config(params), tf, now=0.0)


def imu(stamp, orientation=IDENTITY_Q, rate=(0.0, 0.0, 0.0), acceleration=(0.0, 0.0, 0.0), frame="imu_link"):
    small = diagonal([1e-4] * 3)
    return ImuData(stamp, frame, orientation, small, rate, small, acceleration, small)


def queued(loc: Localizer):
    return [entry[2] for entry in sorted(loc.queue)]


def test_force_two_d():
    values, covariance, update = np.ones(15), np.ones((15, 15)), [False] * 15
    force_two_d(values, covariance, update)
    for index in (Z, ROLL, PITCH, VX + 2, VROLL, VROLL + 1, AZ):
        assert values[index] == 0.0 and covariance[index, index] == 1e-6 and update[index]
    assert values[X] == 1.0 and not update[X]


def test_imu_mounted_sideways_turns_roll_into_pitch():
    """preparePose with imuData: rpy - mounting rpy, then turned by the mounting yaw (pi/2): an IMU roll of 0.1
    is the robot's pitch; its yaw (1.0 + pi/2 as the IMU reads it) is the robot's 1.0; the roll-only mask becomes
    pitch."""
    tf = Tf({("base_link", "imu_link"): (rpy_to_matrix(0, 0, math.pi / 2), np.array([0.2, 0.0, 0.1]))})
    loc = localizer({"imu0": "imu", "imu0_config": flags(ROLL, YAW)}, tf)
    loc.imu(loc.config.sensors[0], imu(1.0, rpy_to_quaternion(0.1, 0.0, 1.0 + math.pi / 2)))
    (measurement,) = queued(loc)
    np.testing.assert_allclose(measurement.values[ROLL : YAW + 1], [0.0, 0.1, 1.0], atol=1e-12)
    assert measurement.update_vector == flags(PITCH, YAW)


def test_twist_of_a_sensor_off_the_origin():
    """prepareTwist: v_base = R v_sensor + t x w_state; a sensor 1 m ahead reading (1, 0.5) while the robot turns
    at 0.5 rad/s measures vx 1, vy 0 at base_link."""
    tf = Tf({("base_link", "sensor"): (np.eye(3), np.array([1.0, 0.0, 0.0]))})
    loc = localizer({"twist0": "t", "twist0_config": flags(VX, VY)}, tf)
    loc.filter.state[VYAW] = 0.5
    loc.twist(loc.config.sensors[0], TwistData(1.0, "sensor", (1.0, 0.5, 0.0), (0, 0, 0), diagonal([0.01] * 6)))
    (measurement,) = queued(loc)
    np.testing.assert_allclose(measurement.values[VX : VY + 1], [1.0, 0.0], atol=1e-12)


def test_differential_orientation_becomes_a_rate():
    """preparePose differential: (previous^-1 current) / dt; yaw 0.3 then 0.4 after 0.1 s: vyaw 1.0, the twist
    covariance (R + R_previous) dt = 2e-4 * 0.1; the first message only starts the chain."""
    loc = localizer(
        {"imu0": "imu", "imu0_config": flags(YAW), "imu0_differential": True},
        Tf({("base_link", "imu_link"): (np.eye(3), np.zeros(3))}),
    )
    sensor = loc.config.sensors[0]
    loc.imu(sensor, imu(1.0, rpy_to_quaternion(0, 0, 0.3)))
    assert loc.queue == []
    loc.imu(sensor, imu(1.1, rpy_to_quaternion(0, 0, 0.4)))
    (measurement,) = queued(loc)
    assert measurement.update_vector == flags(VYAW)
    assert measurement.values[VYAW] == pytest.approx(1.0)
    assert measurement.covariance[VYAW, VYAW] == pytest.approx(2e-4 * 0.1)


def test_relative_pose_starts_at_zero():
    """preparePose relative: initial^-1 current. From (1, 2, yaw 0.5), 1 m straight on: x 1, y 0, yaw 0."""
    loc = localizer({"pose0": "p", "pose0_config": flags(X, Y, YAW), "pose0_relative": True})
    sensor, q = loc.config.sensors[0], rpy_to_quaternion(0, 0, 0.5)
    loc.pose(sensor, PoseData(1.0, "odom", (1.0, 2.0, 0.0), q, diagonal([0.01] * 6)))
    loc.pose(sensor, PoseData(2.0, "odom", (1.0 + math.cos(0.5), 2.0 + math.sin(0.5), 0.0), q, diagonal([0.01] * 6)))
    first, second = queued(loc)
    np.testing.assert_allclose(first.values[:6], np.zeros(6), atol=1e-12)
    np.testing.assert_allclose(second.values[[X, Y, YAW]], [1.0, 0.0, 0.0], atol=1e-12)


def test_gravity_is_removed_along_the_imu_orientation():
    """prepareAcceleration: a ~ a - R' (0, 0, g); tilted 0.1 rad in pitch at rest, only gravity: nothing left."""
    g = 9.80665
    loc = localizer(
        {"imu0": "imu", "imu0_config": flags(AX, AX + 1, AZ), "imu0_remove_gravitational_acceleration": True}, Tf({})
    )
    reading = rpy_to_matrix(0, 0.1, 0).T @ np.array([0.0, 0.0, g])
    loc.imu(loc.config.sensors[0], imu(1.0, rpy_to_quaternion(0, 0.1, 0), acceleration=reading, frame="base_link"))
    (measurement,) = queued(loc)
    np.testing.assert_allclose(measurement.values[AX : AZ + 1], np.zeros(3), atol=1e-12)


def test_imu_parts_with_covariance_minus_one_are_absent():
    loc = localizer({"imu0": "imu", "imu0_config": flags(YAW, VYAW)}, Tf({}))
    data = imu(1.0, frame="base_link")._replace(orientation_covariance=[-1.0] + [0.0] * 8)
    loc.imu(loc.config.sensors[0], data)
    (measurement,) = queued(loc)
    assert measurement.update_vector == flags(VYAW)


def test_old_and_pre_reset_messages_are_ignored():
    loc = localizer({"twist0": "t", "twist0_config": flags(VX)})
    warnings = []
    loc.warn = warnings.append
    sensor, twist = loc.config.sensors[0], TwistData(2.0, "base_link", (1, 0, 0), (0, 0, 0), diagonal([0.01] * 6))
    loc.twist(sensor, twist._replace(stamp=0.0))  # stamp 0: not after the last set_pose (none, time 0)
    loc.twist(sensor, twist)
    loc.twist(sensor, twist._replace(stamp=1.5))
    assert len(loc.queue) == 1 and len(warnings) == 2


def test_update_fuses_in_time_order_then_predicts_after_the_sensor_timeout():
    """integrateMeasurements: queue in stamp order up to now; with an empty queue and the last measurement older
    than sensor_timeout, predict to now (the output's stamp); the same stamp twice is not published again."""
    loc = localizer({"twist0": "t", "twist0_config": flags(VX), "sensor_timeout": 0.5})
    sensor = loc.config.sensors[0]
    for stamp in (1.2, 1.0, 1.4):  # arrive out of order; each topic must not go back in time: use three inputs
        loc.last_message_times.clear()
        loc.twist(sensor, TwistData(stamp, "base_link", (1.0, 0, 0), (0, 0, 0), diagonal([1e-4] * 6)))
    estimate = loc.update(1.3)
    assert estimate.stamp == 1.2 and estimate.publish and len(loc.queue) == 1
    assert estimate.state[X] == pytest.approx(0.2, abs=1e-3)
    estimate = loc.update(1.5)
    assert estimate.stamp == 1.4 and estimate.state[X] == pytest.approx(0.4, abs=1e-3)
    assert not loc.update(1.6).publish  # nothing new, within the time-out
    estimate = loc.update(2.0)
    assert estimate.stamp == 2.0 and estimate.state[X] == pytest.approx(1.0, abs=1e-3)


def test_set_pose_takes_the_pose_and_ignores_older_messages():
    loc = localizer({"twist0": "t", "twist0_config": flags(VX)})
    loc.set_pose(PoseData(5.0, "odom", (1.0, 2.0, 0.0), rpy_to_quaternion(0, 0, 0.7), diagonal([0.2] * 6)), now=5.0)
    assert loc.filter.state[[X, Y, YAW]].tolist() == pytest.approx([1.0, 2.0, 0.7])
    assert loc.filter.covariance[X, X] == 0.2 and loc.filter.covariance[VX, VX] == 1e-6
    loc.twist(loc.config.sensors[0], TwistData(4.0, "base_link", (1, 0, 0), (0, 0, 0), diagonal([0.01] * 6)))
    assert loc.queue == []


def test_disabled_at_startup_waits_and_toggle_off_drops_measurements():
    loc = localizer({"twist0": "t", "twist0_config": flags(VX), "disabled_at_startup": True})
    sensor = loc.config.sensors[0]
    loc.twist(sensor, TwistData(1.0, "base_link", (1, 0, 0), (0, 0, 0), diagonal([0.01] * 6)))
    assert loc.update(1.0) is None
    loc.enabled = True
    assert loc.update(1.0).state[VX] == 1.0
    loc.toggled_on = False
    loc.twist(sensor, TwistData(1.5, "base_link", (3, 0, 0), (0, 0, 0), diagonal([0.01] * 6)))
    assert loc.update(1.5).state[VX] == 1.0 and loc.queue == []
