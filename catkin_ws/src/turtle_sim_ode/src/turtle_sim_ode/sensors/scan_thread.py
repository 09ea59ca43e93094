"""A sensor's scans on a thread of its own beside the physics, as gazebo-classic updates its sensors
(gazebo/sensors/SensorManager.cc: SensorContainer::Run starts a thread in RunLoop, which updates the sensors while
the world steps; Stop joins it). Here the stepping thread copies what a scan needs out of the world at the scan's
sim time and hands the rest (rays cast in C, noise, the cloud) to the thread: ctypes and numpy's large operations
let go of the GIL, so on two cores a scan costs the physics little more than taking its geometry.

One scan in flight at a time: the next waits for it, so no scan is dropped and each is made from the geometry of
its own sim time; a scan that raised is raised again on the stepping thread at the next scan or at close."""
from __future__ import annotations

from concurrent.futures import Future, ThreadPoolExecutor
from typing import Callable, Optional

from turtle_sim_ode.sensors.ray_kernel import usable_cpus


def cpus_beside_stepping() -> int:
    """How many threads a scan's C rays may use on a sensor's thread: the CPUs the stepping thread leaves (at least
    one). On two cores a second band of rays competed with the steps: in turns, 3000 steps with a VLP-16 kept a
    median 0.59, 0.56, 0.65 of the RTF without it in one band, 0.47, 0.52, 0.54 in two."""
    return max(1, usable_cpus() - 1)


class ScanError(RuntimeError):
    """A scan failed on its sensor's thread (the original exception is its __cause__)."""


class ScanThread:
    """Runs one sensor's scans, one at a time and in order, on a thread named ``name``."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix=name)
        self._in_flight: Optional[Future] = None

    def submit(self, scan: Callable[[], None]) -> None:
        """Run ``scan`` on the thread, after waiting for the scan before it if that one is not done yet."""
        self.wait()
        self._in_flight = self._executor.submit(scan)

    def wait(self) -> None:
        """Return once the scan in flight is done; ScanError if it raised."""
        in_flight, self._in_flight = self._in_flight, None
        if in_flight is None:
            return
        error = in_flight.exception()
        if error is not None:
            raise ScanError("%s: a scan failed on its thread: %r" % (self.name, error)) from error

    def close(self) -> None:
        """Wait for the scan in flight and end the thread (joined); ScanError as wait's, after the join."""
        try:
            self.wait()
        finally:
            self._executor.shutdown(wait=True)
