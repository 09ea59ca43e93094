"""The controller life cycle of controller_interface::Controller: init reads the parameters and claims the joints
(a ControllerError says why it cannot), starting, update(time, period), stopping.

A controller talks to the world through plain data: ``inputs`` maps a topic (relative to the controller's
namespace) to its kind and a callback taking a plain value; what it publishes goes to ``outbox`` as
(topic, kind, payload) for the ROS side to send. Kinds name the message types the real controllers use. A topic
is relative to the controller's namespace, to the robot's namespace with a leading "@" (joint_state_controller's
joint_states), or absolute with a leading "/" (diff_drive_controller's /tf).
"""
from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

from turtle_sim_ode.control.hardware import JointData, RobotHW
from turtle_sim_ode.control.params import Params
from turtle_sim_ode.models.description import RobotModel

Outgoing = Tuple[str, str, Any]


class Controller:
    """Base of the simulated controllers; subclasses set ``interface`` and implement the hooks they need."""

    interface = ""  # the hardware interface whose joints it claims ("" claims none)

    def __init__(self) -> None:
        self.claimed: List[str] = []
        self.inputs: Dict[str, Tuple[str, Callable[[Any], None]]] = {}
        self.outputs: Dict[str, str] = {}  # topic -> kind, advertised when the controller is loaded
        self.outbox: List[Outgoing] = []
        self.running = False

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        """Read the parameters, take the joints' handles; raise ControllerError on anything missing or wrong."""

    def claim(self, hw: RobotHW, name: str) -> JointData:
        joint = hw.handle(self.interface, name)
        if name not in self.claimed:
            self.claimed.append(name)
        return joint

    def starting(self, time: float) -> None:
        pass

    def update(self, time: float, period: float) -> None:
        pass

    def stopping(self, time: float) -> None:
        pass

    def publish(self, topic: str, kind: str, payload: Any) -> None:
        self.outbox.append((topic, kind, payload))

    def drain(self) -> List[Outgoing]:
        sent, self.outbox = self.outbox, []
        return sent


class Throttle:
    """Publish at a rate in sim time, as the real controllers do with last_publish_time + 1/rate < now."""

    def __init__(self, rate: float) -> None:
        self.period = 1.0 / rate if rate > 0 else None
        self.last = -float("inf")

    def start(self, time: float, publish_first: bool = True) -> None:
        self.last = time - 1.001 * self.period if (publish_first and self.period) else time

    def due(self, time: float) -> bool:
        if self.period is None or self.last + self.period >= time:
            return False
        # keep the phase (last += period) unless far behind
        self.last = self.last + self.period if time - self.last < 2 * self.period else time
        return True
