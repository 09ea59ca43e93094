"""The TurtleSim window (Tk): the canvas with its pen trails and a drawn turtle per turtle, rotated with theta.
It only reads the node's snapshots, from the main thread."""
from __future__ import annotations

import math
import os
from typing import Callable, List, Optional, Sequence, Tuple

from turtlesim.world import CANVAS_PIXELS, to_pixels

REFRESH_MS = 33  # redraw period

# The turtle, drawn in its own frame: pixels, x forward, y to its left. Shell, head and four flippers.
SHELL_COLOUR = "#2e7d32"
SKIN_COLOUR = "#9ccc65"
OUTLINE_COLOUR = "#1b3d1c"
TURTLE_SCALE = 1.5  # the figure below is 20 px long; scaled, about 30 px, two thirds of a metre (45 px)
_SHELL = [(11.0 * math.cos(a), 8.5 * math.sin(a)) for a in (2 * math.pi * i / 20 for i in range(20))]
_HEAD = [(11.0 + 5.0 * math.cos(a), 4.0 * math.sin(a)) for a in (2 * math.pi * i / 12 for i in range(12))]
_FLIPPERS = [
    [(x0, sy * 6.0), (x0 + 4.0 * dx, sy * 12.5), (x0 + 7.0 * dx, sy * 10.0)]
    for x0, dx in ((5.0, 1.0), (-5.0, -1.0))
    for sy in (1.0, -1.0)
]
_TAIL = [(-10.0, 1.5), (-14.0, 0.0), (-10.0, -1.5)]


def turtle_polygons(x: float, y: float, theta: float) -> List[Tuple[str, List[float]]]:
    """(fill colour, flat canvas coordinates) of each part of a turtle at world pose (x, y, theta)."""
    cx, cy = to_pixels(x, y)
    cos_t, sin_t = math.cos(theta), math.sin(theta)

    def place(points: Sequence[Tuple[float, float]]) -> List[float]:
        flat = []
        for u, v in ((TURTLE_SCALE * u, TURTLE_SCALE * v) for u, v in points):
            flat += [cx + u * cos_t - v * sin_t, cy - (u * sin_t + v * cos_t)]  # canvas rows grow downwards
        return flat

    parts = [(SKIN_COLOUR, place(p)) for p in _FLIPPERS + [_TAIL, _HEAD]]
    return parts + [(SHELL_COLOUR, place(_SHELL))]


class TurtleWindow:
    """A 500x500 Tk window; `snapshot(version)` gives (version, PPM bytes or b"", [(x, y, theta)])."""

    def __init__(self, tk_module, root, snapshot: Callable, should_close: Callable[[], bool], on_close: Callable):
        self._tk = tk_module
        self._root = root
        self._snapshot = snapshot
        self._should_close = should_close
        self._version = -1
        root.title("TurtleSim")
        root.resizable(False, False)
        root.protocol("WM_DELETE_WINDOW", on_close)
        self._canvas = tk_module.Canvas(root, width=CANVAS_PIXELS, height=CANVAS_PIXELS, highlightthickness=0, bd=0)
        self._canvas.pack()
        self._photo = tk_module.PhotoImage(width=CANVAS_PIXELS, height=CANVAS_PIXELS)
        self._canvas.create_image(0, 0, image=self._photo, anchor="nw")

    def run(self) -> None:
        """Show the window until should_close() says so (or the window is closed)."""
        self._root.after(0, self._refresh)
        self._root.mainloop()

    def _refresh(self) -> None:
        if self._should_close():
            self._root.destroy()
            return
        version, image, poses = self._snapshot(self._version)
        if image:
            self._photo.configure(data=image, format="PPM")
            self._version = version
        self._canvas.delete("turtle")
        for x, y, theta in poses:
            for colour, coords in turtle_polygons(x, y, theta):
                self._canvas.create_polygon(coords, fill=colour, outline=OUTLINE_COLOUR, tags="turtle")
        self._root.after(REFRESH_MS, self._refresh)


def open_window(
    snapshot: Callable, should_close: Callable[[], bool], on_close: Callable
) -> Tuple[Optional[TurtleWindow], str]:
    """The window, or (None, why not) when there is no display to show it on."""
    display = os.environ.get("DISPLAY", "")
    if not display:
        return None, "no display (DISPLAY is not set)"
    try:
        import tkinter

        root = tkinter.Tk()
    except Exception as error:  # ImportError without Tk, TclError when the display cannot be opened
        return None, "cannot open display [%s] (%s)" % (display, str(error).strip() or type(error).__name__)
    return TurtleWindow(tkinter, root, snapshot, should_close, on_close), ""
