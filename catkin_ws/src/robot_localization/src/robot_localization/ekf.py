"""The extended Kalman filter of cra-ros-pkg/robot_localization (noetic-devel), without ROS.

State (filter_common.h StateMembers): x, y, z, roll, pitch, yaw in the world frame; vx, vy, vz, vroll, vpitch,
vyaw and ax, ay, az in the body frame. Motion model: omnidirectional, constant acceleration (ekf.cpp
Ekf::predict). Corrections update only the measured entries, with the Joseph form (Ekf::correct). Measurement
book-keeping as FilterBase (filter_base.cpp): the first measurement initializes the filter, later ones predict up
to their time stamp and correct.
"""
from __future__ import annotations

import math
from typing import List, NamedTuple, Sequence

import numpy as np

from robot_localization.rotations import normalize_angle, rpy_to_matrix

STATE_SIZE = 15
X, Y, Z, ROLL, PITCH, YAW, VX, VY, VZ, VROLL, VPITCH, VYAW, AX, AY, AZ = range(STATE_SIZE)
ANGLES = (ROLL, PITCH, YAW)
POSE_SLICE, TWIST_SLICE, ACCELERATION_SLICE = slice(X, YAW + 1), slice(VX, VYAW + 1), slice(AX, AZ + 1)
STATE_NAMES = (
    "X",
    "Y",
    "Z",
    "ROLL",
    "PITCH",
    "YAW",
    "X_VELOCITY",
    "Y_VELOCITY",
    "Z_VELOCITY",
    "ROLL_VELOCITY",
    "PITCH_VELOCITY",
    "YAW_VELOCITY",
    "X_ACCELERATION",
    "Y_ACCELERATION",
    "Z_ACCELERATION",
)
# FilterBase::reset: the process noise used when process_noise_covariance is not given.
DEFAULT_PROCESS_NOISE = np.diag(
    [0.05, 0.05, 0.06, 0.03, 0.03, 0.06, 0.025, 0.025, 0.04, 0.01, 0.01, 0.02, 0.01, 0.01, 0.015]
)
INITIAL_VARIANCE = 1e-9  # FilterBase::reset: small, so that the first measurements are taken as they are
MIN_MEASUREMENT_VARIANCE = 1e-9  # Ekf::correct: a smaller variance would make the gain blow up
BAG_DELTA = 100000.0  # FilterBase::validateDelta: a larger step is a bag replay's time jump...
BAG_DELTA_REPLACEMENT = 0.01  # ...and becomes this step


class Measurement:
    """One prepared measurement (filter_base.h Measurement): full-size vector and covariance, the entries used."""

    def __init__(
        self,
        time: float,
        values: np.ndarray,
        covariance: np.ndarray,
        update_vector: Sequence[bool],
        mahalanobis_threshold: float = math.inf,
        topic: str = "",
    ) -> None:
        self.time = time
        self.values = np.asarray(values, dtype=float)
        self.covariance = np.asarray(covariance, dtype=float)
        self.update_vector = [bool(u) for u in update_vector]
        self.mahalanobis_threshold = mahalanobis_threshold
        self.topic = topic


class Trigonometry(NamedTuple):
    """The sines and cosines of the state's angles Ekf::predict uses (cpi = 1 / cos(pitch), tp = tan(pitch))."""

    sr: float
    cr: float
    sp: float
    cp: float
    sy: float
    cy: float
    cpi: float
    tp: float


def trigonometry(state: np.ndarray) -> Trigonometry:
    sp, cp = math.sin(state[PITCH]), math.cos(state[PITCH])
    return Trigonometry(
        math.sin(state[ROLL]),
        math.cos(state[ROLL]),
        sp,
        cp,
        math.sin(state[YAW]),
        math.cos(state[YAW]),
        1 / cp,
        sp / cp,
    )


def transfer_function(state: np.ndarray, delta: float) -> np.ndarray:
    """Ekf::predict's transferFunction_: x(t + delta) = F x(t); the body velocities and accelerations turned into
    the world by the rotation of roll, pitch and yaw (its rows are the coefficients upstream writes out)."""
    sr, cr, _, _, _, _, cpi, tp = trigonometry(state)
    body_to_world = rpy_to_matrix(state[ROLL], state[PITCH], state[YAW])
    f = np.eye(STATE_SIZE)
    f[X : Z + 1, VX : VZ + 1] = body_to_world * delta
    f[X : Z + 1, AX : AZ + 1] = body_to_world * 0.5 * delta * delta
    f[ROLL, VROLL] = delta
    f[ROLL, VPITCH] = sr * tp * delta
    f[ROLL, VYAW] = cr * tp * delta
    f[PITCH, VPITCH] = cr * delta
    f[PITCH, VYAW] = -sr * delta
    f[YAW, VPITCH] = sr * cpi * delta
    f[YAW, VYAW] = cr * cpi * delta
    f[VX, AX] = f[VY, AY] = f[VZ, AZ] = delta
    return f


def transfer_function_jacobian(state: np.ndarray, delta: float) -> np.ndarray:
    """Ekf::predict's transferFunctionJacobian_: F plus the derivatives of the rotated terms by roll, pitch, yaw."""
    sr, cr, sp, cp, sy, cy, cpi, tp = trigonometry(state)
    velocity, acceleration = state[VX : VZ + 1], state[AX : AZ + 1]
    pitch_rate, yaw_rate = state[VPITCH], state[VYAW]
    half_dt2 = 0.5 * delta * delta

    def rotated(coefficients: Sequence[float]) -> float:
        # d(position)/d(angle): the derivative of a row of the body-to-world rotation times v dt + a dt^2 / 2
        return float(np.dot(coefficients, velocity) * delta + np.dot(coefficients, acceleration) * half_dt2)

    j = transfer_function(state, delta)
    j[X, ROLL] = rotated((0.0, cy * sp * cr + sy * sr, -cy * sp * sr + sy * cr))
    j[X, PITCH] = rotated((-cy * sp, cy * cp * sr, cy * cp * cr))
    j[X, YAW] = rotated((-sy * cp, -sy * sp * sr - cy * cr, -sy * sp * cr + cy * sr))
    j[Y, ROLL] = rotated((0.0, sy * sp * cr - cy * sr, -sy * sp * sr - cy * cr))
    j[Y, PITCH] = rotated((-sy * sp, sy * cp * sr, sy * cp * cr))
    j[Y, YAW] = rotated((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr))
    j[Z, ROLL] = rotated((0.0, cp * cr, -cp * sr))
    j[Z, PITCH] = rotated((-cp, -sp * sr, -sp * cr))
    j[ROLL, ROLL] = 1.0 + (cr * tp * pitch_rate - sr * tp * yaw_rate) * delta
    j[ROLL, PITCH] = (cpi * cpi * sr * pitch_rate + cpi * cpi * cr * yaw_rate) * delta
    j[PITCH, ROLL] = (-sr * pitch_rate - cr * yaw_rate) * delta
    j[YAW, ROLL] = (cr * cpi * pitch_rate - sr * cpi * yaw_rate) * delta
    j[YAW, PITCH] = (sr * tp * cpi * pitch_rate + cr * tp * cpi * yaw_rate) * delta
    return j


class Ekf:
    """FilterBase + Ekf: state, estimate error covariance, predict, correct and processMeasurement."""

    def __init__(self) -> None:
        self.process_noise = DEFAULT_PROCESS_NOISE.copy()
        self.dynamic_process_noise = False
        self.sensor_timeout = 1.0 / 30.0
        self.reset()

    def reset(self) -> None:
        """FilterBase::reset, except the process noise, which stays as configured."""
        self.initialized = False
        self.state = np.zeros(STATE_SIZE)
        self.covariance = np.eye(STATE_SIZE) * INITIAL_VARIANCE
        self.last_measurement_time = 0.0

    def scaled_process_noise(self) -> np.ndarray:
        """FilterBase::computeDynamicProcessNoiseCovariance: the pose and velocity block (6x6 at X) scaled by the
        square of the norm of the six velocities, or the process noise as configured."""
        if not self.dynamic_process_noise:
            return self.process_noise
        scaled = self.process_noise.copy()
        speed = float(np.linalg.norm(self.state[VX : VYAW + 1]))
        scaled[:6, :6] = self.process_noise[:6, :6] * speed * speed
        return scaled

    def predict(self, delta: float) -> None:
        """Ekf::predict: x = F x, angles wrapped, P = J P J' + delta Q (no control term)."""
        f = transfer_function(self.state, delta)
        j = transfer_function_jacobian(self.state, delta)
        noise = self.scaled_process_noise()
        self.state = f @ self.state
        self.wrap_state_angles()
        self.covariance = j @ self.covariance @ j.T + delta * noise

    def correct(self, measurement: Measurement) -> bool:
        """Ekf::correct: Kalman update of the measured, finite entries; False if the Mahalanobis gate refused it
        (or the innovation covariance cannot be inverted, where Eigen would fill the state with NaN)."""
        indices = measured_indices(measurement)
        if not indices:
            return True
        h = np.zeros((len(indices), STATE_SIZE))
        h[np.arange(len(indices)), indices] = 1.0
        r = measurement.covariance[np.ix_(indices, indices)].copy()
        diagonal = np.abs(np.diag(r))  # a negative variance is taken as its absolute value
        np.fill_diagonal(r, np.maximum(diagonal, MIN_MEASUREMENT_VARIANCE))
        pht = self.covariance @ h.T
        try:
            hphr_inverse = np.linalg.inv(h @ pht + r)
        except np.linalg.LinAlgError:
            return False
        gain = pht @ hphr_inverse
        innovation = measurement.values[indices] - self.state[indices]
        for row, index in enumerate(indices):
            if index in ANGLES:
                innovation[row] = wrap_innovation(innovation[row])
        if not passes_mahalanobis_gate(innovation, hphr_inverse, measurement.mahalanobis_threshold):
            return False
        self.state = self.state + gain @ innovation
        residual = np.eye(STATE_SIZE) - gain @ h
        self.covariance = residual @ self.covariance @ residual.T + gain @ r @ gain.T
        self.wrap_state_angles()
        return True

    def process_measurement(self, measurement: Measurement) -> None:
        """FilterBase::processMeasurement: initialize from the first measurement, then predict (forward in time
        only) and correct."""
        delta = 0.0
        if self.initialized:
            delta = measurement.time - self.last_measurement_time
            if delta > 0.0:
                self.predict(validate_delta(delta))
            self.correct(measurement)
        else:
            used = np.zeros(STATE_SIZE, dtype=bool)
            used[measured_indices(measurement)] = True
            self.state[used] = measurement.values[used]
            both = np.outer(used, used)
            self.covariance[both] = measurement.covariance[both]
            self.initialized = True
        if delta >= 0.0:
            self.last_measurement_time = measurement.time

    def predict_to(self, time: float) -> None:
        """RosFilter::integrateMeasurements without measurements: project the state up to `time`."""
        delta = validate_delta(time - self.last_measurement_time)
        self.predict(delta)
        self.last_measurement_time += delta

    def wrap_state_angles(self) -> None:
        for index in ANGLES:
            self.state[index] = normalize_angle(self.state[index])


def measured_indices(measurement: Measurement) -> List[int]:
    """The entries a measurement updates: those in its update vector with a finite value (NaN and inf are left
    out, as Ekf::correct does)."""
    return [i for i, used in enumerate(measurement.update_vector) if used and math.isfinite(measurement.values[i])]


def validate_delta(delta: float) -> float:
    return BAG_DELTA_REPLACEMENT if delta > BAG_DELTA else delta


def wrap_innovation(angle: float) -> float:
    """Ekf::correct's while loops: the innovation in [-pi, pi]."""
    while angle < -math.pi:
        angle += 2.0 * math.pi
    while angle > math.pi:
        angle -= 2.0 * math.pi
    return angle


def passes_mahalanobis_gate(innovation: np.ndarray, inverse_covariance: np.ndarray, sigmas: float) -> bool:
    """FilterBase::checkMahalanobisThreshold: squared distance below sigmas^2 (an infinite threshold lets all in)."""
    if math.isinf(sigmas):
        return True
    return float(innovation @ inverse_covariance @ innovation) < sigmas * sigmas
