"""A venv of its own under .cache/ for an optional benchmark peer (PyBullet for bench.peer, the offscreen renderers
for camera_peers): made by /usr/bin/python3 on first use, its packages from PyPI, under a lock so that concurrent
runs install once."""
from __future__ import annotations

import fcntl
import os
import shutil
import subprocess
import time
from typing import Optional, Sequence, Tuple


def venv_with(venv: str, installs: Sequence[Sequence[str]], check: str, timeout_s: float) -> Tuple[Optional[str], str]:
    """(the venv's python, how it came to be) once the Python code ``check`` runs in it, after one ``pip install``
    per entry of ``installs``, in order, if it did not; or (None, why not). A failed install leaves the venv as it
    is (other peers may share it); pip takes up from there next time."""
    python = os.path.join(venv, "bin", "python")
    check_command = [python, "-c", check]
    os.makedirs(os.path.dirname(venv), exist_ok=True)
    with open(venv + ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if (
            os.access(python, os.X_OK)
            and subprocess.run(check_command, check=False, capture_output=True).returncode == 0
        ):
            return python, "reused " + venv
        if not os.access(python, os.X_OK):
            shutil.rmtree(venv, ignore_errors=True)
            made = subprocess.run(["/usr/bin/python3", "-m", "venv", venv], check=False, capture_output=True, text=True)
            if made.returncode != 0:
                return None, "/usr/bin/python3 -m venv failed: " + (made.stdout + made.stderr).strip()[-300:]
        start = time.monotonic()
        for packages in installs:
            print("  installing %s into %s ..." % (" ".join(packages), venv), flush=True)
            try:
                installed = subprocess.run(
                    [python, "-m", "pip", "install", "-q"] + list(packages),
                    check=False,
                    capture_output=True,
                    text=True,
                    timeout=timeout_s,
                )
            except subprocess.TimeoutExpired:
                return None, "pip install %s took over %d s" % (" ".join(packages), timeout_s)
            if installed.returncode != 0:
                return None, "pip install %s failed: %s" % (" ".join(packages), installed.stderr.strip()[-300:])
        checked = subprocess.run(check_command, check=False, capture_output=True, text=True)
        if checked.returncode != 0:
            last_line = (checked.stdout + checked.stderr).strip().splitlines()[-1:]
            return None, "installed, but %r fails: %s" % (check, "".join(last_line))
        return python, "installed into %s in %.0f s" % (venv, time.monotonic() - start)
