"""The simulation's /clock as a test node hears it: the latest sim time, and waits for a sim time to come (the test
node may start before /use_sim_time is set, so it reads /clock itself rather than rospy's time)."""
from __future__ import annotations

import threading

import rospy
from rosgraph_msgs.msg import Clock


class SimClock:
    def __init__(self) -> None:
        self.now = None
        self._changed = threading.Condition()
        self._subscriber = rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=10)

    def _on_clock(self, message: Clock) -> None:
        with self._changed:
            self.now = message.clock.to_sec()
            self._changed.notify_all()

    def wait_until(self, sim_time: float, timeout: float) -> bool:
        """Whether /clock reached ``sim_time`` within ``timeout`` s of wall time."""
        with self._changed:
            return self._changed.wait_for(lambda: self.now is not None and self.now >= sim_time, timeout)

    def wait_for(self, seconds: float, timeout: float) -> bool:
        """Whether ``seconds`` of sim time passed (from the first /clock heard) within ``timeout`` s of wall time."""
        with self._changed:
            self._changed.wait_for(lambda: self.now is not None, timeout)
            start = self.now
        return start is not None and self.wait_until(start + seconds, timeout)
