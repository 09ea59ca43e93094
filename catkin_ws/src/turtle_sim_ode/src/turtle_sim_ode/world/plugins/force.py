"""gazebo_ros_force (``libgazebo_ros_force.so``, gazebo_plugins/src/gazebo_ros_force.cpp): a wrench from a topic on a
link. Its tags (GazeboRosForce::Load: <bodyName> and <topicName> required), and its per-step work (UpdateChild):
the last wrench received, force and torque in the world frame, added to the link's body at every step."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Optional, Sequence, Tuple

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.world.plugins.tags import text

FORCE = "libgazebo_ros_force.so"
MODEL_PLUGINS = (FORCE,)
Vec3 = Tuple[float, float, float]


@dataclass(frozen=True)
class ForceConfig:
    body: str
    topic: str
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> ForceConfig:
    body, topic = text(plugin, "bodyName", ""), text(plugin, "topicName", "")
    if not body or not topic:
        raise ModelError(f"{plugin.filename} needs <bodyName> and <topicName>")
    return ForceConfig(body.split("::")[-1], topic, robot_namespace_tag(plugin.params))


class LinkWrench:
    """The wrench the plugin holds for a link (zero until one is received), added to its body before each step."""

    def __init__(self, model: BuiltModel, link: str) -> None:
        body = model.links[link].body
        if body is None:
            raise ModelError(f"model '{model.name}': link '{link}' has no body for a force plugin")
        self._body = body
        self.force: Vec3 = (0.0, 0.0, 0.0)
        self.torque: Vec3 = (0.0, 0.0, 0.0)

    def set(self, force: Sequence[float], torque: Sequence[float]) -> bool:
        """Take a wrench; False (and kept as it was) if a value is not finite or beyond physics.sanity's forces."""
        values = tuple(force) + tuple(torque)
        if not all(math.isfinite(v) and abs(v) <= sanity.MAX_FORCE for v in values):
            return False
        self.force, self.torque = tuple(force), tuple(torque)  # type: ignore[assignment]
        return True

    def apply(self) -> None:
        self._body.addForce(self.force)
        self._body.addTorque(self.torque)
