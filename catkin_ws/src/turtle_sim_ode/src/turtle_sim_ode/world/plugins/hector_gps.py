"""hector_gazebo_plugins' GPS (``libhector_gazebo_ros_gps.so``, GazeboRosGps of hector_gazebo_plugins/src/
gazebo_ros_gps.cpp): its tags and defaults, and Update's fix: the link's position and velocity through the sensor
error model (hector_sensor_model), as latitude, longitude and altitude about a reference (the plugin's, or the
world's <spherical_coordinates> with useWorldSphericalCoordinates), and the velocity turned by the heading; a new
reference from the set_reference_geopose service (setGeoposeCb); the fix status and services as the GNSS
dynamic_reconfigure server sets them (dynamicReconfigureCallback)."""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from typing import Dict, Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.text import read_number, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins.hector_sensor_model import ErrorModel, SensorError, Vec3, error_model
from turtle_sim_ode.world.plugins.tags import flag, text

HECTOR_GPS = "libhector_gazebo_ros_gps.so"
MODEL_PLUGINS = (HECTOR_GPS,)
# WGS84, as gazebo_ros_gps.cpp has them.
EQUATORIAL_RADIUS = 6378137.0
FLATTENING = 1.0 / 298.257223563
EXCENTRICITY2 = 2 * FLATTENING - FLATTENING * FLATTENING
# sensor_msgs/NavSatStatus: the status, and the augmentation bits set over STATUS_FIX (0).
STATUS_NO_FIX, STATUS_FIX = -1, 0
STATUS_FLAGS = (("STATUS_SBAS_FIX", 1), ("STATUS_GBAS_FIX", 2))
# The service mask's bits.
SERVICE_FLAGS = (("SERVICE_GPS", 1), ("SERVICE_GLONASS", 2), ("SERVICE_COMPASS", 4), ("SERVICE_GALILEO", 8))
GNSS_FLAGS = ("STATUS_FIX",) + tuple(name for name, _ in STATUS_FLAGS + SERVICE_FLAGS)  # cfg/GNSS.cfg's fields
GNSS_LEVEL = 1  # and their reconfiguration level


@dataclass(frozen=True)
class HectorGpsConfig:
    body: str  # "" = the model's canonical link
    frame: str = "/world"
    fix_topic: str = "fix"
    velocity_topic: str = "fix_velocity"
    reference_latitude: float = 49.9  # degrees
    reference_longitude: float = 8.9
    reference_heading: float = 0.0  # radians, clockwise from north
    reference_altitude: float = 0.0
    use_world_spherical_coordinates: bool = False
    status: int = STATUS_FIX
    service: int = 0
    position: ErrorModel = field(default_factory=ErrorModel)
    velocity: ErrorModel = field(default_factory=ErrorModel)
    update_rate: float = 4.0  # Load's updateTimer.setUpdateRate(4.0), then <updateRate> / <updatePeriod>
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> HectorGpsConfig:
    def number(tag: str, default: float, minimum: float = -math.inf) -> float:
        return read_number(plugin.params.get(tag), f"{plugin.filename} <{tag}>", default, minimum)

    period = number("updatePeriod", 0.0, 0.0)
    rate = number("updateRate", 4.0, 0.0)
    return HectorGpsConfig(
        body=text(plugin, "bodyName", "").split("::")[-1],
        frame=text(plugin, "frameId", "/world"),
        fix_topic=text(plugin, "topicName", "fix"),
        velocity_topic=text(plugin, "velocityTopicName", "fix_velocity"),
        reference_latitude=number("referenceLatitude", 49.9),
        reference_longitude=number("referenceLongitude", 8.9),
        reference_heading=math.radians(number("referenceHeading", 0.0)),
        reference_altitude=number("referenceAltitude", 0.0),
        use_world_spherical_coordinates=flag(plugin, "useWorldSphericalCoordinates", False),
        status=int(number("status", STATUS_FIX)),
        service=int(number("service", 0, 0.0)),
        position=error_model(plugin, ""),
        velocity=error_model(plugin, "velocity"),
        update_rate=1.0 / period if period > 0 else rate,
        robot_namespace=robot_namespace_tag(plugin.params),
    )


@dataclass(frozen=True)
class GpsFix:
    latitude: float
    longitude: float
    altitude: float
    velocity: Vec3  # m/s, turned by the reference heading as Update turns it
    position_covariance: Tuple[float, ...]  # diagonal known
    status: int  # sensor_msgs/NavSatStatus
    service: int


class HectorGps:
    """GazeboRosGps's state on a link: ``update(now)`` at each of its updates."""

    def __init__(
        self,
        model: BuiltModel,
        link: str,
        config: HectorGpsConfig,
        spherical_coordinates: Optional[Tuple[float, float, float, float]],
        rng: Optional[random.Random] = None,
    ) -> None:
        model.link_transform(link)  # KeyError now for a missing link
        self.model, self.link, self.config = model, link, config
        latitude, longitude = config.reference_latitude, config.reference_longitude
        heading, altitude = config.reference_heading, config.reference_altitude
        if config.use_world_spherical_coordinates:
            latitude, longitude, altitude, heading_deg = spherical_coordinates or (0.0, 0.0, 0.0, 0.0)
            heading = math.pi / 2.0 - math.radians(heading_deg)  # SDF: counter-clockwise from east
        self.reference = (latitude, longitude, heading, altitude)
        sin_latitude = math.sin(math.radians(latitude))
        temp = 1.0 / (1.0 - EXCENTRICITY2 * sin_latitude * sin_latitude)
        prime_vertical = EQUATORIAL_RADIUS * math.sqrt(temp)
        self.radius_north = prime_vertical * (1 - EXCENTRICITY2) * temp
        self.radius_east = prime_vertical * math.cos(math.radians(latitude))
        self.status, self.service = config.status, config.service
        rng = rng if rng is not None else random.Random()
        self.position_error = SensorError(config.position, rng)
        self.velocity_error = SensorError(config.velocity, rng)
        self._last: Optional[float] = None

    def set_reference(
        self, latitude: float, longitude: float, altitude: float, orientation: Tuple[float, float, float, float]
    ) -> None:
        """setGeoposeCb: the world origin's new latitude, longitude and altitude, and as the heading (clockwise from
        north) pi/2 minus the yaw of ``orientation`` (x, y, z, w: the world's x axis, counter-clockwise from east,
        tf's getEulerYPR); then Reset. As upstream, the earth radii stay those of the reference the plugin was
        loaded with. ValueError (the reference kept) for a value that is not finite, a latitude or longitude out of
        range, or a zero quaternion."""
        values = (latitude, longitude, altitude) + tuple(orientation)
        norm = math.sqrt(sum(q * q for q in orientation))
        if not all(math.isfinite(v) for v in values) or abs(latitude) > 90.0 or abs(longitude) > 180.0 or not norm:
            raise ValueError(f"not finite, out of range or a zero quaternion: {values}")
        x, y, z, w = (q / norm for q in orientation)
        yaw = math.atan2(2.0 * (x * y + w * z), w * w + x * x - y * y - z * z)
        self.reference = (latitude, longitude, math.pi / 2.0 - yaw, altitude)
        self.reset()

    def reconfigure_status(self, values: Mapping[str, bool], level: int) -> Dict[str, bool]:
        """dynamicReconfigureCallback of the GNSS server. At level 1 (a client changed a flag) the status becomes
        STATUS_NO_FIX without STATUS_FIX, else the bits of the augmentations set (0 for a plain fix), and the
        service the bits of the services set; the flags stay as the client gave them. At any other level (the
        server's first call) nothing changes and the flags are read from the bits as upstream reads them: so
        STATUS_NO_FIX (-1, every bit set) reports both augmentations. Returns the flags to publish."""
        if level == GNSS_LEVEL:
            status = service = 0
            for name, bit in STATUS_FLAGS:
                status |= bit if values[name] else 0
            for name, bit in SERVICE_FLAGS:
                service |= bit if values[name] else 0
            self.status = status if values["STATUS_FIX"] else STATUS_NO_FIX
            self.service = service
            return {name: bool(values[name]) for name in GNSS_FLAGS}
        flags = {"STATUS_FIX": self.status != STATUS_NO_FIX}
        flags.update((name, bool(self.status & bit)) for name, bit in STATUS_FLAGS)
        flags.update((name, bool(self.service & bit)) for name, bit in SERVICE_FLAGS)
        return flags

    def reset(self) -> None:
        self._last = None
        self.position_error.reset()
        self.velocity_error.reset()

    def update(self, now: float) -> GpsFix:
        dt = now - self._last if self._last is not None else 0.0
        self._last = now
        (px, py, pz), _ = self.model.link_transform(self.link)
        linear, _ = self.model.link_twist(self.link)
        vx, vy, vz = self.velocity_error.apply(tuple(linear), dt)  # type: ignore[arg-type]
        x, y, z = self.position_error.apply((px, py, pz), dt)
        # A velocity drift is integrated into the position drift for the next update.
        drift = self.position_error.current_drift
        velocity_drift = self.velocity_error.current_drift
        self.position_error.current_drift = tuple(d + dt * v for d, v in zip(drift, velocity_drift))  # type: ignore
        latitude, longitude, heading, altitude = self.reference
        cos_h, sin_h = math.cos(heading), math.sin(heading)
        model = self.position_error.model  # as reconfigured: Update reads the error model's members
        position, noise = model.drift, model.gaussian_noise
        return GpsFix(
            latitude=latitude + (cos_h * x + sin_h * y) / self.radius_north * 180.0 / math.pi,
            longitude=longitude - (-sin_h * x + cos_h * y) / self.radius_east * 180.0 / math.pi,
            altitude=altitude + z,
            velocity=(cos_h * vx + sin_h * vy, -sin_h * vx + cos_h * vy, vz),
            position_covariance=tuple(
                position[i // 3] ** 2 + noise[i // 3] ** 2 if i % 4 == 0 else 0.0 for i in range(9)
            ),
            status=self.status,
            service=self.service,
        )
