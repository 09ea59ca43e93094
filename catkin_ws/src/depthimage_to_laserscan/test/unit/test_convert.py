"""The depth-to-scan conversion, without ROS. Expected behaviour from ros-perception/depthimage_to_laserscan
(melodic-devel) src/DepthImageToLaserScan.cpp: convert_msg (angle_min/max from the edge columns' rays against the
principal point's, angle_increment over width - 1, the scan_height check) and use_point (shortest in-range range
wins; +-inf beats NaN); include/.../DepthImageToLaserScan.h convert (range hypot(x, z), 16UC1 in millimetres)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from depthimage_to_laserscan.convert import ConversionError, _better, convert, depth_array

FX, CX, CY = 554.25, 319.5, 239.5  # a 640 x 480 camera with a 60 degree field of view


def flat_wall(distance: float, width: int = 640, height: int = 480) -> np.ndarray:
    return np.full((height, width), distance)


def test_angles_from_the_principal_point():
    scan = convert(flat_wall(2.0), FX, CX, CY, 1, 0.45, 10.0)
    assert scan.angle_max == pytest.approx(math.atan2(CX, FX))
    assert scan.angle_min == pytest.approx(-math.atan2(639 - CX, FX))
    assert scan.angle_increment == pytest.approx((scan.angle_max - scan.angle_min) / 639)
    assert len(scan.ranges) == 640


def test_a_flat_wall_reads_its_distance_over_the_cosine():
    scan = convert(flat_wall(2.0), FX, CX, CY, 10, 0.45, 10.0)
    centre = scan.ranges[320]
    assert centre == pytest.approx(math.hypot((320 - CX) * 2.0 / FX, 2.0), rel=1e-6)
    edge = scan.ranges[0]
    assert edge == pytest.approx(math.hypot(CX * 2.0 / FX, 2.0), rel=1e-3) or math.isnan(edge)


def test_the_nearest_row_wins_within_the_band():
    depth = flat_wall(3.0)
    depth[int(CY)] = 1.0  # one row of the 10 is nearer
    assert convert(depth, FX, CX, CY, 10, 0.45, 10.0).ranges[320] == pytest.approx(1.0, rel=1e-3)
    depth[int(CY)] = 0.3  # below range_min: ignored
    assert convert(depth, FX, CX, CY, 10, 0.45, 10.0).ranges[320] == pytest.approx(3.0, rel=1e-3)


def test_use_point_rules():
    inf, nan = math.inf, math.nan
    assert _better(inf, nan, 0.45, 10) == inf
    assert math.isnan(_better(nan, nan, 0.45, 10))
    assert _better(2.0, inf, 0.45, 10) == 2.0
    assert _better(2.0, 1.0, 0.45, 10) == 1.0
    assert _better(11.0, nan, 0.45, 10) is nan or math.isnan(_better(11.0, nan, 0.45, 10))


def test_scan_height_too_large_is_refused():
    with pytest.raises(ConversionError, match="too large for the image height"):
        convert(flat_wall(2.0, height=8), FX, CX, 3.5, 10, 0.45, 10.0)


def test_16uc1_is_millimetres_and_zero_is_no_reading():
    data = np.array([[0, 1500, 2000]], dtype="<u2").tobytes()
    depth = depth_array(data, "16UC1", 3, 1, 6, False)
    assert math.isnan(depth[0, 0]) and depth[0, 1] == pytest.approx(1.5) and depth[0, 2] == pytest.approx(2.0)
    with pytest.raises(ConversionError, match="unsupported encoding: rgb8"):
        depth_array(b"\0" * 9, "rgb8", 3, 1, 9, False)
    with pytest.raises(ConversionError):
        depth_array(b"\0" * 5, "16UC1", 3, 1, 6, False)  # truncated


@settings(max_examples=100, deadline=None)
@given(st.lists(st.one_of(st.floats(0.0, 12.0), st.just(math.nan), st.just(math.inf)), min_size=64, max_size=64))
def test_every_range_is_in_bounds_or_not_finite(row):
    """Invariant: each range is NaN, +-inf, or within [range_min, range_max]."""
    depth = np.tile(np.array(row, dtype=np.float64), (4, 1))
    scan = convert(depth, 55.4, 31.5, 1.5, 2, 0.45, 10.0)
    finite = scan.ranges[np.isfinite(scan.ranges)]
    assert np.all((finite >= np.float32(0.45)) & (finite <= np.float32(10.0)))
