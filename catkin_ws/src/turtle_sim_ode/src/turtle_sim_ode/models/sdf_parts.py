"""Pieces of SDF model text: element readers (numbers, flags, poses, plugins, the version), a link's inertial,
the geometry of its collisions and visuals, a collision's contact surface."""
from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.nested import read_pose
from turtle_sim_ode.models.text import (
    ModelError,
    child_text,
    plugin_params,
    read_number,
    read_optional_number,
    required_attribute,
)
from turtle_sim_ode.models.description import Box, Cylinder, GazeboPlugin, Geometry, Inertial, Pose, Sphere, Vec3
from turtle_sim_ode.models.urdf import (
    MAX_LENGTH,
    _bounded,
    _check_mass,
    _is_positive_definite,
    _offset,
    _vec3,
    mesh_geometry,
    read_surface_value,
)
from turtle_sim_ode.models.transforms import Quat, Transform, compose, pose_transform, rpy_of

Version = Tuple[int, int]

OLDEST_VERSION: Version = (1, 4)
NEWEST_VERSION: Version = (1, 7)
# A bare <model> (no <sdf version>) is read with the newest conventions.
BARE_MODEL_VERSION: Version = NEWEST_VERSION
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
IDENTITY: Transform = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))


def as_pose(transform: Transform) -> Pose:
    return Pose(transform[0], rpy_of(transform[1]))


def optional_float(element: Element, path: str, what: str) -> Optional[float]:
    return read_optional_number(child_text(element, path), f"{what} <{path}>")


def read_float(element: Element, path: str, what: str, default: float) -> float:
    return read_number(child_text(element, path), f"{what} <{path}>", default)


def read_bool(element: Element, path: str, what: str, default: bool) -> bool:
    text = child_text(element, path)
    if text is None:
        return default
    if text.lower() in ("true", "1"):
        return True
    if text.lower() in ("false", "0"):
        return False
    raise ModelError(f"{what} <{path}>: expected true or false, got {text!r}")


def read_plugin(element: Element, what: str) -> GazeboPlugin:
    return GazeboPlugin(
        required_attribute(element, "filename", f"{what} <plugin>"),
        element.get("name", ""),
        plugin_params(element),
    )


def read_version(sdf: Element) -> Version:
    text = sdf.get("version")
    try:
        major, minor = (int(part) for part in (text or "").split("."))
    except ValueError:
        raise ModelError(f"<sdf version={text!r}>: expected a version such as '1.6'") from None
    if not OLDEST_VERSION <= (major, minor) <= NEWEST_VERSION:
        raise ModelError(f"SDF version {text} is not supported (1.4 to 1.7)")
    return major, minor


def parse_inertial(element: Optional[Element], link: str, warnings: List[str]) -> Inertial:
    what = f"link '{link}' <inertial>"
    if element is None:
        warnings.append(f"link '{link}' has no <inertial>: SDF's default mass 1 kg and " f"inertia 1 kg m^2 are used")
        return Inertial(1.0, Pose(), 1.0, 0.0, 0.0, 1.0, 0.0, 1.0)
    mass = read_float(element, "mass", what, 1.0)
    values = {
        k: read_float(element, f"inertia/{k}", what, 1.0 if k in ("ixx", "iyy", "izz") else 0.0)
        for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    }
    _check_mass(mass, values, what)
    result = Inertial(mass, read_pose(element, what), **values)
    if not _is_positive_definite(result.matrix()):
        raise ModelError(f"{what}: inertia matrix is not positive definite ({values})")
    return result


def _positive(element: Element, path: str, what: str, default: float) -> float:
    value = read_float(element, path, what, default)
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


def parse_geometry(
    element: Optional[Element], what: str, static: bool, warnings: List[str]
) -> Tuple[Geometry, Transform]:
    """The shape and where it sits in the collision frame."""
    identity = IDENTITY
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


def read_placed_shape(element: Element, what: str, static: bool, warnings: List[str]) -> Tuple[Pose, Geometry]:
    """A <collision>'s or <visual>'s pose in its link and its shape."""
    geometry, offset = parse_geometry(element.find("geometry"), what, static, warnings)
    return as_pose(compose(pose_transform(read_pose(element, what)), offset)), geometry


# <surface> entries that are read (SURFACE_PATHS) or that hold only their parents' defaults.
_SURFACE_CONTAINERS = {"friction", "friction/ode", "contact", "contact/ode"}


def _surface_leaves(element: Element, prefix: str = "") -> List[str]:
    paths = []
    for child in element:
        path = f"{prefix}{child.tag}"
        paths.extend(_surface_leaves(child, path + "/") if len(child) else [path])
    return paths


def parse_surface(element: Optional[Element], what: str, warnings: Optional[List[str]] = None) -> Dict[str, Any]:
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
