"""Lets a script under scripts/ run as the README shows it, sourced or not: without the workspace's environment
(catkin_ws/devel/setup.bash, the system Python, loopback), the script runs itself again inside it, as demo.sh and
soak.sh source scripts/lib/ros_env.sh before they start Python. Standard library only."""
from __future__ import annotations

import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
WORKSPACE = os.path.join(REPO, "catkin_ws")
# Set in the environment of the run inside, so that a workspace that still cannot be imported is an error, not a loop.
MARK = "TSO_WORKSPACE_ENV"


def in_workspace_env(package: str = "turtle_sim_ode") -> bool:
    try:
        __import__(package)
        __import__("rospy")
    except ImportError:
        return False
    return True


def ensure_workspace_env(script: str, argv: list) -> None:
    """Return if the workspace's Python packages import; else exec ``script`` with ``argv`` under /usr/bin/python3
    with scripts/lib/ros_env.sh sourced (exit 1 with a hint if the workspace was never built)."""
    if in_workspace_env():
        return
    if os.environ.get(MARK):
        sys.exit(
            "%s: the workspace's Python packages still do not import after sourcing %s; run scripts/build.sh"
            % (os.path.basename(script), os.path.join(WORKSPACE, "devel", "setup.bash"))
        )
    if not os.path.isfile(os.path.join(WORKSPACE, "devel", "setup.bash")):
        sys.exit(
            "%s: the workspace is not built (no catkin_ws/devel/setup.bash): run scripts/build.sh first"
            % os.path.basename(script)
        )
    # setup.bash reads the positional parameters as its own options: they are put aside before it is sourced.
    command = 'ws=$1 env_sh=$2; shift 2; args=("$@"); set --; SOURCE_WORKSPACE=$ws . "$env_sh" && exec /usr/bin/python3 "${args[@]}"'
    env = dict(os.environ, **{MARK: "1"})
    os.execve(
        "/bin/bash",
        [
            "bash",
            "-c",
            command,
            "bash",
            WORKSPACE,
            os.path.join(REPO, "scripts", "lib", "ros_env.sh"),
            os.path.abspath(script),
        ]
        + list(argv),
        env,
    )
