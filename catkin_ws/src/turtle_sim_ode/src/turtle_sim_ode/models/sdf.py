"""Parse SDF 1.4-1.7 models (no file access) into the RobotModel of models.description.

SDF places every link relative to the model; the URDF-style tree that models.builder
consumes has each joint's origin = parent link pose^-1 * child link pose, and the root
link's model pose in ``RobotModel.root_pose``. Links no joint reaches (free bodies in
SDF) hang off the root by "floating" joints, which the builder turns into free bodies.
"""
from __future__ import annotations

import re
from typing import Dict, List, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.materials import sdf_visual_alpha, sdf_visual_color
from turtle_sim_ode.models.nested import flatten_nested_models, read_pose
from turtle_sim_ode.models.description import (
    Collision,
    GazeboSurface,
    Joint,
    JointDynamics,
    JointLimits,
    Link,
    Pose,
    RobotModel,
    SensorElement,
    Vec3,
    Visual,
)
from turtle_sim_ode.models.urdf import WORLD_LINK, _find_root, _vec3, check_size, drawn_shape
from turtle_sim_ode.models.sdf_parts import (
    BARE_MODEL_VERSION,
    IDENTITY,
    VISUAL_SHAPES,
    Version,
    as_pose,
    parse_inertial,
    parse_surface,
    read_bool,
    read_float,
    read_placed_shape,
    read_plugin,
    read_version,
)
from turtle_sim_ode.models.text import ModelError, child_text, parse_xml, required_attribute
from turtle_sim_ode.models.textures import sdf_material_script
from turtle_sim_ode.models.transforms import Transform, compose, inverse, pose_transform, quat_rotate
from turtle_sim_ode.physics import sanity

JOINT_TYPES = ("fixed", "continuous", "revolute", "prismatic")
# SDF's default joint limits, meaning "no limit".
UNLIMITED = 1e16


def _parse_link(element: Element, static: bool, model: RobotModel) -> Tuple[Link, Pose]:
    """The link and its pose in the model; its <surface> values go to ``model.surfaces``."""
    name = required_attribute(element, "name", "<link>")
    what = f"link '{name}'"
    for flag, normal in (("kinematic", False), ("gravity", True)):
        if not static and read_bool(element, flag, what, normal) != normal:
            model.warnings.append(f"{what}: <{flag}> is not supported, ignored")
    link = Link(name, None if static else parse_inertial(element.find("inertial"), name, model.warnings))
    for index, visual in enumerate(element.findall("visual")):
        visual_name = visual.get("name") or f"{name}_visual_{index}"
        where = f"{what} visual '{visual_name}'"
        if drawn_shape(visual, where, VISUAL_SHAPES, model.warnings):
            # A plane is drawn as the box it collides as, on moving links too.
            origin, geometry = read_placed_shape(visual, where, True, model.warnings)
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
        origin, geometry = read_placed_shape(collision, where, static, model.warnings)
        plane = collision.find("geometry/plane") is not None
        link.collisions.append(Collision(collision_name, origin, geometry, plane))
        values = parse_surface(collision.find("surface"), where, model.warnings)
        if any(surface.get(key, value) != value for key, value in values.items()):
            model.warnings.append(
                f"{what}: its collisions have different <surface> values; "
                f"the link gets one surface, the last collision's values win"
            )
        surface.update(values)
    if surface:
        model.surfaces[name] = GazeboSurface(**surface)
    model.sensors.extend(SensorElement(name, sensor) for sensor in element.findall("sensor"))
    return link, read_pose(element, what)


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
        frame = "__model__" if read_bool(element, "use_parent_model_frame", what, False) else None
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
    frame = read_pose(element, what)
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
                    read_float(limit, key, what, default)
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
            read_float(axis_element, "dynamics/damping", what, 0.0),
            read_float(axis_element, "dynamics/friction", what, 0.0),
        )
        if read_float(axis_element, "dynamics/spring_stiffness", what, 0.0) != 0.0:
            warnings.append(f"{what}: <spring_stiffness> is not supported, ignored")
    origin = as_pose(compose(inverse(link_poses.get(parent, IDENTITY)), link_poses[child]))
    return Joint(name, joint_type, parent, child, origin, axis, limits, dynamics, frame)


def parse_model(element: Element, version: Version) -> Tuple[RobotModel, Pose]:
    """The model and its own <pose>."""
    name = required_attribute(element, "name", "<model>")
    what = f"model '{name}'"
    if element.find("include") is not None:
        raise ModelError(f"{what}: an <include> inside a model is not supported")
    flatten_nested_models(element, what)
    static = read_bool(element, "static", what, False)
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
            as_pose(compose(inverse(link_poses[roots[0]]), link_poses[free])),
        )
    model.root = _find_root(model.links, {k: j for k, j in model.joints.items() if j.parent != WORLD_LINK})
    if any(joint.child != model.root for joint in model.joints.values() if joint.parent == WORLD_LINK):
        raise ModelError(f"{what}: a joint to the world must hold the root link '{model.root}'")
    model.root_pose = as_pose(link_poses[model.root])
    model.plugins.extend(read_plugin(p, what) for p in element.findall("plugin"))
    if read_bool(element, "self_collide", what, False):
        model.warnings.append(f"{what}: <self_collide> is not applied; build it with " f"self_collide=True")
    return model, read_pose(element, what)


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
        return parse_model(root, BARE_MODEL_VERSION)[0]
    if root.tag != "sdf":
        raise ModelError(f"SDF root element must be <sdf> or <model>, got <{root.tag}>")
    version = read_version(root)
    if root.find("world") is not None:
        raise ModelError(
            "this SDF holds a <world>, not a model: a world is loaded at start-up with the world_name launch argument "
            "(the simulator's ~world_name parameter); to spawn one of its models, send that <model> alone"
        )
    models = root.findall("model")
    if len(models) != 1:
        raise ModelError(f"expected one <model> in <sdf>, found {len(models)}")
    return parse_model(models[0], version)[0]


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
    return parse_model(element, read_version(root) if root.tag == "sdf" else BARE_MODEL_VERSION)
