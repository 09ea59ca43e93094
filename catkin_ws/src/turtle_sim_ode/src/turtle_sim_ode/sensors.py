"""ROS-free sensors on built models: laser scanner (ODE rays), IMU, Kobuki bumpers and cliff sensors.

Ranges follow REP 117: a beam that hits nothing within range_max reads +inf, one that hits
something closer than range_min reads -inf.
"""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from typing import Callable, Iterator, List, Mapping, Optional, Sequence, Set, Tuple
from xml.etree.ElementTree import Element, ParseError

import defusedxml
import defusedxml.ElementTree as SafeET
import ode

from .model_builder import (
    BuiltModel,
    Quat,
    Transform,
    Vec3,
    compose,
    quat_from_rpy,
    quat_matrix,
    quat_multiply,
    quat_rotate,
)
from .physics import ContactWatch, PhysicsWorld
from .urdf_model import ModelError

LASER_PLUGINS = ("libgazebo_ros_laser.so", "libgazebo_ros_ray_sensor.so")
# gazebo_plugins' IMUs: the model plugin (also found inside <sensor type="imu">, as turtlebot3 has it) and the
# sensor plugin.
IMU_PLUGINS = ("libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so")
BUMPER_PLUGIN = "libgazebo_ros_bumper.so"

# kobuki_msgs/BumperEvent and CliffEvent sensor indices and states.
LEFT, CENTER, RIGHT = 0, 1, 2
RELEASED, PRESSED = 0, 1
FLOOR, CLIFF = 0, 1

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

_TWO_PI = 2.0 * math.pi
_NO_ROTATION: Quat = (1.0, 0.0, 0.0, 0.0)
# Below this tilt (sine, ~0.6 deg) a scan is culled by the AABB footprint, above by bounding spheres.
_LEVEL = 0.01


# --- configuration -----------------------------------------------------------------------
@dataclass
class LaserConfig:
    """A Gazebo ``<sensor type="ray">`` with its ROS laser plugin (gazebo_ros_laser names)."""

    link: str
    name: str = "laser"
    samples: int = 360
    resolution: float = 1.0  # Gazebo's rays per sample; rays are cast one per sample here
    min_angle: float = 0.0
    max_angle: float = _TWO_PI
    range_min: float = 0.12
    range_max: float = 3.5
    range_resolution: float = 0.0
    update_rate: float = 5.0  # Hz of sim time
    frame: str = ""  # "" = the link
    topic: str = "scan"  # "" when the sensor has no ROS plugin
    noise_mean: float = 0.0
    noise_stddev: float = 0.0
    # <sensor><pose>: (x, y, z, roll, pitch, yaw) of the sensor in the link frame.
    pose: Tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    robot_namespace: str = ""

    @property
    def angle_increment(self) -> float:
        return (self.max_angle - self.min_angle) / (self.samples - 1) if self.samples > 1 else 0.0

    def validate(self) -> None:
        """Raise ModelError naming the first bad field."""
        what = f"sensor '{self.name}' on link '{self.link}'"
        if not isinstance(self.samples, int) or isinstance(self.samples, bool) or not 1 <= self.samples <= 100_000:
            raise ModelError(f"{what}: samples must be an integer in 1..100000, got {self.samples!r}")
        numbers = ("resolution", "min_angle", "max_angle", "range_min", "range_max", "range_resolution")
        for attr in numbers + ("update_rate", "noise_mean", "noise_stddev"):
            if not math.isfinite(getattr(self, attr)):
                raise ModelError(f"{what}: {attr} must be finite, got {getattr(self, attr)!r}")
        if self.max_angle < self.min_angle:
            raise ModelError(f"{what}: max_angle {self.max_angle} < min_angle {self.min_angle}")
        if not 0 <= self.range_min < self.range_max:
            raise ModelError(f"{what}: need 0 <= range min < range max, got {self.range_min}, {self.range_max}")
        for attr in ("update_rate", "noise_stddev", "range_resolution"):
            if getattr(self, attr) < 0:
                raise ModelError(f"{what}: {attr} must be >= 0, got {getattr(self, attr)!r}")
        if len(self.pose) != 6 or not all(math.isfinite(v) for v in self.pose):
            raise ModelError(f"{what}: pose must be 6 finite numbers, got {self.pose!r}")


@dataclass(frozen=True)
class ImuNoise:
    """Gaussian noise stddevs (rad, rad/s, m/s^2); 0 = exact."""

    orientation: float = 0.0
    angular_velocity: float = 0.0
    linear_acceleration: float = 0.0


def _child_text(element: Optional[Element], path: str) -> Optional[str]:
    found = None if element is None else element.find(path)
    if found is None or found.text is None or not found.text.strip():
        return None
    return found.text.strip()


def _float(element: Optional[Element], path: str, default: float, what: str) -> float:
    text = _child_text(element, path)
    if text is None:
        return default
    try:
        value = float(text)
    except ValueError:
        raise ModelError(f"{what} <{path}> must be a number, got '{text}'") from None
    if not math.isfinite(value):
        raise ModelError(f"{what} <{path}> must be finite, got '{text}'")
    return value


def _laser_config(link: str, sensor: Element) -> LaserConfig:
    name = sensor.get("name", "laser")
    what = f"<sensor name='{name}'>"
    defaults = LaserConfig(link)
    ray = sensor.find("ray")
    horizontal = None if ray is None else ray.find("scan/horizontal")
    samples_text = _child_text(horizontal, "samples")
    try:
        samples = defaults.samples if samples_text is None else int(samples_text)
    except ValueError:
        raise ModelError(f"{what} <samples> must be an integer, got '{samples_text}'") from None
    noise = None if ray is None else ray.find("noise")
    gaussian = noise is not None and (_child_text(noise, "type") or "gaussian").lower() == "gaussian"
    plugin = next((p for p in sensor.findall("plugin") if p.get("filename") in LASER_PLUGINS), None)
    pose_text = _child_text(sensor, "pose")
    pose = defaults.pose
    if pose_text is not None:
        try:
            pose = tuple(float(v) for v in pose_text.split())  # type: ignore[assignment]
        except ValueError:
            raise ModelError(f"{what} <pose> must be 6 numbers, got '{pose_text}'") from None
    config = LaserConfig(
        link=link,
        name=name,
        samples=samples,
        resolution=_float(horizontal, "resolution", defaults.resolution, what),
        min_angle=_float(horizontal, "min_angle", defaults.min_angle, what),
        max_angle=_float(horizontal, "max_angle", defaults.max_angle, what),
        range_min=_float(ray, "range/min", defaults.range_min, what),
        range_max=_float(ray, "range/max", defaults.range_max, what),
        range_resolution=_float(ray, "range/resolution", defaults.range_resolution, what),
        update_rate=_float(sensor, "update_rate", defaults.update_rate, what),
        frame=(_child_text(plugin, "frameName") or "") if plugin is not None else "",
        topic=(_child_text(plugin, "topicName") or defaults.topic) if plugin is not None else "",
        noise_mean=_float(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=_float(noise, "stddev", 0.0, what) if gaussian else 0.0,
        pose=pose,
        robot_namespace=(_child_text(plugin, "robotNamespace") or "") if plugin is not None else "",
    )
    config.validate()
    return config


@dataclass(frozen=True)
class ImuConfig:
    """An IMU plugin's settings (gazebo_plugins' names): on ``link``, published on ``topic`` in ``frame``
    ("" = the link) at ``update_rate`` Hz of sim time (0 = every step), with gaussian noise of ``noise``."""

    link: str
    topic: str = "imu"
    frame: str = ""
    update_rate: float = 0.0
    noise: ImuNoise = field(default_factory=ImuNoise)
    robot_namespace: str = ""


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
    robot_namespace: str = ""


@dataclass
class SensorBlocks:
    """The sensors a URDF's ``<gazebo reference="link"><sensor>`` blocks define (with a ROS plugin)."""

    lasers: List[LaserConfig] = field(default_factory=list)
    imus: List[ImuConfig] = field(default_factory=list)
    contacts: List[ContactConfig] = field(default_factory=list)


def _rate(element: Optional[Element], tags: Sequence[str], default: float, what: str) -> float:
    for tag in tags:
        if _child_text(element, tag) is not None:
            value = _float(element, tag, default, what)
            if value < 0:
                raise ModelError(f"{what} <{tag}> must be >= 0, got {value}")
            return value
    return default


def _param_number(params: Mapping[str, str], tag: str, default: float, what: str) -> float:
    text = params.get(tag)
    if text is None or not text.strip():
        return default
    try:
        value = float(text)
    except ValueError:
        raise ModelError(f"{what} <{tag}> must be a number, got '{text}'") from None
    if not math.isfinite(value) or value < 0:
        raise ModelError(f"{what} <{tag}> must be a finite number >= 0, got '{text}'")
    return value


def imu_config(filename: str, params: Mapping[str, str], link: str = "", sensor_rate: float = 0.0) -> ImuConfig:
    """gazebo_plugins' IMU plugin tags (``params``: tag -> text), as a model plugin or inside a <sensor> on
    ``link``; <bodyName> wins over ``link``, and a model plugin must have it."""
    what = f"<plugin filename='{filename}'>"
    body = (params.get("bodyName") or link).strip().split("::")[-1]
    if not body:
        raise ModelError(f"{what} needs <bodyName> (the link the IMU is on)")
    noise = _param_number(params, "gaussianNoise", 0.0, what)
    rate_tag = "updateRateHZ" if "updateRateHZ" in params else "updateRate"
    return ImuConfig(
        link=body,
        topic=(params.get("topicName") or "imu").strip(),
        frame=(params.get("frameName") or "").strip(),
        update_rate=_param_number(params, rate_tag, sensor_rate, what),
        noise=ImuNoise(noise, noise, noise),
        robot_namespace=(params.get("robotNamespace") or "").strip(),
    )


def _contact_config(link: str, sensor: Element, plugin: Element) -> ContactConfig:
    name = sensor.get("name", "bumper")
    what = f"<sensor name='{name}'>"
    return ContactConfig(
        link=link,
        name=name,
        collisions=tuple(c.text.strip() for c in sensor.findall("contact/collision") if c.text and c.text.strip()),
        topic=_child_text(plugin, "bumperTopicName") or "bumper_states",
        frame=_child_text(plugin, "frameName") or "world",
        update_rate=_rate(sensor, ("update_rate",), 0.0, what),
        robot_namespace=_child_text(plugin, "robotNamespace") or "",
    )


def _safe_xml(text: str, kind: str) -> Element:
    try:
        return SafeET.fromstring(text)
    except ParseError as error:
        raise ModelError(f"{kind} is not well-formed XML: {error}") from None
    except defusedxml.DefusedXmlException as error:
        raise ModelError(f"{kind} rejected by the XML guard: {error}") from None


def _add_sensor(found: SensorBlocks, link: str, sensor: Element) -> None:
    """One <sensor> on ``link`` (URDF and SDF write them alike): ray (``gpu_ray`` too), imu or contact."""
    kind = sensor.get("type")
    plugins = sensor.findall("plugin")
    if kind in ("ray", "gpu_ray"):
        found.lasers.append(_laser_config(link, sensor))
    elif kind == "imu":
        what = f"<sensor name='{sensor.get('name', '')}'>"
        rate = _rate(sensor, ("update_rate",), 0.0, what)
        found.imus += [
            imu_config(p.get("filename"), {c.tag: c.text or "" for c in p}, link, rate)
            for p in plugins
            if p.get("filename") in IMU_PLUGINS
        ]
    elif kind == "contact":
        found.contacts += [_contact_config(link, sensor, p) for p in plugins if p.get("filename") == BUMPER_PLUGIN]


def read_sensors(urdf: str) -> SensorBlocks:
    """The ``<gazebo reference="link"><sensor>`` blocks of a URDF: ray (``gpu_ray`` too), imu and contact.

    urdf_model keeps only contact tags of referenced ``<gazebo>`` blocks, so the raw text is
    read again here. ModelError for malformed XML or bad values, or a sensor on no link.
    """
    robot = _safe_xml(urdf, "URDF")
    links = {link.get("name") for link in robot.findall("link")}
    found = SensorBlocks()
    for gazebo in robot.findall("gazebo"):
        reference = gazebo.get("reference")
        for sensor in gazebo.findall("sensor"):
            if sensor.get("type") not in ("ray", "gpu_ray", "imu", "contact"):
                continue
            if reference is None or reference not in links:
                raise ModelError(f"<sensor name='{sensor.get('name', '')}'> must be in a <gazebo reference=link>")
            _add_sensor(found, reference, sensor)
    return found


def read_sdf_sensors(sdf: str) -> SensorBlocks:
    """The ``<link><sensor>`` elements of an SDF model (``<sdf><model>`` or a bare ``<model>``); a sensor's
    <pose> is in its link's frame, as in Gazebo. ModelError for malformed XML or bad values."""
    root = _safe_xml(sdf, "SDF")
    model = root if root.tag == "model" else root.find("model")
    found = SensorBlocks()
    for link in [] if model is None else model.findall("link"):
        for sensor in link.findall("sensor"):
            _add_sensor(found, link.get("name", ""), sensor)
    return found


# --- ray casting ----------------------------------------------------------------------
def _world_geoms(
    physics: PhysicsWorld, model: BuiltModel, in_reach: Callable[[ode.SpaceBase], bool] = lambda space: True
) -> Iterator[ode.GeomObject]:
    """Every collision geom in the world's spaces but ``model``'s own (the ground plane is apart), less those of
    the sub-spaces (other models, static obstacles) for which ``in_reach`` is false: a sensor that knows how far it
    reaches then tests a few space AABBs instead of every geom in the world."""
    own: Set[ode.GeomObject] = {geom for geoms in model.geoms.values() for geom in geoms}
    own_space = None
    if not model.robot.static:
        own_space = next((geom.getSpace() for geom in own), None)
    stack = [physics.space]
    while stack:
        space = stack.pop()
        for index in range(space.getNumGeoms()):
            geom = space.getGeom(index)
            if geom.isSpace():
                if geom is not own_space and in_reach(geom):
                    stack.append(geom)
            elif geom not in own:
                yield geom


def _ray_distance(ray: ode.GeomRay, geom: ode.GeomObject) -> float:
    best = math.inf
    for contact in ode.collide(ray, geom):
        depth = contact.getContactGeomParams()[2]
        if depth < best:
            best = depth
    return best


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
            delta = (first - bearing + math.pi) % _TWO_PI - math.pi
            return [0] if abs(delta) <= half_width else []
        found: Set[int] = set()
        for shift in (-_TWO_PI, 0.0, _TWO_PI):
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

        collide = ode.collide

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

        for geom in _world_geoms(self.physics, self.model, in_reach):
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
                        delta = (math.atan2(cy - oy, cx - ox) - centre + math.pi) % _TWO_PI - math.pi
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
        if 0 < oz <= range_max * math.hypot(r20, r21):
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


# --- IMU ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class ImuReading:
    """sensor_msgs/Imu contents: quaternion (x, y, z, w), body-frame rates and proper acceleration."""

    stamp: float
    orientation: Tuple[float, float, float, float]
    angular_velocity: Vec3
    linear_acceleration: Vec3
    orientation_covariance: List[float] = field(default_factory=lambda: [0.0] * 9)
    angular_velocity_covariance: List[float] = field(default_factory=lambda: [0.0] * 9)
    linear_acceleration_covariance: List[float] = field(default_factory=lambda: [0.0] * 9)


def _diagonal(stddev: float) -> List[float]:
    variance = stddev * stddev
    return [variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance]


class ImuSensor:
    """An IMU on a model's link.

    ``read(now)`` gives the orientation in the world, the angular velocity in the link frame
    and the proper acceleration in the link frame: the change of the link origin's world
    velocity since the previous ``read`` divided by the time between them, minus gravity
    (at rest: +9.81 up). The first reading, or one at the same time as the previous, takes
    the acceleration of the previous reading (0 at first).
    """

    def __init__(
        self,
        model: BuiltModel,
        link: str,
        gravity: Vec3 = (0.0, 0.0, -9.81),
        noise: Optional[ImuNoise] = None,
        rng: Optional[random.Random] = None,
    ) -> None:
        model.link_transform(link)  # KeyError now for a missing link
        self.model = model
        self.link = link
        self.gravity = tuple(gravity)
        self.noise = noise if noise is not None else ImuNoise()
        self.rng = rng if rng is not None else random.Random()
        self._last: Optional[Tuple[float, Vec3]] = None
        self._acceleration: Vec3 = (0.0, 0.0, 0.0)
        self._covariances = (
            _diagonal(self.noise.orientation),
            _diagonal(self.noise.angular_velocity),
            _diagonal(self.noise.linear_acceleration),
        )

    def reset(self) -> None:
        """Forget the velocity history (after a teleport or world reset)."""
        self._last = None
        self._acceleration = (0.0, 0.0, 0.0)

    def _noisy(self, values: Vec3, stddev: float) -> Vec3:
        if stddev <= 0:
            return values
        gauss = self.rng.gauss
        return (values[0] + gauss(0.0, stddev), values[1] + gauss(0.0, stddev), values[2] + gauss(0.0, stddev))

    def read(self, now: float) -> ImuReading:
        """The IMU's reading at sim time ``now`` (call after steps, e.g. at the publish rate)."""
        _, (w, x, y, z) = self.model.link_transform(self.link)
        velocity, angular = self.model.link_twist(self.link)
        if self._last is not None and now > self._last[0]:
            dt = now - self._last[0]
            previous = self._last[1]
            self._acceleration = (
                (velocity[0] - previous[0]) / dt,
                (velocity[1] - previous[1]) / dt,
                (velocity[2] - previous[2]) / dt,
            )
        self._last = (now, tuple(velocity))  # type: ignore[assignment]
        to_link = (w, -x, -y, -z)
        g = self.gravity
        a = self._acceleration
        proper = quat_rotate(to_link, (a[0] - g[0], a[1] - g[1], a[2] - g[2]))
        rates = quat_rotate(to_link, angular)
        orientation = (x, y, z, w)
        noise = self.noise
        if noise.orientation > 0:
            roll, pitch, yaw = self._noisy((0.0, 0.0, 0.0), noise.orientation)
            nw, nx, ny, nz = quat_multiply((w, x, y, z), quat_from_rpy(roll, pitch, yaw))
            orientation = (nx, ny, nz, nw)
        return ImuReading(
            now,
            orientation,
            self._noisy(rates, noise.angular_velocity),
            self._noisy(proper, noise.linear_acceleration),
            list(self._covariances[0]),
            list(self._covariances[1]),
            list(self._covariances[2]),
        )


# --- bumper --------------------------------------------------------------------------------
def bumper_of(angle: float) -> Optional[int]:
    """Kobuki bumper pressed by a contact at ``angle`` (rad from the base's +x, CCW), or None."""
    angle = (angle + math.pi) % _TWO_PI - math.pi
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

    def changes(self) -> List[Tuple[int, int]]:
        """(bumper, PRESSED or RELEASED) for each bumper whose state changed since the last call."""
        events = []
        for bumper, now in enumerate(self.pressed()):
            if now != self._reported[bumper]:
                self._reported[bumper] = now
                events.append((bumper, PRESSED if now else RELEASED))
        return events


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
        distances = [_ray_distance(ray, self.physics.ground) for ray in self._rays]
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

        for geom in _world_geoms(self.physics, self.model, in_reach):
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
                hit = _ray_distance(self._rays[i], geom)
                if hit < distances[i]:
                    distances[i] = hit
        return [d if d <= reach else math.inf for d in distances]

    def cliffs(self) -> List[bool]:
        """For each sensor: True when it sees a cliff."""
        return [d > self.threshold for d in self.distances()]

    def changes(self) -> List[Tuple[int, int, float]]:
        """(sensor, CLIFF or FLOOR, distance) for each sensor whose state changed since the last call."""
        events = []
        for sensor, distance in enumerate(self.distances()):
            now = distance > self.threshold
            if now != self._reported[sensor]:
                self._reported[sensor] = now
                events.append((sensor, CLIFF if now else FLOOR, distance))
        return events


__all__ = [
    "BumperSensor",
    "CliffSensor",
    "ImuNoise",
    "ImuReading",
    "ImuSensor",
    "LaserConfig",
    "LaserScanner",
    "read_sensors",
    "read_sdf_sensors",
    "imu_config",
    "ImuConfig",
    "ContactConfig",
    "SensorBlocks",
    "IMU_PLUGINS",
    "BUMPER_PLUGIN",
    "bumper_of",
    "LEFT",
    "CENTER",
    "RIGHT",
    "RELEASED",
    "PRESSED",
    "FLOOR",
    "CLIFF",
    "KOBUKI_CLIFF_OFFSETS",
    "KOBUKI_CLIFF_RANGE",
    "KOBUKI_CLIFF_THRESHOLD",
    "LASER_PLUGINS",
]
