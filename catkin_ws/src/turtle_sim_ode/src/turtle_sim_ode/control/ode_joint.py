"""A model's ODE joint as the robot hardware simulation drives it."""
from __future__ import annotations

import math
from typing import Callable, Dict, Optional

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.description import JointLimits
from turtle_sim_ode.physics import ode_constants as oc


class OdeSimJoint:
    """position() and velocity() are the handle's readers themselves (read for every joint at each control update):
    a continuous joint's unwrapped angle, a slider's position, else ODE's angle; and its rate.

    ``limits``: the joint's <limit> as Gazebo's Joint::Load stores it, a limit below 0 (SDF's default) or none at all
    leaving the effort alone."""

    def __init__(self, handle: JointHandle, limits: Optional[JointLimits] = None) -> None:
        self.handle = handle
        self.position: Callable[[], float] = handle.angle
        prismatic = handle.type == "prismatic"
        self.velocity: Callable[[], float] = handle.joint.getPositionRate if prismatic else handle.joint.getAngleRate
        self._add = handle.joint.addForce if prismatic else handle.joint.addTorque
        self._set_param = handle.joint.setParam
        self._motor_force = 0.0  # the motor's force as last set (0: off)
        self._velocity_limit = limits.velocity if limits is not None and limits.velocity >= 0 else math.inf
        self._effort_limit = limits.effort if limits is not None and limits.effort >= 0 else math.inf

    def apply_effort(self, effort: float) -> None:
        """Gazebo's Joint::SetForce for the coming step, through Joint::CheckAndTruncateForce (gazebo-classic
        gazebo/physics/Joint.cc): no effort pushing the joint further beyond its velocity limit, then the effort
        clamped to the effort limit."""
        velocity = self.velocity()
        if (velocity > self._velocity_limit and effort > 0) or (velocity < -self._velocity_limit and effort < 0):
            effort = 0.0
        effort = max(-self._effort_limit, min(self._effort_limit, effort))
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
