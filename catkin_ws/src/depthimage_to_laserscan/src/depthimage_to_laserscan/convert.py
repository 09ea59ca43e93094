"""A depth image's middle rows -> laser ranges, without ROS (numpy).

The conversion of ros-perception/depthimage_to_laserscan (DepthImageToLaserScan::convert_msg and convert,
use_point): angles from the camera's principal point and focal length; for every pixel of the `scan_height` rows
centred on cy, the range hypot(x, z) at angle -atan2(x, z) goes to its angle bin; per bin the shortest range within
[range_min, range_max] wins, else +-inf if any pixel had one, else NaN. The image is taken as rectified (no
distortion), as a simulated camera's is.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

ENCODINGS = {"32FC1": (np.float32, 1.0), "16UC1": (np.uint16, 0.001)}  # dtype, metres per unit


class ConversionError(ValueError):
    """The image cannot be converted; the message says why."""


class Scan(NamedTuple):
    angle_min: float
    angle_max: float
    angle_increment: float
    ranges: np.ndarray  # float32, one per image column


def depth_array(data: bytes, encoding: str, width: int, height: int, step: int, big_endian: bool) -> np.ndarray:
    """The image's depths in metres, height x width (NaN where 16UC1 has 0: no reading)."""
    if encoding not in ENCODINGS:
        raise ConversionError("Depth image has unsupported encoding: %s" % encoding)
    dtype, scale = ENCODINGS[encoding]
    dtype = np.dtype(dtype).newbyteorder(">" if big_endian else "<")
    if width < 2 or height < 1 or step < width * dtype.itemsize or len(data) < step * height:
        raise ConversionError("image of %dx%d with step %d has %d bytes" % (width, height, step, len(data)))
    rows = np.frombuffer(data, dtype=np.uint8, count=step * height).reshape(height, step)
    depth = rows[:, : width * dtype.itemsize].copy().view(dtype).astype(np.float64)
    if encoding == "16UC1":
        depth[depth == 0] = np.nan
    return depth * scale


def convert(
    depth: np.ndarray, fx: float, cx: float, cy: float, scan_height: int, range_min: float, range_max: float
) -> Scan:
    height, width = depth.shape
    if not (fx > 0 and math.isfinite(fx)):
        raise ConversionError("camera_info has no usable focal length: fx = %r" % fx)
    if scan_height // 2 > cy or scan_height // 2 > height - cy:
        raise ConversionError("scan_height ( %d pixels) is too large for the image height." % scan_height)
    angle_max = math.atan2(cx, fx)  # the left edge (column 0) against the optical axis
    angle_min = -math.atan2(width - 1 - cx, fx)
    increment = (angle_max - angle_min) / (width - 1)

    offset = int(cy - scan_height / 2)
    rows = depth[offset : offset + scan_height]
    u = np.arange(width, dtype=np.float64)
    theta = -np.arctan2((u - cx) / fx, 1.0)
    index = ((theta - angle_min) / increment).astype(np.int64)  # truncation, as the C++ int conversion
    x = (u - cx) * rows / fx
    ranges = np.where(np.isfinite(rows), np.hypot(x, rows), rows)

    out = np.full(width, np.nan)
    for row in ranges:  # pixel by pixel, in upstream's order: which of two infinities is kept depends on it
        for col in range(width):
            out[index[col]] = _better(row[col], out[index[col]], range_min, range_max)
    return Scan(angle_min, angle_max, increment, out.astype(np.float32))


def _better(new: float, old: float, range_min: float, range_max: float) -> float:
    """use_point: which of two readings a bin keeps."""
    new_finite, old_finite = math.isfinite(new), math.isfinite(old)
    if not new_finite and not old_finite:
        return new if not math.isnan(new) else old  # an inf says more than a NaN
    if not range_min <= new <= range_max:
        return old
    if not old_finite or new < old:
        return new
    return old
