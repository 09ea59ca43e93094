"""{position,effort}_controllers/GripperActionController (ros_controllers' gripper_action_controller): one joint
moved to a goal's position with at most its max_effort, through the gripper_cmd action (control_msgs/GripperCommand).

Parameters: joint, goal_tolerance (0.01), max_effort (0: the effort when no goal runs), stall_velocity_threshold
(0.001), stall_timeout (1.0 s); for an effort joint gains/<joint> (a Pid, p required). A goal succeeds once the
position error is below goal_tolerance (reached_goal), and is aborted once the joint has not moved faster than the
threshold for stall_timeout (stalled), as checkForSuccess decides; a new goal preempts the running one."""
from __future__ import annotations

from typing import List, Optional, Tuple

from turtle_sim_ode.control.controller import Controller
from turtle_sim_ode.control.hardware import RobotHW, clamp
from turtle_sim_ode.control.joint_controllers import urdf_joint_type
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.pid import Pid, read_gains
from turtle_sim_ode.control.transmissions import EFFORT
from turtle_sim_ode.models.description import RobotModel


class GripperActionController(Controller):
    def __init__(self, interface: str) -> None:
        super().__init__()
        self.interface = interface
        self.results: List[Tuple[str, str, dict]] = []  # goal id, succeeded/aborted/preempted, result fields
        self.active: Optional[str] = None
        self.pid: Optional[Pid] = None

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        if not params.has("joint"):
            raise ControllerError("Could not find joint name on param server")
        name = params.string("joint")
        self.joint = self.claim(hw, name)
        urdf_joint_type(robot, name)
        self.goal_tolerance = abs(params.number("goal_tolerance", 0.01))
        self.default_max_effort = abs(params.number("max_effort", 0.0))
        self.stall_velocity_threshold = params.number("stall_velocity_threshold", 0.001)
        self.stall_timeout = params.number("stall_timeout", 1.0)
        if self.interface == EFFORT:
            try:
                self.pid = Pid(read_gains(params.child("gains").child(name)))
            except ControllerError:
                raise ControllerError("Failed to initialize PID gains from ROS parameter server.") from None
        self.target, self.max_effort, self.computed = 0.0, self.default_max_effort, 0.0
        self.now = self.last_movement = 0.0

    def starting(self, time: float) -> None:
        self.target, self.max_effort = self.joint.position, self.default_max_effort
        self.now = self.last_movement = time
        if self.pid is not None:
            self.pid.reset()
            self.joint.command = 0.0

    def stopping(self, time: float) -> None:
        self._finish("preempted", False, False)

    def submit(self, goal_id: str, position: float, max_effort: float) -> Tuple[bool, str]:
        if not self.running:
            return False, "Can't accept new action goals. Controller is not running."
        self._finish("preempted", False, False)
        self.target, self.max_effort = position, max_effort
        self.active, self.last_movement = goal_id, self.now
        return True, ""

    def cancel(self, goal_id: str) -> None:
        """The running goal canceled: hold the current position with the default effort."""
        if self.active == goal_id:
            self._finish("preempted", False, False)
            self.target, self.max_effort = self.joint.position, self.default_max_effort

    def _finish(self, status: str, reached: bool, stalled: bool) -> None:
        if self.active is not None:
            result = {
                "position": self.joint.position,
                "effort": self.computed,
                "stalled": stalled,
                "reached_goal": reached,
            }
            self.results.append((self.active, status, result))
            self.active = None

    def update(self, time: float, period: float) -> None:
        self.now = time
        error = self.target - self.joint.position
        if self.active is not None:
            if abs(error) < self.goal_tolerance:
                self._finish("succeeded", True, False)
            elif abs(self.joint.velocity) > self.stall_velocity_threshold:
                self.last_movement = time
            elif time - self.last_movement > self.stall_timeout:
                self._finish("aborted", False, True)
        if self.pid is None:  # position joint: the target is the command, max_effort is reported
            self.joint.command, self.computed = self.target, self.max_effort
        else:
            effort = self.pid.compute(error, period, -self.joint.velocity)
            self.computed = self.joint.command = clamp(effort, -abs(self.max_effort), abs(self.max_effort))
