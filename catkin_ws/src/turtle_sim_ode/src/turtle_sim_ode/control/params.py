"""A controller's parameters, read as the real controllers read them from the parameter server.

The ROS side hands over the controller's namespace as the dict rospy.get_param returns; every lookup that fails
raises ControllerError with a message naming the parameter and the namespace, as the real init() logs it.
"""
from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, Optional


class ControllerError(Exception):
    """A controller (or the manager) refuses: the message says why, fit for the log."""


class Params:
    """The parameters below ``namespace`` (a nested dict, as the parameter server's tree)."""

    def __init__(self, tree: Mapping[str, Any], namespace: str) -> None:
        self.tree = tree if isinstance(tree, Mapping) else {}
        self.namespace = namespace.rstrip("/")

    def child(self, name: str) -> "Params":
        value = self.raw(name)
        return Params(value if isinstance(value, Mapping) else {}, f"{self.namespace}/{name}")

    def has(self, name: str) -> bool:
        return self.raw(name) is not None

    def raw(self, name: str) -> Any:
        node: Any = self.tree
        for part in name.strip("/").split("/"):
            if not isinstance(node, Mapping) or part not in node:
                return None
            node = node[part]
        return node

    def _fail(self, name: str, what: str) -> ControllerError:
        return ControllerError(f"{what} '{name}' (namespace: {self.namespace})")

    def string(self, name: str, default: Optional[str] = None) -> str:
        value = self.raw(name)
        if value is None:
            if default is None:
                raise self._fail(name, "No parameter")
            return default
        if not isinstance(value, str):
            raise self._fail(name, f"Parameter is not a string ({value!r}):")
        return value

    def number(self, name: str, default: Optional[float] = None, minimum: float = -math.inf) -> float:
        value = self.raw(name)
        if value is None:
            if default is None:
                raise self._fail(name, "No parameter")
            return default
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise self._fail(name, f"Parameter is not a finite number ({value!r}):")
        if value < minimum:
            raise self._fail(name, f"Parameter must be at least {minimum:g}, got {value!r}:")
        return float(value)

    def flag(self, name: str, default: bool) -> bool:
        value = self.raw(name)
        if value is None:
            return default
        if not isinstance(value, bool):
            raise self._fail(name, f"Parameter is not a bool ({value!r}):")
        return value

    def strings(self, name: str, allow_single: bool = False) -> List[str]:
        """A non-empty list of strings (or one string where the real controller takes one)."""
        value = self.raw(name)
        if value is None:
            raise self._fail(name, "No parameter")
        if allow_single and isinstance(value, str):
            return [value]
        if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
            raise self._fail(name, f"Parameter is not a list of strings ({value!r}):")
        if not value:
            raise self._fail(name, "Parameter is an empty list:")
        return list(value)

    def numbers(self, name: str, length: int, default: float = 0.0) -> List[float]:
        value = self.raw(name)
        if value is None:
            return [default] * length
        ok = isinstance(value, list) and len(value) == length
        ok = ok and all(not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v) for v in value)
        if not ok:
            raise self._fail(name, f"Parameter is not a list of {length} numbers ({value!r}):")
        return [float(v) for v in value]


def as_tree(value: Any) -> Dict[str, Any]:
    return dict(value) if isinstance(value, Mapping) else {}
