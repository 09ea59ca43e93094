"""gazebo_ros_bumper (``libgazebo_ros_bumper.so``) in a ``contact`` sensor: the contacts of the link's collisions."""
from __future__ import annotations

from dataclasses import dataclass
from typing import List, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import child_text, plugin_params, robot_namespace_tag
from turtle_sim_ode.sensors.sensor_element import rate_at, sensor_what

BUMPER_PLUGIN = "libgazebo_ros_bumper.so"
SENSOR_PLUGINS = {BUMPER_PLUGIN: ("contact",)}


@dataclass(frozen=True)
class ContactConfig:
    """A ``<sensor type="contact">`` with libgazebo_ros_bumper.so: contacts of ``link``'s collisions, published
    as gazebo_msgs/ContactsState on ``topic`` (frame ``frame``) at ``update_rate`` Hz (0 = every step)."""

    link: str
    name: str
    collisions: Tuple[str, ...]
    topic: str = "bumper_states"
    frame: str = "world"
    update_rate: float = 0.0
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> ContactConfig:
    name, what = sensor_what(sensor, "bumper")
    return ContactConfig(
        link=link,
        name=name,
        collisions=tuple(c.text.strip() for c in sensor.findall("contact/collision") if c.text and c.text.strip()),
        topic=child_text(plugin, "bumperTopicName") or "bumper_states",
        frame=child_text(plugin, "frameName") or "world",
        update_rate=rate_at(sensor, ("update_rate",), 0.0, what),
        robot_namespace=robot_namespace_tag(plugin_params(plugin)),
    )
