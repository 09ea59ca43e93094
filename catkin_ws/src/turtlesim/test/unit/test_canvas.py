"""Unit tests of the pixel canvas' thick lines."""
from __future__ import annotations

from turtlesim.canvas import Canvas

BG, INK = (0, 0, 0), (255, 255, 255)


def inked(canvas: Canvas):
    return {(c, r) for r in range(canvas.height) for c in range(canvas.width) if canvas.pixel(c, r) == INK}


def test_horizontal_line_of_width_3_covers_three_rows():
    canvas = Canvas(20, 20, BG)
    canvas.draw_line((2.0, 10.5), (12.0, 10.5), INK, 3)
    rows = {r for _, r in inked(canvas)}
    assert rows == {9, 10, 11}
    assert {c for c, r in inked(canvas) if r == 10} == set(range(0, 14))  # round caps of radius 1.5


def test_width_1_diagonal_is_connected():
    canvas = Canvas(20, 20, BG)
    canvas.draw_line((1.0, 1.0), (15.0, 15.0), INK, 1)
    for i in range(2, 14):
        assert (i, i) in inked(canvas)


def test_lines_are_clipped_and_change_the_version_only_when_drawn():
    canvas = Canvas(10, 10, BG)
    version = canvas.version
    canvas.draw_line((30.0, 30.0), (40.0, 40.0), INK, 3)
    assert canvas.version == version and not inked(canvas)
    canvas.draw_line((-5.0, 5.0), (50.0, 5.0), INK, 1)
    assert canvas.version == version + 1 and len(inked(canvas)) >= 10


def test_ppm_header_and_size():
    canvas = Canvas(4, 3, (1, 2, 3))
    data = canvas.ppm()
    assert data.startswith(b"P6 4 3 255\n") and len(data) == len(b"P6 4 3 255\n") + 4 * 3 * 3
