"""An RGB pixel buffer with thick straight lines: the turtles' pen trails, shown by the window and read by the
colour sensors. No ROS, no GUI."""
from __future__ import annotations

import math
from typing import Optional, Tuple

import numpy as np

Rgb = Tuple[int, int, int]


class Canvas:
    def __init__(self, width: int, height: int, background: Rgb):
        self.pixels = np.empty((height, width, 3), dtype=np.uint8)
        self.version = 0  # counts changes, so a window redraws only when something was drawn
        self.fill(background)

    @property
    def width(self) -> int:
        return self.pixels.shape[1]

    @property
    def height(self) -> int:
        return self.pixels.shape[0]

    def fill(self, colour: Rgb) -> None:
        self.pixels[:, :] = colour
        self.version += 1

    def pixel(self, column: int, row: int) -> Rgb:
        """The colour at (column, row), the coordinates clipped to the canvas."""
        column = min(max(column, 0), self.width - 1)
        row = min(max(row, 0), self.height - 1)
        r, g, b = self.pixels[row, column]
        return int(r), int(g), int(b)

    def draw_line(self, start: Tuple[float, float], end: Tuple[float, float], colour: Rgb, width: int) -> None:
        """Paint every pixel whose centre lies within width/2 of the segment start-end (column, row coordinates,
        pixel (c, r) covering [c, c+1) x [r, r+1)); at least the pixels the segment passes through."""
        radius = max(width / 2.0, 0.5)
        (x0, y0), (x1, y1) = start, end
        columns = _span(min(x0, x1) - radius, max(x0, x1) + radius, self.width)
        rows_span = _span(min(y0, y1) - radius, max(y0, y1) + radius, self.height)
        if columns is None or rows_span is None:
            return
        (c0, c1), (r0, r1) = columns, rows_span
        cols, rows = np.meshgrid(np.arange(c0, c1 + 1) + 0.5, np.arange(r0, r1 + 1) + 0.5)
        with np.errstate(over="ignore", invalid="ignore"):  # far-off ends: infinities, no pixel
            dx, dy = x1 - x0, y1 - y0
            length_sq = dx * dx + dy * dy
            if 0.0 < length_sq < math.inf:  # a segment too long to measure (a teleport to 1e300 m) paints its start
                t = np.clip(((cols - x0) * dx + (rows - y0) * dy) / length_sq, 0.0, 1.0)
            else:
                t = np.zeros_like(cols)
            dist_sq = (cols - (x0 + t * dx)) ** 2 + (rows - (y0 + t * dy)) ** 2
            mask = dist_sq <= radius * radius + 1e-9
        if mask.any():
            self.pixels[r0 : r1 + 1, c0 : c1 + 1][mask] = colour
            self.version += 1

    def ppm(self) -> bytes:
        """The canvas as a binary PPM (P6) image."""
        return b"P6 %d %d 255\n" % (self.width, self.height) + self.pixels.tobytes()


def _span(low: float, high: float, size: int) -> Optional[Tuple[int, int]]:
    """The pixel indices from floor(low) to ceil(high) within 0..size-1; None if none (or a bound is NaN). Clipped
    as floats first, so that coordinates far off the canvas (or infinite) never become huge integers."""
    low, high = max(low, 0.0), min(high, size - 1.0)
    if not low <= high:
        return None
    return int(math.floor(low)), int(math.ceil(high))
