"""The filter core (ekf.py) against cra-ros-pkg/robot_localization noetic-devel's equations, worked by hand here:
src/ekf.cpp Ekf::predict and Ekf::correct, src/filter_base.cpp FilterBase::processMeasurement, ::reset,
::checkMahalanobisThreshold, ::computeDynamicProcessNoiseCovariance."""
from __future__ import annotations

import math

import numpy as np
import pytest

from robot_localization.ekf import (
    AX,
    DEFAULT_PROCESS_NOISE,
    STATE_SIZE,
    VX,
    VY,
    VYAW,
    X,
    Y,
    YAW,
    Z,
    Ekf,
    Measurement,
    transfer_function,
    transfer_function_jacobian,
)


def measurement(values: dict, variances: dict, time: float = 1.0, threshold: float = math.inf) -> Measurement:
    vector, covariance, update = np.zeros(STATE_SIZE), np.zeros((STATE_SIZE, STATE_SIZE)), [False] * STATE_SIZE
    for index, value in values.items():
        vector[index], update[index] = value, True
    for index, variance in variances.items():
        covariance[index, index] = variance
    return Measurement(time, vector, covariance, update, threshold)


def moving_filter() -> Ekf:
    """Heading +y (yaw pi/2), level; vx 1, vy 0.5, vyaw 0.2, ax 0.4; P = 0.1 I."""
    ekf = Ekf()
    ekf.state[YAW], ekf.state[VX], ekf.state[VY], ekf.state[VYAW], ekf.state[AX] = math.pi / 2, 1.0, 0.5, 0.2, 0.4
    ekf.covariance = np.eye(STATE_SIZE) * 0.1
    return ekf


def test_reset_values_of_filter_base():
    """FilterBase::reset: zero state, P = 1e-9 I, the default process noise diagonal."""
    ekf = Ekf()
    assert not ekf.initialized
    np.testing.assert_array_equal(ekf.state, np.zeros(STATE_SIZE))
    np.testing.assert_array_equal(ekf.covariance, np.eye(STATE_SIZE) * 1e-9)
    assert np.diag(DEFAULT_PROCESS_NOISE).tolist() == [
        0.05,
        0.05,
        0.06,
        0.03,
        0.03,
        0.06,
        0.025,
        0.025,
        0.04,
        0.01,
        0.01,
        0.02,
        0.01,
        0.01,
        0.015,
    ]


def test_predict_one_step_by_hand():
    """Ekf::predict with yaw pi/2 (cy 0, sy 1), roll = pitch = 0, dt 0.1:
    x += (cy sp sr - sy cr) vy dt = -0.05;  y += sy cp (vx dt + ax dt^2/2) = 0.1 + 0.002;
    yaw += cr/cp vyaw dt = 0.02;  vx += ax dt = 0.04."""
    ekf = moving_filter()
    ekf.predict(0.1)
    assert ekf.state[X] == pytest.approx(-0.05)
    assert ekf.state[Y] == pytest.approx(0.102)
    assert ekf.state[YAW] == pytest.approx(math.pi / 2 + 0.02)
    assert ekf.state[VX] == pytest.approx(1.04)
    assert ekf.state[VY] == pytest.approx(0.5)


def test_predict_covariance_by_hand():
    """P = J P J' + dt Q. Row X of J: J[X,X] 1, J[X,VY] = -sy cr dt = -0.1, J[X,AY] = -0.005, and
    J[X,YAW] = dFx_dY = (-sy cp) (vx dt + ax dt^2/2) = -0.102; row Y: J[Y,Y] 1, J[Y,VX] 0.1, J[Y,AX] 0.005,
    J[Y,YAW] = dFy_dY = (cy sp sr - sy cr) vy dt = -0.05. With P = 0.1 I:
    P[X,X] = 0.1 (1 + 0.01 + 0.000025 + 0.010404) + 0.1 * 0.05;  P[X,Y] = 0.1 (-0.102)(-0.05)."""
    ekf = moving_filter()
    ekf.predict(0.1)
    assert ekf.covariance[X, X] == pytest.approx(0.1 * (1 + 0.01 + 0.000025 + 0.010404) + 0.005)
    assert ekf.covariance[X, Y] == pytest.approx(0.1 * 0.102 * 0.05)
    assert ekf.covariance[YAW, YAW] == pytest.approx(0.1 * (1 + 0.01) + 0.1 * 0.06)  # J[YAW,VYAW] = dt
    np.testing.assert_allclose(ekf.covariance, ekf.covariance.T, atol=1e-15)


def test_jacobian_is_the_derivative_of_the_transfer_function():
    """transferFunctionJacobian_ is 'analytically derived from the transfer function': check it numerically at a
    tilted, turning state (finite differences of x -> F(x) x)."""
    state = np.array([1.0, 2.0, 0.3, 0.2, -0.3, 1.1, 1.5, -0.4, 0.2, 0.3, -0.2, 0.5, 0.1, 0.2, -0.1])
    delta = 0.05

    def step(x):
        return transfer_function(x, delta) @ x

    numeric = np.zeros((STATE_SIZE, STATE_SIZE))
    for i in range(STATE_SIZE):
        h = np.zeros(STATE_SIZE)
        h[i] = 1e-6
        numeric[:, i] = (step(state + h) - step(state - h)) / 2e-6
    np.testing.assert_allclose(transfer_function_jacobian(state, delta), numeric, atol=1e-7)


def test_correct_scalar_by_hand():
    """Ekf::correct with x = 1, P[x,x] = 0.1, P[vx,x] = 0.05, z = 2, R = 0.3: K = P H'/(H P H' + R) =
    (0.25 for x, 0.125 for vx); x = 1.25, vx = 0.125; Joseph form P[x,x] = 0.75^2 0.1 + 0.25^2 0.3 = 0.075."""
    ekf = Ekf()
    ekf.state[X] = 1.0
    ekf.covariance[X, X] = ekf.covariance[VX, VX] = 0.1
    ekf.covariance[X, VX] = ekf.covariance[VX, X] = 0.05
    assert ekf.correct(measurement({X: 2.0}, {X: 0.3}))
    assert ekf.state[X] == pytest.approx(1.25)
    assert ekf.state[VX] == pytest.approx(0.125)
    assert ekf.covariance[X, X] == pytest.approx(0.075)
    assert ekf.covariance[VX, VX] == pytest.approx(0.1 - 0.05 * 0.05 / 0.4)  # P - K S K'
    np.testing.assert_allclose(ekf.covariance, ekf.covariance.T)


def test_correct_wraps_the_angle_innovation_and_the_state():
    """yaw 3.1, z -3.1: innovation -6.2 + 2 pi; with K = 0.5 the yaw passes pi and wraps to the other side."""
    ekf = Ekf()
    ekf.state[YAW] = 3.1
    ekf.covariance[YAW, YAW] = 0.2
    ekf.correct(measurement({YAW: -3.1}, {YAW: 0.2}))
    expected = 3.1 + 0.5 * (2 * math.pi - 6.2)
    assert ekf.state[YAW] == pytest.approx(expected - 2 * math.pi)


@pytest.mark.parametrize("sigmas, accepted", [(1.5, False), (2.0, True), (math.inf, True)])
def test_mahalanobis_gate(sigmas, accepted):
    """checkMahalanobisThreshold: innovation 1, H P H' + R = 0.4: squared distance 2.5 against sigmas^2."""
    ekf = Ekf()
    ekf.covariance[X, X] = 0.1
    assert ekf.correct(measurement({X: 1.0}, {X: 0.3}, threshold=sigmas)) is accepted
    assert ekf.state[X] == pytest.approx(0.25 if accepted else 0.0)


def test_bad_measurement_variances_and_values():
    """A negative variance is used as its absolute value, one below 1e-9 becomes 1e-9, NaN and inf are left out."""
    ekf = Ekf()
    ekf.covariance[X, X] = ekf.covariance[Y, Y] = 0.1
    ekf.correct(measurement({X: 2.0, Y: float("nan"), Z: float("inf")}, {X: -0.3, Y: 1.0, Z: 1.0}))
    assert ekf.state[X] == pytest.approx(0.5) and ekf.state[Y] == 0.0 and ekf.state[Z] == 0.0
    ekf = Ekf()
    ekf.covariance[X, X] = 1e-9
    ekf.correct(measurement({X: 2.0}, {X: 0.0}))
    assert ekf.state[X] == pytest.approx(1.0)  # equal weights: 1e-9 against 1e-9


def test_first_measurement_initializes_the_measured_entries_only():
    """processMeasurement: the first measurement sets its entries of the state and of P, no predict."""
    ekf = Ekf()
    ekf.process_measurement(measurement({X: 3.0, VYAW: 0.2}, {X: 0.5, VYAW: 0.01}, time=5.0))
    assert ekf.initialized and ekf.last_measurement_time == 5.0
    assert ekf.state[X] == 3.0 and ekf.state[VYAW] == 0.2 and ekf.state[Y] == 0.0
    assert ekf.covariance[X, X] == 0.5 and ekf.covariance[VYAW, VYAW] == 0.01 and ekf.covariance[Y, Y] == 1e-9


def test_later_measurements_predict_forward_only():
    """A measurement older than the last one corrects without predicting and leaves the time as it was."""
    ekf = Ekf()
    ekf.process_measurement(measurement({VX: 1.0}, {VX: 0.01}, time=1.0))
    ekf.process_measurement(measurement({VX: 1.0}, {VX: 0.01}, time=1.5))
    assert ekf.state[X] == pytest.approx(0.5) and ekf.last_measurement_time == 1.5
    ekf.process_measurement(measurement({VX: 1.0}, {VX: 0.01}, time=1.2))
    assert ekf.state[X] == pytest.approx(0.5) and ekf.last_measurement_time == 1.5


def test_process_noise_scales_with_delta_and_dynamic_noise_with_speed():
    """P += delta Q; computeDynamicProcessNoiseCovariance multiplies the pose block by |v|^2 (v: the 6 rates)."""
    ekf = Ekf()
    ekf.covariance = np.zeros((STATE_SIZE, STATE_SIZE))
    ekf.predict(0.5)
    np.testing.assert_allclose(np.diag(ekf.covariance), 0.5 * np.diag(DEFAULT_PROCESS_NOISE))
    ekf = Ekf()
    ekf.dynamic_process_noise = True
    ekf.covariance = np.zeros((STATE_SIZE, STATE_SIZE))
    ekf.state[VX], ekf.state[VYAW] = 0.6, 0.8  # |v| = 1.0 ... scaled by 1
    noise = ekf.scaled_process_noise()
    np.testing.assert_allclose(noise, DEFAULT_PROCESS_NOISE)
    ekf.state[VX], ekf.state[VYAW] = 1.2, 1.6  # |v| = 2: the pose block times 4, the rest as it was
    noise = ekf.scaled_process_noise()
    assert noise[X, X] == pytest.approx(0.2) and noise[VX, VX] == pytest.approx(0.025)


def test_bag_time_jump_becomes_a_small_step():
    """validateDelta: a step over 100000 s (a bag replayed) is taken as 0.01 s."""
    ekf = Ekf()
    ekf.process_measurement(measurement({VX: 1.0}, {VX: 0.01}, time=1.0))
    ekf.process_measurement(measurement({VX: 1.0}, {VX: 0.01}, time=2e5))
    assert ekf.state[X] == pytest.approx(0.01)
