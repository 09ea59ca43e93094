"""The runner's display check: one line and exit code 1 where Qt would abort (the real rqt dumps core)."""
import os
import socket
import subprocess
import sys
import tempfile

import pytest

from rqt_standalone import runner as standalone

SRC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src")


@pytest.mark.parametrize(
    "environ",
    [
        {"QT_QPA_PLATFORM": "offscreen"},
        {"QT_QPA_PLATFORM": "minimal"},
        {"WAYLAND_DISPLAY": "wayland-0"},
        {"DISPLAY": "remote.example.com:10.0"},
    ],
)
def test_a_usable_platform_is_not_questioned(environ):
    assert standalone.missing_display(environ) is None


def test_no_display_variables_are_named():
    problem = standalone.missing_display({"QT_QPA_PLATFORM": "xcb"})
    assert "DISPLAY" in problem and "WAYLAND_DISPLAY" in problem


def test_a_local_display_without_a_server_is_named():
    free = next(str(n) for n in range(900, 1000) if not os.path.exists("/tmp/.X11-unix/X%d" % n))
    assert (
        standalone.missing_display({"DISPLAY": ":%s.0" % free})
        == "no display: no X server answers on DISPLAY=:%s.0" % free
    )


def test_a_listening_local_display_passes(monkeypatch):
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "X5")
        server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        server.bind(path)
        server.listen(1)
        real_socket = socket.socket

        class RedirectedSocket(real_socket):
            def connect(self, address):
                return super().connect(path if address.endswith("/tmp/.X11-unix/X5") else address)

        monkeypatch.setattr(standalone.socket, "socket", RedirectedSocket)
        try:
            assert standalone.missing_display({"DISPLAY": ":5"}) is None
        finally:
            server.close()


def run_python(code: str, environ: dict) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        universal_newlines=True,
        env=environ,
        timeout=60,
    )


def test_run_without_display_prints_one_line_and_returns_1():
    """In a process of its own: the factory must never be called, no Qt application made."""
    code = (
        "import sys; sys.path.insert(0, %r)\n"
        "from rqt_standalone.runner import run\n"
        "def factory(args): raise AssertionError('called')\n"
        "sys.exit(run(factory, ['rqt_x'], 'x'))\n" % SRC
    )
    environ = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    result = run_python(code, environ)
    assert result.returncode == 1
    assert result.stdout == ""
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("rqt_x: no display: ")
    assert "python_qt_binding" not in result.stderr


RUN_WITH_FAKE_ROSPY = """
import os, signal, sys, types
sys.path.insert(0, %(src)r)
events = []
rospy = types.ModuleType("rospy")
rospy.init_node = lambda name, argv, anonymous, disable_signals: events.append(
    ("init_node", name == "rqt_gui_py_node_%%d" %% os.getpid(), anonymous, disable_signals))
rospy.myargv = lambda argv: [a for a in argv if ":=" not in a]
rospy.is_shutdown = lambda: %(ros_shutdown)s
rospy.signal_shutdown = lambda reason: events.append(("signal_shutdown",))
sys.modules["rospy"] = rospy
from python_qt_binding.QtCore import QTimer
from python_qt_binding.QtWidgets import QLabel
from rqt_standalone.runner import run

def factory(args):
    events.append(("factory", args))
    widget = QLabel("tool")
    widget.shutdown = lambda: events.append(("shutdown",))
    QTimer.singleShot(200, lambda: %(end)s)
    return widget

code = run(factory, ["rqt_x", "--flag", "__name:=other", "a:=b"], "title")
print(code, events)
"""


@pytest.mark.parametrize(
    "how, end, ros_shutdown",
    [
        ("window closed", "widget.window().close()", "False"),
        ("Ctrl-C", "os.kill(os.getpid(), signal.SIGINT)", "False"),
        ("SIGTERM", "os.kill(os.getpid(), signal.SIGTERM)", "False"),
        ("ROS shutdown", "None", "len(events) > 1"),
    ],
)
def test_run_ends_cleanly(how, end, ros_shutdown):
    """Each way out returns 0 after the widget's shutdown(), then the node's; the node is rqt_gui_py_node_<pid>."""
    code = RUN_WITH_FAKE_ROSPY % {"src": SRC, "end": end, "ros_shutdown": ros_shutdown}
    result = run_python(code, dict(os.environ, QT_QPA_PLATFORM="offscreen"))
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == (
        "0 [('init_node', True, False, True), ('factory', ['--flag']), ('shutdown',), ('signal_shutdown',)]"
    ), how
