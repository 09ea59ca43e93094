"""What a test of a ROS GUI tool asks of the screen and the master: is its window up, is its node registered."""
from __future__ import annotations

import subprocess
import unittest
from typing import List

import numpy as np


def has_window_titled(display: str, title: str) -> bool:
    """True if a window of that exact title exists on the X display (xwininfo's tree quotes the names)."""
    tree = subprocess.run(
        ["xwininfo", "-root", "-tree", "-display", display], stdout=subprocess.PIPE, universal_newlines=True
    ).stdout
    return '"%s"' % title in tree


def node_registered(node: str, caller_id: str) -> bool:
    """True if the ROS master knows the node (rosgraph is imported here: the rest of the package needs no ROS)."""
    import rosgraph

    try:
        rosgraph.Master(caller_id).lookupNode(node)
        return True
    except rosgraph.MasterError:
        return False


def crop_to_widget(image: np.ndarray, widget) -> np.ndarray:
    """The part of a screenshot a top-level Qt widget covers, frame included."""
    frame = widget.frameGeometry()
    return image[frame.top() : frame.bottom() + 1, frame.left() : frame.right() + 1]


def tool_up_failures(display: str, title: str, node: str, caller_id: str) -> List[str]:
    """What is still missing of a started tool: its window on the display, its node at the master."""
    failures = [] if node_registered(node, caller_id) else ["%s not registered" % node]
    return failures + ([] if has_window_titled(display, title) else ["no window titled %r" % title])


def assert_comes_up_and_stops(test: unittest.TestCase, tool, title: str, node: str, timeout: float) -> None:
    """A ToolOnScreen's window and node come up within timeout, and Ctrl-C then ends the tool with exit code 0."""
    import rospy

    _image, failures = tool.wait_for(
        lambda _image: tool_up_failures(tool.display, title, node, rospy.get_name()), timeout
    )
    test.assertEqual(failures, [], "tool output:\n%s" % tool.log())
    test.assertEqual(tool.interrupt(15.0), 0, "Ctrl-C; tool output:\n%s" % tool.log())
