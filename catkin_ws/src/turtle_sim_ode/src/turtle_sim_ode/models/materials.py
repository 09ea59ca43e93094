"""Colours of visuals for the cameras: URDF ``<visual><material>`` (inline ``<color rgba>`` or a named robot-level
material), Gazebo's material scripts by name (``Gazebo/Red`` ...) from ``<gazebo reference><material>`` or SDF
``<material><script><name>``, and SDF ``<material>`` diffuse / ambient colours."""
from __future__ import annotations

from typing import Dict, Optional, Tuple
from xml.etree.ElementTree import Element

RGB = Tuple[float, float, float]

# Gazebo's common material scripts (gazebo.material), by their diffuse colour.
GAZEBO_MATERIALS: Dict[str, RGB] = {
    "Gazebo/White": (1.0, 1.0, 1.0),
    "Gazebo/FlatBlack": (0.1, 0.1, 0.1),
    "Gazebo/Black": (0.0, 0.0, 0.0),
    "Gazebo/Grey": (0.7, 0.7, 0.7),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175),
    "Gazebo/Gray": (0.7, 0.7, 0.7),
    "Gazebo/Red": (1.0, 0.0, 0.0),
    "Gazebo/RedBright": (0.87, 0.26, 0.07),
    "Gazebo/Green": (0.0, 1.0, 0.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0),
    "Gazebo/SkyBlue": (0.53, 0.81, 0.92),
    "Gazebo/Yellow": (1.0, 1.0, 0.0),
    "Gazebo/ZincYellow": (0.9725, 0.9529, 0.2078),
    "Gazebo/DarkYellow": (0.7, 0.7, 0.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468),
    "Gazebo/Indigo": (0.33, 0.0, 0.5),
    "Gazebo/Wood": (1.0, 0.83, 0.61),
    "Gazebo/WoodFloor": (0.6, 0.45, 0.3),
    "Gazebo/Bricks": (0.6, 0.3, 0.25),
    "Gazebo/GreyTransparent": (0.5, 0.5, 0.5),
    "Gazebo/BlueTransparent": (0.0, 0.0, 1.0),
    "Gazebo/GreenTransparent": (0.0, 1.0, 0.0),
    "Gazebo/RedTransparent": (1.0, 0.0, 0.0),
}
# Gazebo's transparent material scripts draw at this opacity (their diffuse alpha in gazebo.material).
TRANSPARENT_SCRIPT_ALPHA = 0.5
# What a link shows when nothing names its colour (Gazebo's default material is a light grey).
DEFAULT_COLOR: RGB = (0.7, 0.7, 0.7)


def rgb_of(text: Optional[str]) -> Optional[RGB]:
    """The first three of 3 or 4 numbers in 0..1 (clamped), or None for text that is not."""
    if text is None:
        return None
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        return None
    if len(values) not in (3, 4):
        return None
    return tuple(min(1.0, max(0.0, v)) for v in values[:3])  # type: ignore[return-value]


def gazebo_material(name: Optional[str]) -> Optional[RGB]:
    """The colour of a Gazebo material script name, None if it is not one of the common ones."""
    return None if name is None else GAZEBO_MATERIALS.get(name.strip())


def urdf_named_materials(robot: Element) -> Dict[str, RGB]:
    """The robot-level ``<material name><color rgba>`` definitions of a URDF."""
    found: Dict[str, RGB] = {}
    for material in robot.findall("material"):
        color = rgb_of(material.find("color").get("rgba") if material.find("color") is not None else None)
        if material.get("name") and color is not None:
            found[material.get("name", "")] = color
    return found


def urdf_visual_color(visual: Element, named: Dict[str, RGB]) -> Optional[RGB]:
    """A URDF ``<visual>``'s ``<material>`` colour: inline rgba, else the named robot-level material's."""
    material = visual.find("material")
    if material is None:
        return None
    color_element = material.find("color")
    color = rgb_of(color_element.get("rgba")) if color_element is not None else None
    return color if color is not None else named.get(material.get("name", ""))


def sdf_visual_color(visual: Element) -> Optional[RGB]:
    """An SDF ``<visual>``'s ``<material>`` colour: diffuse, ambient, else a Gazebo script name."""
    material = visual.find("material")
    if material is None:
        return None
    for tag in ("diffuse", "ambient"):
        color = rgb_of(material.findtext(tag))
        if color is not None:
            return color
    return gazebo_material(material.findtext("script/name"))


def _alpha_of(text: Optional[str]) -> Optional[float]:
    """The fourth of 4 numbers in 0..1 (clamped), or None."""
    try:
        values = [float(v) for v in (text or "").split()]
    except ValueError:
        return None
    return min(1.0, max(0.0, values[3])) if len(values) == 4 else None


def urdf_visual_alpha(visual: Element, named_alphas: Dict[str, float]) -> float:
    """The opacity of a URDF ``<visual>``: its material's rgba alpha (inline, else the named material's), 1 without."""
    material = visual.find("material")
    if material is None:
        return 1.0
    color_element = material.find("color")
    alpha = _alpha_of(color_element.get("rgba")) if color_element is not None else None
    return alpha if alpha is not None else named_alphas.get(material.get("name", ""), 1.0)


def urdf_named_alphas(robot: Element) -> Dict[str, float]:
    """The rgba alphas of a URDF's robot-level named materials."""
    found: Dict[str, float] = {}
    for material in robot.findall("material"):
        color = material.find("color")
        alpha = _alpha_of(color.get("rgba")) if color is not None else None
        if material.get("name") and alpha is not None:
            found[material.get("name", "")] = alpha
    return found


def sdf_visual_alpha(visual: Element) -> float:
    """The opacity Gazebo draws an SDF ``<visual>`` with: its diffuse alpha (a transparent script's), times
    1 - ``<transparency>``."""
    material = visual.find("material")
    alpha = 1.0
    if material is not None:
        diffuse = _alpha_of(material.findtext("diffuse"))
        script = (material.findtext("script/name") or "").strip()
        if diffuse is not None:
            alpha = diffuse
        elif script in GAZEBO_MATERIALS and script.endswith("Transparent"):
            alpha = TRANSPARENT_SCRIPT_ALPHA
    try:
        transparency = min(1.0, max(0.0, float(visual.findtext("transparency") or 0.0)))
    except ValueError:
        transparency = 0.0
    return alpha * (1.0 - transparency)
