"""Wrenches on links and efforts on joints, each held from a start time for a duration (gazebo_ros's
apply_body_wrench and apply_joint_effort), ROS-free."""
from __future__ import annotations

import math
from typing import Sequence, Tuple

from turtle_sim_ode.models.transforms import quat_rotate
from turtle_sim_ode.models.urdf import MAX_LENGTH
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.world.entities import SCOPE, EntityLookup
from turtle_sim_ode.world.joint_effort import effort_applier
from turtle_sim_ode.world.kinematics import add, cross, sub
from turtle_sim_ode.world.records import Load
from turtle_sim_ode.world.values import MAX_FORCE, WorldError, finite, vec3

# Tolerance on sim-time comparisons when scheduling loads (s).
TIME_EPSILON = 1e-9


class LoadControl(EntityLookup):
    """Loads scheduled by name; Simulation calls ``apply_loads`` before each step while ``loads`` is not empty (mixed
    into WorldControl)."""

    def _schedule(self, start_time: float, duration: float) -> Tuple[float, float]:
        """(start, end) in sim seconds: a start in the past is now, a negative duration never
        ends."""
        start = max(finite(start_time, "start_time"), self.physics.sim_time)
        duration = finite(duration, "duration")
        return start, math.inf if duration < 0 else start + duration

    def apply_body_wrench(
        self,
        link: str,
        reference_frame: str,
        reference_point: Sequence[float],
        force: Sequence[float],
        torque: Sequence[float],
        start_time: float = 0.0,
        duration: float = -1.0,
    ) -> None:
        """Push the link's body from ``start_time`` for ``duration`` sim seconds (negative:
        until cleared; shorter than a step: one step).

        Force and torque are in the reference frame's axes, taken at the time of the call; the
        force acts at the body's centre of mass plus ``reference_point`` (in those axes) plus,
        for a model or link frame, that frame's origin relative to the link origin. That is
        gazebo_ros' arithmetic, except that the result is applied in world axes as intended
        (gazebo_ros applies body-axis values as world ones), and that wrenches on one body add.
        """
        model, link_name, body = self._link_body(link)
        frame = self._frame(reference_frame)
        lever = vec3(reference_point, "reference_point", MAX_LENGTH)
        push = vec3(force, "force", MAX_FORCE)
        turn = vec3(torque, "torque", MAX_FORCE)
        start, end = self._schedule(start_time, duration)
        if frame is not None:
            (origin, rotation), _, _ = frame
            push = quat_rotate(rotation, push)
            turn = quat_rotate(rotation, turn)
            lever = add(quat_rotate(rotation, lever), sub(origin, model.link_transform(link_name)[0]))
        turn = add(turn, cross(lever, push))
        add_force, add_torque = body.addForce, body.addTorque

        def apply() -> None:
            add_force(push)
            add_torque(turn)

        self.loads.append(Load("wrench", model.name, f"{model.name}{SCOPE}{link_name}", apply, start, end))

    def clear_body_wrenches(self, link: str) -> None:
        """Drop every wrench on this link, scheduled or running."""
        model, link_name = self._link(link)
        target = f"{model.name}{SCOPE}{link_name}"
        self.loads = [load for load in self.loads if not (load.kind == "wrench" and load.target == target)]

    def apply_joint_effort(self, joint: str, effort: float, start_time: float = 0.0, duration: float = -1.0) -> None:
        """Torque (revolute) or force (prismatic) along the joint axis, positive towards
        increasing position, scheduled as ``apply_body_wrench``; held to the joint's velocity
        and effort limits each step as Gazebo does (see world.joint_effort)."""
        model, handle = self._joint(joint)
        effort = finite(effort, "effort", MAX_FORCE)
        limit = sanity.effort_limit(handle.moved_inertia())
        if abs(effort) > limit:
            raise WorldError(
                f"effort {effort:g} on joint '{joint}' must be at most {limit:.3g} in magnitude: it would accelerate "
                f"what the joint moves beyond {sanity.MAX_JOINT_ACCELERATION:g} per s^2"
            )
        start, end = self._schedule(start_time, duration)
        apply = effort_applier(handle, effort, model.robot.joints[handle.name].limits)  # the joint's limits
        self.loads.append(Load("effort", model.name, handle.name, apply, start, end))

    def clear_joint_forces(self, joint: str) -> None:
        """Drop the efforts on this joint; an unscoped name clears that joint in every model
        (as gazebo_ros matches joint names)."""
        model, handle = self._joint(joint)
        everywhere = joint == handle.name
        self.loads = [
            load
            for load in self.loads
            if not (load.kind == "effort" and load.target == handle.name and (everywhere or load.model == model.name))
        ]

    def apply_loads(self) -> None:
        """Add the forces due in the coming step, and drop the loads that end with it."""
        now = self.physics.sim_time
        next_step = now + self.physics.time_step + TIME_EPSILON
        due = []
        for load in self.loads:
            if load.start <= now + TIME_EPSILON:
                load.apply()
                if load.end <= next_step:
                    continue
            due.append(load)
        self.loads = due
