#!/usr/bin/env python3
"""Soak test of the turtle_sim_ode simulator (issue #9): does it stay flat under a long, busy run?

A master of its own on a free port and roslaunch turtle_sim_ode turtlebot_world.launch real_time_factor:=0, each in a
process group of its own; then, for --duration seconds:
  - the TurtleBot drives a circle (Twist at 10 Hz wall on /mobile_base/commands/velocity), reversing now and then so
    that it stays where it is; /odom and /scan are subscribed, so they are produced;
  - models are spawned and deleted in a loop through /gazebo/spawn_urdf_model, /gazebo/spawn_sdf_model and
    /gazebo/delete_model: a URDF box and an SDF box in turn, some with a robot_namespace, and every --robot-every-th
    a TurtleBot3 burger (plugins: drive, IMU, bumper, ground truth) in a namespace of its own, so that the ROS
    publishers and subscribers of a model are made and dropped too; each call's success is checked;
  - the simulator process is sampled every --sample-period seconds: resident memory (VmRSS), threads, open file
    descriptors (by kind: socket, eventpoll, ...), CPU time, and the sim time reached (/clock). Threads and fds are
    the least of a few reads 50 ms apart, so that a service connection alive only during a call is not counted.

It prints a table of the samples and a summary, writes JSON (--json), and exits 1 if a spawn or delete failed, the
simulator died, sim time stopped advancing between two samples, threads or fds rose more than --max-thread-growth /
--max-fd-growth above the first sample after the warm-up (at the end or at any sample in between: fds that only the
garbage collector frees rise and fall), or memory grew faster than --max-rss-growth-mib-per-min after the warm-up
(both end to end and as the least-squares trend: a sustained growth, not one step of the allocator); 2 if it could
not run, 130 or 143 on Ctrl-C or SIGTERM.

The velocity commands come at 10 Hz wall: above a real-time factor of about 6 the drive's cmd_timeout (0.6 s of sim
time) passes between two of them and the robot drives in bursts, which is load all the same.

Everything it starts is stopped on exit, also on Ctrl-C, SIGTERM and errors. Without the workspace sourced it
sources it itself (scripts/lib/ros_run/workspace_env.py; scripts/soak.sh does too).
"""
from __future__ import annotations

import argparse
import datetime
import importlib
import json
import os
import platform
import shutil
import signal
import sys
import tempfile
import traceback
from typing import Any, Dict, Optional, Sequence

# This file parses the arguments and reports; the soak is in scripts/lib/soak: node (the driving and spawning node),
# sampling (the run and its samples), report (the verdict and the table).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from ros_run.workspace_env import ensure_workspace_env  # noqa: E402

ensure_workspace_env(__file__, sys.argv[1:])  # run as the README shows it, the workspace sourced or not
from ros_run.processes import Processes, ToolError  # noqa: E402
from soak.node import COMMAND_PERIOD_S  # noqa: E402
from soak.report import DEFAULT_MAX_COUNT_GROWTH, DEFAULT_MAX_RSS_GROWTH_MIB_PER_MIN, summarize, table  # noqa: E402
from soak.sampling import run_soak  # noqa: E402


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--duration", type=float, default=60.0, help="seconds of soak (default: %(default)s)")
    parser.add_argument("--json", help="write the samples and summary here")
    parser.add_argument(
        "--warmup",
        type=float,
        help="seconds before the growth baseline is taken (default: 20%% of the duration, at least 10 s)",
    )
    parser.add_argument(
        "--sample-period", type=float, help="seconds between samples (default: duration / 60, at least 5 s)"
    )
    parser.add_argument("--spawn-rate", type=float, default=2.0, help="spawns per second (default: %(default)s)")
    parser.add_argument(
        "--live-models", type=int, default=3, help="soak models alive at a time before the oldest is deleted"
    )
    parser.add_argument(
        "--robot-every",
        type=int,
        default=5,
        help="every Nth spawn is a burger robot with plugins in a namespace of its own (0: never; default %(default)s)",
    )
    parser.add_argument(
        "--max-rss-growth-mib-per-min",
        type=float,
        default=DEFAULT_MAX_RSS_GROWTH_MIB_PER_MIN,
        help="sustained RSS growth after warm-up that fails the soak (default: %(default)s)",
    )
    parser.add_argument("--max-thread-growth", type=int, default=DEFAULT_MAX_COUNT_GROWTH)
    parser.add_argument("--max-fd-growth", type=int, default=DEFAULT_MAX_COUNT_GROWTH)
    parser.add_argument("--keep-logs", help="copy the ROS logs (roscore, roslaunch, nodes) into this directory")
    parser.add_argument("-v", "--verbose", action="store_true", help="print each sample as it is taken")
    args = parser.parse_args(argv)
    if args.duration <= 0 or args.spawn_rate <= 0 or args.live_models < 0 or args.robot_every < 0:
        parser.error("--duration and --spawn-rate must be > 0, --live-models and --robot-every >= 0")
    if args.warmup is None:
        args.warmup = max(10.0, 0.2 * args.duration)
    if args.sample_period is None:
        args.sample_period = max(5.0, args.duration / 60.0)
    if not shutil.which("roscore") or not shutil.which("roslaunch"):
        print("roscore/roslaunch not found: source catkin_ws/devel/setup.bash first", file=sys.stderr)
        return 2
    try:
        for module in ("rospy", "gazebo_msgs.srv"):  # here, to fail early with a clear message
            importlib.import_module(module)
    except ImportError as error:
        print(
            "ROS Python is not importable (%s): run with /usr/bin/python3, workspace sourced" % error, file=sys.stderr
        )
        return 2
    # Ctrl-C (SIGINT, even when the shell started us with it ignored) and SIGTERM unwind, so that every process group
    # started is stopped.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    result: Dict[str, Any] = {
        "soak": "turtle_sim_ode, issue #9",
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "machine": {
            "nproc": len(os.sched_getaffinity(0)),
            "kernel": platform.release(),
            "python": platform.python_version(),
            "load_average_at_start": os.getloadavg()[0],
        },
        "config": {
            "duration_s": args.duration,
            "spawn_rate_hz": args.spawn_rate,
            "live_models": args.live_models,
            "robot_every": args.robot_every,
            "sample_period_s": args.sample_period,
            "max_rss_growth_mib_per_min": args.max_rss_growth_mib_per_min,
            "max_thread_growth": args.max_thread_growth,
            "max_fd_growth": args.max_fd_growth,
            "command_rate_hz": 1.0 / COMMAND_PERIOD_S,
        },
        "warmup_s": args.warmup,
        "samples": [],
        "simulator_alive": True,
    }
    error = None
    with tempfile.TemporaryDirectory(prefix="soak-") as log_dir:
        try:
            with Processes(log_dir) as processes:
                run_soak(args, result, processes)
        except ToolError as failure:
            error = str(failure)
        except KeyboardInterrupt:
            error = "interrupted"
        except Exception:  # what the soak did not expect: still stopped everything, still report and write JSON
            error = traceback.format_exc()
        finally:
            if args.keep_logs:
                shutil.copytree(log_dir, args.keep_logs, dirs_exist_ok=True)
    node = result.pop("node", None)
    if error is not None:
        result["error"] = error
        sys.stdout.flush()
        print("ERROR: " + error, file=sys.stderr, flush=True)
    if node is not None:
        summarize(result, args, node.stats)
        if error is not None:
            result["passed"] = False
        print()
        print(table(result))
    result["machine"]["load_average_at_end"] = os.getloadavg()[0]
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        with open(args.json, "w") as out:
            json.dump(result, out, indent=2)
        print("\nJSON: " + args.json)
    if error == "interrupted":
        return 130
    if error is not None and not result["samples"]:
        return 2  # it never got to soak
    print("\nsoak %s" % ("PASSED" if result.get("passed") else "FAILED"))
    return 0 if result.get("passed") else 1


if __name__ == "__main__":
    sys.exit(main())
