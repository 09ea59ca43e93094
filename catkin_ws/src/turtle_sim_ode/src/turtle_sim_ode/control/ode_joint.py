"""A model's ODE joint as the robot hardware simulation drives it."""
from __future__ import annotations

from typing import Callable

from turtle_sim_ode.models.built import JointHandle
from turtle_sim_ode.physics import ode_constants as oc


class OdeSimJoint:
    """position() and velocity() are the handle's readers themselves (read for every joint at each control update):
    a continuous joint's unwrapped angle, a slider's position, else ODE's angle; and its rate."""

    def __init__(self, handle: JointHandle) -> None:
        self.handle = handle
        self.position: Callable[[], float] = handle.angle
        prismatic = handle.type == "prismatic"
        self.velocity: Callable[[], float] = handle.joint.getPositionRate if prismatic else handle.joint.getAngleRate
        self._add = handle.joint.addForce if prismatic else handle.joint.addTorque
        self._set_param = handle.joint.setParam
        self._motor_force = 0.0  # the motor's force as last set (0: off)

    def apply_effort(self, effort: float) -> None:
        if self._motor_force:  # an effort-driven joint has no motor holding it
            self._set_param(oc.PARAM_FMAX, 0.0)
            self._motor_force = 0.0
        self._add(effort)

    def drive(self, velocity: float, max_force: float) -> None:
        self._set_param(oc.PARAM_VEL, velocity)
        if max_force != self._motor_force:
            self._set_param(oc.PARAM_FMAX, max_force)
            self._motor_force = max_force
