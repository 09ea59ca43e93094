"""Qt without a screen (pytest-qt), and the package's code from the source tree when the workspace is not sourced."""
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("PYTEST_QT_API", "pyqt5")  # python_qt_binding is PyQt5; pytest-qt would take PyQt6 if present
try:
    import rqt_standalone.runner  # noqa: F401
except ImportError:  # not sourced
    sys.modules.pop("rqt_standalone", None)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src"))
