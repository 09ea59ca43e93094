"""The widget on fake services: lists fill from background calls, choosing a level sets it at once, a node that
never answers times out with the window still responsive."""
import threading

import pytest

from rqt_logger_level.logger_level_widget import LoggerLevelWidget


class FakeServices:
    def __init__(self):
        self.loggers = {
            "/turtlesim": {"rosout": "INFO", "rospy.topics": "INFO", "rospy.client": "DEBUG"},
            "/teleop_turtle": {"rosout": "INFO"},
        }
        self.calls = []
        self.hang = threading.Event()  # set: calls to /hung block until released
        self.release = threading.Event()

    def list_nodes(self):
        return sorted(self.loggers) + ["/hung"]

    def get_loggers(self, node):
        self.calls.append((threading.current_thread() is threading.main_thread(), "get", node))
        if node == "/hung":
            self.release.wait(10)
            return []
        return sorted(self.loggers[node].items())

    def set_level(self, node, logger, level):
        self.calls.append((threading.current_thread() is threading.main_thread(), "set", node, logger, level))
        if node not in self.loggers:
            raise RuntimeError("service [%s/set_logger_level] unavailable" % node)
        self.loggers[node][logger] = level.upper()


@pytest.fixture
def fake():
    services = FakeServices()
    yield services
    services.release.set()


@pytest.fixture
def widget(qtbot, fake):
    made = LoggerLevelWidget([], services=fake, timeout=0.5)
    qtbot.addWidget(made)
    made.show()
    qtbot.waitUntil(lambda: made.node_list.count() == 3)
    yield made
    made.shutdown()


def texts(widget_list):
    return [widget_list.item(i).text() for i in range(widget_list.count())]


def test_nodes_then_loggers_then_the_current_level(qtbot, widget, fake):
    assert texts(widget.node_list) == ["/teleop_turtle", "/turtlesim", "/hung"]
    assert texts(widget.level_list) == ["Debug", "Info", "Warn", "Error", "Fatal"]
    widget.choose("/turtlesim")
    qtbot.waitUntil(lambda: widget.logger_list.count() == 3)
    assert texts(widget.logger_list) == ["rosout", "rospy.client", "rospy.topics"]
    widget.choose("/turtlesim", "rospy.client")
    assert widget.level_list.currentItem().text() == "Debug"
    assert all(not in_qt_thread for in_qt_thread, *_ in fake.calls)


def test_choosing_a_level_sets_it_at_once(qtbot, widget, fake):
    widget.choose("/turtlesim")
    qtbot.waitUntil(lambda: widget.logger_list.count() == 3)
    widget.choose("/turtlesim", "rosout", "Warn")
    qtbot.waitUntil(lambda: fake.loggers["/turtlesim"]["rosout"] == "WARN")
    qtbot.waitUntil(lambda: widget.status.text() == "/turtlesim: rosout set to Warn")
    assert (False, "set", "/turtlesim", "rosout", "Warn") in fake.calls
    widget.choose("/turtlesim", "rospy.topics")
    assert widget.level_list.currentItem().text() == "Info"
    widget.choose("/turtlesim", "rosout")
    assert widget.level_list.currentItem().text() == "Warn"


def test_a_hung_node_times_out_and_the_window_stays_usable(qtbot, widget, fake):
    widget.choose("/hung")
    qtbot.waitUntil(lambda: "did not answer" in widget.status.text(), timeout=3000)
    assert widget.status.text() == "/hung did not answer get_loggers: no answer within 0.5 s"
    widget.choose("/teleop_turtle")  # still usable while the hung call's thread waits
    qtbot.waitUntil(lambda: texts(widget.logger_list) == ["rosout"])


def test_refresh_keeps_the_chosen_node(qtbot, widget, fake):
    widget.choose("/teleop_turtle")
    qtbot.waitUntil(lambda: widget.logger_list.count() == 1)
    fake.loggers["/teleop_turtle"]["rospy.rosout"] = "ERROR"
    widget.refresh()
    qtbot.waitUntil(lambda: widget.logger_list.count() == 2)
    assert widget.node_list.currentItem().text() == "/teleop_turtle"


def test_unknown_options_are_refused(fake):
    with pytest.raises(SystemExit):
        LoggerLevelWidget(["--bogus"], services=fake)
