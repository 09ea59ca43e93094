"""The laser scanner: batched ODE rays against every geom but the sensor's own model.

Ranges follow REP 117: a beam that hits nothing within range_max reads +inf, one that hits
something closer than range_min reads -inf.
"""
from __future__ import annotations

import math
import random
from typing import List, Optional, Sequence, Set

import ode

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Transform, compose, quat_from_rpy, quat_matrix
from turtle_sim_ode.physics.trimesh import collide as mesh_aware_collide
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.plugins.laser import LaserConfig
from turtle_sim_ode.sensors.rays import world_geoms

# Below this tilt (sine, ~0.6 deg) a scan is culled by the AABB footprint, above by bounding spheres.
_LEVEL = 0.01


class LaserScanner:
    """A planar laser on a model's link: ``scan()`` casts one ODE ray per sample.

    The ray geoms are created once and belong to no space, so physics steps never see them.
    Each scan tests a geom only with the beams that can reach its bounding sphere, and the
    ground plane only with beams that point down to it within range. The model's own geoms
    are never seen; every other geom (static, other models) is.
    """

    def __init__(
        self,
        physics: PhysicsWorld,
        model: BuiltModel,
        link: str,
        config: LaserConfig,
        rng: Optional[random.Random] = None,
    ) -> None:
        config.validate()
        model.link_transform(link)  # KeyError now for a missing link
        self.physics = physics
        self.model = model
        self.link = link
        self.config = config
        self.rng = rng if rng is not None else random.Random()
        self._mount: Transform = (tuple(config.pose[:3]), quat_from_rpy(*config.pose[3:]))  # type: ignore[assignment]
        increment = config.angle_increment
        self.angles = [config.min_angle + i * increment for i in range(config.samples)]
        self._cos = [math.cos(a) for a in self.angles]
        self._sin = [math.sin(a) for a in self.angles]
        self._rays = [ode.GeomRay(None, config.range_max) for _ in self.angles]

    @property
    def frame(self) -> str:
        return self.config.frame or self.link

    def _candidates(self, bearing: float, half_width: float) -> Sequence[int]:
        """Indices of beams whose angle lies within half_width of bearing (mod 2 pi)."""
        n = len(self.angles)
        increment = self.config.angle_increment
        first = self.config.min_angle
        if increment <= 0:
            delta = (first - bearing + math.pi) % math.tau - math.pi
            return [0] if abs(delta) <= half_width else []
        found: Set[int] = set()
        for shift in (-math.tau, 0.0, math.tau):
            low = max(0, math.ceil((bearing - half_width + shift - first) / increment))
            high = min(n - 1, math.floor((bearing + half_width + shift - first) / increment))
            if low <= high:
                found.update(range(low, high + 1))
        return sorted(found)

    def scan(self) -> List[float]:
        """Ranges (m) of every beam, REP 117: +inf past range_max or no hit, -inf below range_min."""
        config = self.config
        n = len(self._rays)
        origin, rotation = compose(self.model.link_transform(self.link), self._mount)
        (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = quat_matrix(rotation)
        ox, oy, oz = origin
        cosines, sines, rays = self._cos, self._sin, self._rays
        distances = [math.inf] * n
        placed = [False] * n
        cast_beams: List[int] = []

        collide = mesh_aware_collide

        def cast(beams: Sequence[int], geom: ode.GeomObject) -> None:
            for i in beams:
                ray = rays[i]
                if not placed[i]:
                    c, s = cosines[i], sines[i]
                    ray.set(origin, (c * r00 + s * r01, c * r10 + s * r11, c * r20 + s * r21))
                    placed[i] = True
                    cast_beams.append(i)
                for contact in collide(ray, geom):
                    depth = contact.getContactGeomParams()[2]
                    if depth < distances[i]:
                        distances[i] = depth

        range_max = config.range_max
        all_beams = range(n)
        tilt = math.hypot(r20, r21)  # sine of the scan plane's tilt
        level = tilt < _LEVEL
        rise = range_max * tilt + 1e-6  # how far the scan plane leaves z = oz within range
        yaw = math.atan2(r10, r00)

        def in_reach(space: ode.SpaceBase) -> bool:
            """Whether a beam may reach a geom of ``space``, whose AABB holds all of theirs."""
            x0, x1, y0, y1, z0, z1 = space.getAABB()
            if level:  # the geoms' own tests below, which no geom passes if the space fails them
                dx = max(x0 - ox, 0.0, ox - x1)
                dy = max(y0 - oy, 0.0, oy - y1)
                return z0 - rise <= oz <= z1 + rise and dx * dx + dy * dy <= range_max * range_max
            cx, cy, cz = (x0 + x1) / 2 - ox, (y0 + y1) / 2 - oy, (z0 + z1) / 2 - oz
            pz = r02 * cx + r12 * cy + r22 * cz
            in_plane2 = ((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) / 4 - pz * pz
            if in_plane2 < 0:
                return False  # the scan plane misses the AABB's bounding sphere
            # Hits lie in the scan plane within range_max of the sensor: so must a point of the sphere's cut.
            reach = range_max + math.sqrt(in_plane2) + 1e-6
            return cx * cx + cy * cy + cz * cz - pz * pz <= reach * reach

        for geom in world_geoms(self.physics, self.model, in_reach):
            x0, x1, y0, y1, z0, z1 = geom.getAABB()
            if level:
                # The AABB's footprint seen from the sensor: tight for long walls.
                if oz < z0 - rise or oz > z1 + rise:
                    continue
                dx = max(x0 - ox, 0.0, ox - x1)
                dy = max(y0 - oy, 0.0, oy - y1)
                if dx == 0.0 and dy == 0.0:
                    beams: Sequence[int] = all_beams
                else:
                    if dx * dx + dy * dy > range_max * range_max:
                        continue
                    centre = math.atan2((y0 + y1) / 2 - oy, (x0 + x1) / 2 - ox)
                    low = high = 0.0
                    for cx, cy in ((x0, y0), (x0, y1), (x1, y0), (x1, y1)):
                        delta = (math.atan2(cy - oy, cx - ox) - centre + math.pi) % math.tau - math.pi
                        low, high = min(low, delta), max(high, delta)
                    beams = self._candidates(centre - yaw + (low + high) / 2, (high - low) / 2 + _LEVEL)
                cast(beams, geom)
                continue
            # Bounding sphere of the AABB, in the sensor frame.
            cx, cy, cz = (x0 + x1) / 2 - ox, (y0 + y1) / 2 - oy, (z0 + z1) / 2 - oz
            radius2 = ((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) / 4
            px = r00 * cx + r10 * cy + r20 * cz
            py = r01 * cx + r11 * cy + r21 * cz
            pz = r02 * cx + r12 * cy + r22 * cz
            in_plane2 = radius2 - pz * pz  # squared radius of the sphere's cut by the scan plane
            if in_plane2 < 0:
                continue
            d2 = px * px + py * py
            if d2 <= in_plane2:
                beams = all_beams
            else:
                d = math.sqrt(d2)
                cut = math.sqrt(in_plane2)
                if d - cut > range_max:
                    continue
                beams = self._candidates(math.atan2(py, px), math.asin(cut / d) + 1e-9)
            cast(beams, geom)
        # Ground plane z = 0: only beams pointing down to it within range.
        if self.physics.has_ground and 0 < oz <= range_max * math.hypot(r20, r21):
            down = [i for i in all_beams if cosines[i] * r20 + sines[i] * r21 < -oz / range_max]
            cast(down, self.physics.ground)
        return self._ranges(distances, cast_beams)

    def _ranges(self, distances: List[float], cast_beams: List[int]) -> List[float]:
        """REP 117 and noise on the beams that were cast (the others hit nothing: +inf)."""
        config = self.config
        low, high = config.range_min, config.range_max
        stddev, mean, gauss = config.noise_stddev, config.noise_mean, self.rng.gauss
        noisy = stddev > 0 or mean != 0
        for i in sorted(cast_beams):  # in beam order: the noise drawn for each beam stays the same
            d = distances[i]
            if d > high:
                distances[i] = math.inf
            elif d < low:
                distances[i] = -math.inf
            elif noisy:
                distances[i] = min(high, max(low, d + gauss(mean, stddev)))
        return distances
