"""The plotted data, without ROS or Qt: subscriber threads push points, the GUI thread drains them into bounded
per-curve series (the real rqt_plot keeps every point, so that its redraws slow down the longer it runs)."""
from __future__ import annotations

import threading
from typing import Dict, List, Tuple

import numpy as np


class Series:
    """The newest `capacity` points of one curve, oldest first, in one contiguous numpy view.

    The arrays hold twice the capacity: points are appended until the end is reached, then the newest
    capacity - 1 points move to the front, so each append costs O(1) amortised and x()/y() never copy.
    """

    def __init__(self, capacity: int) -> None:
        if capacity < 2:
            raise ValueError("a series needs a capacity of at least 2, got %d" % capacity)
        self.capacity = capacity
        self._x = np.empty(2 * capacity)
        self._y = np.empty(2 * capacity)
        self._start = 0
        self._end = 0

    def __len__(self) -> int:
        return self._end - self._start

    def extend(self, xs, ys) -> None:
        xs = np.asarray(xs, dtype=float)[-self.capacity :]
        ys = np.asarray(ys, dtype=float)[-self.capacity :]
        count = len(xs)
        if self._end + count > len(self._x):
            keep = min(len(self), self.capacity - count)
            self._x[:keep] = self._x[self._end - keep : self._end]
            self._y[:keep] = self._y[self._end - keep : self._end]
            self._start, self._end = 0, keep
        self._x[self._end : self._end + count] = xs
        self._y[self._end : self._end + count] = ys
        self._end += count
        self._start = max(self._start, self._end - self.capacity)

    def clear(self) -> None:
        self._start = self._end = 0

    def x(self) -> np.ndarray:
        return self._x[self._start : self._end]

    def y(self) -> np.ndarray:
        return self._y[self._start : self._end]


class DataWindow:
    """Curves by name. push() may be called from any thread; drain(), the series and everything else only from
    the thread that owns the window (the GUI's)."""

    def __init__(self, capacity: int) -> None:
        self.capacity = capacity
        self._lock = threading.Lock()
        self._pending: Dict[str, Tuple[List[float], List[float]]] = {}
        self.series: Dict[str, Series] = {}
        self.points_drained = 0  # every point ever drained, for the benchmark's count of what arrived

    def add(self, name: str) -> None:
        with self._lock:
            self._pending.setdefault(name, ([], []))
        self.series.setdefault(name, Series(self.capacity))

    def remove(self, name: str) -> None:
        with self._lock:
            self._pending.pop(name, None)
        self.series.pop(name, None)

    def push(self, name: str, x: float, y: float) -> None:
        """One point from a subscriber; points of a curve removed meanwhile are dropped."""
        with self._lock:
            pending = self._pending.get(name)
            if pending is not None:
                pending[0].append(x)
                pending[1].append(y)

    def drain(self) -> List[str]:
        """Moves the pushed points into the series; returns the names of the curves that got some."""
        with self._lock:
            pending, self._pending = self._pending, {name: ([], []) for name in self._pending}
        changed = []
        for name, (xs, ys) in pending.items():
            if xs and name in self.series:
                self.series[name].extend(xs, ys)
                self.points_drained += len(xs)
                changed.append(name)
        return changed

    def clear(self) -> None:
        """Forgets every point, pending ones included; the curves stay."""
        with self._lock:
            self._pending = {name: ([], []) for name in self._pending}
        for series in self.series.values():
            series.clear()

    def latest_x(self) -> float:
        """The largest x of the newest points, or 0.0 when there are none."""
        ends = [series.x()[-1] for series in self.series.values() if len(series)]
        return max(ends) if ends else 0.0
