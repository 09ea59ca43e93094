#!/usr/bin/env python3
"""Benchmark of the turtle_sim_ode simulator (issue #8): prints a table and writes JSON.

1. physics only (no ROS): Simulation.step of one TurtleBot, and the bare PyODE floor for the same bodies;
2. the full node unthrottled (real_time_factor 0), every sensor subscribed: RTF for 1, 5, 10 robots at 1 and 10 ms,
   and 1 robot at 1 ms writing each message at once (write_batch_period 0, issue #33);
3. real time (real_time_factor 1): achieved RTF and the spread of /clock intervals;
4. roslaunch turtlebot_world.launch to the first /odom message;
5. PyBullet (in a venv of its own under .cache/) on the same URDF: steps/s and the circle radius it drives;
6. cameras (issue #15): an RGB-D camera's cost without ROS and in the full node, watched and nobody watching;
7. lidar (issue #23): a VLP-16's (16 x 1800 rays at 10 Hz) and a 64-laser lidar's cost without ROS;
8. ros_control (issue #24): a 1 kHz controller manager's cost in real-time factor, without ROS;
9. scaling (issue #33): 300 IMUs on a TurtleBot against the bare TurtleBot, and a 1000-link chain, through the node's
   per-step loop and plugin adapters without a master.
10. viewer (issue #30): the node's RTF with a viewer's /gazebo/scene_markers subscriber over that without.

The targets (issues #8, #15, #30, #33) are ratios of two figures of the same run where they can be; the table prints the
machine's load and the CPU time the host stole, so a figure measured under load can be told from a quiet one.

Every ROS process runs against a master of its own on a free port and is stopped at the end, also on Ctrl-C, SIGTERM
or error: SIGINT, then SIGKILL to its process group and to every process with its tag in the environment (roslaunch
starts nodes in sessions of their own). Without the workspace sourced it sources it itself (scripts/lib/ros_run/workspace_env.py).
"""
from __future__ import annotations

import argparse
import datetime
import os
import shutil
import signal
import sys
import tempfile
from typing import Any, Callable, Dict, Optional, Sequence

# This file parses the arguments and runs the sections; they are in scripts/lib/bench: physics (1), node and
# probe (2-4), peer (5), camera and node (6), lidar (7), control (8), scaling (9), viewer (10), report (targets,
# table), plan (run sizes).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from ros_run.workspace_env import ensure_workspace_env  # noqa: E402

ensure_workspace_env(__file__, sys.argv[1:])  # run as the README shows it, the workspace sourced or not
from bench.camera import camera_cost  # noqa: E402
from bench.lidar import lidar_cost  # noqa: E402
from bench.control import ros_control_cost  # noqa: E402
from bench.viewer import viewer_cost  # noqa: E402
from bench.node import camera_node, full_node, launch_to_first_odom, real_time  # noqa: E402
from bench.peer import peer  # noqa: E402
from bench.physics import physics_only  # noqa: E402
from bench.plan import FULL, QUICK, REPO, Plan  # noqa: E402
from bench.report import close_machine, machine, table, targets, write_report  # noqa: E402
from bench.scaling import scaling_cost_apart  # noqa: E402
from ros_run.process_stats import cpu_ticks  # noqa: E402
from ros_run.processes import Processes, ToolError  # noqa: E402

DEFAULT_JSON = os.path.join(REPO, "bench_results", "bench_sim.json")


def measure(results: Dict[str, Any], key: str, title: str, run: Callable[[], Dict[str, Any]]) -> None:
    """results[key] = run(), or {"error": why} if it could not be measured."""
    print("%s ..." % title, flush=True)
    try:
        results[key] = run()
    except ToolError as error:
        results[key] = {"error": str(error)}
        print("  ERROR: %s" % error, flush=True)


def cameras(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 6: bench.camera without ROS, then the node."""
    print("  without ROS ...", flush=True)
    return {"in_process": camera_cost(plan.physics_steps, plan.physics_repeats), "node": camera_node(plan, processes)}


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="short smoke run: shorter windows, robots 1 and 2")
    parser.add_argument("--no-peer", action="store_true", help="skip PyBullet")
    parser.add_argument("--json", default=DEFAULT_JSON, help="where to write the results (default: %(default)s)")
    args = parser.parse_args(argv)
    if not shutil.which("roscore") or not shutil.which("roslaunch"):
        print("roscore/roslaunch not found: source catkin_ws/devel/setup.bash first", file=sys.stderr)
        return 2
    # SIGTERM unwinds like Ctrl-C, so every process group started is stopped.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    plan = QUICK if args.quick else FULL
    results: Dict[str, Any] = {
        "benchmark": "turtle_sim_ode, issue #8",
        "mode": "quick" if args.quick else "full",
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "machine": machine(),
    }
    ticks_at_start = cpu_ticks()
    with tempfile.TemporaryDirectory(prefix="bench_sim-") as log_dir, Processes(log_dir) as processes:
        measure(results, "physics_only", "1. physics only", lambda: physics_only(plan))
        if args.no_peer:
            results["peer"] = {"name": "pybullet", "status": "skipped", "reason": "--no-peer"}
        else:
            measure(results, "peer", "5. peer: PyBullet", lambda: peer(plan, results["physics_only"], log_dir))
        measure(results, "full_node", "2. full node, unthrottled", lambda: full_node(plan, processes))
        measure(results, "real_time", "3. real time", lambda: real_time(plan, processes))
        measure(results, "launch", "4. launch to first /odom", lambda: launch_to_first_odom(plan, processes))
        measure(results, "cameras", "6. cameras", lambda: cameras(plan, processes))
        measure(results, "lidar", "7. lidar", lambda: lidar_cost(plan.physics_steps, plan.physics_repeats))
        measure(results, "ros_control", "8. ros_control", lambda: ros_control_cost(plan))
        measure(results, "scaling", "9. scaling", lambda: scaling_cost_apart(plan.physics_steps, plan.physics_repeats))
        measure(results, "viewer", "10. viewer", lambda: viewer_cost(plan, processes))
    close_machine(results, ticks_at_start)
    results["targets"] = targets(results)
    return write_report(results, table(results), args.json)


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("\ninterrupted: every process started was stopped", file=sys.stderr)
        sys.exit(130)
