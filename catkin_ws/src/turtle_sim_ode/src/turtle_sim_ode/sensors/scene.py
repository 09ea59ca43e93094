"""What the cameras see of the world's models. Gazebo's cameras draw visuals, not collisions: a link with visuals is
drawn from them (box, sphere, cylinder, mesh; each in its own colour, at the link's pose composed with its origin);
a link without any is drawn from its collision geoms in the link's colour (Gazebo would draw nothing there). The
result is what both ray casters take: rows of the ray kernel's primitive table and meshes with their poses
(sensors.ray_kernel).

A model's visuals are prepared on a camera's first rendering of it and kept while the model exists (a deleted or
respawned model is a new BuiltModel): a visual mesh is read then, through ``resources`` as collision meshes are. A
visual mesh that cannot be read gives one warning naming it, and its link is drawn from its collisions."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Mapping, Optional, Set, Tuple

import numpy as np
import ode

from turtle_sim_ode.models.builder import BuiltModel, Transform, compose, pose_transform, quat_matrix
from turtle_sim_ode.models.materials import DEFAULT_COLOR, RGB
from turtle_sim_ode.models.meshes import Triangles, mesh_file, scaled_mesh
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.urdf import Geometry, Mesh, Visual
from turtle_sim_ode.physics.trimesh import MeshGeom
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.ray_kernel import STRIDE, MeshItem, mesh_pose, primitive_row, visual_row
from turtle_sim_ode.sensors.rays import world_geoms


@dataclass(frozen=True)
class _Part:
    """One visual, ready to draw: its origin on the link, its shape (a mesh as vertices and faces) and colour."""

    origin: Transform
    geometry: Geometry
    colour: RGB
    mesh: Optional[Tuple[np.ndarray, np.ndarray]] = None


@dataclass
class _View:
    """A model as the cameras draw it: the links drawn from their visuals, the colours of the collision geoms that
    are drawn, and the collision geoms that are not (their links' visuals stand for them)."""

    links: List[Tuple[str, List[_Part]]] = field(default_factory=list)
    colours: Dict[ode.GeomObject, RGB] = field(default_factory=dict)
    hidden: Set[ode.GeomObject] = field(default_factory=set)


class Scene:
    """The models of ``models`` (the live mapping of a simulation's models, by name) as cameras draw them; visual
    meshes are read through ``resources``. ``take_warnings`` hands over what could not be drawn, once."""

    def __init__(self, models: Mapping[str, BuiltModel], resources: Optional[ResourcePaths] = None) -> None:
        self.models = models
        self.resources = resources
        self._views: Dict[BuiltModel, _View] = {}
        self._warnings: List[str] = []

    def take_warnings(self) -> List[str]:
        """The warnings since the last call (a visual mesh that cannot be read: once per model)."""
        found, self._warnings = self._warnings, []
        return found

    def _prepare(self, model: BuiltModel) -> _View:
        view = _View()
        cache: Dict[str, Triangles] = {}
        for link, geoms in model.geoms.items():
            description = model.robot.links[link]
            parts = self._parts(model, link, description.visuals, cache)
            if parts:
                view.links.append((link, parts))
                view.hidden.update(geoms)
            else:
                colour = description.color if description.color is not None else DEFAULT_COLOR
                view.colours.update((geom, colour) for geom in geoms)
        return view

    def _parts(self, model: BuiltModel, link: str, visuals: List[Visual], cache: Dict[str, Triangles]) -> List[_Part]:
        """The link's visuals ready to draw; none if a mesh of them cannot be read (with a warning)."""
        parts = []
        for visual in visuals:
            colour = visual.color if visual.color is not None else DEFAULT_COLOR
            part = _Part(pose_transform(visual.origin), visual.geometry, colour)
            if isinstance(visual.geometry, Mesh):
                what = f"model '{model.name}' link '{link}' visual '{visual.name}' mesh '{visual.geometry.uri}'"
                try:
                    triangles = mesh_file(self.resources, visual.geometry, model.robot.base, what, cache)
                    vertices, faces = scaled_mesh(triangles, visual.geometry.scale, what)
                except ModelError as error:
                    self._warnings.append(f"{error}: the cameras draw link '{link}' from its collisions")
                    return []
                part = _Part(part.origin, part.geometry, colour, (vertices, faces.astype(np.uint32)))
            parts.append(part)
        return parts

    def _current(self, camera_model: BuiltModel) -> List[Tuple[BuiltModel, _View]]:
        """The views of every model but ``camera_model``'s, prepared where new; those of models gone are dropped."""
        models = list(self.models.values())
        live = set(models)
        if any(model not in live for model in self._views):
            self._views = {model: view for model, view in self._views.items() if model in live}
        found = []
        for model in models:
            if model is camera_model:
                continue
            view = self._views.get(model)
            if view is None:
                view = self._views[model] = self._prepare(model)
            found.append((model, view))
        return found

    def drawables(self, physics: PhysicsWorld, camera_model: BuiltModel) -> Tuple[np.ndarray, List[MeshItem]]:
        """What a camera on ``camera_model`` draws now, its own model and the ground plane aside: the primitive
        table (N, STRIDE) and the meshes."""
        views = self._current(camera_model)
        colours: Dict[ode.GeomObject, RGB] = {}
        hidden: Set[ode.GeomObject] = set()
        for _, view in views:
            colours.update(view.colours)
            hidden.update(view.hidden)
        rows: List[np.ndarray] = []
        meshes: List[MeshItem] = []
        for geom in world_geoms(physics, camera_model):
            if geom in hidden:
                continue
            colour = colours.get(geom, DEFAULT_COLOR)
            if isinstance(geom, MeshGeom):
                meshes.append((mesh_pose(geom.getPosition(), geom.getRotation(), colour), geom.vertices, geom.faces))
                continue
            row = primitive_row(geom, colour)
            if row is not None:
                rows.append(row)
        for model, view in views:
            for link, parts in view.links:
                link_pose = model.link_transform(link)
                for part in parts:
                    position, quaternion = compose(link_pose, part.origin)
                    rotation = np.ravel(quat_matrix(quaternion))
                    if part.mesh is None:
                        rows.append(visual_row(part.geometry, position, rotation, part.colour))
                    else:
                        meshes.append((mesh_pose(position, rotation, part.colour),) + part.mesh)
        return (np.array(rows) if rows else np.zeros((0, STRIDE))), meshes
