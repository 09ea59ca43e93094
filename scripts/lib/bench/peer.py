"""Section 5 of the benchmark (scripts/bench_sim.py): scripts/lib/pybullet_peer.py on the same URDF, dt and wheel
command, run by the Python of a venv of its own under .cache/ (installed on first use), against section 1's figures."""
from __future__ import annotations

import json
import os
import subprocess
from typing import Any, Dict, Optional, Tuple

from bench.physics import circle_radius
from bench.plan import CIRCLE, REPO, URDF_PATH, BenchError, Plan
from peers.venv import venv_with

VENV = os.path.join(REPO, ".cache", "bench-venv")
PEER_SCRIPT = os.path.join(REPO, "scripts", "lib", "peers", "pybullet_peer.py")
PEER_PACKAGES = ("pybullet", "numpy")  # pybullet's import fails without numpy, which it does not declare
PIP_TIMEOUT_S = 900  # building PyBullet from its sdist is acceptable up to this
PEER_TIMEOUT_S = 600


def peer_python() -> Tuple[Optional[str], str]:
    """(python of the venv with PyBullet, how it came to be), installing it if needed, or (None, why not)."""
    return venv_with(VENV, [PEER_PACKAGES], "import pybullet", PIP_TIMEOUT_S)


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
