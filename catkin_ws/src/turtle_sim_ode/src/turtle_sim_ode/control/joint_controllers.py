"""ros_controllers' single-joint and joint-group controllers of effort_controllers, velocity_controllers and
position_controllers: forward_command_controller's pass-through ones and the PID ones.

Topics: ``command`` (std_msgs/Float64, or Float64MultiArray for a group) and, for a PID on one joint, ``state``
(control_msgs/JointControllerState, every 10th update, as JointPositionController::update publishes it).
"""
from __future__ import annotations

from typing import List, Optional

from turtle_sim_ode.control.controller import Controller
from turtle_sim_ode.control.hardware import JointData, RobotHW, clamp, position_error
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.pid import Pid, read_gains
from turtle_sim_ode.control.transmissions import EFFORT, POSITION
from turtle_sim_ode.models.description import RobotModel

STATE_EVERY = 10  # updates between two JointControllerState messages


def urdf_joint_type(robot: Optional[RobotModel], name: str) -> str:
    if robot is None:
        raise ControllerError("Failed to parse urdf file")
    joint = robot.joints.get(name)
    if joint is None:
        raise ControllerError(f"Could not find joint '{name}' in urdf")
    return joint.type


def limited_position(joint: JointData, command: float) -> float:
    """enforceJointLimits: a revolute or prismatic joint's command within its position limits."""
    return clamp(command, joint.limits.lower, joint.limits.upper)


class ForwardCommand(Controller):
    """forward_command_controller::ForwardCommandController on ``joint``: the command is the joint's command.
    Starting: 0 for effort and velocity, the current position for position (as each package specialises it)."""

    def __init__(self, interface: str) -> None:
        super().__init__()
        self.interface = interface
        self.command = 0.0

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        self.joint = self.claim(hw, params.string("joint"))
        self.inputs["command"] = ("float64", self._on_command)

    def _on_command(self, value: float) -> None:
        self.command = float(value)

    def starting(self, time: float) -> None:
        self.command = self.joint.position if self.interface == POSITION else 0.0

    def update(self, time: float, period: float) -> None:
        self.joint.command = self.command


class ForwardGroupCommand(Controller):
    """forward_command_controller::ForwardJointGroupCommandController on ``joints``; a command of the wrong
    length is refused with upstream's message."""

    def __init__(self, interface: str) -> None:
        super().__init__()
        self.interface = interface
        self.errors: List[str] = []

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        self.joints = [self.claim(hw, name) for name in params.strings("joints")]
        self.commands = [0.0] * len(self.joints)
        self.inputs["command"] = ("float64_array", self._on_command)

    def _on_command(self, values: List[float]) -> None:
        if len(values) != len(self.joints):
            self.errors.append(
                f"Dimension of command ({len(values)}) does not match number of joints ({len(self.joints)})! "
                "Not executing!"
            )
            return
        self.commands = [float(v) for v in values]

    def starting(self, time: float) -> None:
        if self.interface == POSITION:
            self.commands = [joint.position for joint in self.joints]
        else:
            self.commands = [0.0] * len(self.joints)

    def update(self, time: float, period: float) -> None:
        for joint, command in zip(self.joints, self.commands):
            joint.command = command


class _PidJoint(Controller):
    """What the single-joint Pid controllers share: params ``joint`` and ``pid``, a float64 ``command``, and a
    control_msgs/JointControllerState every STATE_EVERY updates."""

    def __init__(self) -> None:
        super().__init__()
        self.target = 0.0
        self.count = 0

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        self.pid = Pid(read_gains(params.child("pid")))
        self.joint = self.claim(hw, params.string("joint"))
        self.inputs["command"] = ("float64", self._on_command)
        self.outputs["state"] = "joint_controller_state"

    def _on_command(self, value: float) -> None:
        self.target = float(value)

    def _command(self, time: float, period: float, target: float, error: float) -> None:
        """The Pid's output on ``error`` to the joint, and the state now and then."""
        self.joint.command = self.pid.compute(error, period)
        if self.count % STATE_EVERY == 0:
            self.publish("state", "joint_controller_state", state(self.pid, time, target, self.joint, error, period))
        self.count += 1


class PidPosition(_PidJoint):
    """effort_controllers/JointPositionController (effort out) and velocity_controllers/JointPositionController
    (velocity out): a Pid from ``pid`` on the position error, the velocity error being the derivative."""

    def __init__(self, interface: str) -> None:
        super().__init__()
        self.interface = interface

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        super().init(hw, params, robot)
        self.type = urdf_joint_type(robot, self.joint.name)

    def starting(self, time: float) -> None:
        self.target = limited_position(self.joint, self.joint.position)
        self.pid.reset()
        self.count = 0

    def update(self, time: float, period: float) -> None:
        target = limited_position(self.joint, self.target)
        self._command(time, period, target, position_error(self.type, self.joint.position, target))


class PidVelocity(_PidJoint):
    """effort_controllers/JointVelocityController: a Pid on command - velocity, effort out."""

    interface = EFFORT

    def starting(self, time: float) -> None:
        self.target = 0.0
        self.pid.reset()
        self.count = 0

    def update(self, time: float, period: float) -> None:
        self._command(time, period, self.target, self.target - self.joint.velocity)


class PidGroupPosition(Controller):
    """effort_controllers/JointGroupPositionController: one Pid per joint from ``<joint>/pid``."""

    interface = EFFORT

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        names = params.strings("joints")
        self.joints = [self.claim(hw, name) for name in names]
        self.types = [urdf_joint_type(robot, name) for name in names]
        self.pids = []
        for name in names:
            try:
                self.pids.append(Pid(read_gains(params.child(name).child("pid"))))
            except ControllerError as error:
                raise ControllerError(f"Failed to load PID parameters from {name}/pid: {error}") from None
        self.group = ForwardGroupCommand(EFFORT)
        self.group.joints = self.joints
        self.group.commands = [0.0] * len(self.joints)
        self.errors = self.group.errors
        self.inputs["command"] = ("float64_array", self.group._on_command)

    def starting(self, time: float) -> None:
        self.group.commands = [joint.position for joint in self.joints]
        for pid in self.pids:
            pid.reset()

    def update(self, time: float, period: float) -> None:
        for joint, joint_type, pid, target in zip(self.joints, self.types, self.pids, self.group.commands):
            error = position_error(joint_type, joint.position, limited_position(joint, target))
            joint.command = pid.compute(error, period)


def state(pid: Pid, time: float, target: float, joint: JointData, error: float, period: float) -> dict:
    """control_msgs/JointControllerState's fields."""
    gains = pid.gains
    return {
        "stamp": time,
        "set_point": target,
        "process_value": joint.position,
        "process_value_dot": joint.velocity,
        "error": error,
        "time_step": period,
        "command": joint.command,
        "p": gains.p,
        "i": gains.i,
        "d": gains.d,
        "i_clamp": gains.i_max,
        "antiwindup": gains.antiwindup,
    }
