"""Qt without a display for pytest-qt, and the package's code from the source tree when the workspace is not
sourced."""
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
try:
    import rqt_plot.data_window  # noqa: F401
except ImportError:  # not sourced, or the system's real rqt_plot on the path
    sys.modules.pop("rqt_plot", None)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src"))
