"""pointcloud_to_laserscan's projection and parameters, as PointCloudToLaserScanNodelet (lunar-devel 1.4.1,
src/pointcloud_to_laserscan_nodelet.cpp) has them: onInit's defaults, cloudCb's bins and filters."""
import math
import struct
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "src"))

from pointcloud_to_laserscan_dropin.scan import DOUBLE_MAX, ParamError, ScanParams, cloud_xyz, project  # noqa: E402


def test_defaults_are_on_init_s() -> None:
    params = ScanParams()
    assert (params.angle_min, params.angle_max, params.angle_increment) == (-math.pi, math.pi, math.pi / 180)
    assert params.min_height == sys.float_info.min and params.max_height == DOUBLE_MAX  # numeric_limits min / max
    assert (params.range_min, params.range_max, params.scan_time) == (0.0, DOUBLE_MAX, 1 / 30)
    assert (params.use_inf, params.inf_epsilon, params.concurrency_level, params.target_frame) == (True, 1.0, 1, "")
    assert params.bins == 360  # ceil(2 pi / (pi / 180))


def test_nearest_point_per_bin_within_the_band() -> None:
    params = ScanParams(min_height=0.2, max_height=1.0, angle_min=-1.5708, angle_max=1.5708, angle_increment=0.0087)
    points = np.array(
        [
            [2.0, 0.0, 0.5],  # ahead, 2 m
            [3.0, 0.0, 0.5],  # the same bin, farther: not kept
            [1.0, 0.0, 1.5],  # above max_height
            [1.0, 0.0, 0.1],  # below min_height
            [-1.0, 0.0, 0.5],  # behind: outside the angles
            [0.0, 1.0, 0.5],  # left, 1 m
            [np.nan, 0.0, 0.5],
        ]
    )
    ranges = project(points, params)
    assert len(ranges) == math.ceil(3.1416 / 0.0087)
    ahead = int((0.0 + 1.5708) / 0.0087)
    left = int((math.pi / 2 + 1.5708) / 0.0087)
    assert ranges[ahead] == pytest.approx(2.0)
    assert ranges[min(left, len(ranges) - 1)] == pytest.approx(1.0)
    assert np.isinf(np.delete(ranges, [ahead, min(left, len(ranges) - 1)])).all()


def test_use_inf_false_fills_range_max_plus_epsilon_and_default_min_height_drops_the_floor() -> None:
    params = ScanParams(use_inf=False, range_max=10.0, inf_epsilon=1.0)
    ranges = project(np.array([[1.0, 0.0, 0.0], [2.0, 0.5, 0.3]]), params)
    assert ranges.max() == 11.0
    assert np.count_nonzero(ranges < 11.0) == 1  # z = 0 is below the smallest positive double


def test_the_target_frame_transform_is_applied_first() -> None:
    params = ScanParams(min_height=-1.0, max_height=1.0)
    quarter_turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    ranges = project(np.array([[2.0, 0.0, 0.0]]), params, quarter_turn, (1.0, 0.0, 0.0))
    angle = math.atan2(2.0, 1.0)
    assert ranges[int((angle + math.pi) / params.angle_increment)] == pytest.approx(math.hypot(1.0, 2.0))


def test_bad_params_are_named() -> None:
    with pytest.raises(ParamError, match="~angle_increment must be > 0, got 0.0"):
        ScanParams.from_params({"angle_increment": 0})
    with pytest.raises(ParamError, match="~use_inf must be true or false"):
        ScanParams.from_params({"use_inf": "yes"})
    with pytest.raises(ParamError, match="~angle_min 1.0 must be below ~angle_max -1.0"):
        ScanParams.from_params({"angle_min": 1.0, "angle_max": -1.0})
    assert ScanParams.from_params({"min_height": 0, "target_frame": "rslidar"}).min_height == 0.0


def test_cloud_fields_are_read_at_their_offsets() -> None:
    data = b"".join(struct.pack("<fffxxxxf", x, y, z, 7.0) for x, y, z in ((1, 2, 3), (4, 5, 6)))
    xyz = cloud_xyz(data, 20, 2, {"x": 0, "y": 4, "z": 8})
    assert xyz.tolist() == [[1, 2, 3], [4, 5, 6]]
