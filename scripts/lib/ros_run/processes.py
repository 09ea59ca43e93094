"""Process handling shared by the benchmark, the soak, the demo's run and the three-hosts test (scripts/bench_sim.py,
scripts/soak.py, scripts/lib/run_demo.py, scripts/tests/test_three_hosts.py): process groups tagged in their
environment so that nothing they start outlives them, free loopback ports, and the error a tool reports."""
from __future__ import annotations

import contextlib
import itertools
import os
import signal
import socket
import subprocess
from typing import Dict, List, Optional

TAG_VARIABLE = "TURTLE_SIM_ODE_TOOL_TAG"  # in the environment of every process started through Processes
SHUTDOWN_TIMEOUT_S = 5.0


class ToolError(RuntimeError):
    """A tool could not set up or measure what it was asked to (the message says why)."""


def tagged_pids(tag: str) -> List[int]:
    """Processes whose environment has TAG_VARIABLE=tag."""
    needle = ("\0%s=%s\0" % (TAG_VARIABLE, tag)).encode()
    pids = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            with contextlib.suppress(OSError), open("/proc/%s/environ" % entry, "rb") as environ:
                if needle in b"\0" + environ.read():
                    pids.append(int(entry))
    return pids


class Processes:
    """Every process a tool starts, each as a process group whose processes carry a tag of their own in their
    environment: roslaunch starts each node in a session of its own, so the tag finds what killing the group misses.
    All are stopped, last started first, when the context closes."""

    def __init__(self, log_dir: str) -> None:
        self.log_dir = log_dir
        self._running: Dict[subprocess.Popen, str] = {}  # -> tag
        self._order: List[subprocess.Popen] = []
        self._tags = itertools.count()

    def __enter__(self) -> "Processes":
        return self

    def __exit__(self, *_: object) -> None:
        # A second Ctrl-C or SIGTERM while stopping must not leave anything behind.
        with contextlib.suppress(ValueError):
            previous = signal.signal(signal.SIGINT, signal.SIG_IGN), signal.signal(signal.SIGTERM, signal.SIG_IGN)
        try:
            for process in reversed(self._order):
                self.stop(process)
        finally:
            with contextlib.suppress(ValueError, NameError):
                signal.signal(signal.SIGINT, previous[0])
                signal.signal(signal.SIGTERM, previous[1])

    def start(self, command: List[str], env: Dict[str, str], log_name: Optional[str]) -> subprocess.Popen:
        """Start ``command`` as a new process group, output to ``log_name`` in the log directory (None: to ours)."""
        tag = "%d-%d" % (os.getpid(), next(self._tags))
        with contextlib.ExitStack() as stack:
            log = stack.enter_context(open(os.path.join(self.log_dir, log_name), "ab")) if log_name else None
            process = subprocess.Popen(
                command,
                env=dict(env, **{TAG_VARIABLE: tag}),
                stdin=subprocess.DEVNULL,
                stdout=log,
                stderr=subprocess.STDOUT if log else None,
                start_new_session=True,
            )
        self._running[process] = tag
        self._order.append(process)
        return process

    def stop(self, process: subprocess.Popen) -> None:
        """SIGINT to the group (roslaunch stops its nodes), then SIGKILL to whatever is left of it and to every
        process with its tag."""
        if process not in self._running:
            return
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGINT)
        with contextlib.suppress(subprocess.TimeoutExpired):
            process.wait(SHUTDOWN_TIMEOUT_S)
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        for pid in tagged_pids(self._running.pop(process)):
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        process.wait()

    def log_tail(self, log_name: str, lines: int = 20) -> str:
        with contextlib.suppress(OSError), open(os.path.join(self.log_dir, log_name), errors="replace") as log:
            return "".join(log.readlines()[-lines:])
        return ""


def free_port() -> int:
    """A TCP port free on loopback."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]
