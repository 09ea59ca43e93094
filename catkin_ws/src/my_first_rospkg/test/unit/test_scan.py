"""Unit tests of the ROS-free scan minimum (twin of test/test_scan_minimum.cpp)."""
import math

from my_first_rospkg.scan import find_scan_minimum

INF, NAN = math.inf, math.nan


def test_finds_smallest_with_angle():
    m = find_scan_minimum([3.0, 1.5, 0.75, 2.0], -1.0, 0.5, 0.1, 10.0)
    assert (m.found, m.too_close, m.distance, m.angle, m.index) == (True, False, 0.75, 0.0, 2)


def test_skips_nan_positive_infinity_and_out_of_range():
    m = find_scan_minimum([NAN, INF, 0.05, 12.0, 4.0], 0.0, 0.1, 0.1, 10.0)
    assert (m.found, m.distance, m.index) == (True, 4.0, 4)


def test_negative_infinity_is_closer_than_range_min():
    m = find_scan_minimum([0.5, -INF, 0.2], 0.0, 0.1, 0.1, 10.0)
    assert (m.found, m.too_close, m.distance, m.index) == (True, True, 0.1, 1)


def test_nothing_usable():
    assert not find_scan_minimum([NAN, INF], 0.0, 0.1, 0.1, 10.0).found
    assert not find_scan_minimum([], 0.0, 0.1, 0.1, 10.0).found
