"""A command on a pseudo-terminal of its own, for tests of keyboard programs (teleop nodes): its output read until
a text shows, keys written, the terminal's settings compared before and after."""
from __future__ import annotations

import os
import pty
import select
import subprocess
import termios
import time
from typing import List

from workspace_testing.processes import stop_group


class PseudoTerminal:
    """``command`` started in a session of its own with a pseudo-terminal as stdin, stdout and stderr."""

    def __init__(self, command: List[str]) -> None:
        self.master, self.slave = pty.openpty()
        self.settings_before = termios.tcgetattr(self.slave)
        self.output = b""
        self.process = subprocess.Popen(
            command, stdin=self.slave, stdout=self.slave, stderr=self.slave, start_new_session=True
        )

    def read_until(self, text: bytes, timeout: float) -> bool:
        """Read the output until ``text`` is in it (True) or ``timeout`` seconds pass (False)."""
        deadline = time.monotonic() + timeout
        while text not in self.output:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return False
            ready, _, _ = select.select([self.master], [], [], remaining)
            if ready:
                self.output += os.read(self.master, 4096)
        return True

    def write(self, keys: bytes) -> None:
        os.write(self.master, keys)

    def settings(self) -> list:
        return termios.tcgetattr(self.slave)

    def close(self) -> None:
        """Stop the command (and what it started) if still running; close the terminal."""
        if self.process.poll() is None:
            stop_group(self.process, grace=5.0)
        os.close(self.master)
        os.close(self.slave)
