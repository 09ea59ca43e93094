"""Waiting in a test that runs Qt widgets in its own thread: the Qt loop runs while the condition is false."""
from __future__ import annotations

import time
from typing import Callable

TURN_MS = 20  # how long the Qt loop runs between two looks at the condition


def run_qt_until(condition: Callable[[], bool], timeout: float) -> bool:
    """Run the Qt event loop until ``condition()`` holds (True) or ``timeout`` seconds pass (False)."""
    from python_qt_binding.QtCore import QEventLoop, QTimer

    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() >= deadline:
            return False
        loop = QEventLoop()
        QTimer.singleShot(TURN_MS, loop.quit)
        loop.exec_()
    return True
