"""The X window dump reader used by the rviz screenshot test."""
import struct

import numpy as np
import pytest

from workspace_testing.xwd_image import read_xwd


def make_dump(rgb, bits_per_pixel, byte_order=0):
    height, width, _ = rgb.shape
    pixel_bytes = bits_per_pixel // 8
    stride = (width * pixel_bytes + 3) // 4 * 4
    name = b"test\0"
    header = [
        100 + len(name),
        7,
        2,
        24,
        width,
        height,
        0,
        byte_order,
        32,
        byte_order,
        32,
        bits_per_pixel,
        stride,
        4,
        0xFF0000,
        0x00FF00,
        0x0000FF,
        8,
        256,
        0,
        width,
        height,
        0,
        0,
        0,
    ]
    body = bytearray()
    for row in rgb:
        line = bytearray()
        for r, g, b in row:
            value = (int(r) << 16) | (int(g) << 8) | int(b)
            line += value.to_bytes(pixel_bytes, "little" if byte_order == 0 else "big")
        body += line + b"\0" * (stride - len(line))
    return struct.pack(">25I", *header) + name + bytes(body)


@pytest.mark.parametrize("bits_per_pixel, byte_order", [(24, 0), (32, 0), (32, 1)])
def test_reads_true_colour_dumps(bits_per_pixel, byte_order):
    rgb = np.random.default_rng(1).integers(0, 256, size=(5, 7, 3), dtype=np.uint8)
    assert np.array_equal(read_xwd(make_dump(rgb, bits_per_pixel, byte_order)), rgb)


def test_refuses_palette_dumps():
    with pytest.raises(ValueError, match="24 or 32 bits per pixel"):
        read_xwd(make_dump(np.zeros((2, 2, 3), dtype=np.uint8), 24)[:44] + struct.pack(">I", 8) + b"\0" * 200)
