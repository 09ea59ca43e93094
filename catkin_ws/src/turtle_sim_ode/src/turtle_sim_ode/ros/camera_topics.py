"""The ROS side of the camera plugins (libgazebo_ros_camera.so, libgazebo_ros_openni_kinect.so,
libgazebo_ros_depth_camera.so): sensor_msgs/Image, CameraInfo and PointCloud2 of a CameraSensor, all of one
rendering with one sim-time stamp, in the plugin's frameName. Nothing is rendered while no one subscribes to an
image, depth image or point cloud topic; camera_info alone costs no rendering."""
from __future__ import annotations

import struct
from io import BytesIO
from typing import Any, Callable, Dict, Optional, Sequence, Tuple

import numpy as np
import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField

from turtle_sim_ode.models.lights import Light
from turtle_sim_ode.ros.periodic import Periodic, packed_publisher, topic_prefix
from turtle_sim_ode.ros.wire import Packed, release
from turtle_sim_ode.sensors.camera import CLOUD_POINT_STEP, CameraSensor, Frame
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.scene import Scene

# sensor_msgs/PointCloud2 as gazebo_ros_openni_kinect lays it out (PointCloud2Modifier "xyz", "rgb"): x, y, z
# float32, 4 bytes of padding, rgb (a float32's bytes: b, g, r, 0 as PCL and rviz read them), padding to 32.
POINT_STEP = CLOUD_POINT_STEP
_UINT32 = struct.Struct("<I")
POINT_FIELDS = [
    PointField("x", 0, PointField.FLOAT32, 1),
    PointField("y", 4, PointField.FLOAT32, 1),
    PointField("z", 8, PointField.FLOAT32, 1),
    PointField("rgb", 16, PointField.FLOAT32, 1),
]


def camera_info(config: CameraConfig, frame: str, cx: float, cy: float) -> CameraInfo:
    """K and P of the pinhole the picture is rendered with (``config``'s size and FOV, principal point ``cx``, ``cy``),
    but where the plugin's tags say otherwise: gazebo_ros_camera_utils reports focalLength, Cx, Cy when not 0, Tx =
    -fx hackBaseline, and D (plumb_bob: k1, k2, t1, t2, k3) from distortionK1, K2, T1, T2, K3, or with
    <autoDistortion> from the lens (sensors.plugins.camera)."""
    f = config.info_focal_length or config.focal_length
    cx, cy = config.info_cx or cx, config.info_cy or cy
    info = CameraInfo()
    info.header.frame_id = frame
    info.width, info.height = config.width, config.height
    info.distortion_model = "plumb_bob"
    info.D = list(config.distortion)
    info.K = [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0]
    info.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    info.P = [f, 0.0, cx, -f * config.hack_baseline, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
    return info


def packer(message: Any) -> Callable[..., Packed]:
    """Packs ``message`` with a header seq and stamp, as genpy serialises it; with ``data`` (an array or bytes) as
    its uint8[] ``data`` field, and ``is_dense`` for a cloud. With ``data`` the message is in pieces around a view of
    the data, not copied (genpy would copy megabytes of a cloud four times): valid until the data changes."""

    def pack(seq: int, secs: int, nsecs: int, data: Any = None, is_dense: Optional[bool] = None) -> Packed:
        header = message.header
        header.seq, header.stamp.secs, header.stamp.nsecs = seq, secs, nsecs
        if is_dense is not None:
            message.is_dense = is_dense
        buffer = BytesIO()
        message.serialize(buffer)  # data empty: a length of 0, then is_dense for a cloud
        raw = buffer.getvalue()
        if data is None:
            return raw
        view = memoryview(np.ascontiguousarray(data)).cast("B") if isinstance(data, np.ndarray) else data
        tail = len(raw) - (1 if isinstance(message, PointCloud2) else 0)
        return (raw[: tail - 4], _UINT32.pack(len(view)), view, raw[tail:])

    return pack


# Bytes a pixel of each encoding a camera publishes.
BYTES_PER_PIXEL = {"mono8": 1, "mono16": 2, "rgb8": 3, "bgr8": 3, "rgb16": 6}
# Which RGB channel (0 red, 1 green, 2 blue) each Bayer encoding takes at (row % 2, column % 2): gazebo-classic's
# Camera::ConvertRGBToBAYER (gazebo/rendering/Camera.cc), whose GBRG8 and GRBG8 branches take
# G R / B G and G B / R G respectively.
BAYER_CHANNELS = {
    "bayer_rggb8": ((0, 1), (1, 2)),
    "bayer_bggr8": ((2, 1), (1, 0)),
    "bayer_gbrg8": ((1, 0), (2, 1)),
    "bayer_grbg8": ((1, 2), (0, 1)),
}
BYTES_PER_PIXEL.update({encoding: 1 for encoding in BAYER_CHANNELS})


def templates(sensor: CameraSensor) -> Dict[str, Any]:
    """The messages of a camera, but for stamps and data: image, info, and for a depth camera depth, depth_info
    and points."""
    config, frame = sensor.config, sensor.frame
    image = Image(encoding=config.encoding, height=config.height, width=config.width)
    image.step = config.width * BYTES_PER_PIXEL[config.encoding]
    # gazebo_ros_camera_utils.cpp (Init): Cx, Cy where the plugin gives none are (width + 1) / 2, (height + 1) / 2,
    # half a pixel right of and below the centre Gazebo renders about; depthimage_to_laserscan's angle bins fit them.
    cx, cy = (config.width + 1) / 2.0, (config.height + 1) / 2.0
    found = {"image": image, "info": camera_info(config, frame, cx, cy)}
    if config.depth:
        found["depth"] = Image(encoding="32FC1", height=config.height, width=config.width, step=4 * config.width)
        found["depth_info"] = camera_info(config, frame, cx, cy)
        cloud = PointCloud2(height=config.height, width=config.width, fields=POINT_FIELDS)
        cloud.point_step, cloud.row_step = POINT_STEP, POINT_STEP * config.width
        found["points"] = cloud
    for message in found.values():
        message.header.frame_id = frame
    return found


def colour_image(rgb: np.ndarray, encoding: str) -> np.ndarray:
    """The image's pixels in ``encoding`` (one of sensors.plugins.camera.IMAGE_ENCODINGS' values) from 8-bit RGB:
    16-bit channels little-endian (sensor_msgs/Image is_bigendian 0) with 255 as 65535; Bayer mosaics as
    gazebo-classic's Camera::ConvertRGBToBAYER samples the RGB image."""
    if encoding == "bgr8":
        return rgb[:, :, ::-1]
    if encoding in ("mono8", "mono16"):
        grey = rgb.astype(np.float32) @ np.array([0.299, 0.587, 0.114], dtype=np.float32)
        if encoding == "mono8":
            return (grey + 0.5).astype(np.uint8)
        return (grey * 257.0 + 0.5).astype("<u2")
    if encoding == "rgb16":
        return rgb.astype("<u2") * 257
    if encoding in BAYER_CHANNELS:
        return bayer(rgb, BAYER_CHANNELS[encoding])
    return rgb


def bayer(rgb: np.ndarray, channels: Tuple[Tuple[int, int], Tuple[int, int]]) -> np.ndarray:
    """One byte a pixel: the RGB channel ``channels[row % 2][column % 2]`` of each pixel."""
    mosaic = np.empty(rgb.shape[:2], dtype=np.uint8)
    for row in (0, 1):
        for column in (0, 1):
            mosaic[row::2, column::2] = rgb[row::2, column::2, channels[row][column]]
    return mosaic


class CameraPublisher(Periodic):
    """A camera or depth camera plugin's topics, under ``robotNamespace``/``cameraName`` as gazebo_ros has them."""

    def __init__(
        self,
        sensor: CameraSensor,
        scene: Scene,
        namespace: str,
        sun: Optional[Callable[[], Optional[Tuple[float, float, float]]]] = None,
        lights: Optional[Callable[[], Sequence[Light]]] = None,
    ) -> None:
        """``scene``: what the cameras see of the world's models (the simulation's); ``sun``: the direction of the
        world's directional light now, ``lights`` its other lights now (see CameraSensor.light_from), asked before
        each frame."""
        config = sensor.config
        super().__init__(1.0 / config.update_rate)
        self._sensor = sensor
        self._scene = scene
        self._sun = sun
        self._lights = lights
        self._prefix = topic_prefix(namespace) + topic_prefix(config.camera_name)
        topic = self.topic
        messages = templates(sensor)
        self._image = (packed_publisher(topic(config.image_topic), Image), packer(messages["image"]))
        self._info = (packed_publisher(topic(config.info_topic), CameraInfo), packer(messages["info"]))
        self._channels = [self._image, self._info]
        self._depth = self._depth_info = self._points = None
        if config.depth:
            self._depth = (packed_publisher(topic(config.depth_topic), Image), packer(messages["depth"]))
            depth_info = packer(messages["depth_info"])
            self._depth_info = (packed_publisher(topic(config.depth_info_topic), CameraInfo), depth_info)
            self._points = (packed_publisher(topic(config.points_topic), PointCloud2), packer(messages["points"]))
            self._channels += [self._depth, self._depth_info, self._points]
        self.rendered = 0  # renderings made: none while no image, depth or cloud subscriber listens

    def topic(self, name: str) -> str:
        """A topic of the camera's: under ``robotNamespace``/``cameraName``; an absolute name stays as it is."""
        return name if name.startswith("/") else self._prefix + name

    @staticmethod
    def _heard(channel: Optional[tuple]) -> bool:
        return channel is not None and channel[0].heard()

    def publish(self, stamp: rospy.Time, now: float) -> None:
        self.send(stamp, self.render())

    def render(self) -> Optional[Frame]:
        """A frame of the world now, None while no image, depth image or cloud has a subscriber."""
        if not any(self._heard(c) for c in (self._image, self._depth, self._points)):
            return None
        if self._sun is not None:
            self._sensor.light_from(self._sun(), self._lights() if self._lights is not None else ())
        frame: Frame = self._sensor.render(self._scene)
        self.rendered += 1
        for warning in self._scene.take_warnings():
            rospy.logwarn("camera %s: %s", self._sensor.config.camera_name, warning)
        return frame

    def send(self, stamp: rospy.Time, frame: Optional[Frame]) -> None:
        """camera_info (and depth camera_info) to their subscribers, and the frame's image, depth image and cloud."""
        secs, nsecs = stamp.secs, stamp.nsecs
        for channel in (self._info, self._depth_info):
            if self._heard(channel):
                channel[0].publish(channel[1], secs, nsecs)
        if frame is None:
            return
        image, depth, points = (self._heard(c) for c in (self._image, self._depth, self._points))
        if image:
            rgb = colour_image(frame.rgb, self._sensor.config.encoding)
            self._image[0].publish(self._image[1], secs, nsecs, rgb)
        if not (depth or points):
            return
        depth_image, cloud, dense = self._sensor.organised_cloud(frame)
        if depth:
            self._depth[0].publish(self._depth[1], secs, nsecs, depth_image)  # type: ignore[index]
        if points:
            self._points[0].publish(self._points[1], secs, nsecs, cloud, dense)  # type: ignore[index]

    def close(self) -> None:
        for publisher, _ in self._channels:
            release(publisher)
