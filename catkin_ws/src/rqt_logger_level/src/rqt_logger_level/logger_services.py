"""The ROS side: the master's list of logger nodes and the two roscpp services of a node."""
from __future__ import annotations

from typing import List, Tuple

import rosgraph
import rospy
from roscpp.srv import GetLoggers, SetLoggerLevel

from rqt_logger_level.logger_model import GET_SERVICE, SET_SERVICE, logger_nodes


def list_nodes(caller_id: str) -> List[str]:
    _publishers, _subscribers, services = rosgraph.Master(caller_id).getSystemState()
    return logger_nodes(services)


def get_loggers(node: str) -> List[Tuple[str, str]]:
    """[(logger name, level as the node names it)], sorted by name; raises rospy.ServiceException on failure."""
    response = rospy.ServiceProxy(node + GET_SERVICE, GetLoggers)()
    return sorted((logger.name, logger.level) for logger in response.loggers)


def set_level(node: str, logger: str, level: str) -> None:
    rospy.ServiceProxy(node + SET_SERVICE, SetLoggerLevel)(logger, level)
