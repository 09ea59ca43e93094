"""Stopping what a test started in a session of its own (start_new_session=True), children included."""
from __future__ import annotations

import os
import signal
import subprocess


def stop_group(process: subprocess.Popen, grace: float = 15.0) -> None:
    """SIGINT the process group (roslaunch and rosrun pass it on to their nodes, which shut down cleanly), then
    SIGKILL what is left after ``grace`` seconds."""
    for sig, wait in ((signal.SIGINT, grace), (signal.SIGKILL, 5.0)):
        try:
            os.killpg(process.pid, sig)
            process.wait(wait)
            return
        except ProcessLookupError:
            return
        except subprocess.TimeoutExpired:
            continue
