"""gazebo_plugins' cameras: ``libgazebo_ros_camera.so`` in a ``camera`` sensor, ``libgazebo_ros_openni_kinect.so`` /
``libgazebo_ros_depth_camera.so`` in a ``depth`` sensor; their tags and defaults. The picture is sensors.camera's."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.text import ModelError, child_text, plugin_params, read_number, robot_namespace_tag
from turtle_sim_ode.sensors.distortion import LensDistortion
from turtle_sim_ode.sensors.sensor_element import int_at, number_at, rate_at, sensor_pose, sensor_what

# gazebo_ros_triggered_camera: a frame for each message on <triggerTopicName> (image_trigger), as camera_utils has it.
TRIGGERED_CAMERA = "libgazebo_ros_triggered_camera.so"
CAMERA_PLUGINS = ("libgazebo_ros_camera.so", TRIGGERED_CAMERA)
DEPTH_PLUGINS = ("libgazebo_ros_openni_kinect.so", "libgazebo_ros_depth_camera.so")
SENSOR_PLUGINS = {**{name: ("camera",) for name in CAMERA_PLUGINS}, **{name: ("depth",) for name in DEPTH_PLUGINS}}
# <image><format> -> sensor_msgs encoding, as gazebo_ros_camera_utils.cpp (GazeboRosCameraUtils::Init) maps them;
# any other format is published as bgr8 there (with an error), and here (with a warning).
IMAGE_ENCODINGS = {
    "L8": "mono8",
    "L_INT8": "mono8",
    "L16": "mono16",
    "L_INT16": "mono16",
    "R8G8B8": "rgb8",
    "RGB_INT8": "rgb8",
    "B8G8R8": "bgr8",
    "BGR_INT8": "bgr8",
    "R16G16B16": "rgb16",
    "RGB_INT16": "rgb16",
    "BAYER_RGGB8": "bayer_rggb8",
    "BAYER_BGGR8": "bayer_bggr8",
    "BAYER_GBRG8": "bayer_gbrg8",
    "BAYER_GRBG8": "bayer_grbg8",
}
UNKNOWN_FORMAT_ENCODING = "bgr8"
# A camera whose <sensor><update_rate> and plugin <updateRate> are both 0 (Gazebo: as fast as it renders).
DEFAULT_CAMERA_RATE = 30.0


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
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>
    # What gazebo_ros_camera_utils puts in camera_info from the plugin's tags (the picture does not change with them):
    # focalLength, Cx, Cy where not 0 (0: ours), P[3] = -fx hackBaseline, D = distortionK1, K2, T1, T2, K3 (in that
    # order; with <autoDistortion> the lens's k1, k2, p1, p2, k3 instead).
    info_focal_length: float = 0.0
    info_cx: float = 0.0
    info_cy: float = 0.0
    hack_baseline: float = 0.0
    distortion: Tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)
    lens: LensDistortion = LensDistortion()  # <camera><distortion>: drawn in the picture (sensors.distortion)
    border_crop: bool = True  # <borderCrop>: GazeboRosCameraUtils passes it to Distortion::SetCrop
    triggered: bool = False  # libgazebo_ros_triggered_camera.so: frames only when triggered
    trigger_topic: str = "image_trigger"

    @property
    def encoding(self) -> str:
        return IMAGE_ENCODINGS.get(self.image_format, UNKNOWN_FORMAT_ENCODING)

    @property
    def focal_length(self) -> float:
        """fx = fy (pixels) as gazebo_ros_camera_utils computes it: width / (2 tan(hfov / 2))."""
        return self.width / (2.0 * math.tan(self.horizontal_fov / 2.0))


# A camera renders at most this many pixels: a 2048 x 2048 depth camera's buffers (cloud, depth, colour) take 190 MB
# and a frame about 0.1 s; the 8192 x 8192 each side may have would take 3 GB.
MAX_CAMERA_PIXELS = 2048 * 2048


def read(link: str, sensor: Element, plugin: Element, warnings: List[str]) -> CameraConfig:
    """A camera or depth <sensor> with its gazebo_ros plugin; ModelError for bad values."""
    name, what = sensor_what(sensor, "camera")
    camera = sensor.find("camera")
    depth = sensor.get("type") == "depth"
    defaults = CameraConfig(link)
    fov = number_at(camera, "horizontal_fov", defaults.horizontal_fov, what)
    if not 0.0 < fov < math.pi:
        raise ModelError(f"{what} <horizontal_fov> must be in (0, pi), got {fov}")
    image_format = child_text(camera, "image/format") or defaults.image_format
    if image_format not in IMAGE_ENCODINGS:
        warnings.append(
            f"{what}: image format {image_format} is not one gazebo_ros knows: published as "
            f"{UNKNOWN_FORMAT_ENCODING}, as gazebo_ros does"
        )
    near = number_at(camera, "clip/near", defaults.near, what)
    far = number_at(camera, "clip/far", defaults.far, what)
    if not 0.0 < near < far or not math.isfinite(far):
        raise ModelError(f"{what} <clip> needs 0 < near < far, got {near}, {far}")
    noise = None if camera is None else camera.find("noise")
    gaussian = noise is not None and (child_text(noise, "type") or "gaussian").lower() == "gaussian"
    stddev = number_at(noise, "stddev", 0.0, what) if gaussian else 0.0
    if stddev < 0:
        raise ModelError(f"{what} <noise><stddev> must be >= 0, got {stddev}")
    sensor_rate = rate_at(sensor, ("update_rate",), 0.0, what)
    params = plugin_params(plugin)
    plugin_rate = read_number(params.get("updateRate"), f"{what} <updateRate>", 0.0, minimum=0.0)
    rates = [rate for rate in (sensor_rate, plugin_rate) if rate > 0]
    cutoff = read_number(params.get("pointCloudCutoff"), f"{what} <pointCloudCutoff>", defaults.cutoff, minimum=0.0)
    cutoff_max = read_number(
        params.get("pointCloudCutoffMax"), f"{what} <pointCloudCutoffMax>", defaults.cutoff_max, minimum=0.0
    )
    width = int_at(camera, "image/width", defaults.width, what)
    height = int_at(camera, "image/height", defaults.height, what)
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
    lens = lens_distortion(camera, what, depth, warnings)
    if read_bool(params.get("autoDistortion"), f"{what} <autoDistortion>"):
        distortion = lens.ros_coefficients()
    else:
        distortion = tuple(
            tag(name) for name in ("distortionK1", "distortionK2", "distortionT1", "distortionT2", "distortionK3")
        )
    border_crop = read_bool(params.get("borderCrop") or "true", f"{what} <borderCrop>")
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
        noise_mean=number_at(noise, "mean", 0.0, what) if gaussian else 0.0,
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
        pose=sensor_pose(sensor, what),
        robot_namespace=robot_namespace_tag(params),
        triggered=plugin.get("filename") == TRIGGERED_CAMERA,
        trigger_topic=params.get("triggerTopicName") or "image_trigger",
        info_focal_length=given_focal,
        info_cx=tag("Cx"),
        info_cy=tag("Cy"),
        hack_baseline=tag("hackBaseline"),
        distortion=distortion,  # type: ignore[arg-type]
        lens=LensDistortion() if depth else lens,
        border_crop=border_crop,
    )


def read_bool(text: Optional[str], what: str) -> bool:
    """An SDF bool (true/false/1/0, absent: false); ModelError naming ``what`` otherwise."""
    value = (text or "false").strip().lower()
    if value not in ("true", "false", "1", "0"):
        raise ModelError(f"{what} must be true or false, got '{text}'")
    return value in ("true", "1")


def lens_distortion(camera: Optional[Element], what: str, depth: bool, warnings: List[str]) -> LensDistortion:
    """``<camera><distortion>`` (absent: none). A depth camera's is not drawn (a warning says so)."""
    element = None if camera is None else camera.find("distortion")
    if element is None:
        return LensDistortion()
    center = (child_text(element, "center") or "0.5 0.5").split()
    try:
        centre = (float(center[0]), float(center[1]))
    except (ValueError, IndexError):
        raise ModelError(f"{what} <distortion><center> must be two numbers, got '{' '.join(center)}'") from None
    if not all(math.isfinite(value) for value in centre):
        raise ModelError(f"{what} <distortion><center> must be finite, got {centre}")
    where = f"{what} <distortion>"
    lens = LensDistortion(*(number_at(element, name, 0.0, where) for name in ("k1", "k2", "k3", "p1", "p2")), centre)
    if depth and not lens.identity:
        warnings.append(f"{what}: <distortion> is not drawn in a depth camera's pictures here")
    return lens


def without_plugin(link: str, sensor: Element, warnings: List[str]) -> None:
    """A camera or depth sensor without one of the plugins above renders nothing: a warning names it."""
    kind = sensor.get("type", "")
    known = [name for name, types in SENSOR_PLUGINS.items() if kind in types]
    names = ", ".join(p.get("filename", "") for p in sensor.findall("plugin")) or "no plugin"
    warnings.append(
        f"<sensor name='{sensor.get('name', '')}' type='{kind}'> on link '{link}' has {names}, not one of "
        f"{', '.join(known)}: not published"
    )
