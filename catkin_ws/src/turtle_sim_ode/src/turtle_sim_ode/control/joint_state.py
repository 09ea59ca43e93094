"""joint_state_controller/JointStateController: every joint of the JointStateInterface (or those of ``joints``,
in that order) on ``joint_states`` at ``publish_rate`` (required), plus ``extra_joints`` with their defaults."""
from __future__ import annotations

from typing import List, Optional

from turtle_sim_ode.control.controller import Controller, Throttle
from turtle_sim_ode.control.hardware import RobotHW
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.transmissions import JOINT_STATE
from turtle_sim_ode.models.description import RobotModel


class JointStateController(Controller):
    interface = ""  # reads the JointStateInterface, which claims nothing

    def init(self, hw: RobotHW, params: Params, robot: Optional[RobotModel]) -> None:
        names = params.strings("joints") if params.has("joints") else sorted(hw.joints)
        self.joints = [hw.handle(JOINT_STATE, name) for name in names]
        if not params.has("publish_rate"):
            raise ControllerError("Parameter 'publish_rate' not set")
        self.throttle = Throttle(params.number("publish_rate"))
        self.outputs["@joint_states"] = "joint_states"
        self.extra: List[tuple] = []
        extra = params.raw("extra_joints")
        if isinstance(extra, list):  # upstream ignores a bad entry with an error, so do we
            for entry in extra:
                if isinstance(entry, dict) and isinstance(entry.get("name"), str) and entry["name"] not in names:
                    values = [entry.get(k, 0.0) for k in ("position", "velocity", "effort")]
                    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
                        self.extra.append((entry["name"], *[float(v) for v in values]))

    def starting(self, time: float) -> None:
        self.throttle.start(time)

    def update(self, time: float, period: float) -> None:
        if not self.throttle.due(time):
            return
        self.publish(
            "@joint_states",
            "joint_states",
            {
                "stamp": time,
                "name": [j.name for j in self.joints] + [e[0] for e in self.extra],
                "position": [j.position for j in self.joints] + [e[1] for e in self.extra],
                "velocity": [j.velocity for j in self.joints] + [e[2] for e in self.extra],
                "effort": [j.effort for j in self.joints] + [e[3] for e in self.extra],
            },
        )
