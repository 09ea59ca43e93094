"""What the cameras see of the world's models. Gazebo's cameras draw visuals, not collisions: a link with visuals is
drawn from them (box, sphere, cylinder, mesh; each in its own colour, at the link's pose composed with its origin);
a link without any is drawn from its collision geoms in the link's colour (Gazebo would draw nothing there). The
result is what both ray casters take: rows of the ray kernel's primitive table and meshes with their poses
(sensors.ray_kernel).

A model's visuals are prepared on a camera's first rendering of it and kept while the model exists (a deleted or
respawned model is a new BuiltModel): a visual mesh is read then, through ``resources`` as collision meshes are, unless
the spawn service read it ahead outside the world lock (``add_files``). Sensor work for one model never ends the world:
whatever goes wrong while preparing or drawing a link's visuals (a mesh that cannot be read, a number no one
foresaw) gives one warning naming the model, link and file, and that link is drawn from its collisions."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Mapping, Optional, Set, Tuple

import numpy as np
import ode

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import pose_transform, quat_matrix
from turtle_sim_ode.models.materials import DEFAULT_COLOR, RGB
from turtle_sim_ode.models.meshes import MeshFiles, mesh_file, scaled_mesh
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.textures import MaterialScript, read_texture
from turtle_sim_ode.models.description import Mesh, Visual
from turtle_sim_ode.physics.trimesh import MeshGeom
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.ray_kernel import STRIDE, MeshItem, mesh_pose, primitive_row, visual_row
from turtle_sim_ode.sensors.rays import world_geoms


POSE_COLUMNS = 12  # a position and a rotation (row-major), from the first of them: in shape_row's and mesh_pose's rows


def _placed(local: np.ndarray, at: int, positions: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """Copies of rows posed in their links (a position and a rotation from column ``at``) posed in the world by their
    links' ``positions`` (K, 3) and ``rotations`` (K, 3, 3)."""
    placed = local.copy()
    rotation = at + 3
    placed[:, at:rotation] = positions + np.einsum("kij,kj->ki", rotations, local[:, at:rotation])
    turns = local[:, rotation : at + POSE_COLUMNS].reshape(-1, 3, 3)
    placed[:, rotation : at + POSE_COLUMNS] = (rotations @ turns).reshape(-1, 9)
    return placed


# A visual posed in its link: a primitive's row (shape_row) and None, or a mesh's pose (mesh_pose) and its arrays;
# and a textured primitive's image (drawn white by the ray casters, the texture applied after: sensors.texturing).
Part = Tuple[np.ndarray, Optional[Tuple[np.ndarray, np.ndarray]], Optional[np.ndarray]]
# A primitive's row posed in the world and its texture image.
TexturedRow = Tuple[np.ndarray, np.ndarray]
WHITE: RGB = (1.0, 1.0, 1.0)


@dataclass
class _View:
    """A model as the cameras draw it: the links drawn from their visuals, with those visuals as primitive rows and
    mesh poses, posed in their links (``*_links``: the index of each one's link), and the meshes' arrays; the
    colours of the collision geoms drawn, and the collision geoms not drawn (their links' visuals stand for them)."""

    links: List[str] = field(default_factory=list)
    rows: np.ndarray = field(default_factory=lambda: np.zeros((0, STRIDE)))
    row_links: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    mesh_poses: np.ndarray = field(default_factory=lambda: np.zeros((0, POSE_COLUMNS + 3)))
    mesh_links: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    mesh_arrays: List[Tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    textures: Dict[int, np.ndarray] = field(default_factory=dict)  # by index in rows
    colours: Dict[ode.GeomObject, RGB] = field(default_factory=dict)
    hidden: Set[ode.GeomObject] = field(default_factory=set)
    files: Set[str] = field(default_factory=set)  # the mesh files its visuals were drawn from

    @classmethod
    def of_collisions(cls, model: BuiltModel) -> "_View":
        """Every link drawn from its collisions, in its colour."""
        view = cls()
        for link, geoms in model.geoms.items():
            colour = model.robot.links[link].color
            view.colours.update((geom, colour if colour is not None else DEFAULT_COLOR) for geom in geoms)
        return view

    def set_links(self, links: Dict[str, List[Part]]) -> None:
        """The links drawn from their visuals, each with its parts."""
        self.links = list(links)
        rows: List[np.ndarray] = []
        row_links: List[int] = []
        poses: List[np.ndarray] = []
        mesh_links: List[int] = []
        for index, parts in enumerate(links.values()):
            for row, mesh, texture in parts:
                if mesh is None:
                    if texture is not None:
                        self.textures[len(rows)] = texture
                    rows.append(row)
                    row_links.append(index)
                else:
                    poses.append(row)
                    mesh_links.append(index)
                    self.mesh_arrays.append(mesh)
        self.rows, self.row_links = np.array(rows).reshape(-1, STRIDE), np.array(row_links, dtype=int)
        self.mesh_poses = np.array(poses).reshape(-1, POSE_COLUMNS + 3)
        self.mesh_links = np.array(mesh_links, dtype=int)

    def draw(
        self, model: BuiltModel, tables: List[np.ndarray], meshes: List[MeshItem], textured: List[TexturedRow]
    ) -> None:
        """Append the visuals, posed in the world now, to ``tables``, ``meshes`` and (the textured primitives)
        ``textured``: Python work per link, numpy work per visual."""
        if not self.links:
            return
        transforms = [model.link_transform(link) for link in self.links]
        positions = np.array([transform[0] for transform in transforms])
        rotations = np.array([quat_matrix(quaternion) for _, quaternion in transforms])
        if len(self.rows):
            tables.append(_placed(self.rows, 1, positions[self.row_links], rotations[self.row_links]))
            textured.extend((tables[-1][index], texture) for index, texture in self.textures.items())
        if self.mesh_arrays:
            poses = _placed(self.mesh_poses, 0, positions[self.mesh_links], rotations[self.mesh_links])
            meshes.extend((pose,) + arrays for pose, arrays in zip(poses, self.mesh_arrays))


class Scene:
    """The models of ``models`` (the live mapping of a simulation's models, by name) as cameras draw them; visual
    meshes are read through ``resources``. ``take_warnings`` hands over what could not be drawn, once."""

    def __init__(self, models: Mapping[str, BuiltModel], resources: Optional[ResourcePaths] = None) -> None:
        self.models = models
        self.resources = resources
        self._views: Dict[BuiltModel, _View] = {}
        self._warnings: List[str] = []
        self._files: MeshFiles = {}  # visual mesh files read, by resolved path; those of live models are kept
        self._textures: Dict[Tuple[MaterialScript, Optional[str]], np.ndarray] = {}  # images read, by material

    def known_files(self) -> List[str]:
        """The visual mesh files read already (resolved paths)."""
        return list(self._files)

    def add_files(self, files: MeshFiles) -> None:
        """Visual mesh files read ahead (models.meshes.read_visual_meshes), so that no camera reads them while it
        holds the world lock."""
        self._files.update(files)

    def take_warnings(self) -> List[str]:
        """The warnings since the last call (a visual mesh that cannot be read: once per model)."""
        found, self._warnings = self._warnings, []
        return found

    def _prepare(self, model: BuiltModel) -> _View:
        view = _View()
        drawn: Dict[str, List[Part]] = {}
        for link, geoms in model.geoms.items():
            description = model.robot.links[link]
            try:
                parts = self._parts(model, link, description.visuals, view.files)
            except Exception as error:  # one model's visuals never end the world: warned of, drawn from collisions
                self._warnings.append(
                    f"model '{model.name}' link '{link}' visuals{_files_named(description.visuals)}: "
                    f"{type(error).__name__}: {error}: the cameras draw link '{link}' from its collisions"
                )
                parts = []
            if parts:
                drawn[link] = parts
                view.hidden.update(geoms)
            else:
                colour = description.color if description.color is not None else DEFAULT_COLOR
                view.colours.update((geom, colour) for geom in geoms)
        view.set_links(drawn)
        return view

    def _parts(self, model: BuiltModel, link: str, visuals: List[Visual], files: Set[str]) -> List[Part]:
        """The link's visuals posed in it; none if a mesh of them cannot be read (with a warning). ``files`` gets
        the mesh files used."""
        parts = []
        for visual in visuals:
            colour = visual.color if visual.color is not None else DEFAULT_COLOR
            position, quaternion = pose_transform(visual.origin)
            rotation = np.ravel(quat_matrix(quaternion))
            if not isinstance(visual.geometry, Mesh):
                texture = self._texture(model, link, visual)
                if texture is not None:
                    colour = WHITE
                parts.append((visual_row(visual.geometry, position, rotation, colour), None, texture))
                continue
            what = f"model '{model.name}' link '{link}' visual '{visual.name}' mesh '{visual.geometry.uri}'"
            try:
                triangles = mesh_file(self.resources, visual.geometry, model.robot.base, what, self._files)
                vertices, faces = scaled_mesh(triangles, visual.geometry.scale, what)
            except ValueError as error:  # ModelError, and what the checks did not foresee
                self._warnings.append(f"{what}: {error}: the cameras draw link '{link}' from its collisions")
                return []
            files.add(self.resources.resolve(visual.geometry.uri, model.robot.base))  # type: ignore[union-attr]
            parts.append((mesh_pose(position, rotation, colour), (vertices, faces.astype(np.uint32)), None))
        return parts

    def _texture(self, model: BuiltModel, link: str, visual: Visual) -> Optional[np.ndarray]:
        """The image of the visual's material script, read once per material; None where it has none or it cannot
        be read (with a warning: the visual is drawn in its colour)."""
        if visual.texture is None or self.resources is None:
            return None
        key = (visual.texture, model.robot.base)
        if key not in self._textures:
            try:
                self._textures[key] = read_texture(self.resources, visual.texture, model.robot.base)
            except ValueError as error:  # ModelError, ResourceError
                self._warnings.append(
                    f"model '{model.name}' link '{link}' visual '{visual.name}' material '{visual.texture.name}': "
                    f"{error}: drawn in its colour, without the texture"
                )
                return None
        return self._textures[key]

    def _current(self, camera_model: BuiltModel) -> List[Tuple[BuiltModel, _View]]:
        """The views of every model but ``camera_model``'s, prepared where new; those of models gone are dropped."""
        models = list(self.models.values())
        live = set(models)
        if any(model not in live for model in self._views):
            self._views = {model: view for model, view in self._views.items() if model in live}
            used = set().union(*(view.files for view in self._views.values()))
            self._files = {path: found for path, found in self._files.items() if path in used}
        found = []
        for model in models:
            if model is camera_model:
                continue
            view = self._views.get(model)
            if view is None:
                view = self._views[model] = self._prepare(model)
            found.append((model, view))
        return found

    def drawables(
        self, physics: PhysicsWorld, camera_model: BuiltModel, textured: Optional[List[TexturedRow]] = None
    ) -> Tuple[np.ndarray, List[MeshItem]]:
        """What a camera on ``camera_model`` draws now, its own model and the ground plane aside: the primitive
        table (N, STRIDE) and the meshes; ``textured`` gets the textured primitives' rows (in the table too, white)
        and images."""
        views = self._current(camera_model)
        drawn_tables: List[np.ndarray] = []
        drawn_meshes: List[MeshItem] = []
        for index, (model, view) in enumerate(views):
            if not view.links:
                continue
            tables: List[np.ndarray] = []
            meshes: List[MeshItem] = []
            textures: List[TexturedRow] = []
            try:
                view.draw(model, tables, meshes, textures)
            except Exception as error:  # drawn from its collisions, from this rendering on
                self._warnings.append(
                    f"model '{model.name}' visuals cannot be drawn ({type(error).__name__}: {error}): the cameras "
                    "draw its links from their collisions"
                )
                view = self._views[model] = _View.of_collisions(model)
                views[index] = (model, view)
                continue
            drawn_tables += tables
            drawn_meshes += meshes
            if textured is not None:
                textured += textures
        colours: Dict[ode.GeomObject, RGB] = {}
        hidden: Set[ode.GeomObject] = set()
        for _, view in views:
            colours.update(view.colours)
            hidden.update(view.hidden)
        rows: List[np.ndarray] = []
        geom_meshes: List[MeshItem] = []
        for geom in world_geoms(physics, camera_model):
            if geom in hidden:
                continue
            colour = colours.get(geom, DEFAULT_COLOR)
            if isinstance(geom, MeshGeom):
                geom_meshes.append(
                    (mesh_pose(geom.getPosition(), geom.getRotation(), colour), geom.vertices, geom.faces)
                )
                continue
            row = primitive_row(geom, colour)
            if row is not None:
                rows.append(row)
        return np.concatenate([np.array(rows).reshape(-1, STRIDE)] + drawn_tables), geom_meshes + drawn_meshes


def _files_named(visuals: List[Visual]) -> str:
    uris = [visual.geometry.uri for visual in visuals if isinstance(visual.geometry, Mesh)]
    return f" (mesh {', '.join(repr(uri) for uri in uris)})" if uris else ""
