"""A world's <light>s (SDF 1.4-1.7), read with SDF's defaults, and the built-in sun that stands for model://sun
when Gazebo's model database is not there."""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Iterable, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.transforms import quat_from_rpy
from turtle_sim_ode.models.nested import read_pose
from turtle_sim_ode.models.text import ModelError, child_text, read_number

Vec3 = Tuple[float, float, float]
RGBA = Tuple[float, float, float, float]
LIGHT_TYPES = ("point", "directional", "spot")


@dataclass(frozen=True)
class Light:
    """One light, with the fields of gazebo_msgs' light services. Defaults are SDF's (sdformat sdf/1.6/light.sdf):
    diffuse 1 1 1 1, specular .1 .1 .1 1, attenuation range 10, constant 1, linear 1, quadratic 0, direction
    0 0 -1, no shadows, spot inner and outer angle 0, falloff 0 (radians, full cone angles as Ogre's
    setSpotlightRange takes them). ``pose``: position and quaternion (x, y, z, w) in the world; ``direction`` is in
    the light's frame."""

    name: str
    type: str = "point"
    cast_shadows: bool = False
    diffuse: RGBA = (1.0, 1.0, 1.0, 1.0)
    specular: RGBA = (0.1, 0.1, 0.1, 1.0)
    attenuation_range: float = 10.0
    attenuation_constant: float = 1.0
    attenuation_linear: float = 1.0
    attenuation_quadratic: float = 0.0
    direction: Vec3 = (0.0, 0.0, -1.0)
    spot_inner_angle: float = 0.0
    spot_outer_angle: float = 0.0
    spot_falloff: float = 0.0
    pose: Tuple[Vec3, Tuple[float, float, float, float]] = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


# model://sun of Gazebo's model database (osrf/gazebo_models sun/model.sdf).
SUN = Light(
    name="sun",
    type="directional",
    cast_shadows=True,
    diffuse=(0.8, 0.8, 0.8, 1.0),
    specular=(0.1, 0.1, 0.1, 1.0),
    attenuation_range=1000.0,
    attenuation_constant=0.9,
    attenuation_linear=0.01,
    attenuation_quadratic=0.001,
    direction=(-0.5, 0.5, -1.0),
    pose=((0.0, 0.0, 10.0), (0.0, 0.0, 0.0, 1.0)),
)


def _numbers(element: Element, path: str, count: int, default: Tuple[float, ...], what: str) -> Tuple[float, ...]:
    text = child_text(element, path)
    if text is None:
        return default
    parts = text.split()
    if len(parts) != count:
        raise ModelError(f"{what} <{path}> needs {count} numbers, got '{text}'")
    return tuple(read_number(part, f"{what} <{path}>") for part in parts)


def parse_light(element: Element) -> Light:
    """A <light> element (ModelError naming the light and tag for a bad value)."""
    name = element.get("name", "__default__")
    what = f"<light> '{name}'"
    kind = element.get("type", "point")
    if kind not in LIGHT_TYPES:
        raise ModelError(f"{what}: type '{kind}' is not one of {', '.join(LIGHT_TYPES)}")
    defaults = Light(name)
    shadows = (child_text(element, "cast_shadows") or "false").strip().lower()
    if shadows not in ("true", "false", "1", "0"):
        raise ModelError(f"{what} <cast_shadows> must be true or false, got '{shadows}'")
    pose = read_pose(element, what)
    qw, qx, qy, qz = quat_from_rpy(*pose.rpy)
    (range_,) = _numbers(element, "attenuation/range", 1, (defaults.attenuation_range,), what)
    (constant,) = _numbers(element, "attenuation/constant", 1, (defaults.attenuation_constant,), what)
    (linear,) = _numbers(element, "attenuation/linear", 1, (defaults.attenuation_linear,), what)
    (quadratic,) = _numbers(element, "attenuation/quadratic", 1, (defaults.attenuation_quadratic,), what)
    (inner,) = _numbers(element, "spot/inner_angle", 1, (defaults.spot_inner_angle,), what)
    (outer,) = _numbers(element, "spot/outer_angle", 1, (defaults.spot_outer_angle,), what)
    (falloff,) = _numbers(element, "spot/falloff", 1, (defaults.spot_falloff,), what)
    return replace(
        defaults,
        type=kind,
        cast_shadows=shadows in ("true", "1"),
        diffuse=_numbers(element, "diffuse", 4, defaults.diffuse, what),  # type: ignore[arg-type]
        specular=_numbers(element, "specular", 4, defaults.specular, what),  # type: ignore[arg-type]
        attenuation_range=range_,
        attenuation_constant=constant,
        attenuation_linear=linear,
        attenuation_quadratic=quadratic,
        direction=_numbers(element, "direction", 3, defaults.direction, what),  # type: ignore[arg-type]
        spot_inner_angle=inner,
        spot_outer_angle=outer,
        spot_falloff=falloff,
        pose=(pose.xyz, (qx, qy, qz, qw)),
    )


def first_sun(lights: Iterable[Light]) -> Optional[Light]:
    """The first directional light with a direction (what the cameras' ray casters shade with), or None."""
    for light in lights:
        if light.type == "directional" and any(light.direction):
            return light
    return None


def sun_direction(lights: Iterable[Light]) -> Optional[Vec3]:
    """The direction of first_sun, or None."""
    sun = first_sun(lights)
    return sun.direction if sun is not None else None
