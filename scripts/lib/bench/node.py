"""Sections 2 to 4 of the benchmark (scripts/bench_sim.py), the simulator node on a master of its own: unthrottled with
1 to 10 robots, paced to real time, and roslaunch to the first /odom."""
from __future__ import annotations

import os
import statistics
import time
from typing import Any, Dict, List, Optional, Tuple

from bench.camera import CAMERAS, TARGET_SHARE
from bench.plan import CALLER_ID, PACKAGE, STARTUP_TIMEOUT_S, BenchError, Plan
from bench.probe import Probe, first_odom_task, measure_rtf_task
from ros_run.master import master
from ros_run.processes import Processes


UNBATCHED = {"write_batch_period": 0.0}  # every message written when published
TURNS = 5  # 1 TurtleBot at 1 ms: the node and physics only in turns, a window's length each (probe.in_turns)


def package_config(name: str) -> Dict[str, Any]:
    """The default parameters in the package's config/``name``."""
    import yaml

    with open(os.path.join(PACKAGE, "config", name)) as config_file:
        return yaml.safe_load(config_file)


def write_yaml(path: str, values: Dict[str, Any]) -> str:
    """Write ``values`` to ``path``; return ``path``."""
    import yaml

    with open(path, "w") as out:
        yaml.safe_dump(values, out)
    return path


def node_rtf(
    processes: Processes,
    name: str,
    robots: int,
    time_step: float,
    real_time_factor: float,
    warmup: float,
    window: float,
    room: bool = False,
    camera: Optional[Tuple[int, int, float]] = None,
    watch_camera: bool = False,
    watch_scene: bool = False,
    settings: Optional[Dict[str, Any]] = None,
    turns: int = 0,
) -> Dict[str, Any]:
    """RTF and /clock intervals of the node in empty_world.launch with ``robots`` TurtleBots spawned (the first in
    a ``room``, with ``camera``, a viewer's scene subscriber with ``watch_scene``: see bench_probe.measure_rtf_task),
    with ``settings`` over config/simulator.yaml's; ``turns``: then also against physics only in turns."""
    physics = dict(package_config("physics.yaml"), time_step=time_step)
    config = dict(package_config("simulator.yaml"), **(settings or {}))
    config["diff_drive"]["cmd_timeout"] = 0.0  # commands are sent once: the drives must not time out, at any RTF
    physics_path = write_yaml(os.path.join(processes.log_dir, name + "-physics.yaml"), physics)
    config_path = write_yaml(os.path.join(processes.log_dir, name + "-simulator.yaml"), config)
    with master(processes, name, CALLER_ID, STARTUP_TIMEOUT_S) as ros:
        launch = ros.launch(
            "empty_world.launch",
            ["real_time_factor:=%g" % real_time_factor, "physics:=" + physics_path, "config:=" + config_path],
        )
        task = (measure_rtf_task, robots, warmup, window, room, camera, watch_camera, watch_scene, turns)
        with Probe(ros, *task) as probe:
            try:
                # turns: a warmup and two windows more in all (probe.in_turns), and a TurtleBot of the probe's own
                in_turns = warmup + 2 * window + STARTUP_TIMEOUT_S if turns else 0.0
                result = probe.receive(2 * STARTUP_TIMEOUT_S + warmup + window + in_turns)
            except BenchError as error:
                raise ros.failure(launch, error) from None
    result.update(time_step=time_step, real_time_factor=real_time_factor)
    return result


def full_node(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 2: the unthrottled node for each time step and robot count."""
    runs = []
    unbatched: Dict[str, Any] = {}
    for time_step in plan.time_steps:
        for robots in plan.robot_counts:
            name = "rtf-%drobots-%gms" % (robots, time_step * 1e3)
            print("  full node: %d robot(s), %g ms ..." % (robots, time_step * 1e3), flush=True)
            turns = TURNS if (robots, time_step) == (1, 0.001) else 0  # issue #33's target, against physics only
            run = node_rtf(processes, name, robots, time_step, 0.0, plan.warmup_s, plan.window_s, turns=turns)
            run["steps_per_s"] = run["rtf"] / time_step
            run["wall_ms_per_sim_s"] = 1e3 / run["rtf"]
            run["wall_ms_per_sim_s_per_robot"] = run["wall_ms_per_sim_s"] / robots
            del run["clock_interval_ms"]
            runs.append(run)
            if (robots, time_step) == (1, 0.001):  # issue #33: next to it, each message written at once, as before
                print("  full node: 1 robot, 1 ms, write_batch_period 0 ...", flush=True)
                unbatched = node_rtf(
                    processes, "unbatched", 1, 0.001, 0.0, plan.warmup_s, plan.window_s, settings=UNBATCHED
                )
    return {
        "real_time_factor": 0.0,
        "sensors": "all subscribed: /clock, /tf and each robot's odom, joint_states, imu, scan",
        "runs": runs,
        "unbatched_1ms": {key: unbatched[key] for key in ("rtf", "node_cpu_share") if key in unbatched},
        "linearity_at_1ms": {
            "wall": linearity(runs, 0.001, "wall_ms_per_sim_s"),
            "node_cpu": linearity(runs, 0.001, "node_cpu_ms_per_sim_s"),
        },
    }


def camera_node(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 6: the unthrottled node at 1 ms with one TurtleBot in bench_camera's room, without a camera, with an
    RGB-D camera nobody watches, and with each camera of bench_camera.CAMERAS watched (image, depth image, cloud);
    each run's RTF and node CPU against the run without a camera."""
    rows = [("none", None, False)]
    rows += [("%dx%d at %g Hz, unwatched" % CAMERAS[0], CAMERAS[0], False)]
    rows += [("%dx%d at %g Hz, watched" % camera, camera, True) for camera in CAMERAS]
    runs = []
    for label, camera, watched in rows:
        print("  camera node: %s ..." % label, flush=True)
        name = "camera-" + label.replace(" ", "-").replace(",", "")
        run = node_rtf(processes, name, 1, 0.001, 0.0, plan.warmup_s, plan.window_s, True, camera, watched)
        del run["clock_interval_ms"]
        run.update(camera=label, width=camera and camera[0], height=camera and camera[1], rate_hz=camera and camera[2])
        runs.append(run)
    for run in runs:
        run["rtf_share"] = run["rtf"] / runs[0]["rtf"]
        run["node_cpu_ratio"] = run["node_cpu_ms_per_sim_s"] / runs[0]["node_cpu_ms_per_sim_s"]
    return {
        "time_step": 0.001,
        "real_time_factor": 0.0,
        "sensors": "all the robot's subscribed; watched: also the camera's rgb/image_raw, depth/image_raw, depth/points",
        "runs": runs,
        "target_share": TARGET_SHARE,
    }


def linearity(runs: List[Dict[str, Any]], time_step: float, cost: str) -> Optional[float]:
    """``cost`` per sim second of the most robots over the line through the two fewest (1 = linear); None with
    fewer than three robot counts."""
    costs = sorted((run["robots"], run[cost]) for run in runs if run["time_step"] == time_step)
    if len(costs) < 3:
        return None
    (n1, c1), (n2, c2), (n3, c3) = costs[0], costs[1], costs[-1]
    return c3 / (c1 + (c2 - c1) * (n3 - n1) / (n2 - n1))


def real_time(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 3: the node paced to real time."""
    print("  real time: %g s ..." % plan.real_time_window_s, flush=True)
    run = node_rtf(processes, "real-time", 1, 0.001, 1.0, plan.warmup_s, plan.real_time_window_s)
    return {
        "real_time_factor": 1.0,
        "robots": 1,
        "time_step": 0.001,
        "wall_s": run["wall_s"],
        "sim_s": run["sim_s"],
        "rtf": run["rtf"],
        "node_cpu_share": run["node_cpu_share"],
        "clock_interval_ms": run["clock_interval_ms"],
    }


def launch_to_first_odom(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 4: wall seconds from starting roslaunch (master already up) to the first /odom message."""
    times = []
    for index in range(plan.launch_runs):
        print("  launch %d/%d ..." % (index + 1, plan.launch_runs), flush=True)
        with master(processes, "launch-%d" % index, CALLER_ID, STARTUP_TIMEOUT_S) as ros:
            with Probe(ros, first_odom_task) as probe:
                probe.receive(STARTUP_TIMEOUT_S)
                start = time.monotonic()
                launch = ros.launch("turtlebot_world.launch", [])
                try:
                    times.append(probe.receive(STARTUP_TIMEOUT_S + 5) - start)
                except BenchError as error:
                    raise ros.failure(launch, error) from None
    return {
        "command": "roslaunch turtle_sim_ode turtlebot_world.launch",
        "first_odom_s": statistics.median(times),
        "runs_s": times,
    }
