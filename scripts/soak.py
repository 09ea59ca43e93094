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

Everything it starts is stopped on exit, also on Ctrl-C, SIGTERM and errors. Run with /usr/bin/python3 and the
workspace sourced (scripts/soak.sh does both).
"""
from __future__ import annotations

import argparse
import collections
import contextlib
import datetime
import importlib
import json
import math
import os
import platform
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import traceback
import xmlrpc.client
from typing import Any, Deque, Dict, List, Optional, Sequence, Tuple

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from ros_processes import SHUTDOWN_TIMEOUT_S, Processes, cpu_seconds, free_port  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE = os.path.join(REPO, "catkin_ws", "src", "turtle_sim_ode")
MODELS = os.path.join(PACKAGE, "test", "models")
SIMULATOR_NODE = "/gazebo"
ROBOT = "mobile_base"
COMMAND_TOPIC = "/mobile_base/commands/velocity"
COMMAND_PERIOD_S = 0.1  # 10 Hz wall
CIRCLE = (0.25, 0.5)  # v (m/s), w (rad/s): a circle of 0.5 m radius
REVERSE_PERIOD_S = 15.0  # wall seconds between reversals (the robot then goes back round the same circle)
STARTUP_TIMEOUT_S = 90.0
CALL_TIMEOUT_S = 30.0  # a service call taking longer counts as a hung simulator
STEADY_READS = 5  # threads and fds: the least of this many reads 50 ms apart (a service connection's thread and
STEADY_READ_GAP_S = 0.05  # socket live only as long as the call, and a sample must not catch one in passing)
# A healthy run grows 0.05-0.2 MiB/min after the warm-up (60 s and 3 min runs, 2 spawns/s). 2 MiB/min is ten times
# that and more than one allocator step (1 MiB) in the 48 s window of the 60 s soak, and it still catches a leak of
# 17 KiB per spawn and delete (a whole model kept) or of 35 bytes per physics step at 1000 steps/s.
DEFAULT_MAX_RSS_GROWTH_MIB_PER_MIN = 2.0
DEFAULT_MAX_COUNT_GROWTH = 5
SPAWN_GRID = (6, 4)  # boxes are spawned on a grid of this many slots, from x = 4 m: away from the robot's circle
MIB = 1024.0 * 1024.0


class SoakError(RuntimeError):
    """The soak could not be set up or run (the message says why)."""


# --- process groups and the master ----------------------------------------------------------------------------------
def start_master(processes: Processes) -> Dict[str, str]:
    """roscore on a free port; the environment that points ROS processes at it."""
    port = free_port()
    env = dict(
        os.environ,
        ROS_MASTER_URI="http://127.0.0.1:%d" % port,
        ROS_IP="127.0.0.1",
        ROS_HOSTNAME="127.0.0.1",
        ROS_LOG_DIR=processes.log_dir,
    )
    roscore = processes.start(["roscore", "-p", str(port)], env, "roscore.log")
    deadline = time.monotonic() + STARTUP_TIMEOUT_S
    while True:
        with contextlib.suppress(OSError):
            xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getPid("/soak")
            return env
        if roscore.poll() is not None or time.monotonic() > deadline:
            raise SoakError("roscore did not start:\n" + processes.log_tail("roscore.log"))
        time.sleep(0.1)


# --- the simulator process ------------------------------------------------------------------------------------------
def process_alive(pid: int) -> bool:
    try:
        with open("/proc/%d/stat" % pid) as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except OSError:
        return False


def rss_bytes(pid: int) -> int:
    with open("/proc/%d/status" % pid) as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise SoakError("no VmRSS for pid %d" % pid)


def fd_kind(target: str) -> str:
    """What an fd's /proc link points at: socket, eventpoll, pipe, anon (other anon_inode), dev or file."""
    if target.startswith("socket:"):
        return "socket"
    if target.startswith("pipe:"):
        return "pipe"
    if target == "anon_inode:[eventpoll]":
        return "eventpoll"
    if target.startswith("anon_inode:"):
        return "anon"
    return "dev" if target.startswith("/dev/") else "file"


def read_counts(pid: int) -> Tuple[int, Dict[str, int]]:
    """(threads, {fd kind: count}) of ``pid``."""
    threads = len(os.listdir("/proc/%d/task" % pid))
    kinds: Dict[str, int] = collections.Counter()
    fd_dir = "/proc/%d/fd" % pid
    for fd in os.listdir(fd_dir):
        with contextlib.suppress(OSError):  # closed meanwhile
            kinds[fd_kind(os.readlink(os.path.join(fd_dir, fd)))] += 1
    return threads, dict(kinds)


def steady_counts(pid: int) -> Dict[str, Any]:
    """Threads and fds as the least of STEADY_READS reads (a service connection's thread and socket live only while
    a call is served, and a sample must not catch one in passing), the fds by kind as in the read with the fewest,
    and the most threads and fds seen in the reads."""
    reads = []
    for index in range(STEADY_READS):
        if index:
            time.sleep(STEADY_READ_GAP_S)
        reads.append(read_counts(pid))
    fewest_fds = min(reads, key=lambda read: sum(read[1].values()))[1]
    return {
        "threads": min(read[0] for read in reads),
        "fds": sum(fewest_fds.values()),
        "fd_kinds": fewest_fds,
        "threads_max": max(read[0] for read in reads),
        "fds_max": max(sum(read[1].values()) for read in reads),
    }


# --- the soak's ROS node ----------------------------------------------------------------------------------------------
def model_text(name: str) -> str:
    with open(os.path.join(MODELS, name)) as model_file:
        return model_file.read()


class Stats:
    """Counters shared by the soak's threads."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.spawns = collections.Counter()  # kind -> successful spawns
        self.spawn_failures = 0
        self.deletes = 0
        self.delete_failures = 0
        self.failures: List[str] = []  # the first messages
        self.latencies: Dict[str, List[float]] = {"spawn": [], "delete": []}
        self.clock: Optional[float] = None
        self.odom_messages = 0
        self.scan_messages = 0
        self.max_distance_m = 0.0
        self.commands = 0
        self.call_started: Optional[float] = None  # monotonic time of the service call in progress
        self.call_name = ""

    def fail(self, message: str) -> None:
        with self.lock:
            if len(self.failures) < 20:
                self.failures.append(message)


class SoakNode:
    """The soak's ROS node, in this process: drives the robot, listens to /odom, /scan and /clock, and spawns and
    deletes models in a thread of its own."""

    def __init__(self, spawn_rate: float, live_models: int, robot_every: int) -> None:
        import rospy
        from gazebo_msgs.srv import DeleteModel, SpawnModel
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import LaserScan

        self.rospy = rospy
        self.stats = Stats()
        self.spawn_period = 1.0 / spawn_rate
        self.live_models = live_models
        self.robot_every = robot_every
        self._stop = threading.Event()
        self._twist = Twist
        self._threads: List[threading.Thread] = []
        rospy.init_node("soak", anonymous=True, disable_signals=True)
        self._subscribers = [
            rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=1, tcp_nodelay=True),
            rospy.Subscriber("/odom", Odometry, self._on_odom, queue_size=1),
            rospy.Subscriber("/scan", LaserScan, self._on_scan, queue_size=1),
        ]
        self._command_pub = rospy.Publisher(COMMAND_TOPIC, Twist, queue_size=1)
        self._spawn_types = SpawnModel, DeleteModel
        self._models = {
            "urdf_box": model_text("box.urdf"),
            "sdf_box": model_text("box.sdf"),
            "burger": model_text("burger.urdf"),
        }
        self._live: Deque[str] = collections.deque()
        self._spawned = 0

    # --- callbacks (rospy's threads) ---
    def _on_clock(self, message: Any) -> None:
        self.stats.clock = message.clock.to_sec()

    def _on_odom(self, message: Any) -> None:
        position = message.pose.pose.position
        with self.stats.lock:
            self.stats.odom_messages += 1
            self.stats.max_distance_m = max(self.stats.max_distance_m, math.hypot(position.x, position.y))

    def _on_scan(self, _message: Any) -> None:
        with self.stats.lock:
            self.stats.scan_messages += 1

    # --- start-up ---
    def wait_ready(self, launch: subprocess.Popen, timeout: float) -> int:
        """Until the spawn and delete services are offered, the robot publishes /odom and /clock advances; the
        simulator's pid."""
        deadline = time.monotonic() + timeout
        for service in ("spawn_urdf_model", "spawn_sdf_model", "delete_model"):
            while True:
                if launch.poll() is not None:
                    raise SoakError("roslaunch exited (%s) before the simulator was ready" % launch.returncode)
                try:
                    self.rospy.wait_for_service("/gazebo/" + service, timeout=1.0)
                    break
                except self.rospy.ROSException:
                    if time.monotonic() > deadline:
                        raise SoakError("/gazebo/%s not offered within %.0f s" % (service, timeout)) from None
        pid = self.simulator_pid()
        first_clock = None
        while self.stats.odom_messages == 0 or first_clock is None or self.stats.clock in (None, first_clock):
            if first_clock is None:
                first_clock = self.stats.clock
            if launch.poll() is not None or not process_alive(pid):
                raise SoakError("the simulator died before it was ready")
            if time.monotonic() > deadline:
                raise SoakError("no /odom from %s or no advancing /clock within %.0f s" % (ROBOT, timeout))
            time.sleep(0.05)
        return pid

    def simulator_pid(self) -> int:
        """Process id of the simulator node, asked through its XML-RPC API."""
        import rosgraph

        uri = rosgraph.Master(self.rospy.get_name()).lookupNode(SIMULATOR_NODE)
        code, message, pid = xmlrpc.client.ServerProxy(uri).getPid(self.rospy.get_name())
        if code != 1:
            raise SoakError("%s did not tell its pid: %s" % (SIMULATOR_NODE, message))
        return int(pid)

    # --- load ---
    def start(self) -> None:
        for target in (self._drive, self._spawn_loop):
            thread = threading.Thread(target=target, name=target.__name__, daemon=True)
            thread.start()
            self._threads.append(thread)

    def stop(self, timeout: float = CALL_TIMEOUT_S + 1.0) -> None:
        """Stop driving and spawning (the call in progress ends first, if within ``timeout``); the robot is
        stopped."""
        self._stop.set()
        deadline = time.monotonic() + timeout
        for thread in self._threads:
            thread.join(max(0.0, deadline - time.monotonic()))
        with contextlib.suppress(Exception):
            self._command_pub.publish(self._twist())

    def _drive(self) -> None:
        start = time.monotonic()
        next_command = start
        while not self._stop.is_set():
            direction = 1.0 if int((time.monotonic() - start) / REVERSE_PERIOD_S) % 2 == 0 else -1.0
            twist = self._twist()
            twist.linear.x, twist.angular.z = direction * CIRCLE[0], direction * CIRCLE[1]
            self._command_pub.publish(twist)
            self.stats.commands += 1
            next_command += COMMAND_PERIOD_S
            self._stop.wait(max(0.0, next_command - time.monotonic()))

    def _call(self, name: str, service: str, srv_type: Any, *args: Any) -> Tuple[bool, str]:
        """One non-persistent call (as rosservice and spawn_model make them): (success, message)."""
        proxy = self.rospy.ServiceProxy(service, srv_type)
        started = time.monotonic()
        self.stats.call_name, self.stats.call_started = "%s %s" % (service, args[0]), started
        try:
            response = proxy(*args)
            return bool(response.success), response.status_message
        except (self.rospy.ServiceException, self.rospy.ROSException, OSError) as error:
            return False, "%s: %s" % (type(error).__name__, error)
        finally:
            with self.stats.lock:
                self.stats.latencies[name].append(time.monotonic() - started)
            self.stats.call_started = None

    def _spawn_one(self) -> None:
        from geometry_msgs.msg import Point, Pose, Quaternion

        index = self._spawned
        self._spawned += 1
        if self.robot_every and index % self.robot_every == self.robot_every - 1:
            kind, service, namespace = "burger", "/gazebo/spawn_urdf_model", "soak_robot_%d" % index
        else:
            kind, service = (
                ("urdf_box", "/gazebo/spawn_urdf_model") if index % 2 == 0 else ("sdf_box", "/gazebo/spawn_sdf_model")
            )
            namespace = "soak_ns_%d" % index if index % 3 == 0 else ""
        name = "soak_%s_%d" % (kind, index)
        slot = index % (SPAWN_GRID[0] * SPAWN_GRID[1])
        pose = Pose(
            Point(4.0 + 1.5 * (slot % SPAWN_GRID[0]), -2.25 + 1.5 * (slot // SPAWN_GRID[0]), 0.1),
            Quaternion(0, 0, 0, 1),
        )
        ok, message = self._call("spawn", service, self._spawn_types[0], name, self._models[kind], namespace, pose, "")
        with self.stats.lock:
            if ok:
                self.stats.spawns[kind] += 1
                self._live.append(name)
            else:
                self.stats.spawn_failures += 1
        if not ok:
            self.stats.fail("spawn %s (%s, namespace '%s'): %s" % (name, kind, namespace, message))

    def _delete_one(self) -> None:
        name = self._live.popleft()
        ok, message = self._call("delete", "/gazebo/delete_model", self._spawn_types[1], name)
        with self.stats.lock:
            if ok:
                self.stats.deletes += 1
            else:
                self.stats.delete_failures += 1
        if not ok:
            self.stats.fail("delete %s: %s" % (name, message))

    def _spawn_loop(self) -> None:
        next_spawn = time.monotonic()
        try:
            while not self._stop.is_set():
                self._spawn_one()
                while len(self._live) > self.live_models and not self._stop.is_set():
                    self._delete_one()
                next_spawn += self.spawn_period
                # Behind (slow calls): go on at once, without trying to catch up later.
                next_spawn = max(next_spawn, time.monotonic() - self.spawn_period)
                self._stop.wait(max(0.0, next_spawn - time.monotonic()))
        except Exception:
            self.stats.fail("spawn loop: " + traceback.format_exc(limit=3))

    def delete_remaining(self) -> None:
        """Delete the models still in the world (after ``stop``)."""
        while self._live:
            self._delete_one()

    def close(self) -> None:
        self._stop.set()
        with contextlib.suppress(Exception):
            self.rospy.signal_shutdown("soak finished")


# --- sampling and the verdict -----------------------------------------------------------------------------------------
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


def kinds_text(growth: Dict[str, int]) -> str:
    """' [eventpoll +18, socket -1]', or '' if nothing changed."""
    return " [%s]" % ", ".join("%s %+d" % item for item in sorted(growth.items())) if growth else ""


def slope_per_minute(points: Sequence[Tuple[float, float]]) -> Optional[float]:
    """Least-squares slope of (t s, value) points, per minute."""
    if len(points) < 3:
        return None
    mean_t = sum(t for t, _ in points) / len(points)
    mean_v = sum(v for _, v in points) / len(points)
    stt = sum((t - mean_t) ** 2 for t, _ in points)
    if stt <= 0:
        return None
    return 60.0 * sum((t - mean_t) * (v - mean_v) for t, v in points) / stt


def summarize(result: Dict[str, Any], args: argparse.Namespace, stats: Stats) -> None:
    """The summary and the checks of ``result`` (its samples and events) and ``stats`` into ``result``."""
    samples: List[Dict[str, Any]] = result["samples"]
    summary: Dict[str, Any] = {}
    checks: List[Dict[str, Any]] = []

    def check(name: str, passed: bool, detail: str) -> None:
        checks.append({"name": name, "pass": bool(passed), "detail": detail})

    with stats.lock:
        summary.update(
            spawns=sum(stats.spawns.values()),
            spawns_by_kind=dict(stats.spawns),
            spawn_failures=stats.spawn_failures,
            deletes=stats.deletes,
            delete_failures=stats.delete_failures,
            failure_messages=list(stats.failures),
            odom_messages=stats.odom_messages,
            scan_messages=stats.scan_messages,
            commands=stats.commands,
            robot_max_distance_m=round(stats.max_distance_m, 3),
        )
        for kind, values in stats.latencies.items():
            if values:
                ordered = sorted(values)
                summary["%s_latency_s" % kind] = {
                    "mean": round(sum(ordered) / len(ordered), 4),
                    "p99": round(ordered[max(0, math.ceil(0.99 * len(ordered)) - 1)], 4),
                    "max": round(ordered[-1], 4),
                }
    check(
        "spawns_and_deletes_succeed",
        summary["spawns"] > 0
        and summary["spawn_failures"] == 0
        and summary["delete_failures"] == 0
        and not summary["failure_messages"],
        "%d spawns (%d failed), %d deletes (%d failed)"
        % (summary["spawns"], summary["spawn_failures"], summary["deletes"], summary["delete_failures"]),
    )
    check("simulator_alive", result["simulator_alive"], result.get("death") or "alive to the end")
    check("no_hung_call", not result.get("hung_call"), result.get("hung_call") or "every call returned")
    if len(samples) < 2:
        check("enough_samples", False, "%d samples" % len(samples))
        result.update(summary=summary, checks=checks, passed=False)
        return

    first, last = samples[0], samples[-1]
    warm = next((s for s in samples if s["t"] >= result["warmup_s"]), last)
    if warm is last and len(samples) > 2:
        warm = samples[-2]
    stalls = [
        "%.0f-%.0f s" % (a["t"], b["t"])
        for a, b in zip(samples, samples[1:])
        if a["sim_time"] is None or b["sim_time"] is None or b["sim_time"] <= a["sim_time"]
    ]
    sim_span = (last["sim_time"] or 0.0) - (first["sim_time"] or 0.0)
    wall_span = last["t"] - first["t"]
    window_min = (last["t"] - warm["t"]) / 60.0
    after = [(s["t"], s["rss_mib"]) for s in samples if s["t"] >= warm["t"]]
    rss_growth = last["rss_mib"] - warm["rss_mib"]
    rss_rate = rss_growth / window_min if window_min > 0 else None
    rss_slope = slope_per_minute(after)
    summary.update(
        samples=len(samples),
        wall_s=round(wall_span, 2),
        warmup_sample_t=warm["t"],
        rss_start_mib=first["rss_mib"],
        rss_warmup_mib=warm["rss_mib"],
        rss_end_mib=last["rss_mib"],
        rss_max_mib=max(s["rss_mib"] for s in samples),
        rss_growth_mib=round(rss_growth, 3),
        rss_growth_mib_per_min=None if rss_rate is None else round(rss_rate, 3),
        rss_slope_mib_per_min=None if rss_slope is None else round(rss_slope, 3),
        rss_growth_total_mib=round(last["rss_mib"] - first["rss_mib"], 3),
        threads_start=first["threads"],
        threads_warmup=warm["threads"],
        threads_end=last["threads"],
        threads_growth=last["threads"] - warm["threads"],
        threads_max=max(s["threads_max"] for s in samples),
        fds_start=first["fds"],
        fds_warmup=warm["fds"],
        fds_end=last["fds"],
        fds_growth=last["fds"] - warm["fds"],
        fds_max=max(s["fds_max"] for s in samples),
        sim_time_start=first["sim_time"],
        sim_time_end=last["sim_time"],
        sim_time_advanced_s=round(sim_span, 3),
        rtf=round(sim_span / wall_span, 3) if wall_span > 0 else None,
        cpu_s=last["cpu_s"] - first["cpu_s"],
    )
    if result.get("after_cleanup"):
        summary["after_cleanup"] = result["after_cleanup"]
    check(
        "sim_time_advances",
        sim_span > 0 and not stalls,
        "sim time %.1f s -> %.1f s%s"
        % (first["sim_time"] or 0.0, last["sim_time"] or 0.0, "; stalled in " + ", ".join(stalls) if stalls else ""),
    )
    limit = args.max_rss_growth_mib_per_min
    sustained = rss_rate is not None and rss_slope is not None and rss_rate > limit and rss_slope > limit
    check(
        "rss_flat_after_warmup",
        rss_rate is not None and not sustained,
        (
            "%.2f MiB in %.1f min after warm-up: %s MiB/min end to end, trend %s MiB/min (limit %.1f)"
            % (
                rss_growth,
                window_min,
                "n/a" if rss_rate is None else "%.2f" % rss_rate,
                "n/a" if rss_slope is None else "%.2f" % rss_slope,
                limit,
            )
        )
        if rss_rate is not None
        else "not judged: no sample after the warm-up (the soak ended at %.0f s)" % last["t"],
    )
    # Threads and fds: neither at the end nor at any sample after the warm-up more than the tolerance above the
    # warm-up sample (a count that drops back only when the garbage collector runs grows between its runs).
    later = [s for s in samples if s["t"] >= warm["t"]]
    peak_threads = max(s["threads"] for s in later)
    peak_fds = max(later, key=lambda s: s["fds"])
    kinds = sorted(set(warm["fd_kinds"]) | set(last["fd_kinds"]) | set(peak_fds["fd_kinds"]))

    def by_kind(sample: Dict[str, Any]) -> Dict[str, int]:
        return {
            kind: sample["fd_kinds"].get(kind, 0) - warm["fd_kinds"].get(kind, 0)
            for kind in kinds
            if sample["fd_kinds"].get(kind, 0) != warm["fd_kinds"].get(kind, 0)
        }

    summary.update(
        threads_peak_after_warmup=peak_threads,
        fds_peak_after_warmup=peak_fds["fds"],
        fd_kinds_warmup=warm["fd_kinds"],
        fd_kinds_end=last["fd_kinds"],
        fd_growth_by_kind=by_kind(last),
        fd_peak_growth_by_kind=by_kind(peak_fds),
    )
    check(
        "threads_flat_after_warmup",
        max(last["threads"], peak_threads) - warm["threads"] <= args.max_thread_growth,
        "%d after warm-up, %d at the end, at most %d (limit +%d)"
        % (warm["threads"], last["threads"], peak_threads, args.max_thread_growth),
    )
    check(
        "fds_flat_after_warmup",
        max(last["fds"], peak_fds["fds"]) - warm["fds"] <= args.max_fd_growth,
        "%d after warm-up, %d at the end%s, at most %d at %.0f s%s (limit +%d)"
        % (
            warm["fds"],
            last["fds"],
            kinds_text(by_kind(last)),
            peak_fds["fds"],
            peak_fds["t"],
            kinds_text(by_kind(peak_fds)),
            args.max_fd_growth,
        ),
    )
    result.update(summary=summary, checks=checks, passed=all(c["pass"] for c in checks))


def table(result: Dict[str, Any]) -> str:
    lines = [
        "%8s %9s %6s %9s %7s %5s %5s %5s %6s %6s %5s %7s %7s"
        % (
            "t (s)",
            "sim (s)",
            "RTF",
            "RSS MiB",
            "threads",
            "fds",
            "sock",
            "epoll",
            "spawns",
            "dels",
            "fail",
            "odom/s",
            "scan/s",
        )
    ]
    previous = None
    for sample in result["samples"]:
        rtf = odom = scan = "-"
        if previous is not None and sample["t"] > previous["t"]:
            wall = sample["t"] - previous["t"]
            if sample["sim_time"] is not None and previous["sim_time"] is not None:
                rtf = "%.2f" % ((sample["sim_time"] - previous["sim_time"]) / wall)
            odom = "%.0f" % ((sample["odom_messages"] - previous["odom_messages"]) / wall)
            scan = "%.0f" % ((sample["scan_messages"] - previous["scan_messages"]) / wall)
        lines.append(
            "%8.1f %9.1f %6s %9.2f %7d %5d %5d %5d %6d %6d %5d %7s %7s"
            % (
                sample["t"],
                sample["sim_time"] or 0.0,
                rtf,
                sample["rss_mib"],
                sample["threads"],
                sample["fds"],
                sample["fd_kinds"].get("socket", 0),
                sample["fd_kinds"].get("eventpoll", 0),
                sample["spawns"],
                sample["deletes"],
                sample["failures"],
                odom,
                scan,
            )
        )
        previous = sample
    summary = result.get("summary", {})
    if "rss_end_mib" in summary:
        s = summary
        lines += [
            "",
            "warm-up: %.0f s (sample at %.1f s)" % (result["warmup_s"], s["warmup_sample_t"]),
            "RSS: start %.2f MiB, after warm-up %.2f MiB, end %.2f MiB (max %.2f): %+.2f MiB after warm-up = %s MiB/min,"
            " trend %s MiB/min"
            % (
                s["rss_start_mib"],
                s["rss_warmup_mib"],
                s["rss_end_mib"],
                s["rss_max_mib"],
                s["rss_growth_mib"],
                "n/a" if s["rss_growth_mib_per_min"] is None else "%.2f" % s["rss_growth_mib_per_min"],
                "n/a" if s["rss_slope_mib_per_min"] is None else "%.2f" % s["rss_slope_mib_per_min"],
            ),
            "threads: start %d, after warm-up %d, end %d (%+d; peak after warm-up %d; most seen %d)"
            % (
                s["threads_start"],
                s["threads_warmup"],
                s["threads_end"],
                s["threads_growth"],
                s["threads_peak_after_warmup"],
                s["threads_max"],
            ),
            "fds: start %d, after warm-up %d, end %d (%+d%s; peak after warm-up %d%s; most seen %d)"
            % (
                s["fds_start"],
                s["fds_warmup"],
                s["fds_end"],
                s["fds_growth"],
                kinds_text(s["fd_growth_by_kind"]),
                s["fds_peak_after_warmup"],
                kinds_text(s["fd_peak_growth_by_kind"]),
                s["fds_max"],
            ),
            "fds by kind: after warm-up %s, end %s" % (s["fd_kinds_warmup"], s["fd_kinds_end"]),
            "sim time: %.1f s in %.1f s wall: RTF %.2f; simulator CPU %.1f s"
            % (s["sim_time_advanced_s"], s["wall_s"], s["rtf"] or 0.0, s["cpu_s"]),
        ]
    if summary:
        lines.append(
            "spawns: %d %s (%d failed); deletes: %d (%d failed)"
            % (
                summary["spawns"],
                summary["spawns_by_kind"],
                summary["spawn_failures"],
                summary["deletes"],
                summary["delete_failures"],
            )
        )
        for kind in ("spawn", "delete"):
            latency = summary.get("%s_latency_s" % kind)
            if latency:
                lines.append(
                    "%s calls: mean %.1f ms, p99 %.1f ms, max %.1f ms"
                    % (kind, 1000 * latency["mean"], 1000 * latency["p99"], 1000 * latency["max"])
                )
        if "after_cleanup" in summary:
            cleanup = summary["after_cleanup"]
            lines.append(
                "after deleting every soak model: RSS %.2f MiB, %d threads, %d fds %s"
                % (cleanup["rss_mib"], cleanup["threads"], cleanup["fds"], cleanup["fd_kinds"])
            )
        for message in summary["failure_messages"]:
            lines.append("FAILED: " + message)
    lines.append("")
    for item in result.get("checks", []):
        lines.append("%-27s %s  %s" % (item["name"], "PASS" if item["pass"] else "FAIL", item["detail"]))
    return "\n".join(lines)


# --- the run --------------------------------------------------------------------------------------------------------
def run_soak(args: argparse.Namespace, result: Dict[str, Any], processes: Processes) -> None:
    env = start_master(processes)
    os.environ.update({key: env[key] for key in ("ROS_MASTER_URI", "ROS_IP", "ROS_HOSTNAME", "ROS_LOG_DIR")})
    launch = processes.start(
        ["roslaunch", "turtle_sim_ode", "turtlebot_world.launch", "real_time_factor:=0"], env, "launch.log"
    )
    node = SoakNode(args.spawn_rate, args.live_models, args.robot_every)
    result["node"] = node  # for the summary; removed before writing JSON
    try:
        try:
            pid = node.wait_ready(launch, STARTUP_TIMEOUT_S)
        except SoakError as error:
            raise SoakError("%s\nroslaunch:\n%s" % (error, processes.log_tail("launch.log"))) from None
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
                    processes.log_tail("launch.log"),
                )
                break
            call_started = node.stats.call_started
            if call_started is not None and now - call_started > CALL_TIMEOUT_S:
                result["hung_call"] = "%s did not return in %.0f s" % (node.stats.call_name, CALL_TIMEOUT_S)
                break
            if now >= next_sample or now >= end:
                try:
                    sample = take_sample(pid, start, node, cpu_start)
                except (OSError, SoakError):
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
            except (OSError, SoakError):
                if process_alive(pid):
                    raise
                result["simulator_alive"] = False
                result["death"] = "the simulator died while the soak's last models were deleted:\n" + (
                    processes.log_tail("launch.log")
                )
    finally:
        node.stop(SHUTDOWN_TIMEOUT_S)  # at once if stopped already; else (an error, Ctrl-C) before the simulator
        node.close()


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
        except SoakError as failure:
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
