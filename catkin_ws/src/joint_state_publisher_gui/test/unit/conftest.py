"""Qt without a display for pytest-qt, and the package's code from the source tree when the workspace is not
sourced (or the system's broken joint_state_publisher_gui is on the path)."""
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
try:
    import joint_state_publisher_gui.sliders  # noqa: F401
except ImportError:
    sys.modules.pop("joint_state_publisher_gui", None)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src"))
