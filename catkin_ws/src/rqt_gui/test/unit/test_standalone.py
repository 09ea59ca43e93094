"""The runner's display check: one line and exit code 1 where Qt would abort (the real rqt dumps core)."""
import os
import socket
import subprocess
import sys
import tempfile

import pytest

from rqt_gui import standalone

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


def test_run_without_display_prints_one_line_and_returns_1():
    """In a process of its own: the factory must never be called, no Qt application made."""
    code = (
        "import sys; sys.path.insert(0, %r)\n"
        "from rqt_gui.standalone import run\n"
        "def factory(args): raise AssertionError('called')\n"
        "sys.exit(run(factory, ['rqt_x'], 'x'))\n" % SRC
    )
    environ = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    result = subprocess.run(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        universal_newlines=True,
        env=environ,
    )
    assert result.returncode == 1
    assert result.stdout == ""
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("rqt_x: no display: ")
    assert "python_qt_binding" not in result.stderr
