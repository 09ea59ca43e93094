"""Unit tests of the ROS-free integer helpers (twin of test_checked_int.cpp)."""
import pytest

from beginner_tutorials.checked_int import INT64_MAX, INT64_MIN, checked_add, parse_int64


@pytest.mark.parametrize(
    "text, value",
    [("42", 42), ("-7", -7), ("+3", 3), ("9223372036854775807", INT64_MAX), ("-9223372036854775808", INT64_MIN)],
)
def test_parse_accepts_signed_decimals(text, value):
    assert parse_int64(text) == value


@pytest.mark.parametrize(
    "text",
    [
        "",
        "-",
        "+",
        "1.5",
        "abc",
        "12abc",
        " 1",
        "1 ",
        "0x10",
        "1e3",
        "1_000",
        "9223372036854775808",
        "-9223372036854775809",
        "\u0661",
    ],
)
def test_parse_rejects_everything_else(text):
    assert parse_int64(text) is None


def test_add_within_range():
    assert checked_add(1, 2) == 3
    assert checked_add(INT64_MAX, INT64_MIN) == -1
    assert checked_add(INT64_MAX - 1, 1) == INT64_MAX


@pytest.mark.parametrize("a, b", [(INT64_MAX, 1), (INT64_MIN, -1), (INT64_MAX, INT64_MAX), (INT64_MIN, INT64_MIN)])
def test_add_refuses_overflow(a, b):
    assert checked_add(a, b) is None
