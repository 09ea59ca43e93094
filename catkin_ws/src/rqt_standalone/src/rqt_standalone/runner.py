"""Run one tool's widget as a window of its own, as every rqt command does.

    run(widget_factory, argv=None, title="rqt") -> exit code

``widget_factory(args)`` gets the command line without the program name and without ROS remappings
(rospy.myargv) and returns the QWidget to show (a QMainWindow is shown as it is, anything else inside one). The
process becomes the ROS node ``rqt_gui_py_node_<pid>``, as the real rqt tools do. Ctrl-C (SIGINT), SIGTERM, a ROS
shutdown and closing the window all end the Qt loop; the widget's ``shutdown()``, where it has one, is then called
before the node shuts down. Without a display the runner prints one line saying so and returns 1 (Qt itself would
abort with a core dump).
"""
from __future__ import annotations

import errno
import os
import re
import signal
import socket
import sys
from typing import Callable, List, Mapping, Optional, Sequence

# Qt platforms that need no display server.
HEADLESS_PLATFORMS = ("offscreen", "minimal")
# How often the Qt loop lets Python run its signal handlers and look at rospy's shutdown flag (ms).
POLL_INTERVAL_MS = 100
LOCAL_DISPLAY = re.compile(r"^(?:unix)?:(\d+)(?:\.\d+)?$")


def _x_socket_answers(number: str) -> bool:
    """True when an X server listens on the local display ``number`` (abstract or file socket, as Xlib tries)."""
    path = "/tmp/.X11-unix/X" + number
    for address in ("\0" + path, path):
        probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            probe.connect(address)
            return True
        except OSError as error:
            if error.errno not in (errno.ENOENT, errno.ECONNREFUSED):
                return True  # something is there (e.g. permissions): let Qt say what
        finally:
            probe.close()
    return False


def missing_display(environ: Mapping[str, str]) -> Optional[str]:
    """Why Qt would find no screen with this environment, or None when it will find one."""
    platform = environ.get("QT_QPA_PLATFORM", "").split(":")[0]
    if platform in HEADLESS_PLATFORMS or environ.get("WAYLAND_DISPLAY"):
        return None
    display = environ.get("DISPLAY", "")
    if not display:
        return (
            "no display: DISPLAY and WAYLAND_DISPLAY are unset (log in to a desktop, use `ssh -X`, or run under "
            "`xvfb-run -a`)"
        )
    local = LOCAL_DISPLAY.match(display)
    if local and not _x_socket_answers(local.group(1)):
        return "no display: no X server answers on DISPLAY=%s" % display
    return None


def _shutdown_widget(widget: object) -> None:
    shutdown = getattr(widget, "shutdown", None)
    if callable(shutdown):
        shutdown()


def run(widget_factory: Callable[[List[str]], object], argv: Optional[Sequence[str]] = None, title: str = "rqt") -> int:
    """Show ``widget_factory(args)`` in a window until it is closed or the process is interrupted; the exit code."""
    argv = list(sys.argv if argv is None else argv)
    program = os.path.basename(argv[0]) if argv else "rqt"
    problem = missing_display(os.environ)
    if problem:
        print("%s: %s" % (program, problem), file=sys.stderr)
        return 1

    import rospy
    from python_qt_binding.QtCore import QTimer
    from python_qt_binding.QtWidgets import QApplication, QMainWindow

    app = QApplication.instance() or QApplication(argv[:1])
    rospy.init_node("rqt_gui_py_node_%d" % os.getpid(), argv=argv, anonymous=False, disable_signals=True)
    widget = None
    try:
        widget = widget_factory(rospy.myargv(argv)[1:])
        if isinstance(widget, QMainWindow):
            window = widget
        else:
            window = QMainWindow()
            window.setCentralWidget(widget)
            window.resize(window.sizeHint().expandedTo(window.minimumSizeHint()).expandedTo(_default_size()))
        window.setWindowTitle(title)

        def quit_loop(*_signal_args: object) -> None:
            app.quit()

        previous = {sig: signal.signal(sig, quit_loop) for sig in (signal.SIGINT, signal.SIGTERM)}
        # Python runs signal handlers only between bytecodes, never inside Qt's C++ loop: a timer gives it turns.
        ticker = QTimer()
        ticker.timeout.connect(lambda: rospy.is_shutdown() and app.quit())
        ticker.start(POLL_INTERVAL_MS)
        window.show()
        try:
            return app.exec_()
        finally:
            ticker.stop()
            for sig, handler in previous.items():
                signal.signal(sig, handler)
    finally:
        if widget is not None:
            _shutdown_widget(widget)
        rospy.signal_shutdown("%s window closed" % program)


def _default_size():
    from python_qt_binding.QtCore import QSize

    return QSize(800, 600)
