"""Gazebo-style contact surfaces: one geom's surface and how two of them combine into a pair's ODE contact."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Optional, Tuple

from turtle_sim_ode.physics import ode_constants as oc

# The softest contact stiffness (N/m): softer holds no mass up, and its inverse overflows the contact arithmetic.
MIN_KP = 1.0

# Gazebo's ODE contact: axis-dependent friction pyramid scaled by the normal force,
# spring-damper softness from kp/kd.
_CONTACT_MODE = oc.CONTACT_MU2 | oc.CONTACT_SOFT_ERP | oc.CONTACT_SOFT_CFM | oc.CONTACT_APPROX1

# How a geom pair's contacts are made, as set on every ode.Contact of the pair (the kernel's TsoPairSurface):
# (mode, fdir_side, adjust_depth, mu, mu2, soft_erp, soft_cfm, slip1, slip2, min_depth, depth_cap, surface_layer,
#  fdir1 x, y, z). ``fdir_side`` names the geom whose fdir1 (in its own frame) is the first friction direction
# (0 none, 1 the pair's first geom, 2 its second); with ``adjust_depth`` each contact's depth is made
# min(depth - min_depth, depth_cap) + surface_layer, so that ODE (which subtracts the world's surface layer and caps
# the push-out at the world's max correcting velocity) acts with the pair's own min_depth and max_vel.
ContactSurface = Tuple[
    int, int, int, float, float, float, float, float, float, float, float, float, float, float, float
]
# How a geom pair's contacts are made: surface, and whether a line contact is merged.
PairContact = Tuple[ContactSurface, bool]


def is_finite(value: float) -> bool:
    return isinstance(value, (int, float)) and math.isfinite(value)


@dataclass(frozen=True)
class SurfaceParams:
    """Contact surface of one geom, as Gazebo's ODE surface of a collision: friction (<mu1> <mu2> <fdir1> <slip1>
    <slip2>) and contact (<kp> <kd> <minDepth> <maxVel>). ``min_depth`` and ``max_vel`` None: the geom leaves the
    world's contact_surface_layer and contact_max_correcting_vel in force (Gazebo sets them on the link's body;
    body-less geoms take no part, as in Gazebo where static links have no body)."""

    mu: float = 1.0
    mu2: float = 1.0
    kp: float = 1e12
    kd: float = 1.0
    min_depth: Optional[float] = None
    max_vel: Optional[float] = None
    fdir1: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    slip1: float = 0.0
    slip2: float = 0.0

    def validate(self, name: str = "surface") -> None:
        """Raise ValueError naming the first bad field."""
        for attr in ("mu", "mu2", "kd", "slip1", "slip2", "min_depth", "max_vel"):
            value = getattr(self, attr)
            if value is None and attr in ("min_depth", "max_vel"):
                continue
            if not is_finite(value) or value < 0:
                raise ValueError(f"{name}.{attr} must be finite and >= 0, got {value!r}")
        if not is_finite(self.kp) or self.kp < MIN_KP:
            raise ValueError(f"{name}.kp must be finite and >= {MIN_KP:g} N/m, got {self.kp!r}")
        if len(self.fdir1) != 3 or not all(is_finite(v) for v in self.fdir1):
            raise ValueError(f"{name}.fdir1 must be 3 finite numbers, got {self.fdir1!r}")

    def without_body(self) -> "SurfaceParams":
        """This surface on a body-less geom: no min_depth or max_vel (they belong to a body in Gazebo)."""
        if self.min_depth is None and self.max_vel is None:
            return self
        return replace(self, min_depth=None, max_vel=None)


def combine_surfaces(
    a: SurfaceParams,
    b: SurfaceParams,
    time_step: float,
    surface_layer: float = 0.0,
    max_correcting_vel: float = math.inf,
) -> ContactSurface:
    """Gazebo's rule (ODEPhysics::Collide and its ODE's contact joint): min friction and slip, springs in series,
    dampers in parallel; fdir1 of the geom with the smaller mu1 that has one; min_depth and max_vel the smaller of
    the geoms that set them (max_vel at most the world's), else the world's ``surface_layer`` and
    ``max_correcting_vel``."""
    kp = 1.0 / (1.0 / a.kp + 1.0 / b.kp)
    kd = a.kd + b.kd
    denominator = time_step * kp + kd
    erp, cfm = time_step * kp / denominator, 1.0 / denominator
    slip1, slip2 = min(a.slip1, b.slip1), min(a.slip2, b.slip2)
    mode = _CONTACT_MODE | (oc.CONTACT_SLIP1 if slip1 > 0 else 0) | (oc.CONTACT_SLIP2 if slip2 > 0 else 0)
    zero = (0.0, 0.0, 0.0)
    side, fdir1 = 0, zero
    if a.fdir1 != zero:
        side, fdir1 = 1, a.fdir1
    if b.fdir1 != zero and (a.fdir1 == zero or a.mu > b.mu):
        side, fdir1 = 2, b.fdir1
    depths = [s.min_depth for s in (a, b) if s.min_depth is not None]
    speeds = [s.max_vel for s in (a, b) if s.max_vel is not None]
    min_depth = min(depths) if depths else surface_layer
    max_vel = min(min(speeds), max_correcting_vel) if speeds else max_correcting_vel
    # ODE pushes out at (erp / time_step) * depth, capped at its world-wide max correcting velocity: a pair's lower
    # cap is a cap on the depth it sees.
    depth_cap = max_vel * time_step / erp if max_vel < max_correcting_vel else math.inf
    adjust = int(bool(depths or speeds))
    return (
        mode,
        side,
        adjust,
        min(a.mu, b.mu),
        min(a.mu2, b.mu2),
        erp,
        cfm,
        slip1,
        slip2,
        min_depth,
        depth_cap,
        surface_layer,
        float(fdir1[0]),
        float(fdir1[1]),
        float(fdir1[2]),
    )


def ground_surface(surface: SurfaceParams) -> SurfaceParams:
    """The ground plane's surface: no body (so no min_depth, max_vel) and no frame to turn an fdir1 by."""
    return replace(surface.without_body(), fdir1=(0.0, 0.0, 0.0))
