"""{position,velocity,effort}_controllers/JointTrajectoryController (ros_controllers' joint_trajectory_controller).

Parameters: joints (required), constraints/goal_time (0), constraints/stopped_velocity_tolerance (0.01),
constraints/<joint>/trajectory and /goal (0: not checked), state_publish_rate (50), action_monitor_rate (20),
stop_trajectory_duration (0), allow_partial_joints_goal (false); for effort and velocity joints gains/<joint>
(a Pid, p required) and velocity_ff/<joint> (0). The command is velocity_ff * desired velocity + Pid(position
error, velocity error); a position joint takes the desired position.

A trajectory (from the ``command`` topic or a follow_joint_trajectory goal) replaces the current one from its
start time (the header stamp, or the next update if it is zero): a segment from the desired state then to the
first point still ahead, then one between each two points. Goals: the joint names must be the controller's
(INVALID_JOINTS), times strictly increasing and sizes consistent (INVALID_GOAL); while the last segment runs,
a path tolerance exceeded aborts with PATH_TOLERANCE_VIOLATED; after it, the goal succeeds once every joint is
within its goal tolerances, and aborts with GOAL_TOLERANCE_VIOLATED if that has not happened goal_time after
the end.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

from turtle_sim_ode.control.controller import Controller, Throttle
from turtle_sim_ode.control.hardware import RobotHW, shortest_angular_distance
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.pid import Pid, read_gains
from turtle_sim_ode.control.spline import Segment, State
from turtle_sim_ode.control.transmissions import POSITION
from turtle_sim_ode.models.description import RobotModel

SUCCESSFUL, INVALID_GOAL, INVALID_JOINTS = 0, -1, -2
PATH_TOLERANCE_VIOLATED, GOAL_TOLERANCE_VIOLATED = -4, -5


@dataclass
class Tolerance:
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0

    def holds(self, error: Tuple[float, float, float]) -> bool:
        limits = (self.position, self.velocity, self.acceleration)
        return not any(limit > 0.0 and abs(value) > limit for limit, value in zip(limits, error))

    def overridden(self, message: Tuple[float, float, float]) -> "Tolerance":
        """A goal's JointTolerance: > 0 replaces, < 0 removes (0), 0 keeps the default."""
        values = [
            mine if theirs == 0.0 else (theirs if theirs > 0.0 else 0.0)
            for mine, theirs in zip((self.position, self.velocity, self.acceleration), message)
        ]
        return Tolerance(*values)


@dataclass
class Point:
    positions: List[float]
    velocities: List[float]
    accelerations: List[float]
    time_from_start: float


@dataclass
class TrajectoryGoal:
    """A JointTrajectory (stamp 0: now) with the goal's tolerances: name -> (position, velocity, acceleration)."""

    joint_names: List[str]
    points: List[Point]
    stamp: float = 0.0
    path_tolerance: Dict[str, Tuple[float, float, float]] = field(default_factory=dict)
    goal_tolerance: Dict[str, Tuple[float, float, float]] = field(default_factory=dict)
    goal_time_tolerance: float = 0.0
    goal_id: Optional[str] = None


@dataclass
class ActiveGoal:
    goal_id: str
    end_time: float
    path: List[Tolerance]
    goal: List[Tolerance]
    goal_time: float


class JointTrajectoryController(Controller):
    def __init__(self, interface: str) -> None:
        super().__init__()
        self.interface = interface
        self.segments: List[List[Segment]] = []
        self.active: Optional[ActiveGoal] = None
        # goal id, succeeded/aborted/preempted, the result's fields (error_code, error_string)
        self.results: List[Tuple[str, str, dict]] = []
        self.feedback: List[Tuple[str, dict]] = []  # goal id, the state payload, at action_monitor_rate
        self.errors: List[str] = []

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        names = params.strings("joints")
        self.joints = [self.claim(hw, name) for name in names]
        self.names = names
        self.wraps = [joint.type == "continuous" for joint in self.joints]
        constraints = params.child("constraints")
        stopped = constraints.number("stopped_velocity_tolerance", 0.01)
        self.default_path = [Tolerance(constraints.number(f"{n}/trajectory", 0.0)) for n in names]
        self.default_goal = [Tolerance(constraints.number(f"{n}/goal", 0.0), stopped) for n in names]
        self.default_goal_time = constraints.number("goal_time", 0.0)
        self.state_throttle = Throttle(params.number("state_publish_rate", 50.0))
        self.feedback_throttle = Throttle(params.number("action_monitor_rate", 20.0))
        self.stop_duration = params.number("stop_trajectory_duration", 0.0)
        self.allow_partial = params.flag("allow_partial_joints_goal", False)
        self.pids: List[Pid] = []
        self.velocity_ff: List[float] = []
        if self.interface != POSITION:
            for name in names:
                try:
                    self.pids.append(Pid(read_gains(params.child("gains").child(name))))
                except ControllerError:
                    raise ControllerError("Failed to initialize PID gains from ROS parameter server.") from None
                self.velocity_ff.append(params.number(f"velocity_ff/{name}", 0.0))
        self.inputs["command"] = ("joint_trajectory", self._on_command)
        self.outputs["state"] = "joint_trajectory_state"
        self.now = 0.0
        self.period = 0.0

    # --- life cycle ---------------------------------------------------------------
    def starting(self, time: float) -> None:
        self.now = time
        self._hold(time)
        for pid in self.pids:
            pid.reset()
        for joint in self.joints:
            joint.command = joint.position if self.interface == POSITION else 0.0
        self.state_throttle.start(time, publish_first=False)
        self.feedback_throttle.start(time, publish_first=False)

    def stopping(self, time: float) -> None:
        self._finish("preempted", INVALID_GOAL, "Controller stopped")

    def _hold(self, time: float) -> None:
        """setHoldPosition: stay at the current position (ramping to rest over stop_trajectory_duration)."""
        self.segments = [
            [Segment.between(time, (j.position, 0.0, 0.0), time + self.stop_duration, (j.position, 0.0, 0.0))]
            for j in self.joints
        ]

    def desired(self, time: float) -> List[Tuple[float, float, float]]:
        out = []
        for segments in self.segments:
            segment = next((s for s in segments if time < s.end_time), segments[-1])
            if time < segment.start_time:
                segment = segments[0]
            out.append(segment.sample(time))
        return out

    def update(self, time: float, period: float) -> None:
        self.now, self.period = time, period
        desired = self.desired(time)
        errors = []
        for i, (joint, want) in enumerate(zip(self.joints, desired)):
            position_error = want[0] - joint.position
            if self.wraps[i]:
                position_error = shortest_angular_distance(joint.position, want[0])
            errors.append((position_error, want[1] - joint.velocity, want[2]))
        self._check_goal(time, errors)
        for i, joint in enumerate(self.joints):
            if self.interface == POSITION:
                joint.command = desired[i][0]
            else:
                pid = self.pids[i].compute(errors[i][0], period, errors[i][1])
                joint.command = desired[i][1] * self.velocity_ff[i] + pid
        state_due, feedback_due = self.state_throttle.due(time), self.feedback_throttle.due(time)
        if state_due or (feedback_due and self.active is not None):
            actual = [(j.position, j.velocity, 0.0) for j in self.joints]
            state = {"stamp": time, "joint_names": self.names, "desired": desired, "actual": actual, "error": errors}
            if state_due:
                self.publish("state", "joint_trajectory_state", state)
            if feedback_due and self.active is not None:
                self.feedback.append((self.active.goal_id, state))

    def _check_goal(self, time: float, errors: Sequence[Tuple[float, float, float]]) -> None:
        goal = self.active
        if goal is None:
            return
        if time < goal.end_time:
            for name, tolerance, error in zip(self.names, goal.path, errors):
                if not tolerance.holds(error):
                    self._finish("aborted", PATH_TOLERANCE_VIOLATED, f"{name} path error {error[0]:f}")
                    return
            return
        if all(tolerance.holds(error) for tolerance, error in zip(goal.goal, errors)):
            self._finish("succeeded", SUCCESSFUL, "")
        elif time >= goal.end_time + goal.goal_time:
            failed = next(n for n, t, e in zip(self.names, goal.goal, errors) if not t.holds(e))
            error = errors[self.names.index(failed)][0]
            self._finish("aborted", GOAL_TOLERANCE_VIOLATED, f"{failed} goal error {error:f}")

    def _finish(self, status: str, code: int, text: str) -> None:
        if self.active is not None:
            self.results.append((self.active.goal_id, status, {"error_code": code, "error_string": text}))
            self.active = None

    # --- new trajectories -----------------------------------------------------------
    def _on_command(self, goal: TrajectoryGoal) -> None:
        code, text = self.submit(goal)
        if code != SUCCESSFUL:
            self.errors.append(text)

    def submit(self, goal: TrajectoryGoal) -> Tuple[int, str]:
        """Take a trajectory (a goal when goal.goal_id is set): (SUCCESSFUL, "") or (error code, message)."""
        if not self.running:
            return INVALID_GOAL, "Can't accept new commands. Controller is not running."
        if not goal.points:
            self._finish("preempted", SUCCESSFUL, "")
            self._hold(self.now)
            return SUCCESSFUL, ""
        names = goal.joint_names
        if len(set(names)) != len(names) or not set(names) <= set(self.names):
            return INVALID_JOINTS, "Joints on incoming goal don't match the controller joints."
        if set(names) != set(self.names) and not self.allow_partial:
            return INVALID_JOINTS, "Joints on incoming goal don't match the controller joints."
        times = [p.time_from_start for p in goal.points]
        if any(b <= a for a, b in zip(times, times[1:])) or any(not math.isfinite(t) for t in times):
            return INVALID_GOAL, "Trajectory message contains waypoints that are not strictly increasing in time."
        for point in goal.points:
            sizes = {len(point.positions)} | {len(v) for v in (point.velocities, point.accelerations) if v}
            values = point.positions + point.velocities + point.accelerations
            if sizes != {len(names)} or not all(math.isfinite(v) for v in values):
                return INVALID_GOAL, "Size mismatch in trajectory point position, velocity or acceleration data."
        start = goal.stamp if goal.stamp > 0.0 else self.now + self.period
        ahead = [p for p in goal.points if start + p.time_from_start > self.now]
        if not ahead:
            return INVALID_GOAL, (
                f"Dropping all {len(goal.points)} trajectory point(s), as they occur before the current time."
            )
        self._replace(goal, ahead, start)
        return SUCCESSFUL, ""

    def _replace(self, goal: TrajectoryGoal, points: List[Point], start: float) -> None:
        now_desired = self.desired(self.now)
        segments = []
        for i, name in enumerate(self.names):
            if name not in goal.joint_names:  # a partial goal leaves this joint where it is headed
                segments.append(self.segments[i])
                continue
            k = goal.joint_names.index(name)
            states: List[Tuple[float, State]] = [(self.now, now_desired[i])]
            for point in points:
                position = point.positions[k]
                if self.wraps[i]:  # the short way round from the state before
                    position = states[-1][1][0] + shortest_angular_distance(states[-1][1][0], position)
                velocity = point.velocities[k] if point.velocities else None
                acceleration = point.accelerations[k] if point.accelerations else None
                states.append((start + point.time_from_start, (position, velocity, acceleration)))
            if states[1][1][1] is None:  # positions only: the first segment is linear too
                states[0] = (states[0][0], (states[0][1][0], None, None))
            segments.append([Segment.between(t0, s0, t1, s1) for (t0, s0), (t1, s1) in zip(states, states[1:])])
        self.segments = segments
        self._finish("preempted", SUCCESSFUL, "")
        if goal.goal_id is not None:
            self.active = ActiveGoal(
                goal.goal_id,
                start + points[-1].time_from_start,
                [
                    t.overridden(goal.path_tolerance.get(n, (0.0, 0.0, 0.0)))
                    for n, t in zip(self.names, self.default_path)
                ],
                [
                    t.overridden(goal.goal_tolerance.get(n, (0.0, 0.0, 0.0)))
                    for n, t in zip(self.names, self.default_goal)
                ],
                goal_time(goal.goal_time_tolerance, self.default_goal_time),
            )


def goal_time(requested: float, default: float) -> float:
    """A goal's goal_time_tolerance: > 0 replaces the default, < 0 removes it (0), 0 keeps it."""
    return requested if requested > 0 else (0.0 if requested < 0 else default)
