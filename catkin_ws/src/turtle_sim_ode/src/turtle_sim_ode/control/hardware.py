"""The robot hardware that controllers claim joints from: hardware_interface's JointStateInterface and the
Effort/Velocity/PositionJointInterface, filled and written by gazebo_ros_control's DefaultRobotHWSim.

A simulated joint is anything with position(), velocity(), apply_effort(effort) and drive(velocity, max_force)
(control.ode_joint wraps an ODE joint; the unit tests use a point mass). DefaultRobotHWSim::writeSim's control
methods: EFFORT applies the saturated effort; POSITION_PID and VELOCITY_PID run a control_toolbox Pid on the
joint's error and apply its effort, clamped to the effort limit; POSITION and VELOCITY without gains drive the
joint's motor (Gazebo sets the position or the velocity of the joint; here a velocity motor with the effort
limit as its force reaches it within one step where that force allows).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Mapping, Optional, Protocol

from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.pid import Pid, read_gains
from turtle_sim_ode.control.transmissions import (
    EFFORT,
    JOINT_STATE,
    POSITION,
    VELOCITY,
    Limits,
    TransmissionJoint,
    cpp_name,
    limits_from_params,
)

# The force of a velocity motor on a joint without an effort limit (N or N m).
UNLIMITED_MOTOR_FORCE = 1e4


class SimJoint(Protocol):
    def position(self) -> float:
        ...

    def velocity(self) -> float:
        ...

    def apply_effort(self, effort: float) -> None:
        ...

    def drive(self, velocity: float, max_force: float) -> None:
        ...


def clamp(value: float, low: float, high: float) -> float:
    return max(low, min(high, value))


def shortest_angular_distance(source: float, target: float) -> float:
    """angles::shortest_angular_distance: target - source wrapped to [-pi, pi]."""
    delta = math.fmod(target - source + math.pi, 2.0 * math.pi)
    if delta < 0.0:
        delta += 2.0 * math.pi
    return delta - math.pi


def position_error(joint_type: str, current: float, target: float) -> float:
    """The error a position loop works on: the short way round for a continuous joint, else the difference (a
    revolute joint's limits span less than a turn in the models here, so the direct way is the only one)."""
    if joint_type == "continuous":
        return shortest_angular_distance(current, target)
    return target - current


@dataclass
class JointData:
    """One joint's state, as the hardware interfaces hand it to controllers, and its command."""

    name: str
    type: str
    interface: str
    limits: Limits
    position: float = 0.0
    velocity: float = 0.0
    effort: float = 0.0
    command: float = 0.0

    @property
    def motor_force(self) -> float:
        """The force of a velocity motor driving it: the effort limit, if it has one."""
        return self.limits.effort if self.limits.effort < math.inf else UNLIMITED_MOTOR_FORCE


@dataclass
class RobotHW:
    """The joints by name; each offers JointStateInterface and the one command interface of its transmission."""

    joints: Dict[str, JointData] = field(default_factory=dict)

    def interfaces(self) -> List[str]:
        return sorted({JOINT_STATE} | {joint.interface for joint in self.joints.values()})

    def handle(self, interface: str, name: str) -> JointData:
        """hardware_interface's getHandle: the joint if it offers the interface, else the exception's message."""
        joint = self.joints.get(name)
        if joint is None or (interface != JOINT_STATE and joint.interface != interface):
            raise ControllerError(f"Could not find resource '{name}' in '{cpp_name(interface)}'.")
        return joint


class DefaultRobotHWSim(RobotHW):
    """gazebo_ros_control's DefaultRobotHWSim over simulated joints."""

    def __init__(
        self,
        transmissions: List[TransmissionJoint],
        sim_joints: Mapping[str, SimJoint],
        robot_params: Optional[Mapping[str, object]] = None,
    ) -> None:
        """robot_params: the robot namespace's parameter tree (pid_gains under gazebo_ros_control/, and
        joint_limits/)."""
        super().__init__()
        tree = Params(dict(robot_params or {}), "")
        limit_params = tree.raw("joint_limits")
        self.sim_joints = dict(sim_joints)
        self.pids: Dict[str, Pid] = {}
        self.last_position_command: Dict[str, float] = {}
        self.warnings: List[str] = []
        for spec in transmissions:
            limits = limits_from_params(spec.limits, limit_params.get(spec.name) if limit_params else None)
            self.joints[spec.name] = JointData(spec.name, spec.type, spec.interface, limits)
            gains = tree.child("gazebo_ros_control/pid_gains").child(spec.name)
            if spec.interface != EFFORT and gains.has("p"):
                try:
                    self.pids[spec.name] = Pid(read_gains(gains))
                except ControllerError as error:
                    self.warnings.append(str(error))
        # Each joint with its simulated joint's readers and its writer for its control method, looked up once: read
        # and write run every step.
        self._readers = [
            (joint, self.sim_joints[name].position, self.sim_joints[name].velocity)
            for name, joint in self.joints.items()
        ]
        self._writers = [self._writer(joint, self.sim_joints[name]) for name, joint in self.joints.items()]
        self.read()
        for joint in self.joints.values():
            joint.command = joint.position if joint.interface == POSITION else 0.0

    def control_method(self, name: str) -> str:
        """EFFORT, POSITION, POSITION_PID, VELOCITY or VELOCITY_PID, as DefaultRobotHWSim names them."""
        base = self.joints[name].interface.split("/")[1].replace("JointInterface", "").upper()
        return base + "_PID" if name in self.pids else base

    def read(self) -> None:
        for joint, position, velocity in self._readers:
            joint.position = position()
            joint.velocity = velocity()

    def write(self, period: float) -> None:
        """Saturate the commands to the joint limits (joint_limits_interface's saturation handles) and apply
        them for the coming step."""
        for write in self._writers:
            write(period)

    def _writer(self, joint: JointData, sim: SimJoint) -> Callable[[float], None]:
        """What write does with ``joint`` each step, by its control method: a non-finite command counts as 0."""
        limits, pid = joint.limits, self.pids.get(joint.name)
        isfinite = math.isfinite
        if joint.interface == EFFORT:

            def write_effort(_period: float) -> None:
                command = joint.command if isfinite(joint.command) else 0.0
                joint.effort = clamp(command, -limits.effort, limits.effort)
                sim.apply_effort(joint.effort)

            return write_effort
        if joint.interface == POSITION:

            def write_position(period: float) -> None:
                command = joint.command if isfinite(joint.command) else 0.0
                command = self._saturated_position(joint.name, command, period)
                error = position_error(joint.type, joint.position, command)
                if pid is not None:
                    self._apply_pid(joint, sim, error, period)
                else:
                    sim.drive(error / period if period > 0 else 0.0, joint.motor_force)

            return write_position
        if joint.interface == VELOCITY:
            low, high, drive, force = -limits.velocity, limits.velocity, sim.drive, joint.motor_force

            def write_velocity(period: float) -> None:
                command = joint.command if isfinite(joint.command) else 0.0
                command = low if command < low else min(command, high)
                if pid is not None:
                    self._apply_pid(joint, sim, command - joint.velocity, period)
                else:
                    drive(command, force)

            return write_velocity
        return lambda _period: None

    def _saturated_position(self, name: str, command: float, period: float) -> float:
        """PositionJointSaturationHandle: within the position limits and, with a velocity limit, within
        velocity * period of the last command."""
        joint = self.joints[name]
        low, high = joint.limits.lower, joint.limits.upper
        last = self.last_position_command.get(name, joint.position)
        if math.isfinite(joint.limits.velocity) and period > 0:
            low = max(low, last - joint.limits.velocity * period)
            high = min(high, last + joint.limits.velocity * period)
        command = clamp(command, low, high)
        self.last_position_command[name] = command
        return command

    def _apply_pid(self, joint: JointData, sim: SimJoint, error: float, period: float) -> None:
        effort = self.pids[joint.name].compute(error, period)
        joint.effort = clamp(effort, -joint.limits.effort, joint.limits.effort)
        sim.apply_effort(joint.effort)
