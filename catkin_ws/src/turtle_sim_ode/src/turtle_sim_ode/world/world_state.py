"""A world file's saved <state> applied as gazebo-classic applies it when it loads a world (World::Load calls
World::SetState with the first <state>): sim time set to the saved one; each model named moved to its saved world
pose (Model::SetState: SetWorldPose), then each of its links to its saved world pose and velocity (Link::SetState:
SetWorldPose, SetLinearVel, SetAngularVel); each light named to its saved pose. Models and links the world does not
have are named in warnings (Gazebo logs an error and goes on). The poses models return to on reset_world stay the
ones of the world's <model> and <include> tags, as Gazebo keeps a model's initial pose."""
from __future__ import annotations

from dataclasses import replace
from typing import Dict, List

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Transform, compose, inverse, quat_from_rpy
from turtle_sim_ode.models.lights import Light
from turtle_sim_ode.models.world_state import Six, WorldState
from turtle_sim_ode.physics.world import PhysicsWorld


def _transform(pose: Six) -> Transform:
    return (pose[0], pose[1], pose[2]), quat_from_rpy(pose[3], pose[4], pose[5])


def apply_world_state(
    state: WorldState, physics: PhysicsWorld, models: Dict[str, BuiltModel], lights: Dict[str, Light]
) -> List[str]:
    """Apply ``state`` to a freshly loaded world; return warnings."""
    warnings = list(state.warnings)
    physics.set_time(state.sim_time)
    for name, model_state in state.models.items():
        model = models.get(name)
        if model is None:
            warnings.append(f"<state> has model '{name}', which the world does not have: ignored")
            continue
        model.set_transform(_transform(model_state.pose))
        for link, link_state in model_state.links.items():
            frame = model.links.get(link)
            if frame is None:
                warnings.append(f"<state> has link '{link}' of model '{name}', which it does not have: ignored")
                continue
            if frame.body is None:  # a static model's links moved with it
                continue
            position, quaternion = compose(_transform(link_state.pose), inverse(frame.offset))
            frame.body.setPosition(position)
            frame.body.setQuaternion(quaternion)
            frame.body.setLinearVel(link_state.velocity[:3])
            frame.body.setAngularVel(link_state.velocity[3:])
    for name, pose in state.lights.items():
        if name in lights:
            (x, y, z), (qw, qx, qy, qz) = _transform(pose)
            lights[name] = replace(lights[name], pose=((x, y, z), (qx, qy, qz, qw)))
        else:
            warnings.append(f"<state> has light '{name}', which the world does not have: ignored")
    return warnings
