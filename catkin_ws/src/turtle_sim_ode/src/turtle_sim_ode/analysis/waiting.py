"""Waiting for a condition in tests and tools, on the wall clock: sim time may stand still (paused) or jump back to 0
(a restarted simulator) while they wait."""
from __future__ import annotations

import time
from typing import Callable, TypeVar

T = TypeVar("T")


def wait_for(condition: Callable[[], T], timeout: float, period: float = 0.05) -> T:
    """Call ``condition`` every ``period`` s until it returns something true or ``timeout`` wall seconds have
    passed; return its last value."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value or time.monotonic() >= deadline:
            return value
        time.sleep(period)
