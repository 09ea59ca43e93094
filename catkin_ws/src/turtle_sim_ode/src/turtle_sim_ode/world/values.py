"""Checks of the values a world request carries: each returns the value as a plain float or tuple, or raises
WorldError with a message fit for a service's status_message."""
from __future__ import annotations

import math
from typing import Any, Sequence, Tuple

from turtle_sim_ode.models.transforms import Quat, Vec3
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.sanity import MAX_FORCE, MAX_SPEED  # noqa: F401 (the request limits, for callers)


class WorldError(ValueError):
    """A world request names an unknown entity or carries a bad value; nothing was changed."""


def finite(value: object, what: str, limit: float = math.inf) -> float:
    """``value`` as a float; WorldError unless it is a finite number of magnitude at most ``limit``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise WorldError(f"{what} must be a finite number, got {value!r}")
    if abs(value) > limit:
        raise WorldError(f"{what} must be at most {limit:g} in magnitude, got {value!r}")
    return sanity.number(value, what, error=WorldError)


def vector(values: Any, size: int, what: str, limit: float = math.inf) -> Tuple[float, ...]:
    """``size`` finite numbers, each of magnitude at most ``limit``, as a tuple of floats, or WorldError."""
    try:
        ok = len(values) == size and all(
            not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v) for v in values
        )
    except TypeError:
        ok = False
    if not ok:
        raise WorldError(f"{what} must be {size} finite numbers, got {values!r}")
    if any(abs(v) > limit for v in values):
        raise WorldError(f"{what} must be at most {limit:g} in magnitude on each axis, got {tuple(values)!r}")
    return tuple(sanity.number(v, what, error=WorldError) for v in values)


def vec3(values: Any, what: str, limit: float = math.inf) -> Vec3:
    """Three finite numbers of magnitude at most ``limit``, or WorldError."""
    x, y, z = vector(values, 3, what, limit)
    return (x, y, z)


def orientation(quaternion: Sequence[float], what: str) -> Quat:
    """Unit (w, x, y, z) from a ROS (x, y, z, w) quaternion; all zeros mean no rotation. Scaled before
    squaring, so that huge components do not overflow to a zero quaternion."""
    x, y, z, w = vector(quaternion, 4, what)
    scale = max(abs(x), abs(y), abs(z), abs(w))
    if scale == 0:
        return (1.0, 0.0, 0.0, 0.0)
    x, y, z, w = x / scale, y / scale, z / scale, w / scale
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    if norm * scale < 1e-10:
        return (1.0, 0.0, 0.0, 0.0)
    return (w / norm, x / norm, y / norm, z / norm)


def update_rate(value: object, what: str) -> float:
    """A max_update_rate: finite and >= 0 (0 = as fast as possible)."""
    rate = finite(value, what)
    if rate < 0:
        raise WorldError(f"{what} must be >= 0, got {rate}")
    return sanity.update_rate(rate, what, WorldError)


def integer(value: object, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise WorldError(f"{what} must be an integer, got {value!r}")
    return value
