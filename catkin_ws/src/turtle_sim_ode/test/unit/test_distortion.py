"""Lens distortion as gazebo-classic draws it (gazebo/rendering/Distortion.cc: Distortion::Distort, Brown's model in
texture coordinates about <center>; Distortion::SetCamera: barrel distortion, k1 < 0, is cropped by Distort(1, 1) -
Distort(0, 0)), camera_info's D as GazeboRosCameraUtils::Init orders it (k1, k2, p1, p2, k3; gazebo_plugins/src/
gazebo_ros_camera_utils.cpp), and the <distortion> tags as the camera plugins read them."""
from __future__ import annotations

import math
from typing import List

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.sensors.config import read_sdf_sensors
from turtle_sim_ode.sensors.distortion import DistortionMap, LensDistortion, distort, undistort

PINCUSHION = LensDistortion(k1=0.1, k2=0.1, k3=0.1)  # gazebo_plugins' test/camera/distortion_pincushion.world
BARREL = LensDistortion(k1=-0.1, k2=-0.1, k3=-0.1)  # and distortion_barrel.world


def test_distort_is_browns_model_about_the_centre() -> None:
    # Distortion::Distort by hand: n = (0.3, -0.1) from (0.5, 0.5), r^2 = 0.1.
    lens = LensDistortion(k1=0.2, k2=-0.05, k3=0.01, p1=0.003, p2=-0.004)
    x, y, r2 = 0.3, -0.1, 0.1
    radial = 1 + 0.2 * r2 - 0.05 * r2**2 + 0.01 * r2**3
    expected = (
        0.5 + x * radial + (-0.004) * (r2 + 2 * x * x) + 2 * 0.003 * x * y,
        0.5 + y * radial + 0.003 * (r2 + 2 * y * y) + 2 * (-0.004) * x * y,
    )
    assert distort(np.array([0.8, 0.4]), lens) == pytest.approx(expected, abs=1e-15)
    # The centre stays; an off-centre lens centre moves the fixed point with it.
    assert distort(np.array([0.5, 0.5]), lens) == pytest.approx((0.5, 0.5))
    shifted = LensDistortion(k1=0.3, center=(0.4, 0.6))
    assert distort(np.array([0.4, 0.6]), shifted) == pytest.approx((0.4, 0.6))


def test_pincushion_pushes_outward_and_barrel_pulls_inward() -> None:
    corner = np.array([1.0, 1.0])
    assert np.all(distort(corner, PINCUSHION) > 1.0)
    assert np.all(distort(corner, BARREL) < 1.0)
    # r^2 = 0.5 at the corner: 0.5 + 0.5 (1 - 0.05 - 0.025 - 0.0125)
    assert distort(corner, BARREL) == pytest.approx((0.5 + 0.5 * 0.9125,) * 2)


lenses = st.builds(
    LensDistortion,
    k1=st.floats(-0.2, 0.2),
    k2=st.floats(-0.1, 0.1),
    k3=st.floats(-0.05, 0.05),
    p1=st.floats(-0.01, 0.01),
    p2=st.floats(-0.01, 0.01),
    center=st.tuples(st.floats(0.4, 0.6), st.floats(0.4, 0.6)),
)


@settings(max_examples=60, deadline=None)
@given(lenses, st.lists(st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0)), min_size=1, max_size=20))
def test_undistort_inverts_distort(lens: LensDistortion, points: List[tuple]) -> None:
    uv = np.array(points)
    source, found = undistort(distort(uv, lens), lens)
    assert found.all()
    assert source == pytest.approx(uv, abs=1e-7)


def test_the_map_of_no_distortion_is_the_picture_itself() -> None:
    rgb = np.random.default_rng(1).integers(0, 256, (7, 9, 3), dtype=np.uint8)
    assert np.array_equal(DistortionMap.of(9, 7, LensDistortion()).apply(rgb), rgb)


def test_a_distorted_pixel_shows_the_pinhole_pixel_it_comes_from() -> None:
    width = height = 101
    rgb = np.zeros((height, width, 3), dtype=np.uint8)
    rgb[70, 80] = 255  # one lit pinhole pixel, texture coordinates ((80.5) / 101, (70.5) / 101)
    source = np.array([80.5 / width, 70.5 / height])
    for lens in (PINCUSHION, BARREL):
        picture = DistortionMap.of(width, height, lens, border_crop=False).apply(rgb)
        row, column = np.unravel_index(np.argmax(picture[:, :, 0]), picture.shape[:2])
        expected = distort(source, lens) * [width, height] - 0.5  # pixel coordinates of Distort(source)
        assert abs(column - expected[0]) <= 1.0 and abs(row - expected[1]) <= 1.0


def test_barrel_corners_are_black_without_border_crop_and_filled_with_it() -> None:
    rgb = np.full((50, 50, 3), 200, dtype=np.uint8)
    assert BARREL.barrel and not PINCUSHION.barrel
    uncropped = DistortionMap.of(50, 50, BARREL, border_crop=False).apply(rgb)
    assert np.all(uncropped[0, 0] == 0) and np.all(uncropped[25, 25] == 200)
    assert np.all(DistortionMap.of(50, 50, BARREL).apply(rgb) == 200)  # <borderCrop> true, the default: cropped
    for crop in (True, False):  # pincushion has no border to crop
        assert np.all(DistortionMap.of(50, 50, PINCUSHION, border_crop=crop).apply(rgb) == 200)


CAMERA = """<sdf version="1.6"><model name="m"><link name="l"><sensor type="camera" name="cam"><camera>
<image><width>40</width><height>30</height></image>{distortion}</camera>
<plugin name="p" filename="libgazebo_ros_camera.so">{tags}</plugin></sensor></link></model></sdf>"""
LENS = "<distortion><k1>-0.1</k1><k2>0.02</k2><k3>0.003</k3><p1>0.004</p1><p2>0.005</p2><center>0.4 0.6</center></distortion>"
TAGS = """<distortionK1>1</distortionK1><distortionK2>2</distortionK2><distortionK3>3</distortionK3>
<distortionT1>4</distortionT1><distortionT2>5</distortionT2>"""


def read_camera(distortion: str = "", tags: str = ""):  # type: ignore[no-untyped-def]
    sensors = read_sdf_sensors(CAMERA.format(distortion=distortion, tags=tags))
    (config,) = sensors.configs
    return config, sensors.warnings


def test_camera_info_d_is_k1_k2_t1_t2_k3() -> None:
    config, _ = read_camera(LENS, TAGS)
    assert config.distortion == (1, 2, 4, 5, 3)  # the plugin's tags, without <autoDistortion>
    assert config.lens == LensDistortion(-0.1, 0.02, 0.003, 0.004, 0.005, (0.4, 0.6))  # the picture's lens
    auto, _ = read_camera(LENS, TAGS + "<autoDistortion>true</autoDistortion>")
    assert auto.distortion == pytest.approx((-0.1, 0.02, 0.004, 0.005, 0.003))  # the lens's k1, k2, p1, p2, k3


def test_border_crop_is_read_with_the_plugins_default() -> None:
    assert read_camera(LENS)[0].border_crop  # GazeboRosCameraUtils::Load: true when missing
    assert not read_camera(LENS, "<borderCrop>false</borderCrop>")[0].border_crop


@pytest.mark.parametrize(
    "distortion, tags",
    [
        ("<distortion><center>0.5</center></distortion>", ""),
        ("<distortion><center>nan 0.5</center></distortion>", ""),
        ("<distortion><k1>x</k1></distortion>", ""),
        ("", "<autoDistortion>maybe</autoDistortion>"),
        ("", "<borderCrop>2</borderCrop>"),
    ],
)
def test_bad_distortion_tags_are_refused_by_name(distortion: str, tags: str) -> None:
    with pytest.raises(ModelError, match="distortion|autoDistortion|borderCrop"):
        read_camera(distortion, tags)


def test_depth_cameras_say_they_draw_no_distortion() -> None:
    sdf = CAMERA.replace('type="camera"', 'type="depth"').replace(
        "libgazebo_ros_camera.so", "libgazebo_ros_openni_kinect.so"
    )
    sensors = read_sdf_sensors(sdf.format(distortion=LENS, tags=""))
    (config,) = sensors.configs
    assert config.lens.identity and any("not drawn" in warning for warning in sensors.warnings)
    assert math.isclose(config.horizontal_fov, 1.047)
