"""A virtual X screen of a test's own."""
from __future__ import annotations

import os
import subprocess
from typing import Tuple


def start_xvfb(screen: str = "1024x768x24") -> Tuple[subprocess.Popen, str]:
    """Xvfb on a display number it picks itself (-displayfd), so parallel tests never collide; -noreset keeps it
    accepting connections when its last client leaves (it refuses them while it resets). Returns the server (stop
    it with processes.stop_group) and the DISPLAY value."""
    read_end, write_end = os.pipe()
    server = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write_end), "-screen", "0", screen, "-nolisten", "tcp", "-noreset"],
        pass_fds=(write_end,),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    os.close(write_end)
    with os.fdopen(read_end) as display_number:
        return server, ":" + display_number.readline().strip()
