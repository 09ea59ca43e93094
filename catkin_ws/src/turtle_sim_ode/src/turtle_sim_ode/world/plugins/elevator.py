"""gazebo_ros_elevator (``libgazebo_ros_elevator.so``, gazebo_plugins/src/gazebo_ros_elevator.cpp): gazebo-classic's
ElevatorPlugin (plugins/ElevatorPlugin.cc) driven by a ROS topic. Its tags (ElevatorPlugin::Load): <lift_joint> and
<door_joint> (prismatic joints, 'model::joint' scoped or not), <floor_height> (3 m, with a warning, where absent),
<door_wait_time> (5 s); GazeboRosElevator::Load: <topic> ("elevator"), <robotNamespace>.

A floor number asks for a ride (MoveToFloor, ignored while a ride is under way): close the door, move the car to
floor * floor_height, open the door, wait door_wait_time, close the door; each state ends when its controller says
so. Every step (Update, on the world's update-begin) runs the front state, then both controllers:

- door: a PID (p 2, i 0, d 1, gazebo::common::PID) on position - target (1 m open, 0 closed) whose force is set on
  the door joint; still (STATIONARY) within 0.05 m. Upstream never moves the door's previous time on from its first
  update, so the door's derivative divides by the time since then; so here.
- lift: a PID (p 100000, i 0, d 100000) on position - floor * floor_height, with the step as its time; still
  within 0.15 m.

Forces are truncated to the joints' effort limits as Joint::SetForce does. The wait counts sim time here (upstream's
common::Timer counts wall time: the same at real time)."""
from __future__ import annotations

import threading
from collections import deque
from dataclasses import dataclass
from typing import Deque, List, Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.control.ode_joint import truncated_effort
from turtle_sim_ode.world.plugins.tags import number, text

ELEVATOR = "libgazebo_ros_elevator.so"
MODEL_PLUGINS = (ELEVATOR,)

DOOR_GAINS = (2.0, 0.0, 1.0)  # DoorController: doorPID.Init(2, 0, 1.0)
LIFT_GAINS = (100000.0, 0.0, 100000.0)  # LiftController: liftPID.Init(100000, 0, 100000.0)
DOOR_OPEN, DOOR_CLOSED = 1.0, 0.0  # m: DoorController::Update's targets
DOOR_STILL, LIFT_STILL = 0.05, 0.15  # m: within these of its target a controller is STATIONARY
DEFAULT_FLOOR_HEIGHT = 3.0
DEFAULT_DOOR_WAIT = 5.0


@dataclass(frozen=True)
class ElevatorConfig:
    lift_joint: str
    door_joint: str
    floor_height: float = DEFAULT_FLOOR_HEIGHT
    door_wait_time: float = DEFAULT_DOOR_WAIT
    topic: str = "elevator"
    robot_namespace: str = ""
    warnings: Tuple[str, ...] = ()

    @property
    def joints_needed(self) -> Tuple[str, str]:
        return (self.lift_joint, self.door_joint)


def _joint(model_name: str, plugin: GazeboPlugin, tag: str) -> str:
    """The joint a tag names, without its 'model::' scope (Model::GetJoint takes both)."""
    name = text(plugin, tag, "")
    if not name:
        raise ModelError(f"{plugin.filename} needs <{tag}>")
    prefix = model_name + "::"
    return name[len(prefix) :] if name.startswith(prefix) else name


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> ElevatorConfig:
    warnings = ()
    if "floor_height" not in plugin.params:
        warnings = (f"{plugin.filename}: no <floor_height>: {DEFAULT_FLOOR_HEIGHT:g} m (upstream's warning)",)
    return ElevatorConfig(
        _joint(model_name, plugin, "lift_joint"),
        _joint(model_name, plugin, "door_joint"),
        number(plugin, "floor_height", DEFAULT_FLOOR_HEIGHT),
        number(plugin, "door_wait_time", DEFAULT_DOOR_WAIT),
        text(plugin, "topic", "elevator"),
        text(plugin, "robotNamespace", ""),
        warnings,
    )


class GazeboPid:
    """gazebo::common::PID::Update without integral limits or command clamps (Init's defaults leave none): the
    command is -(p e + i sum(e dt) + d (e - last e) / dt); 0 for dt <= 0."""

    def __init__(self, gains: Tuple[float, float, float]) -> None:
        self.p, self.i, self.d = gains
        self._integral = 0.0
        self._last = 0.0

    def update(self, error: float, dt: float) -> float:
        if dt <= 0.0:
            return 0.0
        self._integral += dt * error
        derivative = (error - self._last) / dt
        self._last = error
        return -(self.p * error + self.i * self._integral + self.d * derivative)


class _Controller:
    """A joint driven to a target by a PID; ``still`` within ``tolerance`` of it."""

    def __init__(self, model: BuiltModel, joint: str, gains: Tuple[float, float, float], tolerance: float) -> None:
        self.handle: JointHandle = model.joint(joint)
        if self.handle.type != "prismatic":  # upstream pushes any joint; a force needs a slider here
            raise ModelError(f"elevator joint '{joint}' is {self.handle.type}, not prismatic")
        limits = model.robot.joints[joint].limits
        self._effort_limit = limits.effort if limits is not None else 0.0
        self._pid = GazeboPid(gains)
        self._tolerance = tolerance
        self.target = 0.0
        self.still = True
        self._started: Optional[float] = None  # the first update's time (None: bootstrap at the next)
        self._previous = 0.0

    def update(self, now: float, keep_first_time: bool) -> None:
        if self._started is None:  # upstream bootstraps its time on the first update
            self._started = self._previous = now
            return
        error = self.handle.angle() - self.target
        force = self._pid.update(error, now - self._previous)
        if not keep_first_time:
            self._previous = now
        self.handle.joint.addForce(truncated_effort(force, self.handle.rate(), 0.0, self._effort_limit))
        self.still = abs(error) < self._tolerance

    def reset(self) -> None:
        self._started = None


class Elevator:
    """The plugin's per-step work on ``model`` (a step hook: ``step``, ``reset``); ``move_to_floor`` from any
    thread."""

    def __init__(self, model: BuiltModel, config: ElevatorConfig) -> None:
        self.config = config
        self.door = _Controller(model, config.door_joint, DOOR_GAINS, DOOR_STILL)
        self.lift = _Controller(model, config.lift_joint, LIFT_GAINS, LIFT_STILL)
        # (kind, value): "close", "move" (floor), "open", "wait" (seconds); the front one runs, started or not.
        self._states: Deque[List] = deque()
        self._front_started: Optional[float] = None
        self._lock = threading.Lock()

    @property
    def busy(self) -> bool:
        return bool(self._states)

    def move_to_floor(self, floor: int) -> bool:
        """Queue a ride; False (nothing queued) while one is under way, as upstream ignores the message."""
        with self._lock:
            if self._states:
                return False
            wait = self.config.door_wait_time
            self._states.extend((["close", 0], ["move", floor], ["open", 0], ["wait", wait], ["close", 0]))
            return True

    def _front_done(self, now: float) -> bool:
        kind, value = self._states[0]
        if self._front_started is None:  # each state's Start takes one update
            self._front_started = now
            if kind in ("close", "open"):
                self.door.target = DOOR_OPEN if kind == "open" else DOOR_CLOSED
            elif kind == "move":
                self.lift.target = value * self.config.floor_height
            return False
        if kind in ("close", "open"):
            return self.door.still
        if kind == "move":
            return self.lift.still
        return now - self._front_started >= value

    def step(self, now: float, dt: float) -> None:
        with self._lock:
            if self._states and self._front_done(now):
                self._states.popleft()
                self._front_started = None
        self.door.update(now, keep_first_time=True)
        self.lift.update(now, keep_first_time=False)

    def reset(self) -> None:
        """ElevatorPlugin::Reset: the rides forgotten, the controllers' times bootstrapped again (targets kept)."""
        with self._lock:
            self._states.clear()
            self._front_started = None
        self.door.reset()
        self.lift.reset()
