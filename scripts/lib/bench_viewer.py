"""Section 9 of the benchmark (scripts/bench_sim.py, issue #30): what the viewer costs the simulator. The unthrottled
node at 1 ms with one TurtleBot driving in bench_camera's furnished room (static models around it, as in
turtlebot3_world), without and with a viewer's subscriber on /gazebo/scene_markers; the ratio of the two RTFs is what
an open viewer leaves of the simulator's speed (target: at least TARGET_RATIO)."""
from __future__ import annotations

from typing import Any, Dict

from bench_node import node_rtf
from bench_plan import Plan
from ros_processes import Processes

TARGET_RATIO = 0.9


def viewer_cost(plan: Plan, processes: Processes) -> Dict[str, Any]:
    runs = {}
    for label, watched in (("no viewer", False), ("viewer", True)):
        print("  scene: %s ..." % label, flush=True)
        name = "scene-" + ("watched" if watched else "unwatched")
        run = node_rtf(processes, name, 1, 0.001, 0.0, plan.warmup_s, plan.window_s, True, watch_scene=watched)
        del run["clock_interval_ms"]
        runs[label] = run
    ratio = runs["viewer"]["rtf"] / runs["no viewer"]["rtf"]
    print("  RTF with a viewer / without: %.3f (target >= %g)" % (ratio, TARGET_RATIO), flush=True)
    return {
        "time_step": 0.001,
        "real_time_factor": 0.0,
        "world": "bench_camera's furnished room, one TurtleBot driving a circle in it",
        "runs": runs,
        "rtf_ratio": ratio,
        "scene_hz": runs["viewer"]["rates_per_robot_hz"].get("scene", 0.0),
        "target_ratio": TARGET_RATIO,
    }
