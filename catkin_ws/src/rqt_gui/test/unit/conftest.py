"""Qt without a screen (pytest-qt), and the package's code from the source tree when the workspace is not sourced."""
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("PYTEST_QT_API", "pyqt5")  # python_qt_binding is PyQt5; pytest-qt would take PyQt6 if present
try:
    import rqt_gui.main_window  # noqa: F401
except ImportError:  # not sourced, or the system's rqt_gui on the path
    sys.modules.pop("rqt_gui", None)
    sys.modules.pop("rqt_standalone", None)
    HERE = os.path.dirname(os.path.abspath(__file__))
    sys.path[:0] = [
        os.path.join(HERE, "..", "..", "src"),
        os.path.join(HERE, "..", "..", "..", "rqt_standalone", "src"),
    ]
