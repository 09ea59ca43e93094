"""The plot itself, drawn with pyqtgraph: 3 curves of a 10 s window redraw in 1.9 ms against matplotlib's
(Qt5Agg) 14 ms on this machine (README, "Limits"), which is what keeps the 25 Hz refresh smooth."""
from __future__ import annotations

from typing import Dict, Iterable, Tuple

import numpy as np
from python_qt_binding.QtCore import Qt  # imported first: pyqtgraph then uses the same binding (PyQt5)
from python_qt_binding.QtGui import QColor
import pyqtgraph

from .data_window import Series

# rqt_plot's DataPlot._colors, in its order
CURVE_COLOURS = (
    Qt.blue,
    Qt.red,
    Qt.cyan,
    Qt.magenta,
    Qt.green,
    Qt.darkYellow,
    Qt.black,
    Qt.darkCyan,
    Qt.darkRed,
    Qt.gray,
)
DEFAULT_X_WIDTH = 10.0  # s shown when autoscroll is on, rqt_plot's default x range


class PlotCanvas(pyqtgraph.PlotWidget):
    """Curves by name over time. With autoscroll the x range keeps its width and follows the newest point; the y
    range grows to hold what is visible and never shrinks until clear() (rqt_plot's SCALE_EXTEND | SCALE_VISIBLE)."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent, background="w")
        self._curves: Dict[str, pyqtgraph.PlotDataItem] = {}
        self._colour_index = 0
        self._y_range = None
        self.autoscroll = True
        self.plotItem.showGrid(x=True, y=True, alpha=0.3)
        self.plotItem.setLabel("bottom", "time", units="s")
        self.plotItem.addLegend(offset=(10, 10))
        self.plotItem.disableAutoRange()
        self.setXRange(0.0, DEFAULT_X_WIDTH, padding=0)
        self.setYRange(0.0, 1.0, padding=0)

    def add_curve(self, name: str) -> None:
        colour = QColor(CURVE_COLOURS[self._colour_index % len(CURVE_COLOURS)])
        self._colour_index += 1
        item = self.plotItem.plot(name=name, pen=pyqtgraph.mkPen(colour, width=1.5))
        item.setClipToView(True)  # only the visible part of a curve is handed to Qt
        item.setDownsampling(auto=True, method="peak")
        self._curves[name] = item

    def remove_curve(self, name: str) -> None:
        item = self._curves.pop(name, None)
        if item is not None:
            self.plotItem.removeItem(item)
            self.plotItem.legend.removeItem(name)

    def curve_names(self):
        return list(self._curves)

    def clear_values(self) -> None:
        for item in self._curves.values():
            item.setData([], [])
        self._y_range = None

    def show(self, series: Dict[str, Series], changed: Iterable[str]) -> None:
        """Draws the curves in `changed` after new data and moves the axes: x to the newest point (autoscroll),
        y to hold the visible values. With autoscroll only the visible stretch of a curve is handed to pyqtgraph,
        so a frame costs the same with 20,000 points kept as with 600; without, the whole series (to pan over)."""
        (x_low, x_high), _ = self.plotItem.viewRange()
        filled = [s for s in series.values() if len(s)]
        if self.autoscroll and filled:
            # the range keeps its width and ends at the newest point, but starts no earlier than the oldest one:
            # curves first grow from the left edge, then scroll
            width = x_high - x_low
            x_low = max(max(s.x()[-1] for s in filled) - width, min(s.x()[0] for s in filled))
            x_high = x_low + width
            self.setXRange(x_low, x_high, padding=0)
        for name in changed:
            if name in self._curves and name in series:
                first, end = self._visible(series[name], x_low, x_high)
                if self.autoscroll:  # one point either side, so that lines run to the edges
                    first, end = max(first - 1, 0), min(end + 1, len(series[name]))
                else:
                    first, end = 0, len(series[name])
                # fewer than two points are not drawn: pyqtgraph 0.13.1 fails to paint a line of one
                x, y = (series[name].x()[first:end], series[name].y()[first:end]) if end - first > 1 else ([], [])
                self._curves[name].setData(x, y)
        for values in filled:
            first, end = self._visible(values, x_low, x_high)
            visible = values.y()[first:end]
            finite = visible[np.isfinite(visible)]
            if len(finite):
                low, high = float(finite.min()), float(finite.max())
                if self._y_range is not None:
                    low, high = min(low, self._y_range[0]), max(high, self._y_range[1])
                self._y_range = (low, high)
        if self._y_range is not None:
            low, high = self._y_range
            margin = 0.05 * (high - low) if high > low else 0.5
            self.setYRange(low - margin, high + margin, padding=0)

    @staticmethod
    def _visible(values: Series, x_low: float, x_high: float) -> Tuple[int, int]:
        """Index range of the points with x in [x_low, x_high] (x is sorted as it arrives)."""
        return int(np.searchsorted(values.x(), x_low)), int(np.searchsorted(values.x(), x_high, "right"))
