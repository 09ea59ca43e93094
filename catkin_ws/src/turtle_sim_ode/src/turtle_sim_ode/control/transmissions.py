"""The joints a robot offers to ros_control: its URDF's <transmission> blocks (transmission_interface's parser)
read as gazebo_ros_control's DefaultRobotHWSim::initSim takes them, and each joint's limits."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Tuple

from turtle_sim_ode.models.description import Joint, RobotModel

EFFORT = "hardware_interface/EffortJointInterface"
VELOCITY = "hardware_interface/VelocityJointInterface"
POSITION = "hardware_interface/PositionJointInterface"
JOINT_STATE = "hardware_interface/JointStateInterface"
COMMAND_INTERFACES = (EFFORT, VELOCITY, POSITION)


def cpp_name(interface: str) -> str:
    """hardware_interface::EffortJointInterface, as ControllerState.claimed_resources names an interface."""
    return interface.replace("/", "::")


@dataclass(frozen=True)
class Limits:
    """joint_limits_interface's JointLimits from a URDF joint: position limits for revolute and prismatic joints,
    velocity and effort limits where the URDF gives them > 0 (infinite otherwise)."""

    lower: float = -math.inf
    upper: float = math.inf
    velocity: float = math.inf
    effort: float = math.inf

    @classmethod
    def of(cls, joint: Joint) -> "Limits":
        urdf = joint.limits
        if urdf is None:
            return cls()
        positional = joint.type in ("revolute", "prismatic")
        return cls(
            lower=urdf.lower if positional else -math.inf,
            upper=urdf.upper if positional else math.inf,
            velocity=urdf.velocity if urdf.velocity > 0 else math.inf,
            effort=urdf.effort if urdf.effort > 0 else math.inf,
        )


@dataclass(frozen=True)
class TransmissionJoint:
    """One simulated joint: its name, URDF type, the command interface its transmission names, and limits."""

    name: str
    type: str
    interface: str
    limits: Limits


def _interface(text: str) -> str:
    """With or without the hardware_interface/ prefix (the prefix-less form is deprecated but accepted);
    hardware_interface::X is accepted too."""
    text = text.strip().replace("::", "/")
    return text if "/" in text else "hardware_interface/" + text


def read_transmissions(robot: RobotModel) -> Tuple[List[TransmissionJoint], List[str]]:
    """(joints, warnings) of every usable transmission of the URDF (models.urdf keeps the elements); the warnings
    say what was skipped and why, as DefaultRobotHWSim warns. A joint the model lacks, or an interface that is not
    simulated, is an error."""
    joints: List[TransmissionJoint] = []
    warnings: List[str] = []
    for element in robot.transmissions:
        name = element.get("name", "")
        joint_elements = element.findall("joint")
        if not joint_elements:
            warnings.append(f"Transmission {name} has no associated joints.")
            continue
        if len(joint_elements) > 1:
            warnings.append(
                f"Transmission {name} has more than one joint. Currently the default robot hardware simulation "
                "interface only supports one."
            )
            continue
        joint_name = joint_elements[0].get("name", "")
        interfaces = [i.text or "" for i in joint_elements[0].findall("hardwareInterface")]
        if not interfaces:
            interfaces = [i.text or "" for i in element.findall("actuator/hardwareInterface")]
            if interfaces:
                warnings.append(
                    f"The <hardware_interface> element of tranmission {name} should be nested inside the <joint> "
                    "element, not <actuator>."
                )
        if not interfaces:
            warnings.append(
                f"Joint {joint_name} of transmission {name} does not specify any hardware interface. Not adding "
                "it to the robot hardware simulation."
            )
            continue
        if len(interfaces) > 1:
            warnings.append(
                f"Joint {joint_name} of transmission {name} specifies multiple hardware interfaces. Currently the "
                "default robot hardware simulation interface only supports one. Using the first entry"
            )
        interface = _interface(interfaces[0])
        if interface not in COMMAND_INTERFACES:
            raise ValueError(f"No matching hardware interface found for '{interfaces[0].strip()}'")
        urdf_joint = robot.joints.get(joint_name)
        if urdf_joint is None or urdf_joint.type in ("fixed", "floating", "planar"):
            raise ValueError(f'This robot has a joint named "{joint_name}" which is not in the gazebo model.')
        joints.append(TransmissionJoint(joint_name, urdf_joint.type, interface, Limits.of(urdf_joint)))
    return joints, warnings


def limits_from_params(limits: Limits, params: Optional[dict]) -> Limits:
    """joint_limits_interface::getJointLimits(name, nh): <ns>/joint_limits/<joint> overrides the URDF's
    (has_position_limits with min/max_position, has_velocity_limits with max_velocity, has_effort_limits with
    max_effort)."""
    if not isinstance(params, dict):
        return limits

    def value(flag: str, key: str) -> Optional[float]:
        number = params.get(key)
        if params.get(flag) is True and isinstance(number, (int, float)) and not isinstance(number, bool):
            return float(number)
        return None

    lower, upper = value("has_position_limits", "min_position"), value("has_position_limits", "max_position")
    velocity, effort = value("has_velocity_limits", "max_velocity"), value("has_effort_limits", "max_effort")
    return Limits(
        lower=limits.lower if lower is None else lower,
        upper=limits.upper if upper is None else upper,
        velocity=limits.velocity if velocity is None else abs(velocity),
        effort=limits.effort if effort is None else abs(effort),
    )
