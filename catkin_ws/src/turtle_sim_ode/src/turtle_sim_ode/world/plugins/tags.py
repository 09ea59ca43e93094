"""A model plugin's tags (``<plugin>`` children, as text) read with a message naming the plugin and the tag."""
from __future__ import annotations

import math
from typing import Tuple

from turtle_sim_ode.models.text import ModelError, read_number
from turtle_sim_ode.models.description import GazeboPlugin


def number(plugin: GazeboPlugin, tag: str, default: float, minimum: float = 0.0) -> float:
    return read_number(plugin.params.get(tag), f"{plugin.filename} <{tag}>", default, minimum)


def flag(plugin: GazeboPlugin, tag: str, default: bool) -> bool:
    text = plugin.params.get(tag)
    if text is None:
        return default
    value = text.strip().lower()
    if value not in ("true", "false", "1", "0"):
        raise ModelError(f"{plugin.filename} <{tag}> must be true or false, got '{text}'")
    return value in ("true", "1")


def text(plugin: GazeboPlugin, tag: str, default: str) -> str:
    given = plugin.params.get(tag)
    return given.strip() if given is not None and given.strip() else default


def triple(plugin: GazeboPlugin, tag: str) -> Tuple[float, float, float]:
    given = plugin.params.get(tag, "0 0 0")
    try:
        values = tuple(float(v) for v in given.split())
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise ModelError(f"{plugin.filename} <{tag}> must be 3 numbers, got '{given}'")
    return values  # type: ignore[return-value]
