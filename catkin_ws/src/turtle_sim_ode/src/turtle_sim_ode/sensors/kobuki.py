"""The Kobuki base's bumpers, cliff sensors and wheel drops, and its core sensor state's bits, as
kobuki_gazebo_plugins simulates them."""
from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence, Tuple

import ode

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Quat, Vec3, compose, inverse, quat_rotate
from turtle_sim_ode.models.description import RobotModel
from turtle_sim_ode.physics.contacts import ContactWatch
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.rays import ray_distance, world_geoms

_NO_ROTATION: Quat = (1.0, 0.0, 0.0, 0.0)

# kobuki_msgs/BumperEvent, CliffEvent and WheelDropEvent sensor indices and states.
LEFT, CENTER, RIGHT = 0, 1, 2
RELEASED, PRESSED = 0, 1
FLOOR, CLIFF = 0, 1
WHEEL_LEFT, WHEEL_RIGHT = 0, 1
RAISED, DROPPED = 0, 1
# kobuki_msgs/SensorState bit flags for bumper and cliff (left, centre, right) and wheel_drop (left, right).
STATE_BITS_LCR = (4, 2, 1)
STATE_BITS_WHEELS = (2, 1)

# kobuki_gazebo_plugins (gazebo_ros_kobuki_updates.cpp) bumper sectors, angle of the contact
# measured from the base's +x axis, counter-clockwise: LEFT (30 deg, 90 deg], CENTER
# [-30 deg, 30 deg], RIGHT [-90 deg, -30 deg); contacts behind the base press nothing.
BUMPER_SECTOR = math.pi / 6
# kobuki_description cliff sensors on base_link (left, front, right), looking straight down,
# with the Gazebo ray range of 0.01..0.15 m; the plugin's cliff_detection_threshold.
KOBUKI_CLIFF_OFFSETS: Tuple[Vec3, Vec3, Vec3] = (
    (0.08734, 0.13601, 0.0214),
    (0.156, 0.0, 0.0214),
    (0.08734, -0.13601, 0.0214),
)
KOBUKI_CLIFF_RANGE = 0.15
KOBUKI_CLIFF_THRESHOLD = 0.04


def report_changes(reported: List[bool], current: Sequence[bool], on: int, off: int) -> List[Tuple[int, int]]:
    """(index, on or off) for each flag of ``current`` that differs from ``reported``, which is updated."""
    events = []
    for index, now in enumerate(current):
        if now != reported[index]:
            reported[index] = now
            events.append((index, on if now else off))
    return events


# --- bumper --------------------------------------------------------------------------------
def bumper_of(angle: float) -> Optional[int]:
    """Kobuki bumper pressed by a contact at ``angle`` (rad from the base's +x, CCW), or None."""
    angle = (angle + math.pi) % math.tau - math.pi
    if BUMPER_SECTOR < angle <= math.pi / 2:
        return LEFT
    if -BUMPER_SECTOR <= angle <= BUMPER_SECTOR:
        return CENTER
    if -math.pi / 2 <= angle < -BUMPER_SECTOR:
        return RIGHT
    return None


class BumperSensor:
    """Kobuki's three bumpers: contacts of ``link``'s geoms with anything but the ground plane
    during the last step, by the angle of the contact point around the link's origin (see
    ``bumper_of``). Watches contacts from construction on; ``close()`` stops that."""

    def __init__(self, physics: PhysicsWorld, model: BuiltModel, link: str = "base_link") -> None:
        geoms = model.geoms.get(link)
        if not geoms:
            raise KeyError(f"model '{model.name}' has no collision geoms on link '{link}'")
        self.physics = physics
        self.model = model
        self.link = link
        self._watch: Optional[ContactWatch] = physics.watch_contacts(geoms)
        self._reported = [False, False, False]

    def close(self) -> None:
        if self._watch is not None:
            self.physics.unwatch_contacts(self._watch)
            self._watch = None

    def pressed(self) -> List[bool]:
        """[left, center, right]: pressed during the last step."""
        state = [False, False, False]
        if self._watch is None:
            return state
        ground = self.physics.ground
        (ox, oy, oz), (w, x, y, z) = self.model.link_transform(self.link)
        to_link = (w, -x, -y, -z)
        for contact in self._watch.contacts:
            if contact.other is ground:
                continue
            px, py, pz = contact.position
            lx, ly, _ = quat_rotate(to_link, (px - ox, py - oy, pz - oz))
            bumper = bumper_of(math.atan2(ly, lx))
            if bumper is not None:
                state[bumper] = True
        return state

    @property
    def state(self) -> List[bool]:
        """[left, center, right] as last reported by changes()."""
        return list(self._reported)

    def changes(self) -> List[Tuple[int, int]]:
        """(bumper, PRESSED or RELEASED) for each bumper whose state changed since the last call."""
        return report_changes(self._reported, self.pressed(), PRESSED, RELEASED)


# --- cliff ----------------------------------------------------------------------------------
class CliffSensor:
    """Kobuki's three cliff sensors: downward ODE rays from ``offsets`` (left, front, right) in
    ``link``'s frame. A sensor sees a cliff when the nearest geom below it (ground included,
    the model's own geoms excluded) is farther than ``threshold``, or out of ``max_range``."""

    def __init__(
        self,
        physics: PhysicsWorld,
        model: BuiltModel,
        link: str = "base_link",
        threshold: float = KOBUKI_CLIFF_THRESHOLD,
        offsets: Sequence[Vec3] = KOBUKI_CLIFF_OFFSETS,
        max_range: float = KOBUKI_CLIFF_RANGE,
    ) -> None:
        if not math.isfinite(threshold) or not 0 < threshold:
            raise ValueError(f"threshold must be finite and > 0, got {threshold!r}")
        if not math.isfinite(max_range) or not 0 < max_range:
            raise ValueError(f"max_range must be finite and > 0, got {max_range!r}")
        model.link_transform(link)
        self.physics = physics
        self.model = model
        self.link = link
        self.threshold = threshold
        self.offsets = [tuple(offset) for offset in offsets]
        self.max_range = max_range
        self._rays = [ode.GeomRay(None, max_range) for _ in self.offsets]
        self._reported = [False] * len(self.offsets)

    def distances(self) -> List[float]:
        """Distance (m) from each sensor down to the nearest geom; +inf beyond ``max_range``."""
        base = self.model.link_transform(self.link)
        down = quat_rotate(base[1], (0.0, 0.0, -1.0))
        starts = [compose(base, (offset, _NO_ROTATION))[0] for offset in self.offsets]
        for ray, start in zip(self._rays, starts):
            ray.set(start, down)
        ground = self.physics.ground if self.physics.has_ground else None
        distances = [math.inf if ground is None else ray_distance(ray, ground) for ray in self._rays]
        reach = self.max_range
        # The box around all rays: the starts' box stretched by the (common) ray vector.
        xs, ys, zs = zip(*starts)
        dx, dy, dz = down[0] * reach, down[1] * reach, down[2] * reach
        bx0, bx1 = min(xs) + min(dx, 0.0), max(xs) + max(dx, 0.0)
        by0, by1 = min(ys) + min(dy, 0.0), max(ys) + max(dy, 0.0)
        bz0, bz1 = min(zs) + min(dz, 0.0), max(zs) + max(dz, 0.0)

        def in_reach(space: ode.SpaceBase) -> bool:
            """Whether that box meets the space's AABB (which holds its geoms' AABBs)."""
            x0, x1, y0, y1, z0, z1 = space.getAABB()
            return bx0 <= x1 and x0 <= bx1 and by0 <= y1 and y0 <= by1 and bz0 <= z1 and z0 <= bz1

        for geom in world_geoms(self.physics, self.model, in_reach):
            x0, x1, y0, y1, z0, z1 = geom.getAABB()
            for i, (sx, sy, sz) in enumerate(starts):
                ex, ey, ez = sx + down[0] * reach, sy + down[1] * reach, sz + down[2] * reach
                if (
                    min(sx, ex) > x1
                    or max(sx, ex) < x0
                    or min(sy, ey) > y1
                    or max(sy, ey) < y0
                    or min(sz, ez) > z1
                    or max(sz, ez) < z0
                ):
                    continue
                hit = ray_distance(self._rays[i], geom)
                if hit < distances[i]:
                    distances[i] = hit
        return [d if d <= reach else math.inf for d in distances]

    def cliffs(self) -> List[bool]:
        """For each sensor: True when it sees a cliff."""
        return [d > self.threshold for d in self.distances()]

    @property
    def state(self) -> List[bool]:
        """[left, front, right]: a cliff, as last reported by changes()."""
        return list(self._reported)

    def changes(self) -> List[Tuple[int, int, float]]:
        """(sensor, CLIFF or FLOOR, distance) for each sensor whose state changed since the last call."""
        events = []
        for sensor, distance in enumerate(self.distances()):
            now = distance > self.threshold
            if now != self._reported[sensor]:
                self._reported[sensor] = now
                events.append((sensor, CLIFF if now else FLOOR, distance))
        return events


# --- wheel drop -----------------------------------------------------------------------------
class WheelDropSensor:
    """Kobuki's wheel-drop switches: a wheel whose collisions touched nothing during the last step has dropped
    (kobuki_gazebo_plugins' contact sensors on the wheel links; a wheel's contacts are with the floor or an
    obstacle, never its own model). Watches contacts from construction on; ``close()`` stops that."""

    def __init__(self, physics: PhysicsWorld, model: BuiltModel, links: Sequence[str]) -> None:
        self.physics = physics
        self._watches: List[ContactWatch] = []
        for link in links:
            geoms = model.geoms.get(link)
            if not geoms:
                self.close()
                raise KeyError(f"model '{model.name}' has no collision geoms on wheel link '{link}'")
            self._watches.append(physics.watch_contacts(geoms))
        self._reported = [False] * len(self._watches)

    def close(self) -> None:
        for watch in self._watches:
            self.physics.unwatch_contacts(watch)
        self._watches = []

    def dropped(self) -> List[bool]:
        return [not watch.contacts for watch in self._watches]

    @property
    def state(self) -> List[bool]:
        """[left, right]: dropped, as last reported by changes()."""
        return list(self._reported)

    def changes(self) -> List[Tuple[int, int]]:
        """(wheel, DROPPED or RAISED) for each wheel whose state changed since the last call."""
        return report_changes(self._reported, self.dropped(), DROPPED, RAISED)


def state_bits(flags: Sequence[bool], bits: Sequence[int]) -> int:
    """kobuki_msgs/SensorState's bit field of the flags that are set (``bits``: STATE_BITS_LCR or _WHEELS)."""
    return sum(bit for flag, bit in zip(flags, bits) if flag)


# --- where a model's sensors are -------------------------------------------------------------
def sensor_links(robot: RobotModel, kind: str) -> Dict[str, str]:
    """{sensor name: its link} of the model's <sensor type=kind> blocks (the first of a name wins)."""
    found: Dict[str, str] = {}
    for block in robot.sensors:
        name = block.element.get("name", "")
        if block.element.get("type") == kind and block.link and name not in found:
            found[name] = block.link
    return found


def offsets_in(model: BuiltModel, base: str, links: Sequence[str]) -> List[Vec3]:
    """Each link frame's origin in ``base``'s frame (constant where fixed joints join them, as for sensors)."""
    to_base = inverse(model.link_transform(base))
    return [compose(to_base, model.link_transform(link))[0] for link in links]
