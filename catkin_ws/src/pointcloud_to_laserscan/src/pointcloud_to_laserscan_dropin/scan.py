"""ROS-free core of pointcloud_to_laserscan (PointCloudToLaserScanNodelet::onInit's parameters and cloudCb's
projection, lunar-devel 1.4.1): the nearest point in each angular bin of a cloud's points within a height band."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional

import numpy as np

DOUBLE_MIN = sys.float_info.min  # std::numeric_limits<double>::min(): the smallest positive double, not -max
DOUBLE_MAX = sys.float_info.max


class ParamError(ValueError):
    """A parameter with a value the node cannot work with (named, with the value)."""


@dataclass(frozen=True)
class ScanParams:
    """onInit's private parameters and defaults."""

    target_frame: str = ""
    transform_tolerance: float = 0.01
    min_height: float = DOUBLE_MIN  # upstream's default: points at z <= 0 are dropped unless min_height is set
    max_height: float = DOUBLE_MAX
    angle_min: float = -math.pi
    angle_max: float = math.pi
    angle_increment: float = math.pi / 180.0
    scan_time: float = 1.0 / 30.0
    range_min: float = 0.0
    range_max: float = DOUBLE_MAX
    use_inf: bool = True
    inf_epsilon: float = 1.0
    concurrency_level: int = 1

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> "ScanParams":
        """From a mapping of parameter name to value (the private ones given); ParamError naming a bad one."""
        fields: Dict[str, Any] = {}
        defaults = cls()
        for name in cls.__dataclass_fields__:
            if name not in params:
                continue
            value, default = params[name], getattr(defaults, name)
            if isinstance(default, bool):
                if not isinstance(value, bool):
                    raise ParamError(f"~{name} must be true or false, got {value!r}")
            elif isinstance(default, int):
                if isinstance(value, bool) or not isinstance(value, int):
                    raise ParamError(f"~{name} must be an integer, got {value!r}")
            elif isinstance(default, float):
                if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value):
                    raise ParamError(f"~{name} must be a number, got {value!r}")
                value = float(value)
            elif not isinstance(value, str):
                raise ParamError(f"~{name} must be a string, got {value!r}")
            fields[name] = value
        result = cls(**fields)
        result.validate()
        return result

    def validate(self) -> None:
        if not (self.angle_increment > 0 and math.isfinite(self.angle_increment)):
            raise ParamError(f"~angle_increment must be > 0, got {self.angle_increment}")
        if not (math.isfinite(self.angle_min) and math.isfinite(self.angle_max) and self.angle_min < self.angle_max):
            raise ParamError(f"~angle_min {self.angle_min} must be below ~angle_max {self.angle_max}")
        if self.bins > 10_000_000:
            raise ParamError(f"~angle_increment {self.angle_increment} makes {self.bins} rays (at most 10000000)")
        if self.concurrency_level < 0:
            raise ParamError(f"~concurrency_level must be >= 0, got {self.concurrency_level}")
        if self.transform_tolerance < 0:
            raise ParamError(f"~transform_tolerance must be >= 0, got {self.transform_tolerance}")

    @property
    def bins(self) -> int:
        """cloudCb's ranges_size: ceil((angle_max - angle_min) / angle_increment)."""
        return int(math.ceil((self.angle_max - self.angle_min) / self.angle_increment))


def cloud_xyz(
    data: bytes, point_step: int, count: int, offsets: Mapping[str, int], big_endian: bool = False
) -> np.ndarray:
    """The x, y, z float32 fields of ``count`` points of a PointCloud2's ``data`` as an (N, 3) float64 array."""
    dtype = np.dtype(
        {
            "names": ["x", "y", "z"],
            "formats": [">f4" if big_endian else "<f4"] * 3,
            "offsets": [offsets["x"], offsets["y"], offsets["z"]],
            "itemsize": point_step,
        }
    )
    points = np.frombuffer(data, dtype=dtype, count=count)
    return np.stack((points["x"], points["y"], points["z"]), axis=1).astype(np.float64)


def project(xyz: np.ndarray, params: ScanParams, rotation: Optional[np.ndarray] = None, translation=None) -> np.ndarray:  # type: ignore[no-untyped-def]
    """cloudCb: the ranges of the scan (inf, or range_max + inf_epsilon without use_inf, where no point falls); each
    point not NaN, with min_height <= z <= max_height, range_min <= hypot(x, y) <= range_max and angle_min <=
    atan2(y, x) <= angle_max lowers its bin to its range. ``rotation``, ``translation``: the cloud into the target
    frame first (tf2's transform of the cloud)."""
    if rotation is not None:
        xyz = xyz @ np.asarray(rotation).T + np.asarray(translation)
    empty = math.inf if params.use_inf else params.range_max + params.inf_epsilon
    ranges = np.full(params.bins, empty)
    x, y, z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    with np.errstate(invalid="ignore"):
        ranges_xy = np.hypot(x, y)
        angles = np.arctan2(y, x)
        keep = ~np.isnan(xyz).any(axis=1)
        keep &= (z <= params.max_height) & (z >= params.min_height)
        keep &= (ranges_xy >= params.range_min) & (ranges_xy <= params.range_max)
        keep &= (angles >= params.angle_min) & (angles <= params.angle_max)
    index = ((angles[keep] - params.angle_min) / params.angle_increment).astype(np.int64)
    index = np.minimum(index, params.bins - 1)  # angle == angle_max: upstream writes one past the end
    np.minimum.at(ranges, index, ranges_xy[keep])
    return ranges
