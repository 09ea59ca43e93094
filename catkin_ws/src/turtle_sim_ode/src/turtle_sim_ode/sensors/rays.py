"""Ray casting shared by the laser and the cliff sensors: the geoms a ray may hit, and its distance to one."""
from __future__ import annotations

import math
from typing import Callable, Iterator, Set

import ode

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.physics.trimesh import collide
from turtle_sim_ode.physics.world import PhysicsWorld


def world_geoms(
    physics: PhysicsWorld, model: BuiltModel, in_reach: Callable[[ode.SpaceBase], bool] = lambda space: True
) -> Iterator[ode.GeomObject]:
    """Every collision geom in the world's spaces but ``model``'s own (the ground plane is apart), less those of
    the sub-spaces (other models, static obstacles) for which ``in_reach`` is false: a sensor that knows how far it
    reaches then tests a few space AABBs instead of every geom in the world."""
    own: Set[ode.GeomObject] = {geom for geoms in model.geoms.values() for geom in geoms}
    own_space = None
    if not model.robot.static:
        own_space = next((geom.getSpace() for geom in own), None)
    stack = [physics.space]
    while stack:
        space = stack.pop()
        for index in range(space.getNumGeoms()):
            geom = space.getGeom(index)
            if geom.isSpace():
                if geom is not own_space and in_reach(geom):
                    stack.append(geom)
            elif geom not in own:
                yield geom


def ray_distance(ray: ode.GeomRay, geom: ode.GeomObject) -> float:
    best = math.inf
    for contact in collide(ray, geom):
        depth = contact.getContactGeomParams()[2]
        if depth < best:
            best = depth
    return best
