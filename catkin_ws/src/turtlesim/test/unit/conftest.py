"""Let the unit tests import the package's Python code from the source tree when the workspace is not sourced.

When it is sourced, the devel space's turtlesim package (which holds the generated messages) already reaches
src/turtlesim, and it must stay first: putting src/ first would hide turtlesim.msg and turtlesim.srv.
"""
import os
import sys

try:
    import turtlesim.world  # noqa: F401
except ImportError:  # not sourced, or only a system turtlesim (ros-noetic-turtlesim) on the path
    sys.modules.pop("turtlesim", None)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src"))
