"""A model's ODE joint as the robot hardware simulation drives it."""
from __future__ import annotations

from turtle_sim_ode.models.built import JointHandle
from turtle_sim_ode.physics import ode_constants as oc


class OdeSimJoint:
    def __init__(self, handle: JointHandle) -> None:
        self.handle = handle
        self._add = handle.joint.addForce if handle.type == "prismatic" else handle.joint.addTorque
        self._motor_force = 0.0  # the motor's force as last set (0: off)

    def position(self) -> float:
        return self.handle.angle()

    def velocity(self) -> float:
        return self.handle.rate()

    def apply_effort(self, effort: float) -> None:
        if self._motor_force:  # an effort-driven joint has no motor holding it
            self.handle.joint.setParam(oc.PARAM_FMAX, 0.0)
            self._motor_force = 0.0
        self._add(effort)

    def drive(self, velocity: float, max_force: float) -> None:
        self.handle.joint.setParam(oc.PARAM_VEL, velocity)
        if max_force != self._motor_force:
            self.handle.joint.setParam(oc.PARAM_FMAX, max_force)
            self._motor_force = max_force
