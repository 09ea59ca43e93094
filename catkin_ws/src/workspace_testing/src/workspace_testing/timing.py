"""Time checks that hold on any machine: a piece of work timed against a reference timed in the same run, so that a
slow or busy machine slows both. The suites assert no wall time against a fixed number."""
from __future__ import annotations

import time
from typing import Callable, Tuple, TypeVar

Result = TypeVar("Result")


def timed(work: Callable[[], Result]) -> Tuple[Result, float]:
    """work()'s result and the wall seconds it took."""
    start = time.perf_counter()
    result = work()
    return result, time.perf_counter() - start


def best_seconds(work: Callable[[], object], repeat: int = 3) -> float:
    """The shortest of ``repeat`` timings of work(): the machine's undisturbed speed at it."""
    return min(timed(work)[1] for _ in range(repeat))


def assert_within(seconds: float, reference_seconds: float, ratio: float, what: str) -> None:
    """``what`` took at most ``ratio`` times the reference measured in the same run."""
    assert seconds <= ratio * reference_seconds, "%s took %.3f s: over %g x the %.4f s of the reference (same run)" % (
        what,
        seconds,
        ratio,
        reference_seconds,
    )
