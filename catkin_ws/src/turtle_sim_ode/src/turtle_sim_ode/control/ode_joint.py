"""A model's ODE joint as the robot hardware simulation drives it."""
from __future__ import annotations

from typing import Callable, Dict, Optional

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.description import JointLimits
from turtle_sim_ode.physics import ode_constants as oc


def truncated_effort(effort: float, rate: float, velocity_limit: float, effort_limit: float) -> float:
    """Gazebo classic's Joint::CheckAndTruncateForce (physics/Joint.cc, called by Joint::SetForce before the engine
    adds the effort): none in the direction in which the joint already moves faster than its velocity limit, then
    truncated to its effort limit. ``effort`` at joint velocity ``rate``; a limit <= 0 (or absent) is none (Gazebo's
    SDF default is -1; a URDF limit without a velocity reads 0 here)."""
    if velocity_limit > 0:
        if rate > velocity_limit and effort > 0:
            effort = 0.0
        elif rate < -velocity_limit and effort < 0:
            effort = 0.0
    if effort_limit > 0:
        effort = max(-effort_limit, min(effort_limit, effort))
    return effort


class OdeSimJoint:
    """position() and velocity() are the handle's readers themselves (read for every joint at each control update):
    a continuous joint's unwrapped angle, a slider's position, else ODE's angle; and its rate.

    ``limits``: the joint's <limit>, applied to every effort as truncated_effort does."""

    def __init__(self, handle: JointHandle, limits: Optional[JointLimits] = None) -> None:
        self.handle = handle
        self.position: Callable[[], float] = handle.angle
        prismatic = handle.type == "prismatic"
        self.velocity: Callable[[], float] = handle.joint.getPositionRate if prismatic else handle.joint.getAngleRate
        self._add = handle.joint.addForce if prismatic else handle.joint.addTorque
        self._set_param = handle.joint.setParam
        self._motor_force = 0.0  # the motor's force as last set (0: off)
        self._velocity_limit = limits.velocity if limits is not None else 0.0
        self._effort_limit = limits.effort if limits is not None else 0.0

    def apply_effort(self, effort: float) -> None:
        """Gazebo's Joint::SetForce for the coming step: the effort truncated first (truncated_effort)."""
        effort = truncated_effort(effort, self.velocity(), self._velocity_limit, self._effort_limit)
        if self._motor_force:  # an effort-driven joint has no motor holding it
            self._set_param(oc.PARAM_FMAX, 0.0)
            self._motor_force = 0.0
        self._add(effort)

    def drive(self, velocity: float, max_force: float) -> None:
        self._set_param(oc.PARAM_VEL, velocity)
        if max_force != self._motor_force:
            self._set_param(oc.PARAM_FMAX, max_force)
            self._motor_force = max_force


def ode_sim_joints(model: BuiltModel) -> Dict[str, OdeSimJoint]:
    """Every movable joint of ``model`` with the limits its description gives it."""
    return {name: OdeSimJoint(model.joint(name), model.robot.joints[name].limits) for name in model.joints}
