"""Section 5 of the benchmark (scripts/bench_sim.py): scripts/lib/pybullet_peer.py on the same URDF, dt and wheel
command, run by the Python of a venv of its own under .cache/ (installed on first use), against section 1's figures."""
from __future__ import annotations

import fcntl
import json
import os
import shutil
import subprocess
import time
from typing import Any, Dict, Optional, Tuple

from bench_physics import circle_radius
from bench_plan import CIRCLE, REPO, URDF_PATH, BenchError, Plan

VENV = os.path.join(REPO, ".cache", "bench-venv")
PEER_SCRIPT = os.path.join(REPO, "scripts", "lib", "pybullet_peer.py")
PEER_PACKAGES = ("pybullet", "numpy")  # pybullet's import fails without numpy, which it does not declare
PIP_TIMEOUT_S = 900  # building PyBullet from its sdist is acceptable up to this
PEER_TIMEOUT_S = 600


def peer_python() -> Tuple[Optional[str], str]:
    """(python of the venv with PyBullet, how it came to be), installing it if needed, or (None, why not)."""
    python = os.path.join(VENV, "bin", "python")
    check = [python, "-c", "import pybullet"]
    os.makedirs(os.path.dirname(VENV), exist_ok=True)
    with open(VENV + ".lock", "w") as lock:  # concurrent runs install once
        fcntl.flock(lock, fcntl.LOCK_EX)
        if os.access(python, os.X_OK) and subprocess.run(check, capture_output=True).returncode == 0:
            return python, "reused " + VENV
        shutil.rmtree(VENV, ignore_errors=True)
        made = subprocess.run(["/usr/bin/python3", "-m", "venv", VENV], capture_output=True, text=True)
        if made.returncode != 0:
            return None, "/usr/bin/python3 -m venv failed: " + (made.stdout + made.stderr).strip()[-300:]
        print("  installing %s into %s ..." % (" ".join(PEER_PACKAGES), VENV), flush=True)
        start = time.monotonic()
        try:
            installed = subprocess.run(
                [python, "-m", "pip", "install", "-q"] + list(PEER_PACKAGES),
                capture_output=True,
                text=True,
                timeout=PIP_TIMEOUT_S,
            )
        except subprocess.TimeoutExpired:
            shutil.rmtree(VENV, ignore_errors=True)
            return None, "pip install %s took over %d s" % (" ".join(PEER_PACKAGES), PIP_TIMEOUT_S)
        if installed.returncode != 0 or subprocess.run(check, capture_output=True).returncode != 0:
            shutil.rmtree(VENV, ignore_errors=True)
            return None, "pip install %s failed: %s" % (" ".join(PEER_PACKAGES), installed.stderr.strip()[-300:])
        return python, "installed into %s in %.0f s" % (VENV, time.monotonic() - start)


def peer(plan: Plan, ours: Dict[str, Any], log_dir: str) -> Dict[str, Any]:
    """Section 5: scripts/lib/pybullet_peer.py run by the venv's Python, compared with ``ours`` (section 1)."""
    python, how = peer_python()
    if python is None:
        return {"name": "pybullet", "status": "unavailable", "reason": how}
    out = os.path.join(log_dir, "pybullet.json")
    command = [python, PEER_SCRIPT, "--urdf", URDF_PATH, "--out", out]
    command += ["--time-step", repr(ours["time_step"]), "--steps", str(plan.physics_steps)]
    command += ["--repeats", str(plan.physics_repeats), "--circle-seconds", repr(plan.circle_seconds)]
    command += ["--linear", repr(CIRCLE[0]), "--angular", repr(CIRCLE[1])]
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=PEER_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        raise BenchError("PyBullet peer took over %d s" % PEER_TIMEOUT_S) from None
    if result.returncode != 0:
        raise BenchError("PyBullet peer failed:\n" + (result.stdout + result.stderr)[-2000:])
    with open(out) as out_file:
        measured = json.load(out_file)
    return {
        "name": "pybullet",
        "status": "ok",
        "venv": how,
        "version": measured["version"],
        "time_step": ours["time_step"],
        "steps_per_s": measured["steps_per_s"],
        "us_per_step": 1e6 / measured["steps_per_s"],
        "ratio_to_ours": measured["steps_per_s"] / ours["steps_per_s"],
        "contacts_per_step": measured["contacts_per_step"],
        "collision_shapes": measured["collision_shapes"],
        "circle_radius_m": circle_radius(measured["track_xy"]),
        "ours_circle_radius_m": ours["circle_radius_m"],
        "circle_expected_radius_m": CIRCLE[0] / CIRCLE[1],
        "notes": measured["notes"],
    }
