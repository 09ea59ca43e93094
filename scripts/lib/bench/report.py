"""The benchmark's report (scripts/bench_sim.py): the machine it ran on, the targets of issues #8 and #15 judged on the
results, and the human-readable table."""
from __future__ import annotations

import json
import os
import platform
import shutil
import subprocess
from typing import Any, Callable, Dict, List, Optional, Tuple

from bench.camera import CAMERAS, TARGET_SHARE
from bench.camera import table as camera_table
from bench.lidar import table as lidar_table
from bench.control import table as control_table
from bench.scaling import table as scaling_table
from ros_run.process_stats import cpu_ticks


def debian_version(package: str) -> str:
    """The installed version of a Debian package, or "unknown"."""
    if not shutil.which("dpkg-query"):
        return "unknown"
    result = subprocess.run(
        ["dpkg-query", "-W", "-f", "${Version}", package], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
    )
    return result.stdout.decode().strip() or "unknown"


def machine() -> Dict[str, Any]:
    """What the figures were measured on."""
    cpu_model = "unknown"
    with open("/proc/cpuinfo") as cpuinfo:
        for line in cpuinfo:
            if line.startswith("model name"):
                cpu_model = line.split(":", 1)[1].strip()
                break
    return {
        "nproc": len(os.sched_getaffinity(0)),
        "cpu_model": cpu_model,
        "kernel": platform.release(),
        "python": platform.python_version(),
        "ros_distro": os.environ.get("ROS_DISTRO", "unknown"),
        "pyode": debian_version("python3-pyode"),
        "ode": debian_version("libode8"),
        "load_average_at_start": os.getloadavg()[0],
    }


def close_machine(results: Dict[str, Any], ticks_at_start: Tuple[int, int]) -> None:
    """What the machine did during the run: the share of CPU time the host stole, the load at the end."""
    ticks, stolen = (end - start for end, start in zip(cpu_ticks(), ticks_at_start))
    results["machine"]["stolen_cpu_share"] = stolen / ticks if ticks else 0.0
    results["machine"]["load_average_at_end"] = os.getloadavg()[0]


def write_report(results: Dict[str, Any], text: str, json_path: str) -> int:
    """Print the table ``text``, write ``results`` as JSON; exit status 1 if a section failed."""
    print()
    print(text)
    os.makedirs(os.path.dirname(os.path.abspath(json_path)), exist_ok=True)
    with open(json_path, "w") as out:
        json.dump(results, out, indent=2)
    print("\nJSON: " + json_path)
    return 1 if any("error" in value for value in results.values() if isinstance(value, dict)) else 0


def find_run(results: Dict[str, Any], robots: int, time_step: float) -> Optional[Dict[str, Any]]:
    """The full-node run with ``robots`` and ``time_step``, if there was one."""
    runs = results.get("full_node", {}).get("runs", [])
    return next((r for r in runs if r["robots"] == robots and r["time_step"] == time_step), None)


def targets(results: Dict[str, Any]) -> List[Dict[str, Any]]:
    """Issue #8's, #15's, #30's and #33's targets: name, value, goal, pass (None when not measured in this run)."""
    one_1ms, one_10ms, ten_1ms = find_run(results, 1, 0.001), find_run(results, 1, 0.01), find_run(results, 10, 0.001)
    physics_rtf = results.get("physics_only", {}).get("rtf")
    turns = (one_1ms or {}).get("in_turns", {})
    rows: List[Tuple[str, Optional[float], str, Callable[[float], bool]]] = [
        ("1 TurtleBot, 1 ms: RTF", one_1ms and one_1ms["rtf"], ">= 25", lambda v: v >= 25),
        (
            "1 TurtleBot, 1 ms: RTF / physics-only RTF (section 1)",
            one_1ms and physics_rtf and one_1ms["rtf"] / physics_rtf,
            ">= 0.85",
            lambda v: v >= 0.85,
        ),
        (
            "1 TurtleBot, 1 ms: the same in turns (median)",
            turns.get("median_ratio"),
            ">= 0.85",
            lambda v: v >= 0.85,
        ),
        ("1 TurtleBot, 10 ms: RTF (quiet machine)", one_10ms and one_10ms["rtf"], ">= 250", lambda v: v >= 250),
        ("10 TurtleBots, 1 ms: RTF", ten_1ms and ten_1ms["rtf"], ">= 2.5", lambda v: v >= 2.5),
        (
            "node CPU per sim s linear in robots, 1 ms",
            results.get("full_node", {}).get("linearity_at_1ms", {}).get("node_cpu"),
            "0.8 .. 1.2",
            lambda v: 0.8 <= v <= 1.2,
        ),
        (
            "10 TurtleBots, 1 ms: share of linear (wall)",
            results.get("full_node", {}).get("linearity_at_1ms", {}).get("wall") and 1.0 / linear_wall(results),
            ">= 0.85",
            lambda v: v >= 0.85,
        ),
        ("real time: RTF", results.get("real_time", {}).get("rtf"), "1.00 +- 0.02", lambda v: abs(v - 1) <= 0.02),
        ("launch to first /odom (s)", results.get("launch", {}).get("first_odom_s"), "< 3", lambda v: v < 3),
    ]
    cameras = results.get("cameras", {})
    in_process = cameras.get("in_process", {}).get("cameras", [])
    node_runs = cameras.get("node", {}).get("runs", [])
    target = CAMERAS[0]
    unwatched = next((r for r in node_runs if r["rate_hz"] and "unwatched" in r["camera"]), None)
    watched = next(
        (r for r in node_runs if (r["width"], r["height"], r["rate_hz"]) == target and r is not unwatched), None
    )
    in_process_row = next((r for r in in_process if (r["width"], r["height"], r["rate_hz"]) == target), None)
    goal = ">= %.2f" % TARGET_SHARE
    rows += [
        (
            "320x240 RGB-D 15 Hz watched, node: RTF share",
            watched and watched["rtf_share"],
            goal,
            lambda v: v >= TARGET_SHARE,
        ),
        (
            "320x240 RGB-D 15 Hz, no ROS: RTF share",
            in_process_row and in_process_row["rtf_share"],
            goal,
            lambda v: v >= TARGET_SHARE,
        ),
        (
            "camera nobody watches: node CPU ratio",
            unwatched and unwatched["node_cpu_ratio"],
            "<= 1.10",
            lambda v: v <= 1.10,
        ),
        ("viewer open: RTF share", results.get("viewer", {}).get("rtf_ratio"), ">= 0.90", lambda v: v >= 0.9),
    ]
    rows += scaling_targets(results)
    return [
        {"target": name, "value": value, "goal": goal, "pass": None if value is None else check(value)}
        for name, value, goal, check in rows
    ]


def linear_wall(results: Dict[str, Any]) -> float:
    return results["full_node"]["linearity_at_1ms"]["wall"]


def scaling_targets(results: Dict[str, Any]) -> List[Tuple[str, Optional[float], str, Callable[[float], bool]]]:
    """Issue #33's, each a ratio to a baseline of the same run: the VLP-16 against the robot without it, the
    controller manager against the same base driven by its motors alone, 300 IMUs against the bare TurtleBot (and
    real time kept), the 1000-link chain against real time."""
    lidars = results.get("lidar", {}).get("lidars", [])
    vlp16 = next((row for row in lidars if (row["lasers"], row["samples"]) == (16, 1800)), None)
    scaling = results.get("scaling", {})
    imus, chain = scaling.get("imus", {}), scaling.get("chain", {})
    return [
        ("VLP-16 at 10 Hz: RTF share", vlp16 and vlp16["rtf_share"], ">= 0.50", lambda v: v >= 0.5),
        (  # of the base driven by four motors without a manager: the manager's cost, not ODE's motor rows (control.py)
            "controller manager at 1 kHz: RTF share of the driven base",
            results.get("ros_control", {}).get("rtf_share_of_driven"),
            ">= 0.85",
            lambda v: v >= 0.85,
        ),
        ("300 IMUs: RTF share of the bare TurtleBot", imus.get("rtf_share"), ">= 0.50", lambda v: v >= 0.5),
        ("300 IMUs: real time kept (real-time mode)", imus.get("real_time_kept"), ">= 0.90", lambda v: v >= 0.9),
        ("1000-link chain: real time kept", chain.get("real_time_kept"), ">= 0.50", lambda v: v >= 0.5),
    ]


def table(results: Dict[str, Any]) -> str:
    """The human-readable report of ``results``."""
    m = results["machine"]
    lines = [
        "turtle_sim_ode benchmark (issue #8), %s run, %s" % (results["mode"], results["date"]),
        "machine: %d cores, %s, Linux %s, Python %s, ROS %s, PyODE %s, ODE %s, load %.2f at start, %.2f at end, "
        "%.0f %% of the CPU time stolen by the host"
        % (
            m["nproc"],
            m["cpu_model"],
            m["kernel"],
            m["python"],
            m["ros_distro"],
            m["pyode"],
            m["ode"],
            m["load_average_at_start"],
            m["load_average_at_end"],
            100 * m["stolen_cpu_share"],
        ),
        "",
    ]

    def section(title: str, key: str, body: Callable[[Dict[str, Any]], List[str]]) -> None:
        lines.append(title)
        value = results.get(key)
        if value is None:
            lines.append("   not run")
        elif "error" in value:
            lines.append("   ERROR: " + value["error"].strip().replace("\n", "\n   "))
        else:
            lines.extend("   " + line for line in body(value))
        lines.append("")

    def physics_lines(p: Dict[str, Any]) -> List[str]:
        bare = p["bare_pyode"]
        return [
            "%-34s %9.0f steps/s %7.1f us/step  RTF %6.1f  contacts %d"
            % ("ours: Simulation.step", p["steps_per_s"], p["us_per_step"], p["rtf"], p["contacts_per_step"]),
            "%-34s %9.0f steps/s %7.1f us/step  RTF %6.1f  contacts %d"
            % (
                "floor: bare PyODE collide+quickStep",
                bare["steps_per_s"],
                bare["us_per_step"],
                bare["rtf"],
                bare["contacts_per_step"],
            ),
            "%-34s %9.2f x" % ("our cost / floor cost", p["overhead_ratio"]),
            "%-34s %9.0f steps/s %7.1f us/step  RTF %6.1f"
            % (
                "ours, contacts in Python",
                p["python_contacts"]["steps_per_s"],
                p["python_contacts"]["us_per_step"],
                p["python_contacts"]["rtf"],
            ),
            "%-34s %9.3f m (expected %.3f)"
            % ("circle v 0.5 m/s, w 0.5 rad/s", p["circle_radius_m"], p["circle_expected_radius_m"]),
        ]

    def full_node_lines(f: Dict[str, Any]) -> List[str]:
        rows = [
            "                                  wall ms per sim s   node CPU",
            "robots  dt ms      RTF   steps/s    total  per robot  ms/sim s  share   odom Hz  scan Hz  imu Hz  clock Hz",
        ]
        for r in f["runs"]:
            rates = r["rates_per_robot_hz"]
            rows.append(
                "%6d %6g %8.2f %9.0f %8.1f %10.1f %9.1f %6.2f %9.1f %8.1f %7.1f %9.1f"
                % (
                    r["robots"],
                    r["time_step"] * 1e3,
                    r["rtf"],
                    r["steps_per_s"],
                    r["wall_ms_per_sim_s"],
                    r["wall_ms_per_sim_s_per_robot"],
                    r["node_cpu_ms_per_sim_s"],
                    r["node_cpu_share"],
                    rates["odom"],
                    rates["scan"],
                    rates["imu"],
                    r["clock_hz"],
                )
            )
        unbatched, batched = f.get("unbatched_1ms"), find_run({"full_node": f}, 1, 0.001)
        if unbatched and batched:
            rows.append(
                "1 robot, 1 ms, each message written at once (write_batch_period 0): RTF %.2f, batched %.2f (x %.2f)"
                % (unbatched["rtf"], batched["rtf"], batched["rtf"] / unbatched["rtf"])
            )
        turns = (batched or {}).get("in_turns")
        if turns:
            rows.append(
                "1 robot, 1 ms, in turns with physics only (%g s each, the node paused meanwhile): ratios %s, median %.2f"
                % (turns["window_s"], " ".join("%.2f" % ratio for ratio in turns["ratios"]), turns["median_ratio"])
            )
        linear = f["linearity_at_1ms"]
        if linear["wall"] is None:
            rows.append("linearity in robots: n/a (needs 3 robot counts)")
        else:
            rows.append(
                "linearity in robots at 1 ms, cost of the most robots over the line through the two fewest: "
                "wall %.2f, node CPU %.2f" % (linear["wall"], linear["node_cpu"])
            )
        return rows

    def real_time_lines(r: Dict[str, Any]) -> List[str]:
        c = r["clock_interval_ms"]
        return [
            "RTF %.4f over %.1f wall s (%.1f sim s), node CPU share %.2f"
            % (r["rtf"], r["wall_s"], r["sim_s"], r["node_cpu_share"]),
            "/clock interval ms: mean %.3f  stdev %.3f  p99 %.3f  (%d intervals)"
            % (c["mean"], c["stdev"], c["p99"], c["count"]),
        ]

    def launch_lines(launch: Dict[str, Any]) -> List[str]:
        return ["median %.2f s   runs: %s" % (launch["first_odom_s"], "  ".join("%.2f" % t for t in launch["runs_s"]))]

    def peer_lines(p: Dict[str, Any]) -> List[str]:
        if p["status"] != "ok":
            return ["%s %s%s" % (p["name"], p["status"], ": " + p["reason"] if "reason" in p else "")]
        return [
            "PyBullet %s (%s)" % (p["version"], p["venv"]),
            "%9.0f steps/s %7.1f us/step at %g ms: %.2f x ours"
            % (p["steps_per_s"], p["us_per_step"], p["time_step"] * 1e3, p["ratio_to_ours"]),
            "circle radius %.3f m (ours %.3f m, expected %.3f)"
            % (p["circle_radius_m"], p["ours_circle_radius_m"], p["circle_expected_radius_m"]),
            "collision shapes: " + ", ".join("%s %s" % item for item in sorted(p["collision_shapes"].items())),
        ] + ["note: " + note for note in p["notes"]]

    def camera_lines(c: Dict[str, Any]) -> List[str]:
        rows = ["no ROS (scripts/lib/bench_camera.py; renderer: %s):" % c["in_process"]["renderer"]]
        rows += ["   " + line for line in camera_table(c["in_process"]).splitlines()[:-1]]
        rows.append("full node, 1 ms, unthrottled, the robot's sensors subscribed:")
        rows.append("   camera                         RTF   RTF share  node CPU ms/sim s  ratio  image Hz  cloud Hz")
        for r in c["node"]["runs"]:
            rates = r["rates_per_robot_hz"]
            rows.append(
                "   %-28s %6.2f %9.2f %18.1f %6.2f %9s %9s"
                % (
                    r["camera"],
                    r["rtf"],
                    r["rtf_share"],
                    r["node_cpu_ms_per_sim_s"],
                    r["node_cpu_ratio"],
                    "%.1f" % rates["image"] if "image" in rates else "-",
                    "%.1f" % rates["points"] if "points" in rates else "-",
                )
            )
        return rows

    section("1. physics only: 1 TurtleBot, 1 ms, quickStep 50 iterations, no ROS", "physics_only", physics_lines)
    section(
        "2. full node, real_time_factor 0, /clock /tf odom joint_states imu scan subscribed (rates per sim s)",
        "full_node",
        full_node_lines,
    )
    section("3. real time, real_time_factor 1, 1 TurtleBot, 1 ms", "real_time", real_time_lines)
    section("4. roslaunch turtle_sim_ode turtlebot_world.launch to first /odom, fresh master", "launch", launch_lines)
    section("5. peer: the same URDF in PyBullet, same dt and wheel command", "peer", peer_lines)
    section(
        "6. cameras: 1 TurtleBot with an RGB-D camera in a furnished room, rates in sim time", "cameras", camera_lines
    )
    section(
        "7. lidar: 1 TurtleBot with a 3D lidar (libgazebo_ros_velodyne_laser.so) in the furnished room, no ROS",
        "lidar",
        lambda r: lidar_table(r).splitlines(),
    )
    section(
        "8. ros_control: a 1 kHz controller manager (diff_drive + joint_state), no ROS", "ros_control", control_table
    )
    section("9. scaling: the node's per-step loop and plugin adapters, no master, 1 ms", "scaling", scaling_table)
    loaded = m["load_average_at_end"] > 0.5 * m["nproc"] or m["stolen_cpu_share"] > 0.05
    lines.append(
        "targets (%s: load %.2f on %d cores, %.0f %% stolen)"
        % (
            "measured under load" if loaded else "quiet machine",
            m["load_average_at_end"],
            m["nproc"],
            100 * m["stolen_cpu_share"],
        )
    )
    lines.append("   %-44s %10s  %-13s %s" % ("target", "value", "goal", "result"))
    for t in results["targets"]:
        value = "-" if t["value"] is None else "%.2f" % t["value"]
        verdict = {True: "PASS", False: "FAIL", None: "n/a"}[t["pass"]]
        lines.append("   %-44s %10s  %-13s %s" % (t["target"], value, t["goal"], verdict))
    return "\n".join(lines)
