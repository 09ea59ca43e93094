"""Invariants of the whole filter (localizer + EKF) on generated input sequences (Hypothesis): the estimate error
covariance stays symmetric positive definite and the state finite; two_d_mode keeps z, roll and pitch at 0; a
constant true state fed again and again is reached from a wrong start."""
from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from robot_localization.ekf import PITCH, ROLL, VX, VYAW, X, Y, YAW, Z
from robot_localization.localizer import Localizer
from robot_localization.params import Config
from robot_localization.prepare import ImuData, PoseData, TwistData
from robot_localization.rotations import rpy_to_matrix, rpy_to_quaternion

# Double precision's limit: wild inputs (an IMU turning 1000s of rad/s differentially) blow the covariance up to
# 1e20, where rounding leaves eigenvalues and asymmetries of 1e-16 times the largest (upstream's Eigen alike).
RELATIVE_PRECISION = 1e-12

angles = st.floats(-math.pi, math.pi)
speeds = st.floats(-2.0, 2.0)
variances = st.floats(1e-6, 10.0)
steps = st.floats(0.001, 0.2)
inputs = st.one_of(
    st.tuples(st.just("odom"), steps, speeds, speeds, variances),
    st.tuples(st.just("imu"), steps, st.tuples(angles, angles, angles), speeds, variances),
    st.tuples(st.just("pose"), steps, st.tuples(speeds, speeds, angles), st.just(0.0), variances),
)


def params(two_d_mode: bool) -> dict:
    everything = [True] * 15
    return {
        "two_d_mode": two_d_mode,
        "odom0": "odom",
        "odom0_config": [False] * 6 + [True, True, True, False, False, True] + [False] * 3,
        "imu0": "imu",
        "imu0_config": everything,
        "imu0_differential": True,
        "imu0_remove_gravitational_acceleration": True,
        "pose0": "pose",
        "pose0_config": [True, True, True, True, True, True] + [False] * 9,
    }


def lookup(target: str, source: str, stamp: float):
    if (target, source) == ("base_link", "imu_link"):
        return rpy_to_matrix(0.0, 0.0, 0.3), np.array([0.1, 0.0, 0.2])
    return None


def symmetric_positive_definite(covariance: np.ndarray) -> bool:
    """Symmetric and positive definite up to RELATIVE_PRECISION of its largest eigenvalue."""
    eigenvalues = np.linalg.eigvalsh(0.5 * (covariance + covariance.T))
    scale = max(float(eigenvalues.max()), 1e-300)
    asymmetry = float(np.abs(covariance - covariance.T).max())
    return asymmetry <= RELATIVE_PRECISION * scale and float(eigenvalues.min()) > -RELATIVE_PRECISION * scale


def feed(loc: Localizer, item, time: float) -> None:
    kind, _, a, b, variance = item
    odom, imu, pose = loc.config.sensors[0], loc.config.sensors[2], loc.config.sensors[1]
    covariance6 = (np.eye(6) * variance).flatten().tolist()
    covariance3 = (np.eye(3) * variance).flatten().tolist()
    if kind == "odom":
        twist = TwistData(time, "base_link", (a, 0.1 * b, 0.0), (0.0, 0.0, b), covariance6)
        empty = PoseData(time, "odom", (0, 0, 0), (0, 0, 0, 1), [0.0] * 36)
        loc.odometry(odom, empty, twist, "base_link")
    elif kind == "imu":
        data = ImuData(
            time,
            "imu_link",
            rpy_to_quaternion(*a),
            covariance3,
            (0.1 * b, -0.1 * b, b),
            covariance3,
            (b, 0.0, 9.80665),
            covariance3,
        )
        loc.imu(imu, data)
    else:
        loc.pose(pose, PoseData(time, "odom", (a[0], a[1], 0.0), rpy_to_quaternion(0, 0, a[2]), covariance6))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(sequence=st.lists(inputs, min_size=1, max_size=40), two_d_mode=st.booleans())
def test_covariance_stays_symmetric_positive_definite(sequence, two_d_mode):
    loc = Localizer(Config(params(two_d_mode)), lookup, now=0.0)
    time = 0.0
    for item in sequence:
        time += item[1]
        feed(loc, item, time)
        estimate = loc.update(time)
        if estimate is None:
            continue
        assert np.all(np.isfinite(estimate.state))
        assert symmetric_positive_definite(estimate.covariance), np.linalg.eigvalsh(estimate.covariance)
        if two_d_mode:
            # exactly: forceTwoD measures them (and vz, vroll, vpitch) as 0, and with roll = pitch = vz = 0 the
            # Jacobian of Ekf::predict couples them to no other entry, so no innovation moves them
            assert np.all(estimate.state[[Z, ROLL, PITCH]] == 0.0), estimate.state[[Z, ROLL, PITCH]]


@settings(max_examples=15, deadline=None, derandomize=True)
@given(
    truth=st.tuples(st.floats(-50, 50), st.floats(-50, 50), angles),
    start=st.tuples(st.floats(-50, 50), st.floats(-50, 50), angles),
    variance=st.floats(1e-4, 1.0),
)
def test_constant_true_state_is_reached(truth, start, variance):
    """A robot at rest: absolute pose and zero twist, repeated at 50 Hz for 8 s after one wrong pose. The steady
    state's gain for x follows from P growing by q dt = 0.05 * 0.02 a step
    (for R = 1 the steady gain is about sqrt(0.05 * 0.02 / R) = 0.03 a step: a time constant of ~33 steps, 0.7 s),
    leaving an error below 1e-3 of the initial one."""
    loc = Localizer(Config(params(True)), lookup, now=0.0)
    pose, odom = loc.config.sensors[1], loc.config.sensors[0]
    covariance6 = (np.eye(6) * variance).flatten().tolist()
    loc.pose(pose, PoseData(0.02, "odom", (start[0], start[1], 0), rpy_to_quaternion(0, 0, start[2]), covariance6))
    loc.update(0.02)
    empty = PoseData(0, "odom", (0, 0, 0), (0, 0, 0, 1), [0.0] * 36)
    for k in range(2, 400):
        time = 0.02 * k
        loc.pose(pose, PoseData(time, "odom", (truth[0], truth[1], 0), rpy_to_quaternion(0, 0, truth[2]), covariance6))
        still = TwistData(time, "base_link", (0, 0, 0), (0, 0, 0), (np.eye(6) * 1e-4).flatten().tolist())
        loc.odometry(odom, empty._replace(stamp=time), still, "base_link")
        estimate = loc.update(time)
    error = [
        estimate.state[X] - truth[0],
        estimate.state[Y] - truth[1],
        math.remainder(estimate.state[YAW] - truth[2], 2 * math.pi),
    ]
    initial = max(abs(start[0] - truth[0]), abs(start[1] - truth[1]), 1.0)
    assert max(abs(e) for e in error) < 1e-3 * initial, error
    assert abs(estimate.state[VX]) < 1e-3 and abs(estimate.state[VYAW]) < 1e-3


non_finite = st.sampled_from([math.nan, math.inf, -math.inf])
finite_or_not = st.one_of(st.floats(-10.0, 10.0), non_finite)
any_number = st.floats(allow_nan=True, allow_infinity=True)


def raw_inputs(numbers):
    """One message of each kind with numbers (values, quaternion components, covariances) drawn from `numbers`."""
    vector = st.tuples(numbers, numbers, numbers)
    quaternion = st.tuples(numbers, numbers, numbers, numbers)
    return st.tuples(st.sampled_from(["odom", "imu", "pose"]), steps, vector, quaternion, numbers)


def feed_raw(loc: Localizer, item, time: float) -> None:
    kind, _, vector, quaternion, variance = item
    covariance6, covariance3 = [variance] * 36, [variance] * 9
    if kind == "odom":
        empty = PoseData(time, "odom", (0, 0, 0), (0, 0, 0, 1), [0.0] * 36)
        loc.odometry(
            loc.config.sensors[0], empty, TwistData(time, "base_link", vector, vector, covariance6), "base_link"
        )
    elif kind == "imu":
        data = ImuData(time, "imu_link", quaternion, covariance3, vector, covariance3, vector, covariance3)
        loc.imu(loc.config.sensors[2], data)
    else:
        loc.pose(loc.config.sensors[1], PoseData(time, "odom", vector, quaternion, covariance6))


def run_with(bad, good) -> Localizer:
    loc = Localizer(Config(params(False)), lookup, now=0.0)
    time = 0.0
    with np.errstate(all="ignore"):
        for item in bad:
            time += item[1]
            feed_raw(loc, item, time)
            loc.update(time)
        for item in good:
            time += item[1]
            feed(loc, item, time)
            loc.update(time)
    return loc


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(bad=st.lists(raw_inputs(finite_or_not), min_size=1, max_size=10), good=st.lists(inputs, max_size=10))
def test_non_finite_numbers_are_left_out(bad, good):
    """NaN and infinities in values, quaternions and covariances: left out (values) or the message dropped
    (covariances), so the estimate stays finite."""
    loc = run_with(bad, good)
    assert np.all(np.isfinite(loc.filter.state)) and np.all(np.isfinite(loc.filter.covariance))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(bad=st.lists(raw_inputs(any_number), min_size=1, max_size=10), good=st.lists(inputs, max_size=10))
def test_any_numbers_never_raise(bad, good):
    """Any floats, 1e308 included (whose products overflow, as upstream's do): the filter never raises."""
    run_with(bad, good)
