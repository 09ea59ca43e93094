"""Node list and level names. Expected from ros-visualization/rqt_logger_level logger_level_service_caller.py
(get_node_names: a node listed when it offers <node>/set_logger_level; get_levels) and rospy/client.py
(_logging_level_names: what get_loggers answers)."""
import pytest

from rqt_logger_level.logger_model import LEVELS, level_index, logger_nodes


def test_nodes_offering_their_own_set_logger_level_sorted():
    services = [
        ("/turtlesim/set_logger_level", ["/turtlesim"]),
        ("/turtlesim/get_loggers", ["/turtlesim"]),
        ("/clear", ["/turtlesim"]),
        ("/teleop_turtle/set_logger_level", ["/teleop_turtle"]),
        ("/rosout/set_logger_level", ["/rosout"]),
        ("/other/set_logger_level", ["/impostor"]),  # someone else's: not /other's own
        ("/ns/deep/node/set_logger_level", ["/ns/deep/node"]),
    ]
    assert logger_nodes(services) == ["/ns/deep/node", "/rosout", "/teleop_turtle", "/turtlesim"]


def test_levels_as_the_real_tool_lists_them():
    assert LEVELS == ("Debug", "Info", "Warn", "Error", "Fatal")


@pytest.mark.parametrize(
    "reported, row", [("DEBUG", 0), ("INFO", 1), ("WARN", 2), ("ERROR", 3), ("FATAL", 4), ("warn", 2), ("Warning", 2)]
)
def test_reported_levels_find_their_row(reported, row):
    assert level_index(reported) == row


def test_an_unknown_level_has_no_row():
    assert level_index("NOTSET") is None and level_index("") is None
