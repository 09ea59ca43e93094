"""Section 9 of the benchmark (scripts/bench_sim.py, issue #30): what the viewer costs the simulator. The unthrottled
node at 1 ms with one TurtleBot driving in bench_camera's furnished room (static models around it, as in
turtlebot3_world), without and with a viewer's subscriber on /gazebo/scene_markers; the ratio of the two RTFs is what
an open viewer leaves of the simulator's speed (target: at least TARGET_RATIO)."""
from __future__ import annotations

import statistics
from typing import Any, Dict, List

from bench.node import node_rtf
from bench.plan import Plan
from ros_run.processes import Processes

TARGET_RATIO = 0.9


# Runs alternate (without, with, without, with): the machine's load drifts between runs.
PAIRS = 2


def viewer_cost(plan: Plan, processes: Processes) -> Dict[str, Any]:
    runs: Dict[str, List[Dict[str, Any]]] = {"no viewer": [], "viewer": []}
    for pair in range(PAIRS):
        for label, watched in (("no viewer", False), ("viewer", True)):
            print("  scene: %s (%d/%d) ..." % (label, pair + 1, PAIRS), flush=True)
            name = "scene-%s-%d" % ("watched" if watched else "unwatched", pair)
            run = node_rtf(processes, name, 1, 0.001, 0.0, plan.warmup_s, plan.window_s, True, watch_scene=watched)
            del run["clock_interval_ms"]
            runs[label].append(run)
    rtf = {label: statistics.mean(run["rtf"] for run in of) for label, of in runs.items()}
    cpu = {label: statistics.mean(run["node_cpu_ms_per_sim_s"] for run in of) for label, of in runs.items()}
    ratio = rtf["viewer"] / rtf["no viewer"]
    print(
        "  RTF with a viewer / without: %.3f (target >= %g); node CPU per sim second with / without: %.3f"
        % (ratio, TARGET_RATIO, cpu["viewer"] / cpu["no viewer"]),
        flush=True,
    )
    return {
        "time_step": 0.001,
        "real_time_factor": 0.0,
        "world": "bench_camera's furnished room, one TurtleBot driving a circle in it",
        "runs": runs,
        "rtf": rtf,
        "rtf_ratio": ratio,
        "node_cpu_ratio": cpu["viewer"] / cpu["no viewer"],
        "scene_messages_per_wall_s": statistics.mean(
            run["rates_per_robot_hz"].get("scene", 0.0) * run["rtf"] for run in runs["viewer"]
        ),
        "target_ratio": TARGET_RATIO,
    }
