#!/usr/bin/env python3
"""Benchmark of the turtle_sim_ode simulator (issue #8): prints a table and writes JSON.

1. physics only (no ROS): Simulation.step of one TurtleBot, and the bare PyODE floor for the same bodies;
2. the full node unthrottled (real_time_factor 0), every sensor subscribed: RTF for 1, 5, 10 robots at 1 and 10 ms;
3. real time (real_time_factor 1): achieved RTF and the spread of /clock intervals;
4. roslaunch turtlebot_world.launch to the first /odom message;
5. PyBullet (in a venv of its own under .cache/) on the same URDF: steps/s and the circle radius it drives.

Every ROS process runs against a master of its own on a free port and is stopped at the end, also on Ctrl-C, SIGTERM
or error: SIGINT, then SIGKILL to its process group and to every process with its tag in the environment (roslaunch
starts nodes in sessions of their own). Run with /usr/bin/python3 and the workspace sourced.
"""
from __future__ import annotations

import argparse
import contextlib
import datetime
import fcntl
import json
import math
import multiprocessing
import os
import platform
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import traceback
import xmlrpc.client
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Set, Tuple

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from ros_processes import SHUTDOWN_TIMEOUT_S, Processes, cpu_seconds, free_port  # noqa: E402
from tcpros_reader import Reader, TopicStream, clock_stamp  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE = os.path.join(REPO, "catkin_ws", "src", "turtle_sim_ode")
URDF_PATH = os.path.join(PACKAGE, "urdf", "turtlebot.urdf")
DEFAULT_JSON = os.path.join(REPO, "bench_results", "bench_sim.json")
VENV = os.path.join(REPO, ".cache", "bench-venv")
PEER_SCRIPT = os.path.join(REPO, "scripts", "lib", "pybullet_peer.py")
PEER_PACKAGES = ("pybullet", "numpy")  # pybullet's import fails without numpy, which it does not declare
PIP_TIMEOUT_S = 900  # building PyBullet from its sdist is acceptable up to this
PEER_TIMEOUT_S = 600
MODEL = "mobile_base"
CIRCLE = (0.5, 0.5)  # v (m/s), w (rad/s): a circle of radius v / w
CIRCLE_SAMPLE_PERIOD_S = 0.01
CIRCLE_SAMPLES_FROM_S = 1.0  # leave out the start (the robot accelerates onto the circle)
SETTLE_STEPS = 500
ROBOT_SPACING_M = 3.0  # between spawn points: 1 m circles never meet
ROBOTS_PER_ROW = 5
STARTUP_TIMEOUT_S = 60.0
READ_BATCH_S = 0.002  # the probe drains the simulator's topics every 2 ms (see tcpros_reader.Reader)


@dataclass(frozen=True)
class Plan:
    """Sizes and durations of one run."""

    physics_steps: int  # per timed repeat
    physics_repeats: int  # the best repeat counts
    circle_seconds: float  # sim seconds driven for the circle fit
    robot_counts: Tuple[int, ...]
    time_steps: Tuple[float, ...]
    warmup_s: float  # wall seconds before a window
    window_s: float  # wall seconds measured, full node unthrottled
    real_time_window_s: float
    launch_runs: int


FULL = Plan(2000, 10, 20.0, (1, 5, 10), (0.001, 0.01), 3.0, 10.0, 30.0, 3)
QUICK = Plan(1000, 5, 10.0, (1, 2), (0.001, 0.01), 1.0, 3.0, 5.0, 1)


class BenchError(RuntimeError):
    """A measurement could not be made (the message says why)."""


# --- machine ------------------------------------------------------------------------------------------------------
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


def cpu_ticks() -> Tuple[int, int]:
    """(all, stolen) CPU ticks of the machine so far (/proc/stat): on a virtual machine the host may take cores
    away for a while, and the figures of that stretch then come out low."""
    with open("/proc/stat") as stat:
        fields = [int(field) for field in stat.readline().split()[1:]]
    return sum(fields), fields[7] if len(fields) > 7 else 0


# --- 1. physics only ----------------------------------------------------------------------------------------------
def turtlebot_simulation(contact_kernel: bool = True) -> Any:
    """A Simulation (default physics) with the TurtleBot as MODEL, its drive commanded CIRCLE with no timeout;
    ``contact_kernel`` False collides in Python instead of the compiled kernel."""
    from turtle_sim_ode.world.simulation import Simulation

    sim = Simulation(contact_kernel=contact_kernel)
    with open(URDF_PATH) as urdf:
        sim.spawn_urdf(MODEL, urdf.read(), (0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    robot = sim.robots[MODEL]
    robot.params.cmd_timeout = 0.0
    robot.drive.set_command(CIRCLE[0], CIRCLE[1], sim.sim_time)
    return sim


def best_steps_per_second(steppers: Sequence[Callable[[], None]], steps: int, repeats: int) -> List[float]:
    """Best steps/s of each stepper over ``repeats`` runs of ``steps``, timed in turns so that all see the same load
    of the machine."""
    best = [math.inf] * len(steppers)
    for _ in range(repeats):
        for index, step in enumerate(steppers):
            start = time.perf_counter()
            for _ in range(steps):
                step()
            best[index] = min(best[index], time.perf_counter() - start)
    return [steps / seconds for seconds in best]


# PyODE frees a World's C object with its wrapper and with it every body and joint, which the wrappers that die later
# free again: the bare world lives as long as the process.
_BARE_WORLDS: List[Any] = []


class BarePyOde:
    """The simulation's world, bodies (at their current state), hinge motors, geoms and contact surfaces made again
    directly with PyODE, and stepped by a minimal loop: collide with the ground, contact joints, quickStep."""

    def __init__(self, sim: Any) -> None:
        import ode
        from turtle_sim_ode.physics import ode_constants
        from turtle_sim_ode.models.builder import compose, inverse
        from turtle_sim_ode.physics.world import combine_surfaces, configure_world

        physics, model = sim.physics, sim.models[MODEL]
        params = physics.params
        self.time_step = params.time_step
        self.world = ode.World()
        _BARE_WORLDS.append(self.world)
        configure_world(self.world, params)
        self.ground = ode.GeomPlane(None, (0.0, 0.0, 1.0), 0.0)
        self.bodies = {}
        for body in model.bodies:
            copy = ode.Body(self.world)
            copy.setMass(body.getMass())
            copy.setPosition(body.getPosition())
            copy.setQuaternion(body.getQuaternion())
            copy.setLinearVel(body.getLinearVel())
            copy.setAngularVel(body.getAngularVel())
            self.bodies[body] = copy
        # (geom, body, surface, contacts kept) of the TurtleBot's cylinders and spheres: one contact per cylinder,
        # since ours merges the two ends of a wheel's line contact into one.
        self.ground_pairs = []
        for geom in (geom for link_geoms in model.geoms.values() for geom in link_geoms):
            if isinstance(geom, ode.GeomCylinder):
                copy, kept = ode.GeomCylinder(None, *geom.getParams()), 1
            else:
                copy, kept = ode.GeomSphere(None, geom.getRadius()), params.max_contacts
            body = geom.getBody()
            copy.setBody(self.bodies[body])
            offset = compose(
                inverse((body.getPosition(), body.getQuaternion())), (geom.getPosition(), geom.getQuaternion())
            )
            copy.setOffsetPosition(offset[0])
            copy.setOffsetQuaternion(offset[1])
            surface = combine_surfaces(physics.surface(physics.ground), physics.surface(geom), self.time_step)
            self.ground_pairs.append((copy, self.bodies[body], surface, kept))
        self.joints = []  # the TurtleBot's wheel hinges
        for handle in model.joints.values():
            joint = ode.HingeJoint(self.world)
            joint.attach(self.bodies[handle.joint.getBody(0)], self.bodies[handle.joint.getBody(1)])
            joint.setAnchor(handle.joint.getAnchor())
            joint.setAxis(handle.joint.getAxis())
            for param in (ode_constants.PARAM_VEL, ode_constants.PARAM_FMAX):
                joint.setParam(param, handle.joint.getParam(param))
            self.joints.append(joint)
        self.contact_joints: List[Any] = []
        self._collide, self._contact_joint = ode.collide, ode.ContactJoint

    def step(self) -> None:
        world, ground, keep = self.world, self.ground, self.contact_joints.append
        collide, contact_joint = self._collide, self._contact_joint
        self.contact_joints.clear()  # dropping a wrapper destroys its joint
        for geom, body, (mode, mu, mu2, erp, cfm), kept in self.ground_pairs:
            for contact in collide(ground, geom)[:kept]:
                contact.setMode(mode)
                contact.setMu(mu)
                contact.setMu2(mu2)
                contact.setSoftERP(erp)
                contact.setSoftCFM(cfm)
                joint = contact_joint(world, None, contact)
                joint.attach(None, body)
                keep(joint)
        world.quickStep(self.time_step)


def circle_radius(points: Sequence[Sequence[float]]) -> float:
    """Radius of the least-squares circle through (x, y) points."""
    from turtle_sim_ode.analysis.path_fit import fit_circle

    return fit_circle(points)[1]


def circle_track(seconds: float) -> List[Tuple[float, float]]:
    """base_footprint's (x, y) in our simulation driving CIRCLE, sampled as the PyBullet peer samples."""
    sim = turtlebot_simulation()
    model = sim.models[MODEL]
    dt = sim.physics.time_step
    sample_every = max(1, round(CIRCLE_SAMPLE_PERIOD_S / dt))
    track = []
    for step in range(1, round(seconds / dt) + 1):
        sim.step()
        if step % sample_every == 0 and step * dt >= CIRCLE_SAMPLES_FROM_S:
            position, _ = model.link_pose("base_footprint")
            track.append((position[0], position[1]))
    return track


def physics_only(plan: Plan) -> Dict[str, Any]:
    """Section 1: our steps/s, the bare PyODE floor's, and the circle radius we drive."""
    sim, in_python = turtlebot_simulation(), turtlebot_simulation(contact_kernel=False)
    if not sim.physics.uses_contact_kernel:
        raise BenchError("the contact kernel (libturtle_sim_ode_contacts.so) is not built: run scripts/build.sh")
    for _ in range(SETTLE_STEPS):
        sim.step()
        in_python.step()
    bare = BarePyOde(sim)
    ours, floor, python_contacts = best_steps_per_second(
        (sim.step, bare.step, in_python.step), plan.physics_steps, plan.physics_repeats
    )
    dt = sim.physics.time_step
    return {
        "time_step": dt,
        "solver": sim.physics.params.solver,
        "solver_iterations": sim.physics.params.solver_iterations,
        "steps_per_s": ours,
        "us_per_step": 1e6 / ours,
        "rtf": ours * dt,
        "contacts_per_step": sim.physics.contact_count,
        "bare_pyode": {
            "steps_per_s": floor,
            "us_per_step": 1e6 / floor,
            "rtf": floor * dt,
            "contacts_per_step": len(bare.contact_joints),
        },
        "overhead_ratio": floor / ours,
        "python_contacts": {  # the Python collision path the kernel replaces (same results, bitwise)
            "steps_per_s": python_contacts,
            "us_per_step": 1e6 / python_contacts,
            "rtf": python_contacts * dt,
        },
        "circle_radius_m": circle_radius(circle_track(plan.circle_seconds)),
        "circle_expected_radius_m": CIRCLE[0] / CIRCLE[1],
    }


# --- process groups and masters -----------------------------------------------------------------------------------
class Master:
    """A roscore of our own on a free port; ``ros_env`` points ROS processes at it, ``close`` stops it and what was
    launched on it."""

    def __init__(self, processes: Processes, name: str) -> None:
        self.processes = processes
        self.name = name
        self.started: List[subprocess.Popen] = []
        port = free_port()
        self.uri = "http://127.0.0.1:%d" % port
        self.ros_env = {
            "ROS_MASTER_URI": self.uri,
            "ROS_IP": "127.0.0.1",
            "ROS_HOSTNAME": "127.0.0.1",
            "ROS_LOG_DIR": processes.log_dir,
        }
        roscore = self._start(["roscore", "-p", str(port)], "roscore")
        deadline = time.monotonic() + STARTUP_TIMEOUT_S
        while True:
            with contextlib.suppress(OSError):
                xmlrpc.client.ServerProxy(self.uri).getPid("/bench_sim")
                return
            if roscore.poll() is not None or time.monotonic() > deadline:
                self.close()
                raise BenchError("roscore did not start:\n" + processes.log_tail(name + "-roscore.log"))
            time.sleep(0.1)

    def _start(self, command: List[str], log: str) -> subprocess.Popen:
        process = self.processes.start(command, dict(os.environ, **self.ros_env), "%s-%s.log" % (self.name, log))
        self.started.append(process)
        return process

    def launch(self, launch_file: str, arguments: Sequence[str]) -> subprocess.Popen:
        return self._start(["roslaunch", "turtle_sim_ode", launch_file] + list(arguments), "launch")

    def close(self) -> None:
        for process in reversed(self.started):
            self.processes.stop(process)

    def failure(self, launch: subprocess.Popen, error: BenchError) -> BenchError:
        """``error`` with the launch's exit status and the tail of its log."""
        status = "running" if launch.poll() is None else "exited %s" % launch.returncode
        return BenchError(
            "%s\nroslaunch (%s):\n%s" % (error, status, self.processes.log_tail(self.name + "-launch.log"))
        )


@contextlib.contextmanager
def master(processes: Processes, name: str) -> Iterator[Master]:
    """A fresh master; it and every launch made on it are stopped on leaving."""
    ros = Master(processes, name)
    try:
        yield ros
    finally:
        ros.close()


# --- probes: ROS nodes of the benchmark, each in a forked child on one master -------------------------------------
class Probe:
    """Runs ``task(send, *args)`` as a ROS node on master ``ros`` in a forked child process; ``receive`` returns what
    it sends."""

    def __init__(self, ros: Master, task: Callable[..., None], *args: Any) -> None:
        context = multiprocessing.get_context("fork")
        self._connection, child_end = context.Pipe()
        self._process = context.Process(target=_probe_main, args=(child_end, ros.ros_env, task, args), daemon=True)
        self._process.start()
        child_end.close()

    def __enter__(self) -> "Probe":
        return self

    def __exit__(self, *_: object) -> None:
        self._process.terminate()
        self._process.join(SHUTDOWN_TIMEOUT_S)
        if self._process.is_alive():
            self._process.kill()
            self._process.join()

    def receive(self, timeout: float) -> Any:
        if not self._connection.poll(timeout):
            raise BenchError("the benchmark's ROS node gave no answer in %.0f s" % timeout)
        kind, value = self._connection.recv()
        if kind == "error":
            raise BenchError(value)
        return value


def _probe_main(connection: Any, ros_env: Dict[str, str], task: Callable[..., None], args: Tuple[Any, ...]) -> None:
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    os.environ.update(ros_env)
    try:
        import rospy

        from turtle_sim_ode.ros.node import stop_hearing_own_clock

        rospy.init_node("bench_sim_probe", anonymous=True, disable_signals=True)
        stop_hearing_own_clock()  # /use_sim_time: the probe times with the wall clock and reads /clock itself
        task(lambda value: connection.send(("value", value)), *args)
    except BenchError as error:
        connection.send(("error", str(error)))
    except Exception:
        connection.send(("error", traceback.format_exc(limit=3)))


def wait_until(condition: Callable[[], bool], timeout: float) -> bool:
    """Poll ``condition`` until it holds (True) or ``timeout`` wall seconds pass (False)."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def robot_topics(name: str) -> Dict[str, str]:
    """Kind -> topic of a TurtleBot spawned as model ``name`` in namespace ``name``."""
    return {
        "odom": "/%s/odom" % name,
        "joint_states": "/%s/joint_states" % name,
        "imu": "/%s/%s/sensors/imu_data" % (name, name),
        "scan": "/%s/scan" % name,
    }


def spread(values: Sequence[float]) -> Dict[str, float]:
    """Mean, standard deviation and 99th percentile."""
    ordered = sorted(values)
    return {
        "mean": statistics.mean(ordered),
        "stdev": statistics.stdev(ordered) if len(ordered) > 1 else 0.0,
        "p99": ordered[max(0, math.ceil(0.99 * len(ordered)) - 1)],
        "count": len(ordered),
    }


def node_pid(name: str) -> int:
    """Process id of the ROS node ``name``, asked through its XML-RPC API."""
    import rosgraph

    code, message, pid = xmlrpc.client.ServerProxy(rosgraph.Master("/bench_sim").lookupNode(name)).getPid("/bench_sim")
    if code != 1:
        raise BenchError("%s did not tell its pid: %s" % (name, message))
    return pid


def measure_rtf_task(send: Callable[[Any], None], robots: int, warmup_s: float, window_s: float) -> None:
    """Spawn ``robots`` TurtleBots driving circles, subscribe to all they publish, and send the RTF, /clock
    intervals and message rates over a window of ``window_s`` wall seconds after ``warmup_s``."""
    import rospy
    from gazebo_msgs.srv import SpawnModel
    from geometry_msgs.msg import Point, Pose, Quaternion, Twist
    import rosgraph
    from nav_msgs.msg import Odometry

    rospy.wait_for_service("/gazebo/spawn_urdf_model", STARTUP_TIMEOUT_S)
    spawn = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)
    with open(URDF_PATH) as urdf_file:
        urdf = urdf_file.read()
    clock: List[Tuple[float, float]] = []  # (wall, sim) of each /clock message
    topics = {"/clock": "clock", "/tf": "tf"}
    robot_topic_sets = []
    for index in range(robots):
        name = "robot_%d" % index
        position = Point(ROBOT_SPACING_M * (index % ROBOTS_PER_ROW), ROBOT_SPACING_M * (index // ROBOTS_PER_ROW), 0.0)
        answer = spawn(name, urdf, name, Pose(position, Quaternion(0, 0, 0, 1)), "world")
        if not answer.success:
            raise BenchError("spawning %s failed: %s" % (name, answer.status_message))
        command = rospy.Publisher("/%s/%s/commands/velocity" % (name, name), Twist, queue_size=1, latch=True)
        command.publish(Twist(linear=Point(CIRCLE[0], 0, 0), angular=Point(0, 0, CIRCLE[1])))
        robot_topic_sets.append(robot_topics(name))
        topics.update({topic: kind for kind, topic in robot_topic_sets[-1].items()})

    # Raw TCPROS readers, not rospy subscribers: every message is still sent and read, but this process spends
    # about a microsecond on each instead of a rospy callback's tens, which would load the machine it measures.
    def published() -> Set[str]:
        return {topic for topic, _ in rospy.get_published_topics()}

    if not wait_until(lambda: set(topics) <= published(), STARTUP_TIMEOUT_S):
        raise BenchError("not published: %s" % sorted(set(topics) - published()))

    def on_clock(wall: float, payload: bytes) -> None:
        clock.append((wall, clock_stamp(payload)))

    # /clock on a reader of its own that wakes for each message, sent without delay (Nagle's algorithm would batch
    # them), for its arrival times; the rest drained every READ_BATCH_S.
    master_uri, caller_id = rosgraph.get_master_uri(), rospy.get_name()
    clock_stream = TopicStream(master_uri, caller_id, "/clock", on_clock, tcp_nodelay=True)
    streams = [TopicStream(master_uri, caller_id, topic) for topic in topics if topic != "/clock"]
    readers = [Reader([clock_stream]), Reader(streams, READ_BATCH_S)]
    streams.append(clock_stream)

    def counts() -> Dict[str, int]:
        return {stream.topic: stream.count for stream in streams}

    try:
        if not wait_until(lambda: all(counts().values()), STARTUP_TIMEOUT_S):
            silent = sorted(topic for topic, count in counts().items() if not count)
            raise BenchError("no message on %s" % silent)
        simulator = node_pid("/gazebo")
        time.sleep(warmup_s)
        start_counts, start, start_cpu = counts(), time.monotonic(), cpu_seconds(simulator)
        time.sleep(window_s)
        end_counts, end, end_cpu = counts(), time.monotonic(), cpu_seconds(simulator)
        last = {stream.topic: stream.last for stream in streams}
    finally:
        for reader in readers:
            reader.close()
    errors = [reader.error for reader in readers if reader.error is not None]
    if errors:
        raise BenchError("reading the topics failed: %s" % errors[0])
    window = [(wall, sim) for wall, sim in list(clock) if start <= wall <= end]
    if len(window) < 2:
        raise BenchError("only %d /clock messages in %.1f wall seconds" % (len(window), window_s))
    wall_s, sim_s = window[-1][0] - window[0][0], window[-1][1] - window[0][1]
    per_kind: Dict[str, int] = {}
    for topic, kind in topics.items():
        if kind != "clock":
            per_kind[kind] = per_kind.get(kind, 0) + end_counts[topic] - start_counts[topic]
    intervals_ms = [1e3 * (later[0] - earlier[0]) for earlier, later in zip(window, window[1:])]
    odometry = [Odometry().deserialize(last[of_robot["odom"]]).twist.twist for of_robot in robot_topic_sets]
    send(
        {
            "robots": robots,
            "wall_s": wall_s,
            "sim_s": sim_s,
            "rtf": sim_s / wall_s,
            # CPU time of the simulator node (all threads) per sim second: less sensitive to other load than RTF.
            "node_cpu_ms_per_sim_s": 1e3 * (end_cpu - start_cpu) / sim_s,
            "node_cpu_share": (end_cpu - start_cpu) / (end - start),
            "clock_hz": (len(window) - 1) / sim_s,
            "clock_interval_ms": spread(intervals_ms),
            "rates_per_robot_hz": {kind: count / robots / sim_s for kind, count in sorted(per_kind.items())},
            # Odometry of the slowest robot: all drive their circles.
            "slowest_odom_speed_m_s": min(twist.linear.x for twist in odometry),
            "slowest_odom_turn_rad_s": min(twist.angular.z for twist in odometry),
        }
    )


def first_odom_task(send: Callable[[Any], None]) -> None:
    """Subscribe to /odom, send "ready", then the wall time (time.monotonic) of the first message."""
    import rospy

    received = threading.Event()
    arrival: List[float] = []

    def on_odom(_message: Any) -> None:
        if not received.is_set():
            arrival.append(time.monotonic())
            received.set()

    rospy.Subscriber("/odom", rospy.AnyMsg, on_odom)
    send("ready")
    if not received.wait(STARTUP_TIMEOUT_S):
        raise BenchError("no /odom message in %.0f s" % STARTUP_TIMEOUT_S)
    send(arrival[0])


# --- 2. and 3. the full node --------------------------------------------------------------------------------------
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
) -> Dict[str, Any]:
    """RTF and /clock intervals of the node in empty_world.launch with ``robots`` TurtleBots spawned."""
    physics = dict(package_config("physics.yaml"), time_step=time_step)
    config = package_config("simulator.yaml")
    config["diff_drive"]["cmd_timeout"] = 0.0  # commands are sent once: the drives must not time out, at any RTF
    physics_path = write_yaml(os.path.join(processes.log_dir, name + "-physics.yaml"), physics)
    config_path = write_yaml(os.path.join(processes.log_dir, name + "-simulator.yaml"), config)
    with master(processes, name) as ros:
        launch = ros.launch(
            "empty_world.launch",
            ["real_time_factor:=%g" % real_time_factor, "physics:=" + physics_path, "config:=" + config_path],
        )
        with Probe(ros, measure_rtf_task, robots, warmup, window) as probe:
            try:
                result = probe.receive(2 * STARTUP_TIMEOUT_S + warmup + window)
            except BenchError as error:
                raise ros.failure(launch, error) from None
    result.update(time_step=time_step, real_time_factor=real_time_factor)
    return result


def full_node(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 2: the unthrottled node for each time step and robot count."""
    runs = []
    for time_step in plan.time_steps:
        for robots in plan.robot_counts:
            name = "rtf-%drobots-%gms" % (robots, time_step * 1e3)
            print("  full node: %d robot(s), %g ms ..." % (robots, time_step * 1e3), flush=True)
            run = node_rtf(processes, name, robots, time_step, 0.0, plan.warmup_s, plan.window_s)
            run["steps_per_s"] = run["rtf"] / time_step
            run["wall_ms_per_sim_s"] = 1e3 / run["rtf"]
            run["wall_ms_per_sim_s_per_robot"] = run["wall_ms_per_sim_s"] / robots
            del run["clock_interval_ms"]
            runs.append(run)
    return {
        "real_time_factor": 0.0,
        "sensors": "all subscribed: /clock, /tf and each robot's odom, joint_states, imu, scan",
        "runs": runs,
        "linearity_at_1ms": {
            "wall": linearity(runs, 0.001, "wall_ms_per_sim_s"),
            "node_cpu": linearity(runs, 0.001, "node_cpu_ms_per_sim_s"),
        },
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


# --- 4. launch ----------------------------------------------------------------------------------------------------
def launch_to_first_odom(plan: Plan, processes: Processes) -> Dict[str, Any]:
    """Section 4: wall seconds from starting roslaunch (master already up) to the first /odom message."""
    times = []
    for index in range(plan.launch_runs):
        print("  launch %d/%d ..." % (index + 1, plan.launch_runs), flush=True)
        with master(processes, "launch-%d" % index) as ros:
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


# --- 5. PyBullet --------------------------------------------------------------------------------------------------
def peer_python() -> Tuple[Optional[str], str]:
    """(python of the venv with PyBullet, how it came to be), installing it if needed, or (None, why not)."""
    python = os.path.join(VENV, "bin", "python")
    check = [python, "-c", "import pybullet"]
    os.makedirs(os.path.dirname(VENV), exist_ok=True)
    with open(VENV + ".lock", "w") as lock:  # concurrent runs install once
        fcntl.flock(lock, fcntl.LOCK_EX)
        if os.access(python, os.X_OK) and subprocess.run(check, capture_output=True).returncode == 0:
            return python, "reused " + VENV
        shutil.rmtree(VENV, ignore_errors=True)
        made = subprocess.run(["/usr/bin/python3", "-m", "venv", VENV], capture_output=True, text=True)
        if made.returncode != 0:
            return None, "/usr/bin/python3 -m venv failed: " + (made.stdout + made.stderr).strip()[-300:]
        print("  installing %s into %s ..." % (" ".join(PEER_PACKAGES), VENV), flush=True)
        start = time.monotonic()
        try:
            installed = subprocess.run(
                [python, "-m", "pip", "install", "-q"] + list(PEER_PACKAGES),
                capture_output=True,
                text=True,
                timeout=PIP_TIMEOUT_S,
            )
        except subprocess.TimeoutExpired:
            shutil.rmtree(VENV, ignore_errors=True)
            return None, "pip install %s took over %d s" % (" ".join(PEER_PACKAGES), PIP_TIMEOUT_S)
        if installed.returncode != 0 or subprocess.run(check, capture_output=True).returncode != 0:
            shutil.rmtree(VENV, ignore_errors=True)
            return None, "pip install %s failed: %s" % (" ".join(PEER_PACKAGES), installed.stderr.strip()[-300:])
        return python, "installed into %s in %.0f s" % (VENV, time.monotonic() - start)


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


# --- targets and the table ----------------------------------------------------------------------------------------
def find_run(results: Dict[str, Any], robots: int, time_step: float) -> Optional[Dict[str, Any]]:
    """The full-node run with ``robots`` and ``time_step``, if there was one."""
    runs = results.get("full_node", {}).get("runs", [])
    return next((r for r in runs if r["robots"] == robots and r["time_step"] == time_step), None)


def targets(results: Dict[str, Any]) -> List[Dict[str, Any]]:
    """Issue #8's targets: name, value, goal, pass (None when not measured in this run)."""
    one_1ms, one_10ms, ten_1ms = find_run(results, 1, 0.001), find_run(results, 1, 0.01), find_run(results, 10, 0.001)
    physics_rtf = results.get("physics_only", {}).get("rtf")
    rows: List[Tuple[str, Optional[float], str, Callable[[float], bool]]] = [
        ("1 TurtleBot, 1 ms: RTF", one_1ms and one_1ms["rtf"], ">= 25", lambda v: v >= 25),
        (
            "1 TurtleBot, 1 ms: RTF / physics-only RTF",
            one_1ms and physics_rtf and one_1ms["rtf"] / physics_rtf,
            ">= 0.80",
            lambda v: v >= 0.8,
        ),
        ("1 TurtleBot, 10 ms: RTF", one_10ms and one_10ms["rtf"], ">= 200", lambda v: v >= 200),
        ("10 TurtleBots, 1 ms: RTF", ten_1ms and ten_1ms["rtf"], ">= 2.5", lambda v: v >= 2.5),
        (
            "node CPU per sim s linear in robots, 1 ms",
            results.get("full_node", {}).get("linearity_at_1ms", {}).get("node_cpu"),
            "0.8 .. 1.2",
            lambda v: 0.8 <= v <= 1.2,
        ),
        ("real time: RTF", results.get("real_time", {}).get("rtf"), "1.00 +- 0.02", lambda v: abs(v - 1) <= 0.02),
        ("launch to first /odom (s)", results.get("launch", {}).get("first_odom_s"), "< 3", lambda v: v < 3),
    ]
    return [
        {"target": name, "value": value, "goal": goal, "pass": None if value is None else check(value)}
        for name, value, goal, check in rows
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

    section("1. physics only: 1 TurtleBot, 1 ms, quickStep 50 iterations, no ROS", "physics_only", physics_lines)
    section(
        "2. full node, real_time_factor 0, /clock /tf odom joint_states imu scan subscribed (rates per sim s)",
        "full_node",
        full_node_lines,
    )
    section("3. real time, real_time_factor 1, 1 TurtleBot, 1 ms", "real_time", real_time_lines)
    section("4. roslaunch turtle_sim_ode turtlebot_world.launch to first /odom, fresh master", "launch", launch_lines)
    section("5. peer: the same URDF in PyBullet, same dt and wheel command", "peer", peer_lines)
    lines.append("targets")
    lines.append("   %-44s %10s  %-13s %s" % ("target", "value", "goal", "result"))
    for t in results["targets"]:
        value = "-" if t["value"] is None else "%.2f" % t["value"]
        verdict = {True: "PASS", False: "FAIL", None: "n/a"}[t["pass"]]
        lines.append("   %-44s %10s  %-13s %s" % (t["target"], value, t["goal"], verdict))
    return "\n".join(lines)


# --- main ---------------------------------------------------------------------------------------------------------
def measure(results: Dict[str, Any], key: str, title: str, run: Callable[[], Dict[str, Any]]) -> None:
    """results[key] = run(), or {"error": why} if it could not be measured."""
    print("%s ..." % title, flush=True)
    try:
        results[key] = run()
    except BenchError as error:
        results[key] = {"error": str(error)}
        print("  ERROR: %s" % error, flush=True)


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
    results["machine"]["load_average_at_end"] = os.getloadavg()[0]
    ticks, stolen = (end - start for end, start in zip(cpu_ticks(), ticks_at_start))
    results["machine"]["stolen_cpu_share"] = stolen / ticks if ticks else 0.0
    results["targets"] = targets(results)
    print()
    print(table(results))
    os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
    with open(args.json, "w") as out:
        json.dump(results, out, indent=2)
    print("\nJSON: " + args.json)
    return 1 if any("error" in value for value in results.values() if isinstance(value, dict)) else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("\ninterrupted: every process started was stopped", file=sys.stderr)
        sys.exit(130)
