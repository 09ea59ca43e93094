#!/usr/bin/env python3
"""rostest node: with turtlesim_node and turtle_teleop_key (in a pseudo-terminal, as a user types it) running,
`rosrun rqt_graph rqt_graph` under Xvfb puts its window up as the node rqt_gui_py_node_<pid>; the graph its code
builds from the master holds /teleop_turtle -> /turtlesim on /turtle1/cmd_vel; the screenshot shows a drawn graph
(white scene with outlines and text, no node drawn dead); Ctrl-C ends the tool with exit code 0."""
from __future__ import annotations

import os
import pty
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np
import rospy
import rostest
from workspace_testing.processes import stop_group
from workspace_testing.tool_checks import tool_up_failures
from workspace_testing.tool_window import ToolOnScreen, matches, save_png

from rqt_graph.graph_model import Edge, GraphOptions, build_graph, node_id
from rqt_graph.ros_query import query_system_state

TITLE = "rqt_graph__RosGraph - rqt"
TELEOP_EDGE = Edge(node_id("/teleop_turtle"), node_id("/turtlesim"), "/turtle1/cmd_vel")


def cropped(image: np.ndarray) -> np.ndarray:
    """The screen without Xvfb's black background around the window."""
    ys, xs = np.nonzero(image.max(axis=2) > 0)
    return image[ys.min() : ys.max() + 1, xs.min() : xs.max() + 1] if len(xs) else image


class GraphWindow(unittest.TestCase):
    def test_tutorial_graph_on_screen(self):
        timeout = rospy.get_param("~timeout")
        shot_path = rospy.get_param("~screenshot") or os.path.join(tempfile.gettempdir(), "rqt_graph_turtlesim.png")
        terminal, terminal_side = pty.openpty()
        teleop = subprocess.Popen(
            ["rosrun", "turtlesim", "turtle_teleop_key"],
            stdin=terminal_side,
            stdout=terminal_side,
            stderr=terminal_side,
            start_new_session=True,
        )
        try:
            deadline = time.monotonic() + timeout
            graph = build_graph(query_system_state(rospy.get_name()), GraphOptions())
            while TELEOP_EDGE not in graph.edges and time.monotonic() < deadline:
                time.sleep(0.2)  # the connection comes up in the nodes' own time; nothing to wait on
                graph = build_graph(query_system_state(rospy.get_name()), GraphOptions())
            self.assertIn(TELEOP_EDGE, graph.edges, graph)
            self.assertEqual(
                {n: graph.nodes.get(n) for n in ("/turtlesim", "/teleop_turtle")},
                {"/turtlesim": True, "/teleop_turtle": True},
            )

            log_path = os.path.join(tempfile.gettempdir(), "rqt_graph_window.log")
            with ToolOnScreen(["rosrun", "rqt_graph", "rqt_graph"], log_path) as tool:
                node = "/rqt_gui_py_node_%d" % tool.process.pid

                def failures_of(image: np.ndarray):
                    failures = tool_up_failures(tool.display, TITLE, node, rospy.get_name())
                    white = matches(image, (255, 255, 255), 0)
                    rows, columns = np.nonzero(white.sum(axis=1) > 300)[0], np.nonzero(white.sum(axis=0) > 200)[0]
                    if len(rows) < 200 or len(columns) < 300:
                        failures.append("no graph scene: %d x %d white" % (len(columns), len(rows)))
                    else:
                        scene = image[rows.min() : rows.max() + 1, columns.min() : columns.max() + 1]
                        ink = int(np.count_nonzero(matches(scene, (0, 0, 0), 90)))
                        if ink < 400:  # two ellipses, their names, an arrow and its label
                            failures.append("graph scene has %d dark pixels" % ink)
                        dead = int(np.count_nonzero(matches(scene, (255, 0, 0), 60)))
                        if dead > 20:  # graph_view.DEAD: a node that did not answer the tool
                            failures.append("graph scene has %d red (dead node) pixels" % dead)
                    return failures

                image, failures = tool.wait_for(failures_of, timeout)
                if image is not None:
                    save_png(cropped(image), shot_path)
                self.assertEqual(failures, [], "screenshot %s; tool output:\n%s" % (shot_path, tool.log()))
                self.assertEqual(tool.interrupt(15.0), 0, "Ctrl-C; tool output:\n%s" % tool.log())
        finally:
            stop_group(teleop)
            os.close(terminal)
            os.close(terminal_side)


if __name__ == "__main__":
    rospy.init_node("test_graph_window")
    rostest.rosrun("rqt_graph", "graph_window", GraphWindow, sys.argv)
