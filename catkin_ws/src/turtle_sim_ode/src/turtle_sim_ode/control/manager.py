"""controller_manager::ControllerManager, ROS-free: load (the type from <name>/type, then init), unload,
switch (BEST_EFFORT / STRICT, resource conflicts), list, types, reload-libraries, and update at each control
period. Refusals return False and leave their reason in the log, with upstream's words."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple

from turtle_sim_ode.control.controller import Controller
from turtle_sim_ode.control.diff_drive import DiffDriveController
from turtle_sim_ode.control.gripper import GripperActionController
from turtle_sim_ode.control.hardware import RobotHW
from turtle_sim_ode.control.joint_controllers import (
    ForwardCommand,
    ForwardGroupCommand,
    PidGroupPosition,
    PidPosition,
    PidVelocity,
)
from turtle_sim_ode.control.joint_state import JointStateController
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.transmissions import EFFORT, POSITION, VELOCITY, cpp_name
from turtle_sim_ode.control.trajectory import JointTrajectoryController
from turtle_sim_ode.models.description import RobotModel

BEST_EFFORT, STRICT = 1, 2
BASE_CLASS = "controller_interface::ControllerBase"

CONTROLLER_TYPES: Dict[str, Callable[[], Controller]] = {
    "joint_state_controller/JointStateController": JointStateController,
    "diff_drive_controller/DiffDriveController": DiffDriveController,
    "effort_controllers/JointEffortController": lambda: ForwardCommand(EFFORT),
    "effort_controllers/JointPositionController": lambda: PidPosition(EFFORT),
    "effort_controllers/JointVelocityController": PidVelocity,
    "effort_controllers/JointGroupEffortController": lambda: ForwardGroupCommand(EFFORT),
    "effort_controllers/JointGroupPositionController": PidGroupPosition,
    "effort_controllers/JointTrajectoryController": lambda: JointTrajectoryController(EFFORT),
    "velocity_controllers/JointVelocityController": lambda: ForwardCommand(VELOCITY),
    "velocity_controllers/JointPositionController": lambda: PidPosition(VELOCITY),
    "velocity_controllers/JointGroupVelocityController": lambda: ForwardGroupCommand(VELOCITY),
    "velocity_controllers/JointTrajectoryController": lambda: JointTrajectoryController(VELOCITY),
    "position_controllers/JointPositionController": lambda: ForwardCommand(POSITION),
    "position_controllers/JointGroupPositionController": lambda: ForwardGroupCommand(POSITION),
    "position_controllers/JointTrajectoryController": lambda: JointTrajectoryController(POSITION),
    "position_controllers/GripperActionController": lambda: GripperActionController(POSITION),
    "effort_controllers/GripperActionController": lambda: GripperActionController(EFFORT),
}


@dataclass
class Loaded:
    name: str
    type: str
    controller: Controller
    state: str = "initialized"  # then running / stopped, as list_controllers reports


class ControllerManager:
    def __init__(self, hw: RobotHW, robot: Optional[RobotModel], log: Callable[[str, str], None]) -> None:
        """log(level, text), level one of debug/info/warn/error."""
        self.hw = hw
        self.robot = robot
        self.log = log
        self.loaded: List[Loaded] = []
        self.time = 0.0
        self._running: List[Controller] = []  # those update runs, in load order (updated by switch)

    def find(self, name: str) -> Optional[Loaded]:
        return next((entry for entry in self.loaded if entry.name == name), None)

    # --- services -------------------------------------------------------------------
    def load(self, name: str, params: Mapping[str, object], namespace: str = "") -> bool:
        """params: the controller's parameter tree; namespace: where it is, for messages (default: name)."""
        if self.find(name):
            self.log("error", f"A controller named '{name}' was already loaded inside the controller manager")
            return False
        tree = Params(params, namespace or name)
        controller_type = tree.raw("type")
        if not isinstance(controller_type, str):
            self.log(
                "error",
                f"Could not load controller '{name}' because the type was not specified. Did you load the "
                f"controller configuration on the parameter server (namespace: '{tree.namespace}')?",
            )
            return False
        factory = CONTROLLER_TYPES.get(controller_type)
        if factory is None:
            self.log(
                "error",
                f"Could not load controller '{name}' because controller type '{controller_type}' does not exist.",
            )
            self.log(
                "error", "Use 'rosservice call controller_manager/list_controller_types' to get the available types"
            )
            return False
        controller = factory()
        try:
            controller.init(self.hw, tree, self.robot)
        except ControllerError as error:
            self.log("error", str(error))
            self.log("error", f"Initializing controller '{name}' failed")
            return False
        self.loaded.append(Loaded(name, controller_type, controller))
        return True

    def unload(self, name: str) -> bool:
        entry = self.find(name)
        if entry is None:
            self.log(
                "error", f"Could not unload controller with name '{name}' because no controller with this name exists"
            )
            return False
        if entry.state == "running":
            self.log("error", f"Could not unload controller with name '{name}' because it is still running")
            return False
        self.loaded.remove(entry)
        return True

    def switch(self, start: Sequence[str], stop: Sequence[str], strictness: int) -> bool:
        if strictness == 0:
            self.log(
                "warn",
                "Controller Manager: To switch controllers you need to specify a strictness level of "
                "controller_manager_msgs::SwitchController::STRICT (2) or ::BEST_EFFORT (1). Defaulting to "
                "::BEST_EFFORT.",
            )
            strictness = BEST_EFFORT
        to_stop, to_start = [], []
        for names, verb, chosen in ((stop, "stop", to_stop), (start, "start", to_start)):
            for name in names:
                entry = self.find(name)
                if entry is None:
                    if strictness == STRICT:
                        self.log(
                            "error",
                            f"Could not {verb} controller with name '{name}' because no controller with this name exists",
                        )
                        return False
                    continue
                chosen.append(entry)
        for entry in self.loaded:
            running, stopping, starting = entry.state == "running", entry in to_stop, entry in to_start
            if not running and stopping and not starting:
                if strictness == STRICT:
                    self.log("error", f"Could not stop controller '{entry.name}' since it is not running")
                    return False
                to_stop.remove(entry)
            if running and starting and not stopping:
                if strictness == STRICT:
                    self.log("error", f"Controller '{entry.name}' is already running")
                    return False
                to_start.remove(entry)
            if not running and stopping and starting:  # a restart of a stopped one
                if strictness == STRICT:
                    self.log(
                        "error",
                        f"Could no start or stop controller '{entry.name}' because of conflicting switching command",
                    )
                    return False
                to_stop.remove(entry)
        after = [e for e in self.loaded if (e.state == "running" and e not in to_stop) or e in to_start]
        if not self._conflict_free(after):
            self.log("error", "Could not switch controllers, due to resource conflict")
            return False
        for entry in to_stop:
            entry.controller.stopping(self.time)
            entry.controller.running = False
            entry.state = "stopped"
        for entry in to_start:
            entry.controller.running = True
            entry.controller.starting(self.time)
            entry.state = "running"
        self._running = [entry.controller for entry in self.loaded if entry.state == "running"]
        return True

    def _conflict_free(self, entries: List[Loaded]) -> bool:
        owners: Dict[str, List[str]] = {}
        for entry in entries:
            for resource in entry.controller.claimed:
                owners.setdefault(resource, []).append(entry.name)
        conflicts = {resource: names for resource, names in owners.items() if len(names) > 1}
        for resource, names in sorted(conflicts.items()):
            self.log("warn", f"Resource conflict on [{resource}].  Controllers = [{', '.join(names)}, ]")
        return not conflicts

    def listing(self) -> List[Tuple[str, str, str, List[Tuple[str, List[str]]]]]:
        """(name, state, type, [(hardware interface, resources)]) of each loaded controller, in load order."""
        return [
            (
                e.name,
                e.state,
                e.type,
                [(cpp_name(e.controller.interface), list(e.controller.claimed))] if e.controller.interface else [],
            )
            for e in self.loaded
        ]

    @staticmethod
    def types() -> List[Tuple[str, str]]:
        return [(name, BASE_CLASS) for name in sorted(CONTROLLER_TYPES)]

    def reload_libraries(self, force_kill: bool) -> bool:
        if self.loaded and not force_kill:
            self.log(
                "error",
                "Controller manager: Cannot reload controller libraries because there are still "
                f"{len(self.loaded)} controllers running",
            )
            return False
        if self.loaded:
            self.log("info", "Controller manager: Killing all running controllers")
            self.switch([], [e.name for e in self.loaded if e.state == "running"], BEST_EFFORT)
            self.loaded.clear()
        return True

    # --- the control loop -----------------------------------------------------------------
    def update(self, time: float, period: float) -> None:
        self.time = time
        for controller in self._running:
            controller.update(time, period)
