"""Parse SDF 1.4-1.7 models and worlds (no file access) into the RobotModel of models.urdf.

SDF places every link relative to the model; the URDF-style tree that models.builder
consumes has each joint's origin = parent link pose^-1 * child link pose, and the root
link's model pose in ``RobotModel.root_pose``. Links no joint reaches (free bodies in
SDF) hang off the root by "floating" joints, which the builder turns into free bodies.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Set, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.builder import (
    Quat,
    Transform,
    compose,
    inverse,
    pose_transform,
    quat_rotate,
    rpy_of,
)
from turtle_sim_ode.models.lights import SUN, Light, parse_light
from turtle_sim_ode.models.world_state import WorldState, parse_world_state
from turtle_sim_ode.models.materials import RGB, rgb_of, sdf_visual_alpha, sdf_visual_color
from turtle_sim_ode.models.nested import flatten_nested_models, read_pose
from turtle_sim_ode.models.textures import sdf_material_script
from turtle_sim_ode.models.text import (
    ModelError,
    child_text,
    parse_xml,
    plugin_params,
    read_number,
    read_optional_number,
    required_attribute,
)
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.models.urdf import (
    MAX_LENGTH,
    Box,
    Collision,
    Cylinder,
    GazeboPlugin,
    GazeboSurface,
    Geometry,
    Inertial,
    Joint,
    JointDynamics,
    JointLimits,
    Link,
    Pose,
    RobotModel,
    SensorElement,
    Sphere,
    Vec3,
    WORLD_LINK,
    Visual,
    _bounded,
    _check_mass,
    _find_root,
    _is_positive_definite,
    _offset,
    _vec3,
    check_size,
    drawn_shape,
    mesh_geometry,
    read_surface_value,
)

if TYPE_CHECKING:
    from turtle_sim_ode.physics.settings import PhysicsParams

Version = Tuple[int, int]

OLDEST_VERSION: Version = (1, 4)
NEWEST_VERSION: Version = (1, 7)
# A bare <model> (no <sdf version>) is read with the newest conventions.
BARE_MODEL_VERSION: Version = NEWEST_VERSION
JOINT_TYPES = ("fixed", "continuous", "revolute", "prismatic")
# SDF's default joint limits, meaning "no limit".
UNLIMITED = 1e16
# A <plane> (static models only) becomes a box this thick whose top face is the plane:
# thick enough that nothing tunnels through it in a step, and no ODE plane (an infinite
# half-space) that would also catch everything below it.
PLANE_THICKNESS = 0.1
SURFACE_PATHS = {
    "mu1": "friction/ode/mu",
    "mu2": "friction/ode/mu2",
    "kp": "contact/ode/kp",
    "kd": "contact/ode/kd",
    "max_vel": "contact/ode/max_vel",
    "min_depth": "contact/ode/min_depth",
    "fdir1": "friction/ode/fdir1",
    "slip1": "friction/ode/slip1",
    "slip2": "friction/ode/slip2",
}
# The <geometry> shapes of an SDF visual the cameras draw (others are skipped with a warning).
VISUAL_SHAPES = ("box", "cylinder", "sphere", "plane", "mesh")
# <world> children that change nothing the simulator models.
SILENT_WORLD_TAGS = ("light", "scene", "gui", "atmosphere", "spherical_coordinates", "magnetic_field", "wind", "audio")
# <gravity> when a world has none: SDF's default (sdformat's world.sdf).
SDF_GRAVITY: Vec3 = (0.0, 0.0, -9.8)
GROUND_PLANE_URI = "model://ground_plane"
SUN_URI = "model://sun"
# Gazebo's own inline copy of its ground plane (worlds saved from the GUI contain one).
GROUND_PLANE_NAME = "ground_plane"


@dataclass(frozen=True)
class SdfPhysics:
    """<physics type="ode"> and <gravity>; None where the world leaves the simulator's default."""

    max_step_size: Optional[float] = None
    real_time_factor: Optional[float] = None
    real_time_update_rate: Optional[float] = None
    solver: Optional[str] = None
    iterations: Optional[int] = None
    cfm: Optional[float] = None
    erp: Optional[float] = None
    contact_max_correcting_vel: Optional[float] = None
    contact_surface_layer: Optional[float] = None
    gravity: Optional[Vec3] = None
    sor: Optional[float] = None

    def apply(self, params: PhysicsParams) -> PhysicsParams:
        """A copy of ``params`` with the values this world sets (real-time pacing is the
        caller's); ModelError if they are out of range."""
        given = {
            "time_step": self.max_step_size,
            "solver": self.solver,
            "solver_iterations": self.iterations,
            "cfm": self.cfm,
            "erp": self.erp,
            "contact_max_correcting_vel": self.contact_max_correcting_vel,
            "contact_surface_layer": self.contact_surface_layer,
            "gravity": self.gravity,
            "sor": self.sor,
        }
        result = replace(params, **{k: v for k, v in given.items() if v is not None})
        try:
            result.validate()
        except ValueError as error:
            raise ModelError(f"world <physics>: {error}") from None
        return result


@dataclass(frozen=True)
class WorldModel:
    """A <model> written inline in the world, at ``pose`` (its model frame)."""

    name: str
    pose: Pose
    model: RobotModel
    # The folder of the file the model came from (an <include>d model's), for its relative mesh names.
    base: Optional[str] = None
    # Its place among the world's <model>s and <include>s: Gazebo loads them in that order.
    index: int = field(default=0, compare=False)

    @property
    def spawn_pose(self) -> Tuple[float, float, float, float, float, float]:
        """(x, y, z, roll, pitch, yaw) for build_model."""
        return self.pose.xyz + self.pose.rpy


@dataclass(frozen=True)
class Include:
    """An <include> for the caller to resolve (model:// files are never opened here)."""

    uri: str
    name: Optional[str] = None
    pose: Pose = Pose()
    static: Optional[bool] = None
    index: int = field(default=0, compare=False)  # as WorldModel's


@dataclass
class World:
    """<world>: physics, inline models, includes for the caller, world plugins."""

    name: str
    physics: SdfPhysics
    models: List[WorldModel] = field(default_factory=list)
    includes: List[Include] = field(default_factory=list)
    plugins: List[GazeboPlugin] = field(default_factory=list)
    # model://ground_plane (or an inline "ground_plane" model); without one the world has no ground, as in Gazebo.
    ground_plane: bool = False
    sun: bool = False
    # The world's <light>s in order (model://sun is models.lights.SUN); <scene><background> (None: Gazebo's).
    lights: List[Light] = field(default_factory=list)
    state: Optional[WorldState] = None  # the first <state> (see models.world_state)
    background: Optional[RGB] = None
    # <spherical_coordinates>: latitude_deg, longitude_deg, elevation, heading_deg (None: Gazebo's zeros).
    spherical_coordinates: Optional[Tuple[float, float, float, float]] = None
    # <gui><camera><pose>: where Gazebo's client first looks from (None: its default view).
    user_camera: Optional[Pose] = None
    warnings: List[str] = field(default_factory=list)


# --- small helpers ------------------------------------------------------------------
_rpy = rpy_of  # the name world.simulation imports
_IDENTITY: Transform = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))


def _as_pose(transform: Transform) -> Pose:
    return Pose(transform[0], _rpy(transform[1]))


def _optional_float(element: Element, path: str, what: str) -> Optional[float]:
    return read_optional_number(child_text(element, path), f"{what} <{path}>")


def _float(element: Element, path: str, what: str, default: float) -> float:
    return read_number(child_text(element, path), f"{what} <{path}>", default)


def _bool(element: Element, path: str, what: str, default: bool) -> bool:
    text = child_text(element, path)
    if text is None:
        return default
    if text.lower() in ("true", "1"):
        return True
    if text.lower() in ("false", "0"):
        return False
    raise ModelError(f"{what} <{path}>: expected true or false, got {text!r}")


_pose = read_pose


def _plugin(element: Element, what: str) -> GazeboPlugin:
    return GazeboPlugin(
        required_attribute(element, "filename", f"{what} <plugin>"),
        element.get("name", ""),
        plugin_params(element),
    )


def _version(sdf: Element) -> Version:
    text = sdf.get("version")
    try:
        major, minor = (int(part) for part in (text or "").split("."))
    except ValueError:
        raise ModelError(f"<sdf version={text!r}>: expected a version such as '1.6'") from None
    if not OLDEST_VERSION <= (major, minor) <= NEWEST_VERSION:
        raise ModelError(f"SDF version {text} is not supported (1.4 to 1.7)")
    return major, minor


# --- model parts ----------------------------------------------------------------------
def _parse_inertial(element: Optional[Element], link: str, warnings: List[str]) -> Inertial:
    what = f"link '{link}' <inertial>"
    if element is None:
        warnings.append(f"link '{link}' has no <inertial>: SDF's default mass 1 kg and " f"inertia 1 kg m^2 are used")
        return Inertial(1.0, Pose(), 1.0, 0.0, 0.0, 1.0, 0.0, 1.0)
    mass = _float(element, "mass", what, 1.0)
    values = {
        k: _float(element, f"inertia/{k}", what, 1.0 if k in ("ixx", "iyy", "izz") else 0.0)
        for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    }
    _check_mass(mass, values, what)
    result = Inertial(mass, _pose(element, what), **values)
    if not _is_positive_definite(result.matrix()):
        raise ModelError(f"{what}: inertia matrix is not positive definite ({values})")
    return result


def _positive(element: Element, path: str, what: str, default: float) -> float:
    value = _float(element, path, what, default)
    if value <= 0:
        raise ModelError(f"{what} <{path}> must be > 0, got {value}")
    return _bounded(value, MAX_LENGTH, f"{what} <{path}> (m)")


def _plane_to_z(normal: Vec3) -> Quat:
    """Rotation taking +z to the unit vector ``normal``."""
    w = 1.0 + normal[2]
    if w < 1e-9:  # upside down: half a turn about x
        return (0.0, 1.0, 0.0, 0.0)
    x, y = -normal[1], normal[0]  # z x normal
    norm = math.sqrt(w * w + x * x + y * y)
    return (w / norm, x / norm, y / norm, 0.0)


def _parse_geometry(
    element: Optional[Element], what: str, static: bool, warnings: List[str]
) -> Tuple[Geometry, Transform]:
    """The shape and where it sits in the collision frame."""
    identity = _IDENTITY
    shape = None if element is None else next(iter(element), None)
    if shape is None:
        raise ModelError(f"{what}: missing <geometry> shape")
    what = f"{what} <{shape.tag}>"
    if shape.tag == "box":
        size = _vec3(child_text(shape, "size"), f"{what} <size>", (1.0, 1.0, 1.0))
        if min(size) <= 0:
            raise ModelError(f"{what} <size> must be > 0, got {size}")
        return Box(_offset(size, f"{what} <size>")), identity
    if shape.tag == "cylinder":
        return (Cylinder(_positive(shape, "radius", what, 0.5), _positive(shape, "length", what, 1.0)), identity)
    if shape.tag == "sphere":
        return Sphere(_positive(shape, "radius", what, 1.0)), identity
    if shape.tag == "plane":
        if not static:
            raise ModelError(f"{what}: planes are only supported in static models")
        normal = _vec3(child_text(shape, "normal"), f"{what} <normal>", (0.0, 0.0, 1.0))
        length = math.sqrt(sum(n * n for n in normal))
        if length < 1e-9:
            raise ModelError(f"{what} <normal> must not be zero")
        normal = (normal[0] / length, normal[1] / length, normal[2] / length)
        size = (child_text(shape, "size") or "1 1").split()
        if len(size) != 2:
            raise ModelError(f"{what} <size>: expected 2 numbers, got {' '.join(size)!r}")
        sx, sy = (read_number(s, f"{what} <size>") for s in size)
        if min(sx, sy) <= 0:
            raise ModelError(f"{what} <size> must be > 0, got {sx} {sy}")
        _offset((sx, sy, PLANE_THICKNESS), f"{what} <size>")
        half = PLANE_THICKNESS / 2
        return (
            Box((sx, sy, PLANE_THICKNESS)),
            ((-half * normal[0], -half * normal[1], -half * normal[2]), _plane_to_z(normal)),
        )
    if shape.tag == "mesh":
        if shape.find("submesh") is not None:
            warnings.append(f"{what}: <mesh><submesh> is not supported; the whole mesh is used")
        return mesh_geometry(child_text(shape, "uri"), child_text(shape, "scale"), f"{what} <mesh>"), identity
    raise ModelError(f"{what}: unsupported geometry")


def _placed(element: Element, what: str, static: bool, warnings: List[str]) -> Tuple[Pose, Geometry]:
    """A <collision>'s or <visual>'s pose in its link and its shape."""
    geometry, offset = _parse_geometry(element.find("geometry"), what, static, warnings)
    return _as_pose(compose(pose_transform(_pose(element, what)), offset)), geometry


# <surface> entries that are read (SURFACE_PATHS) or that hold only their parents' defaults.
_SURFACE_CONTAINERS = {"friction", "friction/ode", "contact", "contact/ode"}


def _surface_leaves(element: Element, prefix: str = "") -> List[str]:
    paths = []
    for child in element:
        path = f"{prefix}{child.tag}"
        paths.extend(_surface_leaves(child, path + "/") if len(child) else [path])
    return paths


def _parse_surface(element: Optional[Element], what: str, warnings: Optional[List[str]] = None) -> Dict[str, Any]:
    if element is None:
        return {}
    if warnings is not None:
        read = set(SURFACE_PATHS.values()) | _SURFACE_CONTAINERS
        for path in _surface_leaves(element):
            if path not in read:
                warnings.append(f"{what} <surface> <{path}> is not simulated, ignored")
    values = {}
    for key, path in SURFACE_PATHS.items():
        text = child_text(element, path)
        if text is not None:
            values[key] = read_surface_value(key, text, f"{what} <surface> <{path}>")
    return values


def _parse_link(element: Element, static: bool, model: RobotModel) -> Tuple[Link, Pose]:
    """The link and its pose in the model; its <surface> values go to ``model.surfaces``."""
    name = required_attribute(element, "name", "<link>")
    what = f"link '{name}'"
    for flag, normal in (("kinematic", False), ("gravity", True)):
        if not static and _bool(element, flag, what, normal) != normal:
            model.warnings.append(f"{what}: <{flag}> is not supported, ignored")
    link = Link(name, None if static else _parse_inertial(element.find("inertial"), name, model.warnings))
    for index, visual in enumerate(element.findall("visual")):
        visual_name = visual.get("name") or f"{name}_visual_{index}"
        where = f"{what} visual '{visual_name}'"
        if drawn_shape(visual, where, VISUAL_SHAPES, model.warnings):
            # A plane is drawn as the box it collides as, on moving links too.
            origin, geometry = _placed(visual, where, True, model.warnings)
            link.visuals.append(
                Visual(
                    visual_name,
                    origin,
                    geometry,
                    sdf_visual_color(visual),
                    texture=sdf_material_script(visual),
                    alpha=sdf_visual_alpha(visual),
                )
            )
    surface: Dict[str, float] = {}
    for index, collision in enumerate(element.findall("collision")):
        collision_name = collision.get("name") or f"{name}_collision_{index}"
        where = f"{what} collision '{collision_name}'"
        origin, geometry = _placed(collision, where, static, model.warnings)
        plane = collision.find("geometry/plane") is not None
        link.collisions.append(Collision(collision_name, origin, geometry, plane))
        values = _parse_surface(collision.find("surface"), where, model.warnings)
        if any(surface.get(key, value) != value for key, value in values.items()):
            model.warnings.append(
                f"{what}: its collisions have different <surface> values; "
                f"the link gets one surface, the last collision's values win"
            )
        surface.update(values)
    if surface:
        model.surfaces[name] = GazeboSurface(**surface)
    model.sensors.extend(SensorElement(name, sensor) for sensor in element.findall("sensor"))
    return link, _pose(element, what)


def _axis(
    element: Element, what: str, version: Version, joint_in_model: Transform, link_poses: Dict[str, Transform]
) -> Vec3:
    """The unit joint axis in the joint frame, whatever frame the SDF version writes it in."""
    xyz = sanity.unit_vector(
        _vec3(child_text(element, "xyz"), f"{what} <axis><xyz>", (0.0, 0.0, 1.0)), f"{what}: axis", ModelError
    )
    # 1.4: always the model frame. 1.5, 1.6: the joint frame unless <use_parent_model_frame>.
    # 1.7: the joint frame unless <xyz expressed_in="__model__" or a link name>.
    if version == (1, 4):
        frame: Optional[str] = "__model__"
    elif version < (1, 7):
        frame = "__model__" if _bool(element, "use_parent_model_frame", what, False) else None
    else:
        xyz_element = element.find("xyz")
        frame = (xyz_element.get("expressed_in") or None) if xyz_element is not None else None
    if frame is None:
        return xyz
    if frame == "__model__":
        in_model = xyz
    elif frame in link_poses:
        in_model = quat_rotate(link_poses[frame][1], xyz)
    else:
        raise ModelError(f"{what} <xyz expressed_in='{frame}'>: only '__model__' and link names " f"are supported")
    w, x, y, z = joint_in_model[1]
    return quat_rotate((w, -x, -y, -z), in_model)


def _parse_joint(element: Element, version: Version, link_poses: Dict[str, Transform], warnings: List[str]) -> Joint:
    name = required_attribute(element, "name", "<joint>")
    what = f"joint '{name}'"
    joint_type = required_attribute(element, "type", what)
    if joint_type not in JOINT_TYPES:
        raise ModelError(f"{what}: unsupported type '{joint_type}' (supported: {JOINT_TYPES})")
    parent, child = child_text(element, "parent"), child_text(element, "child")
    if parent is None or child is None:
        raise ModelError(f"{what}: needs <parent> and <child>")
    if parent == WORLD_LINK and joint_type == "fixed":
        raise ModelError(f"{what}: fixed joints to the world are not supported; make the model <static> instead")
    for role, link in (("parent", parent), ("child", child)):
        if link not in link_poses and not (role == "parent" and link == WORLD_LINK):
            raise ModelError(f"{what}: {role} link '{link}' does not exist")
    frame = _pose(element, what)
    joint_in_model = compose(link_poses[child], pose_transform(frame))
    axis_element = element.find("axis")
    axis: Vec3 = (0.0, 0.0, 1.0)
    limits, dynamics = None, JointDynamics()
    if joint_type != "fixed":
        if axis_element is None:  # SDF's defaults: z axis, no limits, no dynamics
            axis_element = Element("axis")
        axis = _axis(axis_element, what, version, joint_in_model, link_poses)
        limit = axis_element.find("limit")
        if limit is not None:
            limits = JointLimits(
                *(
                    _float(limit, key, what, default)
                    for key, default in (
                        ("lower", -UNLIMITED),
                        ("upper", UNLIMITED),
                        ("effort", -1.0),
                        ("velocity", -1.0),
                    )
                )
            )
            if limits.lower > limits.upper:
                raise ModelError(f"{what}: limit lower {limits.lower} > upper {limits.upper}")
        if joint_type == "revolute" and (limits is None or (limits.lower <= -UNLIMITED and limits.upper >= UNLIMITED)):
            joint_type = "continuous"
        dynamics = JointDynamics(
            _float(axis_element, "dynamics/damping", what, 0.0), _float(axis_element, "dynamics/friction", what, 0.0)
        )
        if _float(axis_element, "dynamics/spring_stiffness", what, 0.0) != 0.0:
            warnings.append(f"{what}: <spring_stiffness> is not supported, ignored")
    origin = _as_pose(compose(inverse(link_poses.get(parent, _IDENTITY)), link_poses[child]))
    return Joint(name, joint_type, parent, child, origin, axis, limits, dynamics, frame)


def _parse_model(element: Element, version: Version) -> Tuple[RobotModel, Pose]:
    """The model and its own <pose>."""
    name = required_attribute(element, "name", "<model>")
    what = f"model '{name}'"
    if element.find("include") is not None:
        raise ModelError(f"{what}: an <include> inside a model is not supported")
    flatten_nested_models(element, what)
    static = _bool(element, "static", what, False)
    link_elements, joint_elements = element.findall("link"), element.findall("joint")
    if not link_elements:
        raise ModelError(f"{what} has no <link>")
    check_size(what, link_elements, joint_elements)
    model = RobotModel(name, {}, {}, "", static=static)
    link_poses: Dict[str, Transform] = {}
    for link_element in link_elements:
        link, pose = _parse_link(link_element, static, model)
        if link.name in model.links:
            raise ModelError(f"{what}: duplicate link name '{link.name}'")
        model.links[link.name] = link
        link_poses[link.name] = pose_transform(pose)
    for joint_element in joint_elements:
        joint = _parse_joint(joint_element, version, link_poses, model.warnings)
        if joint.name in model.joints:
            raise ModelError(f"{what}: duplicate joint name '{joint.name}'")
        model.joints[joint.name] = joint
    # A joint to the world (a lift's, an arm's base) holds the root link: the tree is the other joints.
    in_tree = {key: joint for key, joint in model.joints.items() if joint.parent != WORLD_LINK}
    children = {joint.child for joint in in_tree.values()}
    roots = [link for link in model.links if link not in children]
    for free in roots[1:]:  # SDF links without a joint are free bodies
        model.joints[f"__free_{free}"] = Joint(
            f"__free_{free}",
            "floating",
            roots[0],
            free,
            _as_pose(compose(inverse(link_poses[roots[0]]), link_poses[free])),
        )
    model.root = _find_root(model.links, {k: j for k, j in model.joints.items() if j.parent != WORLD_LINK})
    if any(joint.child != model.root for joint in model.joints.values() if joint.parent == WORLD_LINK):
        raise ModelError(f"{what}: a joint to the world must hold the root link '{model.root}'")
    model.root_pose = _as_pose(link_poses[model.root])
    model.plugins.extend(_plugin(p, what) for p in element.findall("plugin"))
    if _bool(element, "self_collide", what, False):
        model.warnings.append(f"{what}: <self_collide> is not applied; build it with " f"self_collide=True")
    return model, _pose(element, what)


# --- public ------------------------------------------------------------------------------
# The root element's name, or the start of markup skipped before it: a processing instruction or a comment.
_MARKUP = re.compile(r"<(\?|!--|[A-Za-z_][\w.-]*)")
_MARKUP_ENDS = {"?": "?>", "!--": "-->"}
_FORMATS = {"robot": "urdf", "sdf": "sdf", "model": "sdf"}


def model_format(xml: str) -> str:
    """'urdf', 'sdf' or 'unknown' from the root element (gazebo_ros's spawn services take either format). Linear
    in the text, whatever it holds: a regular expression that skipped comments with ``.*?`` took quadratic time
    on a text of unterminated ones."""
    position = 0
    while True:
        match = _MARKUP.search(xml, position)
        if match is None:
            return "unknown"
        token = match.group(1)
        if token not in _MARKUP_ENDS:
            return _FORMATS.get(token, "unknown")
        end = xml.find(_MARKUP_ENDS[token], match.end())
        if end < 0:
            return "unknown"
        position = end + len(_MARKUP_ENDS[token])


def parse_sdf_model(text: str) -> RobotModel:
    """Parse ``<sdf version><model>`` or a bare ``<model>`` (read as SDF 1.7).

    The model's own <pose> is not applied: build_model's pose places the model frame.
    """
    root = parse_xml(text, "SDF")
    if root.tag == "model":
        return _parse_model(root, BARE_MODEL_VERSION)[0]
    if root.tag != "sdf":
        raise ModelError(f"SDF root element must be <sdf> or <model>, got <{root.tag}>")
    version = _version(root)
    if root.find("world") is not None:
        raise ModelError(
            "this SDF holds a <world>, not a model: a world is loaded at start-up with the world_name launch argument "
            "(the simulator's ~world_name parameter); to spawn one of its models, send that <model> alone"
        )
    models = root.findall("model")
    if len(models) != 1:
        raise ModelError(f"expected one <model> in <sdf>, found {len(models)}")
    return _parse_model(models[0], version)[0]


def parse_included_model(text: str, name: Optional[str], static: Optional[bool]) -> Tuple[RobotModel, Pose]:
    """An <include>d model file (``<sdf><model>``): the model, renamed to ``name`` and made ``static`` where the
    <include> says so, and its own <pose>."""
    root = parse_xml(text, "SDF")
    models = root.findall("model") if root.tag == "sdf" else [root] if root.tag == "model" else []
    if len(models) != 1:
        raise ModelError(f"expected one <model> in the model file, found {len(models)}")
    element = models[0]
    if name is not None:
        element.set("name", name)
    if static is not None:
        for old in element.findall("static"):
            element.remove(old)
        flag = Element("static")
        flag.text = "true" if static else "false"
        element.insert(0, flag)
    return _parse_model(element, _version(root) if root.tag == "sdf" else BARE_MODEL_VERSION)


def _parse_physics(world: Element, warnings: List[str]) -> SdfPhysics:
    blocks = world.findall("physics")
    chosen = next(
        (b for b in blocks if b.get("default", "").lower() in ("true", "1")),
        blocks[0] if blocks else Element("physics"),
    )
    what = "<physics>"
    if chosen.get("type", "ode") != "ode":
        warnings.append(f"<physics type='{chosen.get('type')}'>: only its ODE settings are read")
    # SDF 1.4 keeps gravity in <physics>, later versions in <world>.
    gravity_text = child_text(world, "gravity") or child_text(chosen, "gravity")
    solver = child_text(chosen, "ode/solver/type")
    if solver not in (None, "quick", "world"):
        raise ModelError(f"{what} <ode><solver><type>: expected quick or world, got {solver!r}")
    iterations = _optional_float(chosen, "ode/solver/iters", what)
    if iterations is not None and (iterations != int(iterations) or iterations < 1):
        raise ModelError(f"{what} <ode><solver><iters>: expected a positive integer, " f"got {iterations}")
    step = _optional_float(chosen, "max_step_size", what)
    if step is not None and step <= 0:
        raise ModelError(f"{what} <max_step_size> must be > 0, got {step}")
    for path, idle in (("ode/solver/precon_iters", "0"), ("ode/solver/use_dynamic_moi_rescaling", "0")):
        if child_text(chosen, path) not in (None, idle, "false"):
            warnings.append(f"{what} <{path}> {child_text(chosen, path)} is not simulated, ignored")
    return SdfPhysics(
        max_step_size=step,
        real_time_factor=_optional_float(chosen, "real_time_factor", what),
        real_time_update_rate=_optional_float(chosen, "real_time_update_rate", what),
        solver=solver,
        iterations=None if iterations is None else int(iterations),
        cfm=_optional_float(chosen, "ode/constraints/cfm", what),
        erp=_optional_float(chosen, "ode/constraints/erp", what),
        contact_max_correcting_vel=_optional_float(chosen, "ode/constraints/contact_max_correcting_vel", what),
        contact_surface_layer=_optional_float(chosen, "ode/constraints/contact_surface_layer", what),
        sor=_optional_float(chosen, "ode/solver/sor", what),
        # SDF's default, as Gazebo gives a world without <gravity> (not the simulator's own -9.81).
        gravity=SDF_GRAVITY if gravity_text is None else _vec3(gravity_text, "<gravity>", (0.0, 0.0, 0.0)),
    )


def parse_sdf_world(text: str) -> World:
    """Parse ``<sdf version><world>``: physics, inline models, includes (not opened), plugins."""
    root = parse_xml(text, "SDF")
    if root.tag != "sdf":
        raise ModelError(f"SDF root element must be <sdf>, got <{root.tag}>")
    version = _version(root)
    worlds = root.findall("world")
    if len(worlds) != 1:
        raise ModelError(f"expected one <world> in <sdf>, found {len(worlds)}")
    element = worlds[0]
    warnings: List[str] = []
    world = World(element.get("name", "default"), _parse_physics(element, warnings), warnings=warnings)
    names: Set[str] = set()
    for index, child in enumerate(element):
        if child.tag == "model":
            model, pose = _parse_model(child, version)
            world.ground_plane = world.ground_plane or model.name == GROUND_PLANE_NAME
            if model.name in names:
                raise ModelError(f"two models are named '{model.name}'")
            names.add(model.name)
            world.models.append(WorldModel(model.name, pose, model, index=index))
        elif child.tag == "include":
            uri = child_text(child, "uri")
            if uri is None:
                raise ModelError("<include> needs a <uri>")
            if uri == SUN_URI:
                world.sun = True
                world.lights.append(replace(SUN, name=child_text(child, "name") or SUN.name))
            else:
                world.ground_plane = world.ground_plane or uri.rstrip("/") == GROUND_PLANE_URI
                name = child_text(child, "name")
                if name is not None:
                    if name in names:
                        raise ModelError(f"two models are named '{name}'")
                    names.add(name)
                static = child_text(child, "static")
                world.includes.append(
                    Include(
                        uri,
                        name,
                        _pose(child, f"<include> '{uri}'"),
                        None if static is None else _bool(child, "static", f"<include> '{uri}'", False),
                        index,
                    )
                )
        elif child.tag == "plugin":
            world.plugins.append(_plugin(child, "<world>"))
        elif child.tag == "light":
            world.lights.append(parse_light(child))
        elif child.tag == "state":
            if world.state is None:
                world.state = parse_world_state(element)
        elif child.tag == "gui" and child.find("camera/pose") is not None:
            world.user_camera = _pose(child.find("camera"), "<gui><camera>")
        elif child.tag == "scene":
            world.background = rgb_of(child_text(child, "background")) or world.background
        elif child.tag == "spherical_coordinates":
            tags = ("latitude_deg", "longitude_deg", "elevation", "heading_deg")
            values = (_float(child, tag, "<spherical_coordinates>", 0.0) for tag in tags)
            world.spherical_coordinates = tuple(values)  # type: ignore[assignment]
        elif child.tag not in SILENT_WORLD_TAGS + ("physics", "gravity"):
            warnings.append(f"<world> <{child.tag}> is not supported, ignored")
    return world
