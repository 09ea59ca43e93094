"""Rotations as tf2 computes them (tf2::Matrix3x3 and tf2::Quaternion, angles::normalize_angle), in numpy.

A transform is a pair (rotation matrix 3x3, translation 3): p_target = R p_source + t, as tf2::Transform.
"""
from __future__ import annotations

import math
from typing import Sequence, Tuple

import numpy as np

Transform = Tuple[np.ndarray, np.ndarray]
TAU = 2.0 * math.pi


def normalize_angle(angle: float) -> float:
    """angles::normalize_angle (FilterUtilities::clampRotation): the angle in [-pi, pi); NaN for no number."""
    if not math.isfinite(angle):
        return math.nan
    wrapped = math.fmod(angle + math.pi, TAU)
    if wrapped < 0.0:
        wrapped += TAU
    return wrapped - math.pi


def quaternion_to_matrix(quaternion: Sequence[float]) -> np.ndarray:
    """tf2::Matrix3x3(q) of a quaternion (x, y, z, w); like tf2 it assumes a unit quaternion scaled by 2/|q|^2."""
    x, y, z, w = (float(v) for v in quaternion)
    s = 2.0 / (x * x + y * y + z * z + w * w)
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return np.array(
        [
            [1.0 - (yy + zz), xy - wz, xz + wy],
            [xy + wz, 1.0 - (xx + zz), yz - wx],
            [xz - wy, yz + wx, 1.0 - (xx + yy)],
        ]
    )


def matrix_to_rpy(matrix: np.ndarray) -> Tuple[float, float, float]:
    """tf2::Matrix3x3::getRPY (getEulerYPR, solution 1), gimbal lock included."""
    if abs(matrix[2, 0]) >= 1.0:
        roll = math.atan2(matrix[2, 1], matrix[2, 2])
        return roll, (math.pi / 2.0 if matrix[2, 0] < 0.0 else -math.pi / 2.0), 0.0
    pitch = -math.asin(matrix[2, 0])
    cos_pitch = math.cos(pitch)
    roll = math.atan2(matrix[2, 1] / cos_pitch, matrix[2, 2] / cos_pitch)
    yaw = math.atan2(matrix[1, 0] / cos_pitch, matrix[0, 0] / cos_pitch)
    return roll, pitch, yaw


def rpy_to_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """tf2::Matrix3x3::setRPY: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def rpy_to_quaternion(roll: float, pitch: float, yaw: float) -> Tuple[float, float, float, float]:
    """tf2::Quaternion::setRPY as (x, y, z, w)."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def matrix_to_quaternion(rotation: np.ndarray) -> Tuple[float, float, float, float]:
    return rpy_to_quaternion(*matrix_to_rpy(rotation))


def quaternion_to_rpy(quaternion: Sequence[float]) -> Tuple[float, float, float]:
    return matrix_to_rpy(quaternion_to_matrix(quaternion))


def identity() -> Transform:
    return np.eye(3), np.zeros(3)


def compose(first: Transform, second: Transform) -> Transform:
    """first * second (tf2::Transform::operator*): apply second, then first."""
    return first[0] @ second[0], first[0] @ second[1] + first[1]


def inverse_times(first: Transform, second: Transform) -> Transform:
    """first^-1 * second (tf2::Transform::inverseTimes)."""
    return first[0].T @ second[0], first[0].T @ (second[1] - first[1])


def inverse(transform: Transform) -> Transform:
    return transform[0].T, -transform[0].T @ transform[1]


def block_rotation(rotation: np.ndarray) -> np.ndarray:
    """The 6x6 matrix with the rotation on both diagonal blocks: rotates a pose or twist covariance."""
    rot6d = np.zeros((6, 6))
    rot6d[:3, :3] = rotation
    rot6d[3:, 3:] = rotation
    return rot6d
