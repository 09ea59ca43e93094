"""A GUI tool started under a test's own Xvfb, and screenshots of it until they show what is expected."""
from __future__ import annotations

import os
import subprocess
import time
from typing import Callable, List, Optional, Sequence, Tuple

import numpy as np

from .processes import stop_group
from .screen import start_xvfb
from .xwd_image import read_xwd


def matches(image: np.ndarray, colour: Sequence[int], tolerance: int) -> np.ndarray:
    """Mask of the pixels within `tolerance` of `colour` in every channel."""
    return np.all(np.abs(image.astype(int) - np.asarray(colour)) <= tolerance, axis=2)


def save_png(image: np.ndarray, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.imsave(path, image)


class ToolOnScreen:
    """`command` run in a session of its own with DISPLAY set to a fresh Xvfb; its output goes to `log_path`.
    Use as a context manager: leaving it stops the tool (SIGINT first) and the X server."""

    def __init__(self, command: Sequence[str], log_path: str, screen: str = "1024x768x24") -> None:
        self.command = list(command)
        self.log_path = log_path
        self.screen = screen
        self.xvfb: Optional[subprocess.Popen] = None
        self.process: Optional[subprocess.Popen] = None
        self.display = ""

    def __enter__(self) -> "ToolOnScreen":
        self.xvfb, self.display = start_xvfb(self.screen)
        with open(self.log_path, "w") as log:
            self.process = subprocess.Popen(
                self.command,
                env=dict(os.environ, DISPLAY=self.display),
                stdout=log,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        return self

    def __exit__(self, *_exc) -> None:
        if self.process is not None and self.process.poll() is None:
            stop_group(self.process)
        if self.xvfb is not None:
            stop_group(self.xvfb)

    def log(self) -> str:
        with open(self.log_path) as log:
            return log.read()

    def grab(self) -> Optional[np.ndarray]:
        """The whole screen as RGB, or None while it cannot be read (a window mapping)."""
        shot = subprocess.run(
            ["xwd", "-root", "-silent", "-display", self.display], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
        )
        return read_xwd(shot.stdout) if shot.returncode == 0 else None

    def wait_for(
        self, failures_of: Callable[[np.ndarray], List[str]], timeout: float, between: float = 0.5
    ) -> Tuple[Optional[np.ndarray], List[str]]:
        """Screenshots until failures_of(image) is empty or timeout; the last image and its failures. Raises
        RuntimeError with the tool's output if the tool exits meanwhile."""
        deadline = time.monotonic() + timeout
        image, failures = None, ["no screenshot"]
        while True:
            if self.process.poll() is not None:
                raise RuntimeError("%s exited with %s:\n%s" % (self.command, self.process.returncode, self.log()))
            grabbed = self.grab()
            if grabbed is not None:
                image, failures = grabbed, failures_of(grabbed)
            if not failures or time.monotonic() >= deadline:
                return image, failures
            time.sleep(between)  # nothing to wait on but the picture

    def interrupt(self, timeout: float) -> Optional[int]:
        """Ctrl-C as a terminal sends it (SIGINT to the group); the exit code, or None if still running."""
        os.killpg(self.process.pid, 2)
        try:
            return self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            return None
