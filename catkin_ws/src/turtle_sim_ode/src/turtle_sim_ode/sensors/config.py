"""Sensor settings read from model text: the <sensor> blocks of URDF <gazebo reference> and SDF <link> elements
and the plugin tags inside them (gazebo_plugins' names and defaults)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Mapping, Optional, Sequence, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.text import ModelError, child_text, plugin_params, read_number
from turtle_sim_ode.models.urdf import RobotModel, parse_urdf
from turtle_sim_ode.physics import sanity

LASER_PLUGINS = ("libgazebo_ros_laser.so", "libgazebo_ros_ray_sensor.so")
# gazebo_plugins' IMUs: the model plugin (also found inside <sensor type="imu">, as turtlebot3 has it) and the
# sensor plugin.
IMU_PLUGINS = ("libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so")
BUMPER_PLUGIN = "libgazebo_ros_bumper.so"
CAMERA_PLUGINS = ("libgazebo_ros_camera.so",)
DEPTH_PLUGINS = ("libgazebo_ros_openni_kinect.so", "libgazebo_ros_depth_camera.so")
SIMULATED_TYPES = ("ray", "gpu_ray", "imu", "contact", "camera", "depth")
# <image><format> -> sensor_msgs encoding (gazebo_ros_camera_utils' names); the others fall back to rgb8.
IMAGE_ENCODINGS = {"R8G8B8": "rgb8", "RGB_INT8": "rgb8", "B8G8R8": "bgr8", "BGR_INT8": "bgr8", "L8": "mono8"}
IMAGE_ENCODINGS["L_INT8"] = "mono8"
# A camera whose <sensor><update_rate> and plugin <updateRate> are both 0 (Gazebo: as fast as it renders).
DEFAULT_CAMERA_RATE = 30.0


# --- configuration -----------------------------------------------------------------------
@dataclass
class LaserConfig:
    """A Gazebo ``<sensor type="ray">`` with its ROS laser plugin (gazebo_ros_laser names)."""

    link: str
    name: str = "laser"
    samples: int = 360
    resolution: float = 1.0  # Gazebo's rays per sample; rays are cast one per sample here
    min_angle: float = 0.0
    max_angle: float = math.tau
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


def _float(element: Optional[Element], path: str, default: float, what: str) -> float:
    return read_number(child_text(element, path), f"{what} <{path}>", default)


def _laser_config(link: str, sensor: Element) -> LaserConfig:
    name = sensor.get("name", "laser")
    what = f"<sensor name='{name}'>"
    defaults = LaserConfig(link)
    ray = sensor.find("ray")
    horizontal = None if ray is None else ray.find("scan/horizontal")
    samples_text = child_text(horizontal, "samples")
    try:
        samples = defaults.samples if samples_text is None else int(samples_text)
    except ValueError:
        raise ModelError(f"{what} <samples> must be an integer, got '{samples_text}'") from None
    noise = None if ray is None else ray.find("noise")
    gaussian = noise is not None and (child_text(noise, "type") or "gaussian").lower() == "gaussian"
    plugin = next((p for p in sensor.findall("plugin") if p.get("filename") in LASER_PLUGINS), None)
    pose_text = child_text(sensor, "pose")
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
        frame=(child_text(plugin, "frameName") or "") if plugin is not None else "",
        topic=(child_text(plugin, "topicName") or defaults.topic) if plugin is not None else "",
        noise_mean=_float(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=_float(noise, "stddev", 0.0, what) if gaussian else 0.0,
        pose=pose,
        robot_namespace=(child_text(plugin, "robotNamespace") or "") if plugin is not None else "",
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


@dataclass(frozen=True)
class CameraConfig:
    """A ``<sensor type="camera">`` with libgazebo_ros_camera.so, or a ``<sensor type="depth">`` with
    libgazebo_ros_openni_kinect.so / libgazebo_ros_depth_camera.so (``depth`` true): gazebo_plugins' tags and
    defaults. Topics are relative to ``robot_namespace``/``camera_name``, as gazebo_ros_camera_utils has them."""

    link: str
    name: str = "camera"
    depth: bool = False
    horizontal_fov: float = 1.047  # rad, SDF's default
    width: int = 320
    height: int = 240
    image_format: str = "R8G8B8"
    near: float = 0.1
    far: float = 100.0
    noise_mean: float = 0.0  # gaussian noise on the colour values (0..1), SDF <camera><noise>
    noise_stddev: float = 0.0
    update_rate: float = DEFAULT_CAMERA_RATE  # Hz of sim time
    camera_name: str = ""
    image_topic: str = "image_raw"
    info_topic: str = "camera_info"
    depth_topic: str = "depth/image_raw"
    depth_info_topic: str = "depth/camera_info"
    points_topic: str = "points"
    frame: str = ""  # "" = the link
    cutoff: float = 0.4  # depth and points only within (cutoff, cutoff_max), NaN elsewhere
    cutoff_max: float = 5.0
    pose: Tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    robot_namespace: str = ""
    # What gazebo_ros_camera_utils puts in camera_info from the plugin's tags (the picture does not change with them):
    # focalLength, Cx, Cy where not 0 (0: ours), P[3] = -fx hackBaseline, D = distortionK1, K2, K3, T1, T2 in that order.
    info_focal_length: float = 0.0
    info_cx: float = 0.0
    info_cy: float = 0.0
    hack_baseline: float = 0.0
    distortion: Tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)

    @property
    def encoding(self) -> str:
        return IMAGE_ENCODINGS.get(self.image_format, "rgb8")

    @property
    def focal_length(self) -> float:
        """fx = fy (pixels) as gazebo_ros_camera_utils computes it: width / (2 tan(hfov / 2))."""
        return self.width / (2.0 * math.tan(self.horizontal_fov / 2.0))


@dataclass
class SensorBlocks:
    """The sensors a URDF's ``<gazebo reference="link"><sensor>`` blocks define (with a ROS plugin), and warnings
    naming those that are not simulated."""

    lasers: List[LaserConfig] = field(default_factory=list)
    imus: List[ImuConfig] = field(default_factory=list)
    contacts: List[ContactConfig] = field(default_factory=list)
    cameras: List[CameraConfig] = field(default_factory=list)
    warnings: List[str] = field(default_factory=list)


def _rate(element: Optional[Element], tags: Sequence[str], default: float, what: str) -> float:
    for tag in tags:
        if child_text(element, tag) is not None:
            value = _float(element, tag, default, what)
            if value < 0:
                raise ModelError(f"{what} <{tag}> must be >= 0, got {value}")
            return value
    return default


def imu_config(filename: str, params: Mapping[str, str], link: str = "", sensor_rate: float = 0.0) -> ImuConfig:
    """gazebo_plugins' IMU plugin tags (``params``: tag -> text), as a model plugin or inside a <sensor> on
    ``link``; <bodyName> wins over ``link``, and a model plugin must have it."""
    what = f"<plugin filename='{filename}'>"
    body = (params.get("bodyName") or link).strip().split("::")[-1]
    if not body:
        raise ModelError(f"{what} needs <bodyName> (the link the IMU is on)")
    noise = read_number(params.get("gaussianNoise"), f"{what} <gaussianNoise>", 0.0, minimum=0.0)
    rate_tag = "updateRateHZ" if "updateRateHZ" in params else "updateRate"
    return ImuConfig(
        link=body,
        topic=(params.get("topicName") or "imu").strip(),
        frame=(params.get("frameName") or "").strip(),
        update_rate=read_number(params.get(rate_tag), f"{what} <{rate_tag}>", sensor_rate, minimum=0.0),
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
        topic=child_text(plugin, "bumperTopicName") or "bumper_states",
        frame=child_text(plugin, "frameName") or "world",
        update_rate=_rate(sensor, ("update_rate",), 0.0, what),
        robot_namespace=child_text(plugin, "robotNamespace") or "",
    )


def _sensor_pose(sensor: Element, what: str) -> Tuple[float, float, float, float, float, float]:
    pose_text = child_text(sensor, "pose")
    if pose_text is None:
        return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    try:
        pose = tuple(float(v) for v in pose_text.split())
    except ValueError:
        pose = ()
    if len(pose) != 6 or not all(math.isfinite(v) for v in pose):
        raise ModelError(f"{what} <pose> must be 6 finite numbers, got '{pose_text}'")
    for value in pose:  # within the world's lengths, not subnormal (physics.sanity)
        sanity.number(value, f"{what} <pose>", -sanity.MAX_LENGTH, sanity.MAX_LENGTH, ModelError)
    return pose  # type: ignore[return-value]


# A camera renders at most this many pixels: a 2048 x 2048 depth camera's buffers (cloud, depth, colour) take 190 MB
# and a frame about 0.1 s; the 8192 x 8192 each side may have would take 3 GB.
MAX_CAMERA_PIXELS = 2048 * 2048


def _int(element: Optional[Element], path: str, default: int, what: str) -> int:
    text = child_text(element, path)
    try:
        value = default if text is None else int(text)
    except ValueError:
        raise ModelError(f"{what} <{path}> must be an integer, got '{text}'") from None
    if not 1 <= value <= 8192:
        raise ModelError(f"{what} <{path}> must be in 1..8192, got {value}")
    return value


def _camera_config(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> CameraConfig:
    """A camera or depth <sensor> with its gazebo_ros plugin; ModelError for bad values."""
    name = sensor.get("name", "camera")
    what = f"<sensor name='{name}'>"
    camera = sensor.find("camera")
    depth = sensor.get("type") == "depth"
    defaults = CameraConfig(link)
    fov = _float(camera, "horizontal_fov", defaults.horizontal_fov, what)
    if not 0.0 < fov < math.pi:
        raise ModelError(f"{what} <horizontal_fov> must be in (0, pi), got {fov}")
    image_format = child_text(camera, "image/format") or defaults.image_format
    if image_format not in IMAGE_ENCODINGS:
        warnings.append(f"{what}: image format {image_format} is not simulated: published as rgb8")
    near = _float(camera, "clip/near", defaults.near, what)
    far = _float(camera, "clip/far", defaults.far, what)
    if not 0.0 < near < far or not math.isfinite(far):
        raise ModelError(f"{what} <clip> needs 0 < near < far, got {near}, {far}")
    noise = None if camera is None else camera.find("noise")
    gaussian = noise is not None and (child_text(noise, "type") or "gaussian").lower() == "gaussian"
    stddev = _float(noise, "stddev", 0.0, what) if gaussian else 0.0
    if stddev < 0:
        raise ModelError(f"{what} <noise><stddev> must be >= 0, got {stddev}")
    sensor_rate = _rate(sensor, ("update_rate",), 0.0, what)
    params = plugin_params(plugin)
    plugin_rate = read_number(params.get("updateRate"), f"{what} <updateRate>", 0.0, minimum=0.0)
    rates = [rate for rate in (sensor_rate, plugin_rate) if rate > 0]
    cutoff = read_number(params.get("pointCloudCutoff"), f"{what} <pointCloudCutoff>", defaults.cutoff, minimum=0.0)
    cutoff_max = read_number(
        params.get("pointCloudCutoffMax"), f"{what} <pointCloudCutoffMax>", defaults.cutoff_max, minimum=0.0
    )
    width = _int(camera, "image/width", defaults.width, what)
    height = _int(camera, "image/height", defaults.height, what)
    if width * height > MAX_CAMERA_PIXELS:
        raise ModelError(f"{what} <image> {width}x{height} is over {MAX_CAMERA_PIXELS} pixels (2048x2048)")

    def tag(name: str) -> float:
        return read_number(params.get(name) or None, f"{what} <{name}>", 0.0)

    given_focal, computed_focal = tag("focalLength"), width / (2.0 * math.tan(fov / 2.0))
    if given_focal and not math.isclose(given_focal, computed_focal, rel_tol=1e-6):
        warnings.append(
            f"{what}: <focalLength> {given_focal:g} is not width / (2 tan(horizontal_fov / 2)) = {computed_focal:g}: "
            "camera_info reports it, the picture is rendered with the FOV (as in Gazebo)"
        )
    distortion = tuple(
        tag(name) for name in ("distortionK1", "distortionK2", "distortionK3", "distortionT1", "distortionT2")
    )
    # The depth plugins' own defaults for the image topics (gazebo_ros_openni_kinect / _depth_camera).
    image_topic, info_topic = ("ir/image_raw", "ir/camera_info") if depth else ("image_raw", "camera_info")
    return CameraConfig(
        link=link,
        name=name,
        depth=depth,
        horizontal_fov=fov,
        width=width,
        height=height,
        image_format=image_format,
        near=near,
        far=far,
        noise_mean=_float(noise, "mean", 0.0, what) if gaussian else 0.0,
        noise_stddev=stddev,
        update_rate=min(rates) if rates else DEFAULT_CAMERA_RATE,
        camera_name=params.get("cameraName", "").strip("/"),
        image_topic=params.get("imageTopicName") or image_topic,
        info_topic=params.get("cameraInfoTopicName") or info_topic,
        depth_topic=params.get("depthImageTopicName") or defaults.depth_topic,
        depth_info_topic=params.get("depthImageCameraInfoTopicName") or defaults.depth_info_topic,
        points_topic=params.get("pointCloudTopicName") or defaults.points_topic,
        frame=params.get("frameName", ""),
        cutoff=cutoff,
        cutoff_max=cutoff_max,
        pose=_sensor_pose(sensor, what),
        robot_namespace=params.get("robotNamespace", ""),
        info_focal_length=given_focal,
        info_cx=tag("Cx"),
        info_cy=tag("Cy"),
        hack_baseline=tag("hackBaseline"),
        distortion=distortion,  # type: ignore[arg-type]
    )


def _add_sensor(found: SensorBlocks, link: str, sensor: Element) -> None:
    """One <sensor> on ``link`` (URDF and SDF write them alike): ray (``gpu_ray`` too), imu, contact, camera or
    depth."""
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
    elif kind in ("camera", "depth"):
        known = CAMERA_PLUGINS if kind == "camera" else DEPTH_PLUGINS
        chosen = [p for p in plugins if p.get("filename") in known]
        found.cameras += [_camera_config(link, sensor, p, found.warnings) for p in chosen]
        if not chosen:
            names = ", ".join(p.get("filename", "") for p in plugins) or "no plugin"
            found.warnings.append(
                f"<sensor name='{sensor.get('name', '')}' type='{kind}'> on link '{link}' has {names}, not one of "
                f"{', '.join(known)}: not published"
            )


def model_sensors(robot: RobotModel) -> SensorBlocks:
    """The sensors the parsed model carries (``robot.sensors``): ray (``gpu_ray`` too), imu, contact, camera and
    depth, with a ROS plugin; a warning names each sensor of another type (not simulated). ModelError for bad
    values, or a URDF sensor in a <gazebo> block that names no link of the model."""
    found = SensorBlocks()
    for block in robot.sensors:
        kind = block.element.get("type")
        if kind not in SIMULATED_TYPES:
            found.warnings.append(
                f"<sensor name='{block.element.get('name', '')}' type='{kind}'> on link '{block.link}' is not "
                f"simulated: no topics"
            )
            continue
        if block.link is None or block.link not in robot.links:
            raise ModelError(f"<sensor name='{block.element.get('name', '')}'> must be in a <gazebo reference=link>")
        _add_sensor(found, block.link, block.element)
    return found


def read_sensors(urdf: str) -> SensorBlocks:
    """The sensors of a URDF's ``<gazebo reference="link"><sensor>`` blocks (ModelError as parse_urdf's)."""
    return model_sensors(parse_urdf(urdf))


def read_sdf_sensors(sdf: str) -> SensorBlocks:
    """The ``<link><sensor>`` elements of an SDF model; a sensor's <pose> is in its link's frame, as in Gazebo."""
    return model_sensors(parse_sdf_model(sdf))
