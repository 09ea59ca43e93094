"""How the world services move a model's bodies: rigidly (a pose or twist set on a model or link) and through its
joints (set_model_configuration), with the small vector helpers they share. ROS-free, on PyODE bodies."""
from __future__ import annotations

import math
from typing import Dict, List, Sequence

import ode

from turtle_sim_ode.models.builder import BuiltModel, JointHandle, Quat, Vec3, quat_multiply, quat_rotate


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


def subtree(body: ode.Body, children: Dict[int, List[JointHandle]]) -> List[ode.Body]:
    """``body`` and every body below it in the joint tree."""
    bodies = [body]
    for current in bodies:
        bodies.extend(handle.joint.getBody(0) for handle in children.get(id(current), []))
    return bodies


def set_configuration(model: BuiltModel, targets: Dict[str, float]) -> None:
    """Move the bodies below each named joint so it is at its target position; the root body
    stays, every body of the model comes to rest."""
    children: Dict[int, List[JointHandle]] = {}
    for handle in model.joints.values():
        children.setdefault(id(handle.joint.getBody(1)), []).append(handle)
    queue = [model.links[model.root_link].body]
    for parent in queue:  # parents before children; ``queue`` grows while iterating
        for handle in children.get(id(parent), []):
            child = handle.joint.getBody(0)
            queue.append(child)
            if handle.name not in targets:
                continue
            if handle.type == "continuous":
                handle.track_turns()
            delta = targets[handle.name] - handle.angle()
            axis = handle.joint.getAxis()
            if handle.type == "prismatic":
                for body in subtree(child, children):
                    body.setPosition(add(body.getPosition(), tuple(a * delta for a in axis)))
            else:
                anchor = handle.joint.getAnchor()
                turn = (math.cos(delta / 2),) + tuple(math.sin(delta / 2) * a for a in axis)
                for body in subtree(child, children):
                    arm = quat_rotate(turn, sub(body.getPosition(), anchor))
                    body.setPosition(add(anchor, arm))
                    body.setQuaternion(quat_multiply(turn, body.getQuaternion()))
            handle.resync(targets[handle.name])
    for body in model.bodies:
        body.setLinearVel((0.0, 0.0, 0.0))
        body.setAngularVel((0.0, 0.0, 0.0))
