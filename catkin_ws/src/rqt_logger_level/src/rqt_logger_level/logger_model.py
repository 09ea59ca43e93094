"""What rqt_logger_level shows, ROS-free: the nodes offering logger services, and the level names.

Facts of the real tool (ros-visualization/rqt_logger_level, logger_level_service_caller.py): a node is listed when it
offers ``<node>/set_logger_level``; its loggers come from ``<node>/get_loggers`` (roscpp/GetLoggers); the levels are
Debug, Info, Warn, Error, Fatal, sent as those words (both rospy and roscpp upper-case them); get_loggers answers
upper-case names (rospy/client.py _logging_level_names: DEBUG, INFO, WARN, ERROR, FATAL).
"""
from __future__ import annotations

from typing import Iterable, List, Optional, Sequence, Tuple

LEVELS = ("Debug", "Info", "Warn", "Error", "Fatal")
SET_SERVICE = "/set_logger_level"
GET_SERVICE = "/get_loggers"


def logger_nodes(services: Iterable[Tuple[str, Sequence[str]]]) -> List[str]:
    """The nodes, sorted, that provide their own ``<node>/set_logger_level`` (from getSystemState's services)."""
    found = set()
    for service, providers in services:
        if service.endswith(SET_SERVICE):
            node = service[: -len(SET_SERVICE)]
            if node in providers:
                found.add(node)
    return sorted(found)


def level_index(level: str) -> Optional[int]:
    """Row of a level as get_loggers names it ("WARN", "warn", "Warning"), None for one it does not know."""
    word = level.strip().lower()
    if word == "warning":
        word = "warn"
    for index, name in enumerate(LEVELS):
        if name.lower() == word:
            return index
    return None
