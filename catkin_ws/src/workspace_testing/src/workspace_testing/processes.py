"""Stopping what a test started in a session of its own (start_new_session=True), children included."""
from __future__ import annotations

import os
import signal
import subprocess
import tempfile
from typing import Dict, List, Optional


def descendants(pid: int) -> List[int]:
    """Every process below ``pid`` (Linux /proc), children before their own children."""
    found: List[int] = []
    parents = [pid]
    while parents:
        parent = parents.pop()
        try:
            with open(f"/proc/{parent}/task/{parent}/children") as children:
                for child in (int(text) for text in children.read().split()):
                    found.append(child)
                    parents.append(child)
        except (FileNotFoundError, ProcessLookupError, ValueError):
            continue
    return found


def stop_group(process: subprocess.Popen, grace: float = 15.0) -> None:
    """SIGINT the process group (roslaunch and rosrun pass it on to their nodes, which shut down cleanly), then
    SIGKILL what is left after ``grace`` seconds. roslaunch starts each node in a process group of its own, so the
    processes below the group are noted first and any still alive at the end are killed too: a node that outlived
    its roslaunch would otherwise be left behind."""
    below = descendants(process.pid)
    for sig, wait in ((signal.SIGINT, grace), (signal.SIGKILL, 5.0)):
        try:
            os.killpg(process.pid, sig)
            process.wait(wait)
            break
        except ProcessLookupError:
            break
        except subprocess.TimeoutExpired:
            continue
    for pid in below:
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


class LoggedProcess:
    """A command (a test's ``roslaunch``, say) started in a session of its own, its output kept in a temporary file
    for failure messages; ``stop`` ends it with ``stop_group``, ``close`` stops it and drops the output."""

    def __init__(self, command: List[str], env: Optional[Dict[str, str]] = None, grace: float = 15.0) -> None:
        self._log = tempfile.TemporaryFile(mode="w+")
        self._grace = grace
        self.process = subprocess.Popen(
            command, stdout=self._log, stderr=subprocess.STDOUT, start_new_session=True, env=env
        )

    def output(self, tail: int = 6000) -> str:
        """The last ``tail`` characters the command printed (stdout and stderr)."""
        self._log.flush()
        self._log.seek(0)
        return self._log.read()[-tail:]

    def stop(self) -> None:
        """Stop the command and what it started (SIGINT, then SIGKILL after ``grace`` s); nothing once it ended."""
        if self.process.poll() is None:
            stop_group(self.process, self._grace)

    def close(self) -> None:
        self.stop()
        self._log.close()
