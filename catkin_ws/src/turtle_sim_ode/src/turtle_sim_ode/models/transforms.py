"""Rigid transforms of plain float tuples (cheaper than numpy for 3-vectors): quaternions (w, x, y, z) as ODE's."""
from __future__ import annotations

import math
from typing import Tuple

from turtle_sim_ode.models.description import Pose

Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]  # (w, x, y, z) as ODE; only link_pose gives ROS's xyzw
Transform = Tuple[Vec3, Quat]
Matrix3 = Tuple[Vec3, Vec3, Vec3]


# --- rigid transforms (plain floats: cheaper than numpy for 3-vectors) ----------------
def quat_from_rpy(roll: float, pitch: float, yaw: float) -> Quat:
    """URDF fixed-axis rpy: Rz(yaw) * Ry(pitch) * Rx(roll)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (
        cr * cp * cy + sr * sp * sy,
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
    )


def quat_multiply(a: Quat, b: Quat) -> Quat:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def quat_rotate(q: Quat, v: Vec3) -> Vec3:
    w, x, y, z = q
    # v + 2w(u x v) + 2u x (u x v), u = (x, y, z)
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def quat_normalised(q: Quat) -> Quat:
    """``q`` of unit length (the identity for a zero quaternion)."""
    norm = math.sqrt(sum(c * c for c in q))
    return tuple(c / norm for c in q) if norm > 0 else (1.0, 0.0, 0.0, 0.0)  # type: ignore[return-value]


def quat_matrix(q: Quat) -> Matrix3:
    columns = [quat_rotate(q, axis) for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))]
    return tuple(tuple(columns[c][r] for c in range(3)) for r in range(3))  # type: ignore[return-value]


def rpy_of(q: Quat) -> Vec3:
    """Fixed-axis roll, pitch, yaw of a quaternion (inverse of quat_from_rpy)."""
    m = quat_matrix(q)
    cos_pitch = math.hypot(m[0][0], m[1][0])
    pitch = math.atan2(-m[2][0], cos_pitch)
    if cos_pitch < 1e-9:  # gimbal lock: only roll and yaw together are defined; all in yaw
        return (0.0, pitch, math.atan2(-m[0][1], m[1][1]))
    return (math.atan2(m[2][1], m[2][2]), pitch, math.atan2(m[1][0], m[0][0]))


def compose(a: Transform, b: Transform) -> Transform:
    moved = quat_rotate(a[1], b[0])
    return ((a[0][0] + moved[0], a[0][1] + moved[1], a[0][2] + moved[2]), quat_multiply(a[1], b[1]))


def inverse(t: Transform) -> Transform:
    w, x, y, z = t[1]
    conjugate = (w, -x, -y, -z)
    back = quat_rotate(conjugate, t[0])
    return ((-back[0], -back[1], -back[2]), conjugate)


def pose_transform(pose: Pose) -> Transform:
    return (pose.xyz, quat_from_rpy(*pose.rpy))
