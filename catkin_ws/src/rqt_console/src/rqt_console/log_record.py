"""One log message as the console shows it, without ROS or Qt."""
from __future__ import annotations

import time
from typing import Any, Tuple

# rosgraph_msgs/Log's level constants, with rqt_console's labels for them
DEBUG, INFO, WARN, ERROR, FATAL = 1, 2, 4, 8, 16
SEVERITY_LABELS = {DEBUG: "Debug", INFO: "Info", WARN: "Warn", ERROR: "Error", FATAL: "Fatal"}
COLUMNS = ("#", "Message", "Severity", "Node", "Stamp", "Topics", "Location")


class LogRecord:
    """A row of the table. `number` is the running number the console gives it (the "#" column)."""

    __slots__ = ("number", "message", "severity", "node", "stamp", "topics", "location")

    def __init__(
        self,
        message: str,
        severity: int,
        node: str,
        stamp: Tuple[int, int],
        topics: Tuple[str, ...] = (),
        location: str = "",
        number: int = 0,
    ) -> None:
        self.number = number
        self.message = message
        self.severity = severity
        self.node = node
        self.stamp = stamp
        self.topics = tuple(topics)
        self.location = location

    @classmethod
    def from_log(cls, log: Any) -> "LogRecord":
        """From a rosgraph_msgs/Log (or anything with its fields); location as rqt_console: file:function:line."""
        return cls(
            log.msg,
            log.level,
            log.name,
            (log.header.stamp.secs, log.header.stamp.nsecs),
            tuple(sorted(log.topics)),
            "%s:%s:%d" % (log.file, log.function, log.line),
        )

    def severity_label(self) -> str:
        return SEVERITY_LABELS.get(self.severity, str(self.severity))

    def stamp_text(self) -> str:
        """Local time as rqt_console shows it: hh:mm:ss.nnnnnnnnn (yyyy-MM-dd)."""
        local = time.localtime(self.stamp[0])
        return "%s.%09d (%s)" % (time.strftime("%H:%M:%S", local), self.stamp[1], time.strftime("%Y-%m-%d", local))

    def column_text(self, column: int) -> str:
        if column == 0:
            return "#%d" % self.number
        if column == 1:
            return self.message
        if column == 2:
            return self.severity_label()
        if column == 3:
            return self.node
        if column == 4:
            return self.stamp_text()
        if column == 5:
            return ", ".join(self.topics)
        return self.location

    def __eq__(self, other: object) -> bool:
        return isinstance(other, LogRecord) and all(getattr(self, s) == getattr(other, s) for s in self.__slots__)

    def __repr__(self) -> str:
        return "LogRecord(%s)" % ", ".join("%s=%r" % (s, getattr(self, s)) for s in self.__slots__)
