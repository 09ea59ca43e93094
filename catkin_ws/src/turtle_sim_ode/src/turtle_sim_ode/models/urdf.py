"""Parse and validate a URDF string (no xacro, no file access) into plain dataclasses."""
from __future__ import annotations

from dataclasses import replace
from typing import Dict, List, Optional, Tuple, Union
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.description import (
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
    Mesh,
    Pose,
    RobotModel,
    SensorElement,
    Sphere,
    Vec3,
    Visual,
)
from turtle_sim_ode.models.materials import (
    RGB,
    TRANSPARENT_SCRIPT_ALPHA,
    gazebo_material,
    urdf_named_alphas,
    urdf_named_materials,
    urdf_visual_alpha,
    urdf_visual_color,
)
from turtle_sim_ode.models.text import ModelError, parse_xml, plugin_params, read_number, required_attribute
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.sanity import MAX_INERTIA, MAX_LENGTH, MAX_MASS, MIN_MASS

# Size limits of one model: a request beyond them is refused at once with the limit in the message, rather than
# holding the world for seconds while it is built and slowing every step after (1000 colliding links resting on
# the ground cost ~15 ms a step, 10x the real-time budget; 10,000 collisions on one body ~0.4 s a step).
MAX_LINKS = 1000
MAX_JOINTS = 1000
MAX_COLLISIONS = 1000
MAX_VISUALS = 1000  # each is drawn by every camera, every frame
# The parent link name of a joint that holds a model's root link to the world (SDF's <parent>world</parent>), and
# a URDF root link of that name: the world frame (a fixed joint from it welds the robot where it was placed).
WORLD_LINK = "world"
JOINT_TYPES = ("fixed", "continuous", "revolute", "prismatic")
# <gazebo reference="link"> contact tags -> GazeboSurface fields (Gazebo's ODE surface of the link's collisions).
SURFACE_TAGS = {
    "mu1": "mu1",
    "mu2": "mu2",
    "kp": "kp",
    "kd": "kd",
    "maxVel": "max_vel",
    "minDepth": "min_depth",
    "fdir1": "fdir1",
    "slip1": "slip1",
    "slip2": "slip2",
}

# The <geometry> shapes a URDF visual may have that the cameras draw (others are skipped with a warning).
VISUAL_SHAPES = ("box", "cylinder", "sphere", "mesh")


def read_surface_value(field_name: str, text: Optional[str], what: str) -> Union[float, Vec3]:
    """One GazeboSurface field from its tag's text: ``fdir1`` three finite numbers, ``kp`` a finite number > 0, the
    others finite and >= 0 (Gazebo's ODE would take a negative min_depth or max_vel, or NaN, and misbehave);
    ModelError naming ``what`` (the link and the tag) otherwise."""
    if field_name == "fdir1":
        if text is None:
            raise ModelError(f"{what}: expected 3 numbers, got nothing")
        return _vec3(text, what, (0.0, 0.0, 0.0))
    value = read_number(text, what, minimum=0.0)
    if field_name == "kp" and value <= 0:
        raise ModelError(f"{what} must be > 0, got '{text}'")
    return value


# --- small parsing helpers ------------------------------------------------------
def _vec3(text: Optional[str], what: str, default: Vec3) -> Vec3:
    if text is None:
        return default
    parts = text.split()
    if len(parts) != 3:
        raise ModelError(f"{what}: expected 3 numbers, got {text!r}")
    return (read_number(parts[0], what), read_number(parts[1], what), read_number(parts[2], what))


def mesh_geometry(uri: Optional[str], scale_text: Optional[str], what: str) -> Mesh:
    """A <mesh> collision (no file opened); ModelError without a URI or with a zero or huge scale."""
    if uri is None or not uri.strip():
        raise ModelError(f"{what}: needs a file name (URI)")
    scale = _vec3(scale_text, f"{what} scale", (1.0, 1.0, 1.0))
    for value in scale:
        if value == 0 or abs(value) > MAX_LENGTH:
            raise ModelError(f"{what} scale must be non-zero and at most {MAX_LENGTH:g}, got {scale}")
    return Mesh(uri.strip(), scale)


def _bounded(value: float, limit: float, what: str) -> float:
    """``value`` unless its magnitude exceeds ``limit``."""
    if abs(value) > limit:
        raise ModelError(f"{what} must be at most {limit:g} in magnitude, got {value:g}")
    return value


def _offset(xyz: Vec3, what: str) -> Vec3:
    """A translation whose every coordinate is within MAX_LENGTH metres."""
    for value in xyz:
        _bounded(value, MAX_LENGTH, f"{what} (m)")
    return xyz


def _pose(element: Optional[Element], what: str) -> Pose:
    if element is None:
        return Pose()
    return Pose(
        _offset(_vec3(element.get("xyz"), f"{what} origin xyz", (0.0, 0.0, 0.0)), f"{what} origin xyz"),
        _vec3(element.get("rpy"), f"{what} origin rpy", (0.0, 0.0, 0.0)),
    )


def _positive(value: float, what: str) -> float:
    """A length: > 0 and at most MAX_LENGTH metres."""
    if value <= 0:
        raise ModelError(f"{what} must be > 0, got {value}")
    return _bounded(value, MAX_LENGTH, f"{what} (m)")


def _check_mass(mass: float, inertia: Dict[str, float], what: str) -> None:
    """ModelError unless 0 < mass <= MAX_MASS and every inertia entry is within MAX_INERTIA."""
    if mass <= 0:
        raise ModelError(f"{what}: mass must be > 0, got {mass}")
    if mass < MIN_MASS:
        raise ModelError(
            f"{what}: mass must be at least {MIN_MASS:g} kg (fix lighter links to a heavier one), got {mass}"
        )
    _bounded(mass, MAX_MASS, f"{what}: mass (kg)")
    for key, value in inertia.items():
        _bounded(value, MAX_INERTIA, f"{what}: {key} (kg m^2)")


def _is_positive_definite(m: Tuple[Vec3, Vec3, Vec3]) -> bool:
    """Sylvester's criterion on a symmetric 3x3 matrix."""
    minor2 = m[0][0] * m[1][1] - m[0][1] * m[1][0]
    det = (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )
    return m[0][0] > 0 and minor2 > 0 and det > 0


# --- elements ----------------------------------------------------------------------
def _parse_inertial(element: Element, link: str) -> Inertial:
    what = f"link '{link}' inertial"
    mass_element = element.find("mass")
    if mass_element is None:
        raise ModelError(f"{what}: missing <mass>")
    mass = read_number(mass_element.get("value"), f"{what} mass")
    inertia = element.find("inertia")
    if inertia is None:
        raise ModelError(f"{what}: missing <inertia>")
    values = {k: read_number(inertia.get(k, "0"), f"{what} {k}") for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    _check_mass(mass, values, what)
    result = Inertial(mass, _pose(element.find("origin"), what), **values)
    if not _is_positive_definite(result.matrix()):
        raise ModelError(
            f"{what}: inertia matrix is not positive definite "
            f"(ixx={values['ixx']}, iyy={values['iyy']}, izz={values['izz']}, "
            f"ixy={values['ixy']}, ixz={values['ixz']}, iyz={values['iyz']})"
        )
    return result


def _parse_geometry(element: Optional[Element], what: str, warnings: List[str]) -> Geometry:
    shape = None if element is None else next(iter(element), None)
    if shape is None:
        raise ModelError(f"{what}: missing <geometry> shape")
    if shape.tag == "box":
        size = _vec3(shape.get("size"), f"{what} box size", (0.0, 0.0, 0.0))
        for value in size:
            _positive(value, f"{what} box size")
        return Box(size)
    if shape.tag == "cylinder":
        return Cylinder(
            _positive(read_number(shape.get("radius"), f"{what} cylinder radius"), f"{what} cylinder radius"),
            _positive(read_number(shape.get("length"), f"{what} cylinder length"), f"{what} cylinder length"),
        )
    if shape.tag == "sphere":
        return Sphere(_positive(read_number(shape.get("radius"), f"{what} sphere radius"), f"{what} sphere radius"))
    if shape.tag == "mesh":
        return mesh_geometry(shape.get("filename"), shape.get("scale"), f"{what} mesh")
    raise ModelError(f"{what}: unsupported geometry <{shape.tag}>")


def drawn_shape(visual: Element, what: str, shapes: Tuple[str, ...], warnings: List[str]) -> bool:
    """Whether a <visual>'s shape is one the cameras draw (``shapes``); a warning naming it if not. A visual without
    a shape is for its geometry parser to refuse."""
    geometry = visual.find("geometry")
    shape = None if geometry is None else next(iter(geometry), None)
    if shape is None or shape.tag in shapes:
        return True
    warnings.append(f"{what}: <{shape.tag}> is not drawn by the cameras, skipped")
    return False


def _parse_link(
    element: Element, warnings: List[str], materials: Dict[str, RGB], alphas: Optional[Dict[str, float]] = None
) -> Link:
    name = required_attribute(element, "name", "<link>")
    inertial = element.find("inertial")
    link = Link(name, _parse_inertial(inertial, name) if inertial is not None else None)
    for index, visual in enumerate(element.findall("visual")):
        what = f"link '{name}' visual {visual.get('name') or index}"
        if drawn_shape(visual, what, VISUAL_SHAPES, warnings):
            link.visuals.append(
                Visual(
                    visual.get("name") or f"{name}_visual_{index}",
                    _pose(visual.find("origin"), what),
                    _parse_geometry(visual.find("geometry"), what, warnings),
                    urdf_visual_color(visual, materials),
                    alpha=urdf_visual_alpha(visual, alphas or {}),
                )
            )
    for index, collision in enumerate(element.findall("collision")):
        what = f"link '{name}' collision {collision.get('name') or index}"
        link.collisions.append(
            Collision(
                collision.get("name") or f"{name}_collision_{index}",
                _pose(collision.find("origin"), what),
                _parse_geometry(collision.find("geometry"), what, warnings),
            )
        )
    return link


def _parse_joint(element: Element, warnings: List[str]) -> Joint:
    name = required_attribute(element, "name", "<joint>")
    what = f"joint '{name}'"
    joint_type = required_attribute(element, "type", what)
    if joint_type not in JOINT_TYPES:
        raise ModelError(f"{what}: unsupported type '{joint_type}' (supported: {JOINT_TYPES})")
    parent, child = element.find("parent"), element.find("child")
    if parent is None or child is None:
        raise ModelError(f"{what}: needs <parent link=...> and <child link=...>")
    axis_element = element.find("axis")
    axis = _vec3(None if axis_element is None else axis_element.get("xyz"), f"{what} axis", (1.0, 0.0, 0.0))
    if joint_type != "fixed":
        axis = sanity.unit_vector(axis, f"{what}: axis", ModelError)
    limit = element.find("limit")
    limits = None
    if limit is not None:
        limits = JointLimits(
            *(read_number(limit.get(k, "0"), f"{what} limit {k}") for k in ("lower", "upper", "effort", "velocity"))
        )
        if limits.lower > limits.upper:
            raise ModelError(f"{what}: limit lower {limits.lower} > upper {limits.upper}")
    elif joint_type in ("revolute", "prismatic"):
        raise ModelError(f"{what}: a {joint_type} joint needs <limit>")
    dynamics = element.find("dynamics")
    mimic = element.find("mimic")
    if mimic is not None:
        required_attribute(mimic, "joint", f"{what} <mimic>")
        for key, default in (("multiplier", "1"), ("offset", "0")):
            read_number(mimic.get(key, default), f"{what} <mimic> {key}")
        warnings.append(f"{what}: <mimic> is not simulated; the joint moves on its own")
    return Joint(
        name,
        joint_type,
        required_attribute(parent, "link", f"{what} <parent>"),
        required_attribute(child, "link", f"{what} <child>"),
        _pose(element.find("origin"), what),
        axis,
        limits,
        JointDynamics()
        if dynamics is None
        else JointDynamics(
            read_number(dynamics.get("damping", "0"), f"{what} damping"),
            read_number(dynamics.get("friction", "0"), f"{what} friction"),
        ),
    )


def _tag_value(element: Element) -> Optional[str]:
    """Gazebo tags come as <mu1>1</mu1> or, in old files, <mu1 value="1"/>."""
    text = element.get("value") if element.get("value") is not None else element.text
    return text.strip() if text is not None else None


# <gazebo> children that change only what Gazebo draws: read silently.
VISUAL_TAGS = ("material", "visual")


def _parse_gazebo(element: Element, model: RobotModel) -> None:
    reference = element.get("reference")
    model.sensors.extend(SensorElement(reference, sensor) for sensor in element.findall("sensor"))
    known = ("sensor", "plugin") + VISUAL_TAGS + (tuple(SURFACE_TAGS) if reference is not None else ())
    where = f"<gazebo reference='{reference}'>" if reference is not None else "<gazebo>"
    for tag in dict.fromkeys(child.tag for child in element if child.tag not in known):
        model.warnings.append(f"{where} <{tag}> is not simulated, ignored")
    if reference is None:
        for plugin in element.findall("plugin"):
            model.plugins.append(
                GazeboPlugin(
                    required_attribute(plugin, "filename", "<gazebo><plugin>"),
                    plugin.get("name", ""),
                    plugin_params(plugin),
                )
            )
        return
    script = (element.findtext("material") or "").strip()
    color = gazebo_material(script)
    if color is not None and reference in model.links:  # Gazebo shows its material over the URDF's colours
        link = model.links[reference]
        alpha = TRANSPARENT_SCRIPT_ALPHA if script.endswith("Transparent") else 1.0
        link.visuals = [replace(visual, color=color, alpha=alpha) for visual in link.visuals]
    values = {}
    for child in element:
        if child.tag in SURFACE_TAGS:
            values[SURFACE_TAGS[child.tag]] = read_surface_value(
                SURFACE_TAGS[child.tag], _tag_value(child), f"<gazebo reference='{reference}'> <{child.tag}>"
            )
    if not values:
        return
    if reference not in model.links:
        model.warnings.append(f"<gazebo reference='{reference}'>: no such link, ignored")
        return
    previous = model.surfaces.get(reference, GazeboSurface())
    merged = {k: getattr(previous, k) for k in SURFACE_TAGS.values()}
    merged.update(values)
    model.surfaces[reference] = GazeboSurface(**merged)


# --- validation -----------------------------------------------------------------------
def check_size(what: str, link_elements: List[Element], joint_elements: List[Element]) -> None:
    """ModelError naming the limits if a model has more links, joints, collisions or visuals than allowed."""
    collisions = sum(len(link.findall("collision")) for link in link_elements)
    if len(link_elements) > MAX_LINKS or len(joint_elements) > MAX_JOINTS or collisions > MAX_COLLISIONS:
        raise ModelError(
            f"{what} too large: {len(link_elements)} links, {len(joint_elements)} joints, {collisions} collisions "
            f"(limits {MAX_LINKS}, {MAX_JOINTS}, {MAX_COLLISIONS})"
        )
    visuals = sum(len(link.findall("visual")) for link in link_elements)
    if visuals > MAX_VISUALS:
        raise ModelError(f"{what} too large: {visuals} visuals (limit {MAX_VISUALS})")


def _find_root(links: Dict[str, Link], joints: Dict[str, Joint]) -> str:
    parent_of: Dict[str, str] = {}
    for joint in joints.values():
        for role, link in (("parent", joint.parent), ("child", joint.child)):
            if link not in links:
                raise ModelError(f"joint '{joint.name}': {role} link '{link}' does not exist")
        if joint.child in parent_of:
            raise ModelError(
                f"link '{joint.child}' has two parents: " f"'{parent_of[joint.child]}' and '{joint.parent}'"
            )
        if joint.parent == joint.child:
            raise ModelError(f"joint '{joint.name}' connects link '{joint.child}' to itself")
        parent_of[joint.child] = joint.parent
    roots = [name for name in links if name not in parent_of]
    if len(roots) > 1:
        raise ModelError(f"model has {len(roots)} root links {roots}; exactly one is required")
    if not roots:
        raise ModelError("model has no root link: its joints form a cycle")
    children: Dict[str, List[str]] = {}
    for child, parent in parent_of.items():
        children.setdefault(parent, []).append(child)
    reached, stack = set(), [roots[0]]
    while stack:
        link = stack.pop()
        reached.add(link)
        stack.extend(children.get(link, []))
    unreached = [name for name in links if name not in reached]
    if unreached:
        raise ModelError(f"joints form a cycle through links {unreached}")
    return roots[0]


def parse_urdf(text: str) -> RobotModel:
    """Parse a URDF document; raise ModelError with a clear message on any problem."""
    robot = parse_xml(text, "URDF")
    if robot.tag != "robot":
        raise ModelError(f"URDF root element must be <robot>, got <{robot.tag}>")
    name = required_attribute(robot, "name", "<robot>")
    link_elements, joint_elements = robot.findall("link"), robot.findall("joint")
    if not link_elements:
        raise ModelError("URDF has no <link>")
    check_size("model", link_elements, joint_elements)
    warnings: List[str] = []
    links: Dict[str, Link] = {}
    materials = urdf_named_materials(robot)
    alphas = urdf_named_alphas(robot)
    for element in link_elements:
        link = _parse_link(element, warnings, materials, alphas)
        if link.name in links:
            raise ModelError(f"duplicate link name '{link.name}'")
        links[link.name] = link
    joints: Dict[str, Joint] = {}
    for element in joint_elements:
        joint = _parse_joint(element, warnings)
        if joint.name in joints:
            raise ModelError(f"duplicate joint name '{joint.name}'")
        joints[joint.name] = joint
    model = RobotModel(name, links, joints, _find_root(links, joints), warnings=warnings)
    model.transmissions = robot.findall("transmission")
    for element in robot.findall("gazebo"):
        _parse_gazebo(element, model)
    return model
