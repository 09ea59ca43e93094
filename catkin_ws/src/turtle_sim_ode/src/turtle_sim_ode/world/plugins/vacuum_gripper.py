"""gazebo_ros_vacuum_gripper (``libgazebo_ros_vacuum_gripper.so``, gazebo_plugins/src/gazebo_ros_vacuum_gripper.cpp):
a link that, while switched on, holds the links of other models near it. Its tags (GazeboRosVacuumGripper::Load:
<bodyName> and <topicName> required, <robotNamespace>), and its per-step work (UpdateChild), run as a Simulation
step hook before each physics step (as upstream's, on the world's update-begin event):

- off: nothing is touched; grasping is false.
- on: for every link of every other model (not the gripper's own model, nor a model named as the gripper link, as
  upstream compares names) whose link frame origin is nearer than ``REACH`` (0.05 m) to the gripper link's: the
  link's body gets the gripper link's velocity (linear of its origin, angular), nearer than ``SNAP`` (0.01 m) it is
  moved so its origin is on the gripper link's (orientation kept), and a force of min(1/distance, 20) N (so 20 N
  always, 1/0.05 being 20) is added along Pose3d's ``gripper - link`` position, that is the offset to the gripper
  expressed in the other link's own frame, yet added in the world frame as upstream's Link::AddForce does (the two
  agree while that link is not rotated); an offset of at most 1e-6 m is not normalised (ignition's
  Vector3::Normalize). grasping is true if any link was held in this step.

Links are those Gazebo keeps: links on fixed joints are lumped into their parent (here too), so neither the gripper
nor a held link can be one of them. Links of static models have no body here and are never moved (Gazebo's static
links do not move under forces and velocities either)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Mapping, Optional, Tuple

import ode

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import quat_rotate
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins.p3d import find_body
from turtle_sim_ode.world.plugins.tags import text

VACUUM_GRIPPER = "libgazebo_ros_vacuum_gripper.so"
MODEL_PLUGINS = (VACUUM_GRIPPER,)

# GazeboRosVacuumGripper::UpdateChild's constants.
REACH = 0.05  # m: a link whose origin is nearer than this to the gripper link's is held
SNAP = 0.01  # m: nearer than this, the link is put on the gripper link's origin
MAX_FORCE = 20.0  # N: the 1/distance pull is capped here ("max_force")
# ignition::math::Vector3::Normalize leaves a vector whose length is within this of 0 as it is (math::equal).
NORMALIZE_EPSILON = 1e-6


@dataclass(frozen=True)
class VacuumGripperConfig:
    """libgazebo_ros_vacuum_gripper.so: the gripper link, the std_msgs/Bool status topic, the namespace of the
    topic and of the ``on``/``off`` services."""

    body: str
    topic: str
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> VacuumGripperConfig:
    """Upstream stops loading (the plugin then does nothing) without <bodyName> or <topicName>; here the spawn is
    refused, naming the tag."""
    body, topic = text(plugin, "bodyName", ""), text(plugin, "topicName", "")
    for tag, value in (("bodyName", body), ("topicName", topic)):
        if not value:
            raise ModelError(f"{plugin.filename} needs <{tag}>")
    return VacuumGripperConfig(body, topic, robot_namespace_tag(plugin.params))


def gazebo_links(model: BuiltModel) -> List[str]:
    """The links Gazebo keeps of a model: all but those on fixed joints (lumped into their parent)."""
    lumped = {joint.child for joint in model.robot.joints.values() if joint.type == "fixed"}
    return [link for link in model.links if link not in lumped]


def offset_in_frame(gripper: Tuple[float, float, float], link: Tuple[tuple, tuple]) -> Tuple[float, float, float]:
    """Pose3d's ``gripper_pose - link_pose`` position (CoordPositionSub): the gripper's origin relative to the
    link's, in the link's frame. ``link`` is (position, quaternion wxyz)."""
    (x, y, z), (w, qx, qy, qz) = link
    return quat_rotate((w, -qx, -qy, -qz), (gripper[0] - x, gripper[1] - y, gripper[2] - z))


class VacuumGripper:
    """The plugin's per-step work on gripper link ``link`` of ``model``, over the live ``models`` of the world (a
    Simulation's ``models``: spawns and deletions are seen). A step hook (``step``, ``reset``); ``on`` is switched by
    ``switch_on``/``switch_off``; ``grasping`` tells whether the last step held a link.

    ModelError if ``link`` is not a link Gazebo would keep (missing, or on a fixed joint): upstream's plugin then
    logs the links it found and does nothing."""

    def __init__(self, model: BuiltModel, link: str, models: Mapping[str, BuiltModel]) -> None:
        found = gazebo_links(model)
        name = find_body(found, link)
        if name is None:
            raise ModelError(
                f"vacuum gripper: link named [{link}] does not exist in model '{model.name}' (check it exists and is "
                f"not attached with a fixed joint); found links are: {' '.join(found)}"
            )
        self._model = model
        self._link = name
        self._models = models
        self.on = False
        self.grasping = False
        # Per model name: the model and its movable links (name, body), remade when the name holds another model.
        self._held: Dict[str, Tuple[BuiltModel, List[Tuple[str, ode.Body]]]] = {}

    @property
    def link(self) -> str:
        return self._link

    def switch_on(self) -> bool:
        """Turn on; False if it was on already (upstream warns)."""
        was, self.on = self.on, True
        return not was

    def switch_off(self) -> bool:
        """Turn off; False if it was off already (upstream warns)."""
        was, self.on = self.on, False
        return was

    def _links_of(self, name: str, model: BuiltModel) -> List[Tuple[str, ode.Body]]:
        cached = self._held.get(name)
        if cached is None or cached[0] is not model:
            links = [(link, model.links[link].body) for link in gazebo_links(model)]
            cached = (model, [(link, body) for link, body in links if body is not None])
            self._held[name] = cached
        return cached[1]

    def step(self, now: float, dt: float) -> None:
        if not self.on:
            self.grasping = False
            return
        grasping = False
        gripper, _ = self._model.link_transform(self._link)
        linear, angular = self._model.link_twist(self._link)
        models = list(self._models.items())
        if any(name not in self._models for name in self._held):  # forget deleted models' bodies
            self._held = {name: self._held[name] for name, _ in models if name in self._held}
        for name, other in models:
            if other is self._model or name == self._model.name or name == self._link:
                continue
            for link, body in self._links_of(name, other):
                pose = other.link_transform(link)
                to_gripper = (gripper[0] - pose[0][0], gripper[1] - pose[0][1], gripper[2] - pose[0][2])
                distance = math.sqrt(sum(v * v for v in to_gripper))
                if not distance < REACH:
                    continue
                body.setLinearVel(linear)
                body.setAngularVel(angular)
                if distance < SNAP:  # upstream's "friction like force": the link's origin onto the gripper's
                    x, y, z = body.getPosition()
                    body.setPosition((x + to_gripper[0], y + to_gripper[1], z + to_gripper[2]))
                magnitude = min(1.0 / distance, MAX_FORCE) if distance > 0.0 else MAX_FORCE
                direction = offset_in_frame(gripper, pose)
                if distance > NORMALIZE_EPSILON:
                    direction = (direction[0] / distance, direction[1] / distance, direction[2] / distance)
                body.addForce((magnitude * direction[0], magnitude * direction[1], magnitude * direction[2]))
                grasping = True
        self.grasping = grasping

    def reset(self) -> None:
        """A world reset leaves the switch as it is (upstream's plugin has no Reset)."""
