#!/usr/bin/env python3
"""rostest node: `rqt` under Xvfb puts up "Default - rqt" as the node rqt_gui_py_node_<pid> and Ctrl-C ends it
with 0; its main window, on the same screen, opens all four tools from the Plugins menu in docks and shuts each down
when it closes; every tutorial command (bare on PATH and through rosrun) without a display prints one line naming
it and exits with 1.

The tools are built in this workspace, so they are not <test_depend>s: they depend on rqt_gui, and catkin would see
a cycle."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest
from workspace_testing.qt_wait import run_qt_until
from workspace_testing.tool_checks import assert_comes_up_and_stops, crop_to_widget
from workspace_testing.tool_window import ToolOnScreen, save_png

from rqt_gui import plugins

TITLE = "Default - rqt"
TOOLS = ("rqt_graph", "rqt_plot", "rqt_console", "rqt_logger_level")


class MainWindowTest(unittest.TestCase):
    def test_without_display_every_command_says_so_once(self):
        environ = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
        commands = [["rqt"]] + [[tool] for tool in TOOLS] + [["rosrun", "rqt_gui", "rqt_gui"]]
        commands += [["rosrun", tool, tool] for tool in TOOLS]
        for command in commands:
            if len(command) == 1:
                found = shutil.which(command[0], path=environ["PATH"])
                self.assertTrue(found and "/devel/bin/" in found, "%s on PATH: %s" % (command[0], found))
            result = subprocess.run(
                command, env=environ, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True
            )
            self.assertEqual(result.returncode, 1, "%s: %s" % (command, result.stderr))
            self.assertEqual(result.stderr.count("\n"), 1, "%s: %r" % (command, result.stderr))
            self.assertIn(": no display: DISPLAY and WAYLAND_DISPLAY are unset", result.stderr)

    def test_rqt_opens_the_four_tools(self):
        timeout = rospy.get_param("~timeout")
        shot_path = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "rqt_main_window.png")
        log_path = os.path.join(tempfile.gettempdir(), "rqt_main_window.log")
        with ToolOnScreen(["rqt"], log_path) as tool:
            assert_comes_up_and_stops(self, tool, TITLE, "/rqt_gui_py_node_%d" % tool.process.pid, timeout)

            os.environ["DISPLAY"] = tool.display
            from python_qt_binding.QtWidgets import QApplication

            from rqt_gui.main_window import MainWindow

            app = QApplication(["test_main_window"])
            found = plugins.available()
            self.assertEqual(sorted(p.package for p in found), sorted(TOOLS))
            window = MainWindow(found)
            window.setWindowTitle(TITLE)
            window.show()
            menu = window.menuBar().actions()[0].menu()
            actions = [a for group in menu.actions() if group.menu() for a in group.menu().actions()]
            self.assertEqual(sorted(a.objectName() for a in actions), sorted(TOOLS))
            try:
                for action in actions:
                    action.trigger()
                self.assertEqual(
                    sorted(type(dock.widget()).__name__ for dock in window.docks),
                    sorted(p.factory for p in found),
                    window.statusBar().currentMessage(),
                )
                graph_dock = next(d for d in window.docks if type(d.widget()).__name__ == "GraphWidget")
                graph_dock.raise_()
                graph = graph_dock.widget()
                self.assertTrue(run_qt_until(lambda: "/turtlesim" in graph.graph.nodes, timeout), graph.status.text())
                run_qt_until(lambda: False, 0.5)  # let the window paint
                image = tool.grab()
                self.assertIsNotNone(image)
                save_png(crop_to_widget(image, window), shot_path)
                for dock in list(window.docks):
                    dock.close()
                self.assertTrue(run_qt_until(lambda: not window.docks, timeout))
            finally:
                window.shutdown()
                window.close()
                app.processEvents()


if __name__ == "__main__":
    rospy.init_node("test_main_window")
    rostest.rosrun("rqt_gui", "main_window", MainWindowTest, sys.argv)
