"""The soak's run (scripts/soak.py): a master of its own, the simulator launched on it, the soak's node driving and
spawning, and the simulator process sampled every --sample-period seconds until --duration or its death; then the
soak's models are deleted and the simulator counted once more."""
from __future__ import annotations

import argparse
import os
import time
from typing import Any, Dict

from ros_run.process_stats import cpu_seconds, process_alive, rss_bytes, steady_counts
from ros_run.master import Master
from ros_run.processes import SHUTDOWN_TIMEOUT_S, Processes, ToolError
from soak.node import CALL_TIMEOUT_S, STARTUP_TIMEOUT_S, SoakError, SoakNode

CALLER_ID = "/soak"  # towards the master, before the soak's node exists
MIB = 1024.0 * 1024.0


def take_sample(pid: int, start: float, node: SoakNode, cpu_start: float) -> Dict[str, Any]:
    counted = steady_counts(pid)
    stats = node.stats
    with stats.lock:
        spawns = sum(stats.spawns.values())
        return {
            "t": round(time.monotonic() - start, 3),
            "sim_time": stats.clock,
            "rss_mib": round(rss_bytes(pid) / MIB, 3),
            **counted,
            "cpu_s": round(cpu_seconds(pid) - cpu_start, 2),
            "spawns": spawns,
            "deletes": stats.deletes,
            "failures": stats.spawn_failures + stats.delete_failures,
            "odom_messages": stats.odom_messages,
            "scan_messages": stats.scan_messages,
        }


def run_soak(args: argparse.Namespace, result: Dict[str, Any], processes: Processes) -> None:
    ros = Master(processes, "", CALLER_ID, STARTUP_TIMEOUT_S)  # stopped with ``processes``
    os.environ.update(ros.ros_env)
    launch = ros.launch("turtlebot_world.launch", ["real_time_factor:=0"])
    node = SoakNode(args.spawn_rate, args.live_models, args.robot_every)
    result["node"] = node  # for the summary; removed before writing JSON
    try:
        try:
            pid = node.wait_ready(launch, STARTUP_TIMEOUT_S)
        except ToolError as error:
            raise SoakError("%s\nroslaunch:\n%s" % (error, ros.log_tail("launch"))) from None
        result["simulator_pid"] = pid
        cpu_start = cpu_seconds(pid)
        print("simulator /gazebo is pid %d; soaking for %.0f s" % (pid, args.duration), flush=True)
        node.start()
        start = time.monotonic()
        result["samples"].append(take_sample(pid, start, node, cpu_start))
        next_sample = start + args.sample_period
        end = start + args.duration
        while True:
            now = time.monotonic()
            if launch.poll() is not None or not process_alive(pid):
                result["simulator_alive"] = False
                result["death"] = "the simulator died %.1f s into the soak (roslaunch %s):\n%s" % (
                    now - start,
                    "exited %s" % launch.returncode if launch.poll() is not None else "running",
                    ros.log_tail("launch"),
                )
                break
            call_started = node.stats.call_started
            if call_started is not None and now - call_started > CALL_TIMEOUT_S:
                result["hung_call"] = "%s did not return in %.0f s" % (node.stats.call_name, CALL_TIMEOUT_S)
                break
            if now >= next_sample or now >= end:
                try:
                    sample = take_sample(pid, start, node, cpu_start)
                except (OSError, ToolError):
                    if process_alive(pid):
                        raise
                    continue  # died while sampled: reported above on the next pass
                result["samples"].append(sample)
                if args.verbose:
                    print(
                        "  %6.1f s: sim %.1f s, RSS %.2f MiB, %d threads, %d fds, %d spawns"
                        % (
                            sample["t"],
                            sample["sim_time"] or 0.0,
                            sample["rss_mib"],
                            sample["threads"],
                            sample["fds"],
                            sample["spawns"],
                        ),
                        flush=True,
                    )
                next_sample += args.sample_period
                if now >= end:
                    break
            time.sleep(max(0.0, min(0.2, min(next_sample, end) - time.monotonic())))
        node.stop()
        if result["simulator_alive"] and not result.get("hung_call"):
            node.delete_remaining()
            time.sleep(2.0)
            try:
                counted = steady_counts(pid)
                result["after_cleanup"] = {
                    "rss_mib": round(rss_bytes(pid) / MIB, 3),
                    "threads": counted["threads"],
                    "fds": counted["fds"],
                    "fd_kinds": counted["fd_kinds"],
                }
            except (OSError, ToolError):
                if process_alive(pid):
                    raise
                result["simulator_alive"] = False
                result["death"] = "the simulator died while the soak's last models were deleted:\n" + (
                    ros.log_tail("launch")
                )
    finally:
        node.stop(SHUTDOWN_TIMEOUT_S)  # at once if stopped already; else (an error, Ctrl-C) before the simulator
        node.close()
