"""Joints put at positions by moving the bodies below them, as Gazebo's Joint::SetPosition does in ODE's maximal
coordinates: set_model_configuration (world.control) and the tricycle drive's steering (world.plugins)."""
from __future__ import annotations

import math
from typing import Dict, List

import ode

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.transforms import quat_multiply, quat_rotate


def move_joints(model: BuiltModel, targets: Dict[str, float]) -> None:
    """Move the bodies below each named joint of ``model`` so it is at its target position; the root body stays,
    velocities are not touched (Joint::SetPosition with the world velocity preserved)."""
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
                for body in _subtree(child, children):
                    x, y, z = body.getPosition()
                    body.setPosition((x + axis[0] * delta, y + axis[1] * delta, z + axis[2] * delta))
            else:
                anchor = handle.joint.getAnchor()
                turn = (math.cos(delta / 2),) + tuple(math.sin(delta / 2) * a for a in axis)
                for body in _subtree(child, children):
                    x, y, z = body.getPosition()
                    arm = quat_rotate(turn, (x - anchor[0], y - anchor[1], z - anchor[2]))  # type: ignore[arg-type]
                    body.setPosition((anchor[0] + arm[0], anchor[1] + arm[1], anchor[2] + arm[2]))
                    body.setQuaternion(quat_multiply(turn, body.getQuaternion()))  # type: ignore[arg-type]
            handle.resync(targets[handle.name])


def _subtree(body: ode.Body, children: Dict[int, List[JointHandle]]) -> List[ode.Body]:
    """``body`` and every body below it in the joint tree."""
    bodies = [body]
    for current in bodies:
        bodies.extend(handle.joint.getBody(0) for handle in children.get(id(current), []))
    return bodies
