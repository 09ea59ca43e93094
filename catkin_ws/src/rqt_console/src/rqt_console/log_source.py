"""The ROS side of rqt_console: /rosout_agg into a queue that the GUI drains on a timer. The callback never
touches a widget or a model."""
from __future__ import annotations

import collections
import threading
from typing import Deque, List

import rospy
from rosgraph_msgs.msg import Log

from .log_record import LogRecord

TOPIC = "/rosout_agg"  # rosout's aggregate of every node's log: an absolute name, as rqt_console uses


class LogQueue:
    """Thread-safe; holds at most `limit` records (more than the table keeps would be dropped there anyway)."""

    def __init__(self, limit: int) -> None:
        self._records: Deque[LogRecord] = collections.deque(maxlen=limit)
        self._lock = threading.Lock()
        self.received = 0
        self.paused = False  # while paused, messages are dropped, as rqt_console's Console.queue_message does

    def put(self, record: LogRecord) -> None:
        if self.paused:
            return
        with self._lock:
            self._records.append(record)
            self.received += 1

    def take(self) -> List[LogRecord]:
        with self._lock:
            records = list(self._records)
            self._records.clear()
        return records

    def set_limit(self, limit: int) -> None:
        with self._lock:
            self._records = collections.deque(self._records, maxlen=limit)


class LogSubscriber:
    def __init__(self, queue: LogQueue, topic: str = TOPIC) -> None:
        self._queue = queue
        self._subscriber = rospy.Subscriber(topic, Log, self._on_log, queue_size=1000)

    def _on_log(self, log: Log) -> None:
        self._queue.put(LogRecord.from_log(log))

    def shutdown(self) -> None:
        self._subscriber.unregister()
