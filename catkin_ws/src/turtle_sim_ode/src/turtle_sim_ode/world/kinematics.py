"""How the world services move a model's bodies: rigidly (a pose or twist set on a model or link) and through its
joints (set_model_configuration), with the small vector helpers they share. ROS-free, on PyODE bodies."""
from __future__ import annotations

from typing import Dict, Sequence

import ode

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Quat, Vec3
from turtle_sim_ode.models.joint_positions import move_joints


def add(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a: Vec3, b: Vec3) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def conjugate(q: Quat) -> Quat:
    return (q[0], -q[1], -q[2], -q[3])


def set_rigid_twist(bodies: Sequence[ode.Body], origin: Vec3, linear: Vec3, angular: Vec3) -> None:
    """Move ``bodies`` as one rigid body: ``linear`` is the velocity of the point ``origin``."""
    for body in bodies:
        body.setLinearVel(add(linear, cross(angular, sub(body.getPosition(), origin))))
        body.setAngularVel(angular)


def set_configuration(model: BuiltModel, targets: Dict[str, float]) -> None:
    """Move the bodies below each named joint so it is at its target position; the root body
    stays, every body of the model comes to rest."""
    move_joints(model, targets)
    for body in model.bodies:
        body.setLinearVel((0.0, 0.0, 0.0))
        body.setAngularVel((0.0, 0.0, 0.0))
