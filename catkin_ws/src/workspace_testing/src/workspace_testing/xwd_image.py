"""Read an X window dump (`xwd -root`) into an RGB numpy array: enough to check what a GUI shows under Xvfb."""
from __future__ import annotations

import struct

import numpy as np

_HEADER_FIELDS = (
    "header_size",
    "file_version",
    "pixmap_format",
    "pixmap_depth",
    "pixmap_width",
    "pixmap_height",
    "xoffset",
    "byte_order",
    "bitmap_unit",
    "bitmap_bit_order",
    "bitmap_pad",
    "bits_per_pixel",
    "bytes_per_line",
    "visual_class",
    "red_mask",
    "green_mask",
    "blue_mask",
    "bits_per_rgb",
    "colormap_entries",
    "ncolors",
    "window_width",
    "window_height",
    "window_x",
    "window_y",
    "window_bdrwidth",
)


def _channel(pixels: np.ndarray, mask: int) -> np.ndarray:
    shift = (mask & -mask).bit_length() - 1
    return ((pixels & mask) >> shift).astype(np.uint8)


def read_xwd(data: bytes) -> np.ndarray:
    """Return an (height, width, 3) uint8 RGB image of a TrueColor dump with 24 or 32 bits per pixel."""
    header = dict(zip(_HEADER_FIELDS, struct.unpack(">25I", data[:100])))
    pixel_bytes = header["bits_per_pixel"] // 8
    if header["bits_per_pixel"] not in (24, 32):
        raise ValueError("only 24 or 32 bits per pixel dumps are read, got %d" % header["bits_per_pixel"])
    offset = header["header_size"] + 12 * header["ncolors"]
    height, width, stride = header["pixmap_height"], header["pixmap_width"], header["bytes_per_line"]
    rows = np.frombuffer(data, dtype=np.uint8, count=height * stride, offset=offset).reshape(height, stride)
    pixel_bytes_array = rows[:, : width * pixel_bytes].reshape(height, width, pixel_bytes).astype(np.uint32)
    if header["byte_order"] != 0:  # MSBFirst: most significant byte first
        pixel_bytes_array = pixel_bytes_array[..., ::-1]
    pixels = sum(pixel_bytes_array[..., i] << (8 * i) for i in range(pixel_bytes))
    return np.dstack([_channel(pixels, header[c + "_mask"]) for c in ("red", "green", "blue")])
