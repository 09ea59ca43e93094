"""Sensor data turned into filter measurements, as RosFilter's prepareTwist, prepareAcceleration and forceTwoD
(ros_filter.cpp) do it, without ROS: data and transforms in, full-size vector, covariance and update vector out.

Messages arrive as the plain tuples below; a transform is (R, t) with p_target = R p_source + t (rotations.py).
"""
from __future__ import annotations

import math
from typing import List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from robot_localization.ekf import AX, AZ, PITCH, ROLL, STATE_SIZE, VPITCH, VROLL, VX, VZ, YAW, Z
from robot_localization.rotations import Transform, block_rotation, quaternion_to_matrix, rpy_to_matrix

Prepared = Tuple[np.ndarray, np.ndarray, List[bool]]  # values (15), covariance (15x15), update vector (15)
MASK_LENGTH = 1e-6  # a transformed update-mask row at least this long marks the entry as measured
TWO_D_VARIANCE = 1e-6  # forceTwoD: the variance of the zeros it measures
TWO_D_ENTRIES = (Z, ROLL, PITCH, VZ, VROLL, VPITCH, AZ)


class PoseData(NamedTuple):
    stamp: float
    frame_id: str
    position: Sequence[float]
    orientation: Sequence[float]  # x, y, z, w
    covariance: Sequence[float]  # 36, row-major (x, y, z, roll, pitch, yaw)


class TwistData(NamedTuple):
    stamp: float
    frame_id: str
    linear: Sequence[float]
    angular: Sequence[float]
    covariance: Sequence[float]  # 36, row-major (vx, vy, vz, vroll, vpitch, vyaw)


class ImuData(NamedTuple):
    stamp: float
    frame_id: str
    orientation: Sequence[float]
    orientation_covariance: Sequence[float]  # 9; [0] == -1: no orientation (sensor_msgs/Imu)
    angular_velocity: Sequence[float]
    angular_velocity_covariance: Sequence[float]
    linear_acceleration: Sequence[float]
    linear_acceleration_covariance: Sequence[float]


def force_two_d(values: np.ndarray, covariance: np.ndarray, update: List[bool]) -> None:
    """forceTwoD: measure z, roll, pitch, their velocities and az as 0 with a small variance."""
    for index in TWO_D_ENTRIES:
        values[index] = 0.0
        covariance[index, index] = TWO_D_VARIANCE
        update[index] = True


def rotated_mask(rotation: np.ndarray, mask: Sequence[bool]) -> List[bool]:
    """Which of three entries are measured after rotating: the rows of R diag(mask) that are not zero."""
    rows = rotation @ np.diag(np.array(mask, dtype=float))
    return [bool(np.linalg.norm(row) >= MASK_LENGTH) for row in rows]


def matrix_from(values: Sequence[float], size: int) -> np.ndarray:
    return np.array(values, dtype=float).reshape(size, size)


def prepare_twist(
    twist: TwistData, update: Sequence[bool], transform: Transform, state: np.ndarray, two_d_mode: bool
) -> Prepared:
    """prepareTwist: rotate into the target frame (base_link); a sensor off the origin sees the body's rotation as
    linear velocity, removed with the translation crossed with the state's angular velocity."""
    rotation, translation = transform
    update = list(update)
    angular = rotation @ np.array(twist.angular, dtype=float)
    linear = rotation @ np.array(twist.linear, dtype=float) + np.cross(translation, state[VROLL : VROLL + 3])
    update[VX : VX + 3] = rotated_mask(rotation, update[VX : VX + 3])
    update[VROLL : VROLL + 3] = rotated_mask(rotation, update[VROLL : VROLL + 3])
    rot6d = block_rotation(rotation)
    values = np.zeros(STATE_SIZE)
    covariance = np.zeros((STATE_SIZE, STATE_SIZE))
    values[VX : VX + 3] = linear
    values[VROLL : VROLL + 3] = angular
    covariance[VX : VX + 6, VX : VX + 6] = rot6d @ matrix_from(twist.covariance, 6) @ rot6d.T
    if two_d_mode:
        force_two_d(values, covariance, update)
    return values, covariance, update


def prepare_acceleration(
    imu: ImuData,
    update: Sequence[bool],
    transform: Transform,
    state: np.ndarray,
    angular_acceleration: np.ndarray,
    gravity: Optional[float],
    relative: bool,
    two_d_mode: bool,
) -> Prepared:
    """prepareAcceleration: remove gravity (when `gravity` is given: along the IMU's orientation, or the state's
    where the IMU has none), rotate into base_link and remove the sensor offset's tangential and centripetal
    terms."""
    rotation, translation = transform
    update = list(update)
    acceleration = np.array(imu.linear_acceleration, dtype=float)
    if gravity is not None:
        normal = np.array([0.0, 0.0, gravity])
        if abs(imu.orientation_covariance[0] + 1.0) < 1e-9:
            # no orientation in the message: the state's, carried into the IMU's frame
            attitude = rpy_to_matrix(state[ROLL], state[PITCH], state[YAW]) @ rotation
            acceleration -= attitude.T @ normal
        else:
            attitude = quaternion_to_matrix(normalized(imu.orientation))
            acceleration -= (rotation.T @ attitude.T @ normal) if relative else attitude.T @ normal
    rates = state[VROLL : VROLL + 3]
    acceleration = (
        rotation @ acceleration
        + np.cross(translation, angular_acceleration)
        - np.cross(np.cross(translation, rates), rates)
    )
    update[AX : AX + 3] = rotated_mask(rotation, update[AX : AX + 3])
    values = np.zeros(STATE_SIZE)
    covariance = np.zeros((STATE_SIZE, STATE_SIZE))
    values[AX : AX + 3] = acceleration
    covariance[AX : AX + 3, AX : AX + 3] = rotation @ matrix_from(imu.linear_acceleration_covariance, 3) @ rotation.T
    if two_d_mode:
        force_two_d(values, covariance, update)
    return values, covariance, update


def normalized(quaternion: Sequence[float]) -> np.ndarray:
    """A quaternion of length 1; upstream normalizes one that is off by more than 0.01 (with a warning) and
    treats all zeros as the identity. One with a component that is not finite stays NaN (left out later)."""
    q = np.array(quaternion, dtype=float)
    if not np.all(np.isfinite(q)):
        return np.full(4, math.nan)
    largest = float(np.max(np.abs(q)))
    if largest == 0.0:
        return np.array([0.0, 0.0, 0.0, 1.0])
    scaled = q / largest  # its length cannot overflow
    length = largest * float(np.linalg.norm(scaled))
    return scaled / np.linalg.norm(scaled) if abs(length - 1.0) > 0.01 else q


def pose_covariance(pose: PoseData) -> np.ndarray:
    return matrix_from(pose.covariance, 6)


def pose_transform(pose: PoseData) -> Transform:
    return quaternion_to_matrix(normalized(pose.orientation)), np.array(pose.position, dtype=float)
