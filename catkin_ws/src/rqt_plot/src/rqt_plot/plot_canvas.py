"""The plot itself, drawn with pyqtgraph: 3 curves of a 10 s window redraw in 1.9 ms against matplotlib's
(Qt5Agg) 14 ms on this machine (README, "Limits"), which is what keeps the 25 Hz refresh smooth."""
from __future__ import annotations

from typing import Dict

import numpy as np
from python_qt_binding.QtCore import Qt  # imported first: pyqtgraph then uses the same binding (PyQt5)
from python_qt_binding.QtGui import QColor
import pyqtgraph

from .data_window import Series

# rqt_plot's DataPlot._colors, in its order
CURVE_COLOURS = (
    Qt.blue, Qt.red, Qt.cyan, Qt.magenta, Qt.green, Qt.darkYellow, Qt.black, Qt.darkCyan, Qt.darkRed, Qt.gray,
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

    def show_series(self, name: str, series: Series) -> None:
        if name in self._curves:
            self._curves[name].setData(series.x(), series.y())

    def clear_values(self) -> None:
        for item in self._curves.values():
            item.setData([], [])
        self._y_range = None

    def follow(self, series: Dict[str, Series]) -> None:
        """Moves the axes after new data: x to the newest point (autoscroll), y to hold the visible values."""
        (x_low, x_high), _ = self.plotItem.viewRange()
        if self.autoscroll:
            filled = [s for s in series.values() if len(s)]
            if filled:
                # the range keeps its width and ends at the newest point, but starts no earlier than the oldest
                # one: curves first grow from the left edge, then scroll
                width = x_high - x_low
                x_low = max(max(s.x()[-1] for s in filled) - width, min(s.x()[0] for s in filled))
                x_high = x_low + width
                self.setXRange(x_low, x_high, padding=0)
        for values in series.values():
            visible = values.y()[np.searchsorted(values.x(), x_low) : np.searchsorted(values.x(), x_high, "right")]
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
