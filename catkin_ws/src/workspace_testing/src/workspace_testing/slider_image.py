"""Qt sliders (Fusion style, as under Xvfb) found in a screenshot: where their grooves lie and how far each is
filled, which is how far the slider stands between its minimum and its maximum."""
from __future__ import annotations

from typing import List

import numpy as np

from .tool_window import matches

# A groove's border, its filled part (from the minimum to the handle) and the rest, in Qt 5's Fusion style.
GROOVE_BORDERS = ((171, 171, 171), (34, 100, 141))
FILLED, EMPTY = (56, 161, 227), (217, 217, 217)
MIN_GROOVE_PIXELS = 150
# Rows (columns) of one groove's two borders lie at most this far apart.
GROOVE_WIDTH = 6
HANDLE_HALF = 7  # px


class Groove:
    """One slider: ``line`` is the screen row (column, for a vertical one) through its middle, ``fraction`` the
    filled share of its length, ``handle`` the coordinate along it where its handle is."""

    def __init__(self, line: int, filled: np.ndarray, empty: np.ndarray) -> None:
        self.line = line
        self.fraction = filled.size / float(filled.size + empty.size)
        if filled.size and empty.size:  # the handle sits between the fill and the rest
            before, after = (filled, empty) if filled.max() < empty.min() else (empty, filled)
            self.handle = (int(before.max()) + int(after.min())) // 2
        else:  # at an end: just before the empty groove, or just after the filled one
            self.handle = int(empty.min()) - HANDLE_HALF if empty.size else int(filled.max()) + HANDLE_HALF


def grooves(image: np.ndarray, vertical: bool = False) -> List[Groove]:
    """The horizontal (or vertical) slider grooves on the screen, top to bottom (left to right)."""
    if vertical:
        image = image.transpose(1, 0, 2)
    border = np.zeros(image.shape[:2], dtype=bool)
    for colour in GROOVE_BORDERS:
        border |= matches(image, colour, 6)
    lines = np.nonzero(border.sum(axis=1) >= MIN_GROOVE_PIXELS)[0]
    groups: List[List[int]] = []
    for line in lines:
        if groups and line - groups[-1][-1] <= GROOVE_WIDTH:
            groups[-1].append(int(line))
        else:
            groups.append([int(line)])
    found = []
    for group in groups:
        middle = (group[0] + group[-1]) // 2
        filled = np.nonzero(matches(image[middle : middle + 1], FILLED, 25)[0])[0]
        empty = np.nonzero(matches(image[middle : middle + 1], EMPTY, 10)[0])[0]
        if filled.size + empty.size >= MIN_GROOVE_PIXELS:  # not a frame or a button's edge
            found.append(Groove(middle, filled, empty))
    return found
