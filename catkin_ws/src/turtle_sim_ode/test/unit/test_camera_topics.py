"""The camera plugins' ROS adapter without a master: publishers stand in for rospy's, the packed messages are read
back with genpy; nothing is rendered while no one subscribes to an image, depth image or cloud."""
from __future__ import annotations

import dataclasses
import io
import math
import struct
from typing import Dict, List

import numpy as np
import pytest
import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2
from test_camera import WAFFLE, camera_world

from turtle_sim_ode.ros import camera_topics, periodic
from turtle_sim_ode.ros.wire import joined
from turtle_sim_ode.sensors.config import read_sensors
from turtle_sim_ode.sensors.trigger import TRIGGERED_FRAME_DELAY_S


class FakePublisher:
    """A PackedPublisher's interface: counts of subscribers set by the test, messages kept as genpy objects."""

    made: Dict[str, "FakePublisher"] = {}

    def __init__(self, topic: str, data_class: type) -> None:
        self.topic, self.data_class = topic, data_class
        self.connections = 0
        self.messages: List = []
        FakePublisher.made[topic] = self

    def heard(self) -> bool:
        return self.connections > 0

    def publish(self, pack, *fields) -> None:
        message = self.data_class()
        message.deserialize(joined(pack(len(self.messages) + 1, *fields)))
        self.messages.append(message)

    def unregister(self) -> None:
        pass


@pytest.fixture
def publisher(monkeypatch):
    FakePublisher.made = {}
    monkeypatch.setattr(periodic, "PackedPublisher", FakePublisher)  # camera topics are advertised there
    monkeypatch.setattr(camera_topics, "release", lambda handle: None)
    sim, camera = camera_world(width=64, height=48)
    return camera_topics.CameraPublisher(camera, sim.scene, "robot"), camera


def test_topics_follow_robot_namespace_and_camera_name(publisher) -> None:
    assert set(FakePublisher.made) == {
        "robot/cam/ir/image_raw",
        "robot/cam/ir/camera_info",
        "robot/cam/depth/image_raw",
        "robot/cam/depth/camera_info",
        "robot/cam/points",
    }


def test_nothing_is_rendered_unheard_and_camera_info_alone_renders_nothing(publisher) -> None:
    camera_publisher, camera = publisher
    stamp = rospy.Time(3, 5)
    camera_publisher.publish(stamp, 3.0)
    assert camera_publisher.rendered == 0 and not any(p.messages for p in FakePublisher.made.values())
    FakePublisher.made["robot/cam/ir/camera_info"].connections = 1
    camera_publisher.publish(stamp, 3.0)
    assert camera_publisher.rendered == 0
    info: CameraInfo = FakePublisher.made["robot/cam/ir/camera_info"].messages[0]
    f = 64 / (2 * math.tan(1.047 / 2))
    assert info.K[0] == pytest.approx(f) and info.K[4] == pytest.approx(f)
    # gazebo_ros_camera_utils.cpp, Init: cx_ = (width + 1) / 2, cy_ = (height + 1) / 2 where the plugin gives none
    assert (info.K[2], info.K[5], info.P[2], info.P[6]) == (32.5, 24.5, 32.5, 24.5)
    assert (info.width, info.height, info.header.frame_id, list(info.D)) == (64, 48, "cam_optical", [0.0] * 5)


def test_one_rendering_feeds_image_depth_and_cloud_with_one_stamp(publisher) -> None:
    camera_publisher, camera = publisher
    for topic in ("robot/cam/ir/image_raw", "robot/cam/depth/image_raw", "robot/cam/points"):
        FakePublisher.made[topic].connections = 1
    camera_publisher.publish(rospy.Time(3, 5), 3.0)
    assert camera_publisher.rendered == 1
    image: Image = FakePublisher.made["robot/cam/ir/image_raw"].messages[0]
    depth: Image = FakePublisher.made["robot/cam/depth/image_raw"].messages[0]
    cloud: PointCloud2 = FakePublisher.made["robot/cam/points"].messages[0]
    for message in (image, depth, cloud):
        assert (message.header.stamp.secs, message.header.stamp.nsecs) == (3, 5)
        assert message.header.frame_id == "cam_optical"
        assert (message.height, message.width) == (48, 64)
    assert (image.encoding, image.step, len(image.data)) == ("rgb8", 64 * 3, 64 * 48 * 3)
    assert image.data[(24 * 64 + 32) * 3] > 2 * image.data[(24 * 64 + 32) * 3 + 1]  # red box ahead
    assert (depth.encoding, depth.step) == ("32FC1", 64 * 4)
    depths = np.frombuffer(depth.data, dtype="<f4").reshape(48, 64)
    assert depths[24, 32] == pytest.approx(1.5, abs=0.01) and math.isnan(depths[0, 32])
    assert [(f.name, f.offset, f.datatype) for f in cloud.fields] == [
        ("x", 0, 7),
        ("y", 4, 7),
        ("z", 8, 7),
        ("rgb", 16, 7),
    ]
    assert (cloud.point_step, cloud.row_step, cloud.is_dense, cloud.is_bigendian) == (32, 32 * 64, False, False)
    offset = (24 * 64 + 32) * 32
    x, y, z = struct.unpack_from("<3f", cloud.data, offset)
    assert z == pytest.approx(1.5, abs=0.01)
    b, g, r = cloud.data[offset + 16 : offset + 19]
    assert r > 2 * max(g, b)  # packed as PCL reads rgb: 0x00RRGGBB in a little-endian float


def test_the_spliced_data_is_byte_for_byte_what_genpy_writes(publisher) -> None:
    _, camera = publisher
    messages = camera_topics.templates(camera)
    data = np.arange(2 * 3 * 32, dtype=np.uint8).reshape(2, 3, 32)
    for key, extra in (("image", ()), ("depth", ()), ("points", (False,))):
        message = messages[key]
        packed = joined(camera_topics.packer(message)(7, 8, 9, data, *extra))
        message.data = data.tobytes()
        buffer = io.BytesIO()
        message.serialize(buffer)
        assert packed == buffer.getvalue(), key


def test_a_plain_camera_has_image_and_info_only_in_its_format(monkeypatch) -> None:
    FakePublisher.made = {}
    monkeypatch.setattr(periodic, "PackedPublisher", FakePublisher)  # camera topics are advertised there
    sim, camera = camera_world(kind="camera", plugin="libgazebo_ros_camera.so", width=40, height=30)
    camera.config = dataclasses.replace(camera.config, image_format="L8")
    camera_publisher = camera_topics.CameraPublisher(camera, sim.scene, "")
    assert set(FakePublisher.made) == {"cam/image_raw", "cam/camera_info"}
    FakePublisher.made["cam/image_raw"].connections = 1
    camera_publisher.publish(rospy.Time(1, 0), 1.0)
    image: Image = FakePublisher.made["cam/image_raw"].messages[0]
    assert (image.encoding, image.step, len(image.data), camera_publisher.rendered) == ("mono8", 40, 1200, 1)


def test_camera_info_carries_the_plugins_baseline_distortion_and_lens_tags_as_gazebo_ros() -> None:
    """The first of a repeated tag counts (sdformat's GetElement): the waffle's second <hackBaseline>0 does not."""
    urdf = WAFFLE.replace("</plugin>", "<hackBaseline>0</hackBaseline></plugin>")
    urdf = urdf.replace("<distortionK1>0.0</distortionK1>", "<distortionK1>0.1</distortionK1>")
    urdf = urdf.replace("<distortionK3>0.0</distortionK3>", "<distortionK3>0.3</distortionK3>")
    urdf = urdf.replace("<distortionT2>0.0</distortionT2>", "<distortionT2>0.5</distortionT2>")
    urdf = urdf.replace("<Cx>0.0</Cx>", "<Cx>81.5</Cx>").replace(
        "<focalLength>0</focalLength>", "<focalLength>100</focalLength>"
    )
    blocks = read_sensors(urdf)
    config = blocks.cameras[0]
    info = camera_topics.camera_info(config, "optical", 79.5, 59.5)
    assert info.K == [100.0, 0.0, 81.5, 0.0, 100.0, 59.5, 0.0, 0.0, 1.0]
    assert info.P[3] == pytest.approx(-100.0 * 0.07)
    # D = {k1, k2, t1, t2, k3}: GazeboRosCameraUtils::Init (gazebo_plugins/src/gazebo_ros_camera_utils.cpp)
    assert list(info.D) == [0.1, 0.0, 0.0, 0.5, 0.3]
    assert any("<focalLength> 100" in warning for warning in blocks.warnings), blocks.warnings
    plain = camera_topics.camera_info(
        read_sensors(WAFFLE.replace("<hackBaseline>0.07", "<hackBaseline>0")).cameras[0], "o", 79.5, 59.5
    )
    assert plain.P[3] == 0.0 and list(plain.D) == [0.0] * 5 and plain.K[2] == 79.5


# <image><format> -> (encoding, bytes a pixel): gazebo_plugins/src/gazebo_ros_camera_utils.cpp,
# GazeboRosCameraUtils::Init (type_ and skip_); an unknown format is published as bgr8 there.
FORMATS = [
    ("R8G8B8", "rgb8", 3),
    ("RGB_INT8", "rgb8", 3),
    ("B8G8R8", "bgr8", 3),
    ("BGR_INT8", "bgr8", 3),
    ("L8", "mono8", 1),
    ("L_INT8", "mono8", 1),
    ("L16", "mono16", 2),
    ("L_INT16", "mono16", 2),
    ("R16G16B16", "rgb16", 6),
    ("RGB_INT16", "rgb16", 6),
    ("BAYER_RGGB8", "bayer_rggb8", 1),
    ("BAYER_BGGR8", "bayer_bggr8", 1),
    ("BAYER_GBRG8", "bayer_gbrg8", 1),
    ("BAYER_GRBG8", "bayer_grbg8", 1),
    ("FLOAT32", "bgr8", 3),
]


@pytest.mark.parametrize("image_format, encoding, size", FORMATS)
def test_every_format_gazebo_ros_knows_is_published_in_its_encoding(publisher, image_format, encoding, size) -> None:
    camera_publisher, camera = publisher
    camera.config = dataclasses.replace(camera.config, image_format=image_format)
    camera_publisher = camera_topics.CameraPublisher(camera, camera_publisher._scene, "robot")
    FakePublisher.made["robot/cam/ir/image_raw"].connections = 1
    camera_publisher.publish(rospy.Time(3, 5), 3.0)
    image: Image = FakePublisher.made["robot/cam/ir/image_raw"].messages[0]
    assert (image.encoding, image.step, len(image.data), image.is_bigendian) == (encoding, 64 * size, 64 * 48 * size, 0)


def channel(rgb: np.ndarray, encoding: str) -> np.ndarray:
    return camera_topics.colour_image(rgb, encoding)


def test_sixteen_bit_encodings_scale_255_to_65535_little_endian() -> None:
    rgb = np.array([[[255, 0, 128]]], dtype=np.uint8)
    assert channel(rgb, "rgb16").tobytes() == struct.pack("<3H", 65535, 0, 128 * 257)
    assert channel(np.full((1, 1, 3), 255, np.uint8), "mono16").tobytes() == struct.pack("<H", 65535)
    assert channel(np.full((1, 1, 3), 200, np.uint8), "mono8").tobytes() == bytes([200])


# At (row % 2, column % 2): the channel gazebo-classic's Camera::ConvertRGBToBAYER (gazebo/rendering/Camera.cc) takes
# from the R8G8B8 rendering for each format (its loops: i the column, j the row).
@pytest.mark.parametrize(
    "encoding, layout",
    [
        ("bayer_rggb8", ("RG", "GB")),
        ("bayer_bggr8", ("BG", "GR")),
        ("bayer_gbrg8", ("GR", "BG")),
        ("bayer_grbg8", ("GB", "RG")),
    ],
)
def test_bayer_mosaics_sample_the_channels_as_gazebo_does(encoding, layout) -> None:
    rgb = np.zeros((4, 6, 3), dtype=np.uint8)
    rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2] = 10, 20, 30  # R, G, B
    mosaic = channel(rgb, encoding)
    value = {"R": 10, "G": 20, "B": 30}
    for row in range(4):
        for column in range(6):
            assert mosaic[row, column] == value[layout[row % 2][column % 2]], (row, column)


def test_a_triggered_frame_is_taken_at_its_step_and_sent_a_fixed_sim_time_later(monkeypatch) -> None:
    """GazeboRosTriggeredCamera: a frame a trigger, none untriggered. Here the frame shows (and is stamped with) the
    first step after the trigger and reaches subscribers TRIGGERED_FRAME_DELAY_S of sim time later, whatever the
    rendering's wall time (sensors.trigger); after each rendering the node is told not to catch its wall time up."""
    from turtle_sim_ode.ros.plugins import camera as camera_plugin

    FakePublisher.made = {}
    monkeypatch.setattr(periodic, "PackedPublisher", FakePublisher)
    monkeypatch.setattr(camera_plugin, "subscriber", lambda *args: None)
    monkeypatch.setattr(camera_plugin, "release", lambda handle: None)
    sim, camera = camera_world(kind="camera", plugin="libgazebo_ros_camera.so", width=16, height=12)
    paced_from = []  # sim time stood still for each rendering: the node paces on from its end
    triggered = camera_plugin.TriggeredCameraPublisher(
        camera, sim.scene, "", pace_from_now=lambda: paced_from.append(triggered.rendered)
    )
    images = FakePublisher.made["cam/image_raw"]
    images.connections = 1
    delay = TRIGGERED_FRAME_DELAY_S

    def step(now: float) -> None:
        triggered.publish(periodic.sim_stamp(now), now)

    step(1.0)  # no trigger: nothing rendered
    triggered.frames.trigger()
    triggered.frames.trigger()
    step(1.001)  # the first frame rendered, held until 1.001 + delay
    step(1.002)  # the second
    step(1.0005 + delay)
    assert triggered.rendered == 2 and images.messages == []
    step(1.001 + delay)
    assert [message.header.stamp.to_sec() for message in images.messages] == pytest.approx([1.001])
    step(1.002 + delay)
    assert [message.header.stamp.to_sec() for message in images.messages] == pytest.approx([1.001, 1.002])
    step(1.5)
    assert triggered.rendered == 2 and len(images.messages) == 2  # a frame a trigger
    assert paced_from == [1, 2]
