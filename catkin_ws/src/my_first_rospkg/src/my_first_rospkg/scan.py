"""ROS-free search of the closest return of a laser scan, REP 117 ranges (twin of scan_minimum.h)."""
import math
from typing import NamedTuple, Sequence


class ScanMinimum(NamedTuple):
    """The closest return of a scan; found is False when no beam holds a usable range. too_close: the closest
    object is nearer than range_min (a -inf beam) and distance is range_min."""

    found: bool = False
    too_close: bool = False
    distance: float = 0.0
    angle: float = 0.0
    index: int = 0


def find_scan_minimum(
    ranges: Sequence[float], angle_min: float, angle_increment: float, range_min: float, range_max: float
) -> ScanMinimum:
    """The smallest range within [range_min, range_max], with its angle. Per REP 117, NaN beams (erroneous) and
    +inf beams (nothing within range_max) are skipped, and a -inf beam (an object closer than range_min) beats
    every finite one. Finite values outside [range_min, range_max] are skipped as invalid."""
    minimum = ScanMinimum()
    for i, value in enumerate(ranges):
        too_close = math.isinf(value) and value < 0.0
        valid = math.isfinite(value) and range_min <= value <= range_max
        if not too_close and not valid:
            continue
        distance = range_min if too_close else float(value)
        better = (
            not minimum.found
            or (too_close and not minimum.too_close)
            or (too_close == minimum.too_close and distance < minimum.distance)
        )
        if better:
            minimum = ScanMinimum(True, too_close, distance, angle_min + i * angle_increment, i)
    return minimum
