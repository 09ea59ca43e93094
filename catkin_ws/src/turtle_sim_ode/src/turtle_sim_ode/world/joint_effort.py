"""An effort on a joint as Gazebo classic applies it each step (physics/Joint.cc, Joint::CheckAndTruncateForce,
called by Joint::SetForce): none in the direction in which the joint already moves faster than its velocity limit
(URDF <limit velocity>, SDF <limit><velocity>), then truncated to its effort limit."""
from __future__ import annotations

import math
from typing import Callable, Optional

from turtle_sim_ode.control.ode_joint import truncated_effort
from turtle_sim_ode.models.built import JointHandle
from turtle_sim_ode.models.description import JointLimits


def effort_applier(handle: JointHandle, effort: float, limits: Optional[JointLimits]) -> Callable[[], None]:
    """What a scheduled effort load does before each step."""
    add = handle.joint.addForce if handle.type == "prismatic" else handle.joint.addTorque
    velocity_limit = limits.velocity if limits is not None else math.inf
    effort_limit = limits.effort if limits is not None else 0.0

    def apply() -> None:
        add(truncated_effort(effort, handle.rate(), velocity_limit, effort_limit))

    return apply
