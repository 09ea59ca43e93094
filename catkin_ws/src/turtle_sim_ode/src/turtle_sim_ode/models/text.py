"""Reading model text (URDF, SDF, Gazebo plugin and sensor tags): the error it raises and the one number reader
that every parser, sensor and plugin reader uses, so that a bad number gets the same clear message everywhere."""
from __future__ import annotations

import math
from typing import Dict, Mapping, Optional
from xml.etree.ElementTree import Element, ParseError

import defusedxml
import defusedxml.ElementTree as SafeET

from turtle_sim_ode.physics import sanity

# Far beyond any robot description; a larger text is refused before it is parsed.
MAX_MODEL_CHARS = 10_000_000


class ModelError(ValueError):
    """The model text is malformed or describes a model that cannot be simulated."""


def parse_xml(text: str, kind: str) -> Element:
    """The root element of model text of ``kind`` ('URDF', 'SDF', ...), parsed once with XML entities refused
    (defusedxml); ModelError with the parser's line and column otherwise."""
    if len(text) > MAX_MODEL_CHARS:
        raise ModelError(f"{kind} is {len(text)} characters, more than the {MAX_MODEL_CHARS} allowed")
    try:
        return SafeET.fromstring(text)
    except ParseError as error:
        line, column = error.position
        reason = str(error).split(":")[0]  # expat appends the position we report ourselves
        raise ModelError(f"{kind} is not well-formed XML at line {line}, column {column}: {reason}") from None
    except defusedxml.DefusedXmlException as error:
        raise ModelError(f"{kind} rejected by the XML guard: {error}") from None


def required_attribute(element: Element, attribute: str, what: str) -> str:
    value = element.get(attribute)
    if value is None:
        raise ModelError(f"{what}: missing attribute '{attribute}'")
    if not value.strip():
        raise ModelError(f"{what}: attribute '{attribute}' is empty")
    return value


def child_text(element: Optional[Element], path: str) -> Optional[str]:
    """The stripped text of ``element``'s child at ``path``; None where there is no element, child or text."""
    found = None if element is None else element.find(path)
    if found is None or found.text is None or not found.text.strip():
        return None
    return found.text.strip()


def plugin_params(plugin: Element) -> Dict[str, str]:
    """A ``<plugin>``'s children as tag -> stripped text; of a tag given twice, the first, as sdformat's GetElement
    (and so a gazebo_ros plugin) reads it (turtlebot3_waffle's camera has two <hackBaseline>s: Gazebo takes 0.07)."""
    params: Dict[str, str] = {}
    for child in plugin:
        params.setdefault(child.tag, (child.text or "").strip())
    return params


def robot_namespace_tag(params: Mapping[str, str]) -> Optional[str]:
    """A plugin's <robotNamespace> (from plugin_params): its text wherever the element exists, "" (the root namespace)
    included, as every gazebo_ros plugin's Load reads it when sdf HasElement("robotNamespace"); None without the
    element, so the spawn's robot_namespace applies (GazeboRosApiPlugin::walkChildAddRobotNamespace adds it only
    to plugins without one)."""
    given = params.get("robotNamespace")
    return None if given is None else given.strip()


def read_optional_number(text: Optional[str], what: str, minimum: float = -math.inf) -> Optional[float]:
    """None where ``text`` is absent or blank, else a finite number >= ``minimum``; ModelError naming ``what``
    and the text otherwise."""
    if text is None or not text.strip():
        return None
    text = text.strip()
    try:
        value = float(text)
    except ValueError:
        raise ModelError(f"{what} must be a number, got '{text}'") from None
    if not math.isfinite(value) or value < minimum:
        bound = f" >= {minimum:g}" if minimum > -math.inf else ""
        raise ModelError(f"{what} must be a finite number{bound}, got '{text}'")
    return sanity.number(value, what, error=ModelError)


def read_number(text: Optional[str], what: str, default: Optional[float] = None, minimum: float = -math.inf) -> float:
    """As read_optional_number, with ``default`` where the text is absent; without a default it is required."""
    value = read_optional_number(text, what, minimum)
    if value is not None:
        return value
    if default is None:
        raise ModelError(f"{what} must be a number, got nothing")
    return default
