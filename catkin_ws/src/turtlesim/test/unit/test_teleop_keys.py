"""turtle_teleop_key's key decoding, without ROS or a terminal."""
from __future__ import annotations

import pytest

from turtlesim.teleop import KeyDecoder, velocities


def decode(data: bytes):
    decoder = KeyDecoder()
    return [k for k in (decoder.feed(data[i : i + 1]) for i in range(len(data))) if k is not None]


@pytest.mark.parametrize(
    "data, keys",
    [
        (b"\x1b[A", ["up"]),
        (b"\x1b[B\x1b[C\x1b[D", ["down", "right", "left"]),
        (b"\x1bOA", ["up"]),  # application cursor mode
        (b"AxBq", ["quit"]),  # letters alone are not arrows
        (b"\x1b[Zq", ["quit"]),
    ],
)
def test_escape_sequences_and_quit(data, keys):
    assert decode(data) == keys


def test_velocities_use_the_scales():
    assert velocities("up", 2.0, 2.0) == (2.0, 0.0)
    assert velocities("down", 2.0, 2.0) == (-2.0, 0.0)
    assert velocities("left", 2.0, 3.0) == (0.0, 3.0)
    assert velocities("right", 2.0, 3.0) == (0.0, -3.0)
