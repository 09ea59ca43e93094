"""What a physically sane value is, decided in one place for model text (URDF, SDF, plugin tags) and every world
request: finite, within bounds, not subnormal, mass properties and damping that ODE can integrate at the step.

Each check raises ``error`` (ValueError by default; callers pass ModelError or WorldError, so that the message
reaches the user as their layer reports it) with a message that names the value, what it is and the bound. The
bounds are far beyond any robot's needs and were measured against ODE 0.16 at 1 ms steps: past them a body sinks
through the ground, spins up without limit, or ODE aborts the whole process (test_sanity.py shows each).
"""
from __future__ import annotations

import math
import sys
from typing import Any, Optional, Sequence, Tuple, Type

Vec3 = Tuple[float, float, float]

# Positions and offsets within this many metres of the origin: ODE's collision grid takes coordinates below ~1e8 m.
MAX_LENGTH = 1e6
# Speeds (m/s, rad/s) and forces or torques (N, N m) a request may set.
MAX_SPEED = 1e4
MAX_FORCE = 1e6
# A body's mass (kg): 1e6 kg spheres and 1e9 kg boxes sink through the ground with default contacts; 1 mg is the
# lightest body (lighter links are fixed to a heavier one, which carries their mass).
MIN_MASS = 1e-6
MAX_MASS = 1e5
# Inertia entries (kg m^2).
MAX_INERTIA = 1e12
# A body's smallest radius of gyration, sqrt(I / m), against the distance from its centre of mass to the farthest
# point of its collisions: below about 0.05 a box landing on an edge spins up and falls through the ground (a 0.2 m
# cube with k = 1 mm does, whatever its mass). Model text gets its moments raised to the bound, with a warning.
MIN_GYRATION_RATIO = 0.1
# Joint damping is applied after each step (explicitly): stable while c * dt / I stays below 2; kept below 1.
MAX_DAMPING_STEP_RATIO = 1.0
# An effort may accelerate the lighter side of a joint by at most this (rad/s^2 or m/s^2): a velocity change of
# 1000 (rad/s or m/s) within a 1 ms step. Past it one push flips a TurtleBot into the sky.
MAX_JOINT_ACCELERATION = 1e6
# Constraint force mixing (global, a joint's, a stop's): beyond 1 a constraint holds nothing, and 1e308 aborts ODE.
MAX_CFM = 1.0
# ODE's hinge angle wraps at +-pi: a stop beyond it is never reached, or flips the joint onto the other stop.
MAX_HINGE_STOP = math.pi
# Steps of the world (s): shorter ones never get /clock to advance at any useful rate.
MIN_TIME_STEP = 1e-5
MAX_TIME_STEP = 0.1
# Steps per wall second a world may be paced to (0 = as fast as possible).
MIN_UPDATE_RATE = 1e-3
MAX_UPDATE_RATE = 1e7
# Lengths of a drive (wheel separation, wheel diameter, m).
MAX_DRIVE_LENGTH = 100.0


def is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def number(
    value: Any,
    what: str,
    low: float = -math.inf,
    high: float = math.inf,
    error: Type[Exception] = ValueError,
    low_open: bool = False,
) -> float:
    """``value`` as a float: a finite number, not subnormal, in [low, high] ((low, high] with ``low_open``)."""
    if not is_number(value) or not math.isfinite(value):
        raise error(f"{what} must be a finite number, got {value!r}")
    value = float(value)
    if value != 0 and abs(value) < sys.float_info.min:
        raise error(f"{what} must be 0 or at least {sys.float_info.min:g} in magnitude, got {value!r}")
    if value < low or (low_open and value == low) or value > high:
        left = "(" if low_open else "["
        raise error(f"{what} must be in {left}{low:g}, {high:g}], got {value!r}")
    return value


def unit_vector(values: Sequence[float], what: str, error: Type[Exception] = ValueError) -> Vec3:
    """Three finite numbers scaled to length 1 (scaled down first, so 1e308 does not overflow); not all zero."""
    x, y, z = (number(v, what, error=error) for v in values)
    scale = max(abs(x), abs(y), abs(z))
    if scale == 0:
        raise error(f"{what} must not be zero")
    x, y, z = x / scale, y / scale, z / scale
    norm = math.sqrt(x * x + y * y + z * z)
    return (x / norm, y / norm, z / norm)


def min_moment(mass: float, extent: float) -> float:
    """The smallest principal moment of inertia a body of ``mass`` reaching ``extent`` m from its centre of mass
    may have (MIN_GYRATION_RATIO)."""
    return mass * (MIN_GYRATION_RATIO * extent) ** 2


def principal_moments(inertia: Sequence[Sequence[float]]) -> Vec3:
    """Eigenvalues of a symmetric 3x3 matrix (closed form), ascending."""
    a, b, c = inertia[0][0], inertia[1][1], inertia[2][2]
    d, e, f = inertia[0][1], inertia[1][2], inertia[0][2]
    p1 = d * d + e * e + f * f
    if p1 == 0:
        low, mid, high = sorted((a, b, c))
        return (low, mid, high)
    q = (a + b + c) / 3
    p2 = (a - q) ** 2 + (b - q) ** 2 + (c - q) ** 2 + 2 * p1
    p = math.sqrt(p2 / 6)
    det = ((a - q) * ((b - q) * (c - q) - e * e) - d * (d * (c - q) - e * f) + f * (d * e - (b - q) * f)) / p**3
    phi = math.acos(max(-1.0, min(1.0, det / 2))) / 3
    high = q + 2 * p * math.cos(phi)
    low = q + 2 * p * math.cos(phi + 2 * math.pi / 3)
    return (low, 3 * q - high - low, high)


def stable_damping(coefficient: float, inertia: float, time_step: float) -> float:
    """The largest damping coefficient at most ``coefficient`` that stays stable on ``inertia`` (kg m^2 or kg)."""
    return min(coefficient, MAX_DAMPING_STEP_RATIO * inertia / time_step)


def effort_limit(inertia: float) -> float:
    """The largest effort (N m or N) a joint whose lighter side has ``inertia`` may take (MAX_JOINT_ACCELERATION)."""
    return min(MAX_FORCE, MAX_JOINT_ACCELERATION * inertia)


def hinge_stop(value: float, what: str, error: Type[Exception] = ValueError) -> Optional[float]:
    """A hinge stop within +-pi, or None for an infinite one (no stop)."""
    if is_number(value) and math.isinf(value):
        return None
    value = number(value, what, error=error)
    if abs(value) > MAX_HINGE_STOP:
        raise error(
            f"{what} must be within ±π ({MAX_HINGE_STOP:.4f} rad), got {value!r}: ODE's hinge angle wraps at ±π "
            f"(use ±inf for no stop, or a continuous joint)"
        )
    return value


def update_rate(value: Any, what: str = "max_update_rate", error: Type[Exception] = ValueError) -> float:
    """Steps per wall second: 0 (as fast as possible) or within [MIN_UPDATE_RATE, MAX_UPDATE_RATE]."""
    rate = number(value, what, 0.0, MAX_UPDATE_RATE, error)
    if 0 < rate < MIN_UPDATE_RATE:
        raise error(f"{what} must be 0 (as fast as possible) or at least {MIN_UPDATE_RATE:g}, got {value!r}")
    return rate


def drive_length(value: Any, what: str, error: Type[Exception] = ValueError) -> float:
    return number(value, f"{what} (m)", 0.0, MAX_DRIVE_LENGTH, error, low_open=True)
