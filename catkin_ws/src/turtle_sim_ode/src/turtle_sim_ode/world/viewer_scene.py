"""What Gazebo's client shows of the world, without ROS: every model's visuals with their shape, pose in their link,
colour and opacity as Gazebo draws them (``describe_model``, once per spawned model), and, update by update, the
models that came, the ones that went and the visuals whose links moved (``SceneTracker``), for a viewer that keeps
what it was sent (rviz's MarkerArray display).

Colours: the visual's own (SDF diffuse/ambient, a Gazebo/* script, URDF rgba or named material, a <gazebo reference>
material; see models.materials); a Collada mesh without one keeps the colours and textures its file gives (the
viewer's mesh loader reads them, with the file's <unit> and node transforms); anything else Gazebo's default grey.
A mesh that cannot be drawn (no such file, a format the viewer does not read, a file that does not parse) leaves
that visual out with one warning naming model, link and file; the rest of the model is drawn."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Dict, Iterable, List, Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Transform, compose, pose_transform
from turtle_sim_ode.models.materials import DEFAULT_COLOR, GAZEBO_MATERIALS
from turtle_sim_ode.models.meshes import MeshFiles, mesh_file
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import Box, Cylinder, Mesh, Sphere, Visual

Vec3 = Tuple[float, float, float]
RGBA = Tuple[float, float, float, float]
# A mesh drawn in the colours its own file gives (rviz: mesh_use_embedded_materials with colour 0 0 0 0).
OWN_COLOURS: RGBA = (0.0, 0.0, 0.0, 0.0)
# Formats both this simulator's mesh reader and rviz's mesh loader read.
MESH_SUFFIXES = (".dae", ".stl", ".obj")
IDENTITY: Transform = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))
# The simulator's own ground (no world loaded; a world's ground is its ground plane model's visual), drawn as Gazebo's
# model://ground_plane: a 100 m x 100 m plane in Gazebo/Grey, its top at z = 0, as a thin box.
GROUND_PLANE = "ground_plane"
GROUND_SIZE = 100.0
GROUND_THICKNESS = 0.01
# A link moved when its position changed by more than this (m) or its quaternion by more than this: far below a pixel.
MOVE_TOLERANCE = 1e-5


@dataclass(frozen=True)
class SceneVisual:
    """One visual as the viewer draws it: ``size`` is the box's size, the cylinder's (2r, 2r, length), the sphere's
    (2r, 2r, 2r) or the mesh's scale; ``origin`` its pose in ``link`` (position, quaternion wxyz); ``mesh_path`` the
    mesh file (absolute)."""

    link: str
    name: str
    shape: str  # box, cylinder, sphere, mesh
    size: Vec3
    origin: Transform
    rgba: RGBA
    mesh_path: str = ""


def visual_rgba(visual: Visual, mesh_suffix: str = "") -> RGBA:
    """The colour and opacity Gazebo draws ``visual`` in: its material's; a Collada mesh without one in its own."""
    if visual.color is None:
        if mesh_suffix == ".dae":
            return OWN_COLOURS
        return DEFAULT_COLOR + (visual.alpha,)
    return tuple(visual.color) + (visual.alpha,)  # type: ignore[return-value]


def _shape(visual: Visual) -> Tuple[str, Vec3]:
    geometry = visual.geometry
    if isinstance(geometry, Box):
        return "box", tuple(geometry.size)  # type: ignore[return-value]
    if isinstance(geometry, Cylinder):
        return "cylinder", (2 * geometry.radius, 2 * geometry.radius, geometry.length)
    if isinstance(geometry, Sphere):
        return "sphere", (2 * geometry.radius,) * 3  # type: ignore[return-value]
    assert isinstance(geometry, Mesh)
    return "mesh", tuple(geometry.scale)  # type: ignore[return-value]


class MeshCheck:
    """Whether mesh files can be drawn, each file read once (only its verdict is kept, not its triangles)."""

    def __init__(self, resources: Optional[ResourcePaths]) -> None:
        self.resources = resources
        self._verdicts: Dict[str, str] = {}  # resolved path -> "" (drawable) or why not

    def path_of(self, mesh: Mesh, base: Optional[str], what: str) -> str:
        """The absolute path of ``mesh``'s file; ValueError (ModelError) saying why it cannot be drawn."""
        if self.resources is None:
            raise ModelError(f"{what}: no ROS package path or model path to find it on")
        path = os.path.abspath(self.resources.resolve(mesh.uri, base))
        if path not in self._verdicts:
            suffix = os.path.splitext(path)[1].lower()
            if suffix not in MESH_SUFFIXES:
                self._verdicts[path] = f"the viewer draws {', '.join(MESH_SUFFIXES)} meshes, not '{suffix}'"
            else:
                try:
                    mesh_file(self.resources, mesh, base, what, {})
                    self._verdicts[path] = ""
                except ValueError as error:  # ModelError: missing, unreadable, not parsed
                    self._verdicts[path] = str(error)
        if self._verdicts[path]:
            raise ModelError(f"{what}: {self._verdicts[path]}")
        return path


def describe_model(model: BuiltModel, meshes: MeshCheck) -> Tuple[List[SceneVisual], List[str]]:
    """The visuals of ``model`` as the viewer draws them, links in order, and one warning per visual left out."""
    found: List[SceneVisual] = []
    warnings: List[str] = []
    for link, description in model.robot.links.items():
        for visual in description.visuals:
            shape, size = _shape(visual)
            origin = pose_transform(visual.origin)
            if shape != "mesh":
                found.append(SceneVisual(link, visual.name, shape, size, origin, visual_rgba(visual)))
                continue
            uri = visual.geometry.uri  # type: ignore[union-attr]
            what = f"model '{model.name}' link '{link}' visual '{visual.name}' mesh '{uri}'"
            try:
                path = meshes.path_of(visual.geometry, model.robot.base, what)  # type: ignore[arg-type]
            except ValueError as error:
                warnings.append(f"{error}: the viewer draws the rest of model '{model.name}'")
                continue
            rgba = visual_rgba(visual, os.path.splitext(path)[1].lower())
            found.append(SceneVisual(link, visual.name, shape, size, origin, rgba, path))
    return found, warnings


def ground_plane_visuals() -> List[SceneVisual]:
    size = (GROUND_SIZE, GROUND_SIZE, GROUND_THICKNESS)
    origin = ((0.0, 0.0, -GROUND_THICKNESS / 2), IDENTITY[1])
    return [SceneVisual("link", "visual", "box", size, origin, GAZEBO_MATERIALS["Gazebo/Grey"] + (1.0,))]


# A model's identity (a spawned model is a new BuiltModel; the built-in ground is None) and its links' world poses.
Snapshot = Dict[str, Tuple[Optional[BuiltModel], Dict[str, Transform]]]
Placed = Tuple[int, SceneVisual, Transform]  # a visual's index in its model, the visual, its pose in the world


@dataclass
class SceneUpdate:
    """What changed since the last update: by model, the visuals of models new or respawned (``added``) and of links
    that moved (``moved``), and how many visuals each model gone (or respawned) had (``removed``, indices 0..n-1)."""

    added: Dict[str, List[Placed]] = field(default_factory=dict)
    moved: Dict[str, List[Placed]] = field(default_factory=dict)
    removed: Dict[str, int] = field(default_factory=dict)
    warnings: List[str] = field(default_factory=list)

    def empty(self) -> bool:
        return not (self.added or self.moved or self.removed)


@dataclass
class _Shown:
    identity: Optional[BuiltModel]
    visuals: List[SceneVisual]
    by_link: Dict[str, List[int]]
    link_poses: Dict[str, Transform]


def _moved(old: Transform, new: Transform) -> bool:
    return any(abs(a - b) > MOVE_TOLERANCE for a, b in zip(old[0] + old[1], new[0] + new[1]))


def _place(shown: _Shown, indices: Iterable[int]) -> List[Placed]:
    found = []
    for index in indices:
        visual = shown.visuals[index]
        found.append((index, visual, compose(shown.link_poses[visual.link], visual.origin)))
    return found


class SceneTracker:
    """The scene a viewer was last sent, and what changed since: ``read_poses`` under the world lock (ODE reads
    only), ``update`` outside it (mesh files are checked there, once per model)."""

    def __init__(self, resources: Optional[ResourcePaths]) -> None:
        self.meshes = MeshCheck(resources)
        self._shown: Dict[str, _Shown] = {}
        self._drawn_links: Dict[BuiltModel, List[str]] = {}  # the links with visuals, per live model

    def read_poses(self, models: Mapping[str, BuiltModel], own_ground: bool = False) -> Snapshot:
        """The world poses of the links with visuals of every model in ``models``, and the simulator's own ground
        where ``own_ground`` (call under the world lock)."""
        snapshot: Snapshot = {}
        drawn: Dict[BuiltModel, List[str]] = {}
        for name, model in models.items():
            links = self._drawn_links.get(model)
            if links is None:
                links = [link for link, description in model.robot.links.items() if description.visuals]
            drawn[model] = links
            snapshot[name] = (model, {link: model.link_transform(link) for link in links})
        self._drawn_links = drawn
        if own_ground and GROUND_PLANE not in snapshot:
            snapshot[GROUND_PLANE] = (None, {"link": IDENTITY})
        return snapshot

    def update(self, snapshot: Snapshot) -> SceneUpdate:
        """What changed from the last update (or from nothing) to ``snapshot``; the tracker now holds ``snapshot``."""
        update = SceneUpdate()
        for name in [name for name in self._shown if name not in snapshot]:
            update.removed[name] = len(self._shown.pop(name).visuals)
        for name, (identity, poses) in snapshot.items():
            shown = self._shown.get(name)
            if shown is not None and shown.identity is not identity:  # deleted and spawned again meanwhile
                update.removed[name] = len(shown.visuals)
                shown = None
            if shown is None:
                if identity is None:
                    visuals = ground_plane_visuals()
                else:
                    visuals, warnings = describe_model(identity, self.meshes)
                    update.warnings.extend(warnings)
                by_link: Dict[str, List[int]] = {}
                for index, visual in enumerate(visuals):
                    by_link.setdefault(visual.link, []).append(index)
                shown = self._shown[name] = _Shown(identity, visuals, by_link, dict(poses))
                update.added[name] = _place(shown, range(len(visuals)))
                continue
            changed = [link for link, pose in poses.items() if _moved(shown.link_poses[link], pose)]
            if changed:
                shown.link_poses.update((link, poses[link]) for link in changed)
                update.moved[name] = _place(shown, sorted(i for link in changed for i in shown.by_link.get(link, [])))
        return update

    def everything(self) -> Dict[str, List[Placed]]:
        """The whole scene as last updated, by model (for a viewer that starts now)."""
        return {name: _place(shown, range(len(shown.visuals))) for name, shown in self._shown.items()}
