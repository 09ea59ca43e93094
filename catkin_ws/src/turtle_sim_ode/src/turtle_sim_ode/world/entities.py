"""Gazebo's names of the entities in a world: a model "name", a link "model::link", a joint "joint" (looked up in every
model, in spawn order) or "model::joint", a reference frame ("", "world", "map" and "/map" mean the world)."""
from __future__ import annotations

from typing import Dict, List, Optional, Tuple

import ode

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.transforms import Transform, Vec3
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.world.plugins import DriveRobot
from turtle_sim_ode.world.records import Load
from turtle_sim_ode.world.values import WorldError


WORLD_FRAMES = ("", "world", "map", "/map")
SCOPE = "::"
# A reference frame's world pose, linear and angular velocity; None is the world.
Frame = Optional[Tuple[Transform, Vec3, Vec3]]


class EntityLookup:
    """The models of a world looked up by Gazebo's names; what the world API's parts share (see world.control)."""

    physics: PhysicsWorld
    models: Dict[str, BuiltModel]
    robots: Dict[str, DriveRobot]
    max_update_rate: float
    loads: List[Load]

    def _model(self, name: str) -> BuiltModel:
        model = self.models.get(name)
        if model is None:
            raise WorldError(f"model '{name}' does not exist")
        return model

    def _scoped_link(self, name: str) -> Optional[Tuple[BuiltModel, str]]:
        model_name, scope, link = name.partition(SCOPE)
        model = self.models.get(model_name) if scope else None
        return (model, link) if model is not None and link in model.links else None

    def _link(self, name: str) -> Tuple[BuiltModel, str]:
        found = self._scoped_link(name)
        if found is None:
            raise WorldError(f"link '{name}' does not exist (links are named 'model::link')")
        return found

    def _link_body(self, name: str) -> Tuple[BuiltModel, str, ode.Body]:
        model, link = self._link(name)
        body = model.links[link].body
        if body is None:
            raise WorldError(f"link '{name}' belongs to static model '{model.name}' and has no body")
        return model, link, body

    def _joint(self, name: str) -> Tuple[BuiltModel, JointHandle]:
        model_name, scope, joint = name.partition(SCOPE)
        scoped = self.models.get(model_name) if scope else None
        if scoped is not None and joint in scoped.joints:
            return scoped, scoped.joints[joint]
        for model in self.models.values():
            if name in model.joints:
                return model, model.joints[name]
        for model, fixed in [(scoped, joint)] if scoped is not None else [(m, name) for m in self.models.values()]:
            if fixed in model.robot.joints:
                raise WorldError(
                    f"joint '{name}' is a fixed joint of model '{model.name}': it was merged into its parent body "
                    f"(as Gazebo does), so it has no position, properties or effort"
                )
        raise WorldError(f"joint '{name}' does not exist")

    def _frame(self, name: str) -> Frame:
        """A reference frame as gazebo_ros takes it: a model's frame with its canonical (root)
        link's velocity, or a link's frame with its origin's velocity."""
        if name in WORLD_FRAMES:
            return None
        model = self.models.get(name)
        if model is not None:
            linear, angular = model.link_twist(model.root_link)
            return model.model_transform(), linear, angular
        found = self._scoped_link(name)
        if found is None:
            raise WorldError(
                f"reference frame '{name}' is not a model or link (use '', 'world', " f"a model name or 'model::link')"
            )
        model, link = found
        linear, angular = model.link_twist(link)
        return model.link_transform(link), linear, angular
