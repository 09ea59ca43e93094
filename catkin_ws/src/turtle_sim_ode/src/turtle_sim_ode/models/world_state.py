"""A world file's <state> block, as Gazebo saves it (World::Save: sim time, and each model's world pose with its
links' world poses and velocities), read for the simulation to apply as gazebo-classic's World::Load does: the
first <state> only, through World::SetState (sim time, then Model::SetState for each model it names)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, child_text, read_number

Six = Tuple[float, float, float, float, float, float]
ZERO: Six = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@dataclass
class LinkState:
    """A link's world pose (x y z roll pitch yaw) and velocity (linear, then angular as Gazebo writes it: the
    three numbers Link::SetState hands to SetAngularVel)."""

    pose: Six = ZERO
    velocity: Six = ZERO


@dataclass
class ModelState:
    pose: Six = ZERO
    links: Dict[str, LinkState] = field(default_factory=dict)


@dataclass
class WorldState:
    sim_time: float = 0.0
    models: Dict[str, ModelState] = field(default_factory=dict)
    lights: Dict[str, Six] = field(default_factory=dict)  # world poses (LightState)
    warnings: List[str] = field(default_factory=list)


def _six(element: Element, tag: str, what: str) -> Six:
    text = child_text(element, tag)
    if text is None:
        return ZERO
    parts = text.split()
    if len(parts) != 6:
        raise ModelError(f"{what} <{tag}> needs 6 numbers, got '{text}'")
    a, b, c, d, e, f = (read_number(part, f"{what} <{tag}>") for part in parts)
    return (a, b, c, d, e, f)


def _time(text: Optional[str], what: str) -> float:
    """SDF time: "seconds nanoseconds" (as Gazebo writes it) or seconds."""
    if text is None:
        return 0.0
    parts = text.split()
    if len(parts) == 2:
        return read_number(parts[0], what, minimum=0.0) + read_number(parts[1], what, minimum=0.0) * 1e-9
    if len(parts) == 1:
        return read_number(parts[0], what, minimum=0.0)
    raise ModelError(f"{what} must be 'seconds nanoseconds', got '{text}'")


def _link_states(model: Element, what: str, scope: str, into: ModelState, warnings: List[str]) -> None:
    """The link states of ``model`` and of the models nested in it (Model::SetState sets each nested model's state
    in turn), under the scoped names the flattened model's links have (models.nested): ``inner::link``."""
    for link in model.findall("link"):
        link_what = f"{what} <link name='{link.get('name', '')}'>"
        into.links[scope + link.get("name", "")] = LinkState(
            _six(link, "pose", link_what), _six(link, "velocity", link_what)
        )
    for nested in model.findall("model"):
        name = nested.get("name", "")
        nested_what = f"{what} <model name='{name}'>"
        if nested.find("link") is None and nested.find("pose") is not None:
            warnings.append(f"{nested_what}: a nested model's pose without its links' states is not applied")
        _link_states(nested, nested_what, f"{scope}{name}::", into, warnings)


def parse_world_state(world: Element) -> Optional[WorldState]:
    """The first <state> of a <world>, or None; nested models' link states under their scoped names. Accelerations
    and wrenches are not state here (they are recomputed every step)."""
    element = world.find("state")
    if element is None:
        return None
    state = WorldState(sim_time=_time(child_text(element, "sim_time"), "<state> <sim_time>"))
    if len(world.findall("state")) > 1:
        state.warnings.append("only the first <state> is applied, as Gazebo does")
    for model in element.findall("model"):
        name = model.get("name", "")
        what = f"<state> <model name='{name}'>"
        model_state = ModelState(pose=_six(model, "pose", what))
        _link_states(model, what, "", model_state, state.warnings)
        state.models[name] = model_state
    for light in element.findall("light"):
        state.lights[light.get("name", "")] = _six(light, "pose", f"<state> <light name='{light.get('name', '')}'>")
    return state
