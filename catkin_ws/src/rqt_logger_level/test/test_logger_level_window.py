#!/usr/bin/env python3
"""rostest node: `rosrun rqt_logger_level rqt_logger_level` under Xvfb puts its window up as the node
rqt_gui_py_node_<pid> and Ctrl-C ends it with exit code 0; then the tool's widget, on the same screen, lists
/turtlesim, its loggers, and setting turtlesim's `rosout` logger (where rospy.logwarn goes) to Warn makes
/turtlesim/get_loggers report WARN. The screenshot is of that widget."""
from __future__ import annotations

import os
import sys
import tempfile
import unittest

import rospy
import rostest
from roscpp.srv import GetLoggers
from workspace_testing.qt_wait import run_qt_until
from workspace_testing.tool_checks import assert_comes_up_and_stops, crop_to_widget
from workspace_testing.tool_window import ToolOnScreen, save_png

TITLE = "rqt_logger_level__LoggerLevel - rqt"


def turtlesim_level(logger: str) -> str:
    loggers = rospy.ServiceProxy("/turtlesim/get_loggers", GetLoggers)().loggers
    return {entry.name: entry.level for entry in loggers}.get(logger, "")


class LoggerLevelWindow(unittest.TestCase):
    def test_set_turtlesim_to_warn(self):
        timeout = rospy.get_param("~timeout")
        shot_path = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "rqt_logger_level.png")
        rospy.wait_for_service("/turtlesim/set_logger_level", timeout)
        self.assertEqual(turtlesim_level("rosout"), "INFO")
        log_path = os.path.join(tempfile.gettempdir(), "rqt_logger_level_window.log")
        with ToolOnScreen(["rosrun", "rqt_logger_level", "rqt_logger_level"], log_path) as tool:
            assert_comes_up_and_stops(self, tool, TITLE, "/rqt_gui_py_node_%d" % tool.process.pid, timeout)

            os.environ["DISPLAY"] = tool.display
            from python_qt_binding.QtCore import Qt
            from python_qt_binding.QtWidgets import QApplication, QMainWindow

            from rqt_logger_level.logger_level_widget import LoggerLevelWidget

            app = QApplication(["test_logger_level_window"])
            window = QMainWindow()
            widget = LoggerLevelWidget([])
            window.setCentralWidget(widget)
            window.setWindowTitle(TITLE)
            window.resize(640, 360)
            window.show()
            try:

                def listed(widget_list, name):
                    return bool(widget_list.findItems(name, Qt.MatchExactly))

                self.assertTrue(
                    run_qt_until(lambda: listed(widget.node_list, "/turtlesim"), timeout), widget.status.text()
                )
                widget.choose("/turtlesim")
                self.assertTrue(
                    run_qt_until(lambda: listed(widget.logger_list, "rosout"), timeout), widget.status.text()
                )
                widget.choose("/turtlesim", "rosout", "Warn")
                self.assertTrue(
                    run_qt_until(lambda: widget.status.text() == "/turtlesim: rosout set to Warn", timeout),
                    widget.status.text(),
                )
                self.assertEqual(turtlesim_level("rosout"), "WARN")
                run_qt_until(lambda: False, 0.3)  # let the window paint what it shows now
                image = tool.grab()
                self.assertIsNotNone(image)
                save_png(crop_to_widget(image, window), shot_path)
            finally:
                widget.shutdown()
                window.close()
                app.processEvents()


if __name__ == "__main__":
    rospy.init_node("test_logger_level_window")
    rostest.rosrun("rqt_logger_level", "logger_level_window", LoggerLevelWindow, sys.argv)
