"""Where models/world_arm.urdf rests under effort_controllers/JointPositionController, computed from the URDF.

At rest the controller's D term is 0 and its I term too (control_toolbox Pid clamps the integral to +-i_clamp, 0
when the YAML gives none, as rrbot_control.yaml does), so each joint holds with effort p (target - q) against
gravity: p (target - q) + tau_gravity(q) = 0 with tau_gravity the torque of the links beyond the joint about its
axis (y): sum of m g (x_com - x_joint). Solved by fixed-point iteration (it contracts while tau's slope < p)."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree
from pathlib import Path
from typing import List, Sequence, Tuple

GRAVITY = 9.81
URDF = Path(__file__).resolve().parent / "models" / "world_arm.urdf"
JOINTS = ("shoulder", "elbow")


def _z(element) -> float:
    return float(element.find("origin").get("xyz").split()[2])


def chain(urdf: str = URDF.read_text()) -> Tuple[List[float], List[Tuple[float, float]]]:
    """Each joint's distance along its parent beam from the previous joint, and each moving link's (mass, COM
    distance from its joint)."""
    robot = ElementTree.fromstring(urdf)
    joints = {joint.get("name"): joint for joint in robot.findall("joint")}
    links = {link.get("name"): link for link in robot.findall("link")}
    offsets = [_z(joints[name]) for name in JOINTS[1:]]
    masses = []
    for name in JOINTS:
        inertial = links[joints[name].find("child").get("link")].find("inertial")
        masses.append((float(inertial.find("mass").get("value")), _z(inertial)))
    return offsets, masses


def gravity_torques(angles: Sequence[float], offsets: Sequence[float], masses) -> List[float]:
    """Gravity's torque about each joint's y axis with the arm at ``angles`` (each beam along z at 0)."""
    joint_x, com_x, heading, x = [], [], 0.0, 0.0
    for index, angle in enumerate(angles):
        heading += angle
        joint_x.append(x)
        com_x.append(x + masses[index][1] * math.sin(heading))
        if index < len(offsets):
            x += offsets[index] * math.sin(heading)
    return [
        sum(masses[k][0] * GRAVITY * (com_x[k] - joint_x[i]) for k in range(i, len(angles))) for i in range(len(angles))
    ]


def resting_angles(targets: Sequence[float], p_gain: float) -> List[float]:
    offsets, masses = chain()
    angles = list(targets)
    for _ in range(500):
        torques = gravity_torques(angles, offsets, masses)
        angles = [target + torque / p_gain for target, torque in zip(targets, torques)]
    return angles
