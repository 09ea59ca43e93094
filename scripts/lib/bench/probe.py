"""The benchmark's ROS nodes (scripts/bench_sim.py), each run in a forked child on one master (``Probe``): the task that
spawns robots and times RTF, /clock intervals and message rates, and the one that waits for the first /odom."""
from __future__ import annotations

import math
import multiprocessing
import os
import signal
import statistics
import threading
import time
import traceback
from typing import Any, Callable, Dict, List, Optional, Sequence, Set, Tuple

from bench.camera import CAMERA_TOPICS, room_sdf, with_camera
from bench.plan import CALLER_ID, CIRCLE, STARTUP_TIMEOUT_S, URDF_PATH, BenchError
from ros_run.process_stats import cpu_seconds
from ros_run.master import Master, node_pid

from turtle_sim_ode.analysis.waiting import wait_for
from ros_run.processes import SHUTDOWN_TIMEOUT_S, ToolError
from ros_run.tcpros_reader import Reader, TopicStream, clock_stamp

ROBOT_SPACING_M = 3.0  # between spawn points: 1 m circles never meet
ROBOTS_PER_ROW = 5
READ_BATCH_S = 0.002  # the probe drains the simulator's topics every 2 ms (see tcpros_reader.Reader)


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
    except ToolError as error:
        connection.send(("error", str(error)))
    except Exception:
        connection.send(("error", traceback.format_exc(limit=3)))


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


def measure_rtf_task(
    send: Callable[[Any], None],
    robots: int,
    warmup_s: float,
    window_s: float,
    room: bool = False,
    camera: Optional[Tuple[int, int, float]] = None,
    watch_camera: bool = False,
    watch_scene: bool = False,
    turns: int = 0,
) -> None:
    """Spawn ``robots`` TurtleBots driving circles, subscribe to all they publish, and send the RTF, /clock
    intervals and message rates over a window of ``window_s`` wall seconds after ``warmup_s``. With ``room`` the
    first robot drives in bench_camera's furnished room; with ``camera`` (width, height, rate Hz) it carries
    bench_camera's RGB-D camera; ``watch_camera``: its image, depth image and cloud are subscribed too; ``watch_scene``:
    the viewer's /gazebo/scene_markers too (read whole, as rviz reads it). ``turns`` > 0: then also the node's RTF
    against physics only in turns (``in_turns``)."""
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
    bulk_topics: Dict[str, str] = {}  # the camera's: read as they come, by a reader of their own
    robot_topic_sets = []
    if room:
        rospy.wait_for_service("/gazebo/spawn_sdf_model", STARTUP_TIMEOUT_S)
        answer = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)("room", room_sdf(), "", Pose(), "world")
        if not answer.success:
            raise BenchError("spawning the room failed: %s" % answer.status_message)
    for index in range(robots):
        name = "robot_%d" % index
        position = Point(ROBOT_SPACING_M * (index % ROBOTS_PER_ROW), ROBOT_SPACING_M * (index // ROBOTS_PER_ROW), 0.0)
        if room and index == 0:  # inside the room, on bench_camera's circle
            position = Point(0.0, -1.0, 0.0)
        description = with_camera(urdf, camera) if camera is not None and index == 0 else urdf
        answer = spawn(name, description, name, Pose(position, Quaternion(0, 0, 0, 1)), "world")
        if not answer.success:
            raise BenchError("spawning %s failed: %s" % (name, answer.status_message))
        command = rospy.Publisher("/%s/%s/commands/velocity" % (name, name), Twist, queue_size=1, latch=True)
        command.publish(Twist(linear=Point(CIRCLE[0], 0, 0), angular=Point(0, 0, CIRCLE[1])))
        robot_topic_sets.append(robot_topics(name))
        topics.update({topic: kind for kind, topic in robot_topic_sets[-1].items()})
        if watch_camera and index == 0:
            bulk_topics = {"/%s/%s" % (name, topic): kind for kind, topic in CAMERA_TOPICS.items()}
            topics.update(bulk_topics)
    if watch_scene:
        bulk_topics["/gazebo/scene_markers"] = "scene"
        topics["/gazebo/scene_markers"] = "scene"

    # Raw TCPROS readers, not rospy subscribers: every message is still sent and read, but this process spends
    # about a microsecond on each instead of a rospy callback's tens, which would load the machine it measures.
    def published() -> Set[str]:
        return {topic for topic, _ in rospy.get_published_topics()}

    if not wait_for(lambda: set(topics) <= published(), STARTUP_TIMEOUT_S):
        raise BenchError("not published: %s" % sorted(set(topics) - published()))

    def on_clock(wall: float, payload: bytes) -> None:
        clock.append((wall, clock_stamp(payload)))

    # /clock on a reader of its own that wakes for each message, sent without delay (Nagle's algorithm would batch
    # them), for its arrival times; the rest drained every READ_BATCH_S.
    master_uri, caller_id = rosgraph.get_master_uri(), rospy.get_name()
    clock_stream = TopicStream(master_uri, caller_id, "/clock", on_clock, tcp_nodelay=True)
    batched = [TopicStream(master_uri, caller_id, t) for t in topics if t != "/clock" and t not in bulk_topics]
    readers = [Reader([clock_stream]), Reader(batched, READ_BATCH_S)]
    # megabytes a message: read at once, as a roscpp or rospy subscriber's thread would
    bulk = [TopicStream(master_uri, caller_id, topic, bulk=True) for topic in bulk_topics]
    if bulk:
        readers.append(Reader(bulk))
    streams = batched + bulk + [clock_stream]

    def counts() -> Dict[str, int]:
        return {stream.topic: stream.count for stream in streams}

    try:
        if not wait_for(lambda: all(counts().values()), STARTUP_TIMEOUT_S):
            silent = sorted(topic for topic, count in counts().items() if not count)
            raise BenchError("no message on %s" % silent)
        simulator = node_pid("/gazebo", CALLER_ID)
        time.sleep(warmup_s)
        start_counts, start, start_cpu = counts(), time.monotonic(), cpu_seconds(simulator)
        time.sleep(window_s)
        end_counts, end, end_cpu = counts(), time.monotonic(), cpu_seconds(simulator)
        last = {stream.topic: stream.last for stream in streams}
        turned = in_turns(clock, turns, window_s / turns, warmup_s / turns) if turns else None
    finally:
        for reader in readers:
            reader.close()
    errors = [reader.error for reader in readers if reader.error is not None]
    if errors:
        raise BenchError("reading the topics failed: %s" % errors[0])
    window = clock_window(clock, start, end)
    wall_s, sim_s = spans(window)
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
            **({"in_turns": turned} if turned else {}),
        }
    )


def clock_window(clock: List[Tuple[float, float]], start: float, end: float) -> List[Tuple[float, float]]:
    """The (wall, sim) /clock arrivals from wall time ``start`` to ``end``; BenchError with fewer than two."""
    window = [(wall, sim) for wall, sim in list(clock) if start <= wall <= end]
    if len(window) < 2:
        raise BenchError("only %d /clock messages in %.1f wall seconds" % (len(window), end - start))
    return window


def spans(window: List[Tuple[float, float]]) -> Tuple[float, float]:
    """Wall and sim seconds from the first to the last /clock arrival of ``window``."""
    return window[-1][0] - window[0][0], window[-1][1] - window[0][1]


def in_turns(clock: List[Tuple[float, float]], turns: int, window_s: float, warmup_s: float) -> Dict[str, Any]:
    """The node's RTF and physics only's in turns: ``turns`` times, the node paused (/gazebo/pause_physics), this
    process steps a TurtleBot of its own (bench.physics, Simulation.step, no ROS) for ``window_s`` wall seconds; then
    the node runs again and its RTF is read from /clock over ``window_s`` after ``warmup_s``. Both see the machine of
    the same minute; each turn's ratio is the node's RTF over the physics-only RTF just before it."""
    import rospy
    from std_srvs.srv import Empty

    from bench.physics import SETTLE_STEPS, sustained_steps_per_second, turtlebot_simulation

    rospy.wait_for_service("/gazebo/pause_physics", STARTUP_TIMEOUT_S)
    pause = rospy.ServiceProxy("/gazebo/pause_physics", Empty)
    unpause = rospy.ServiceProxy("/gazebo/unpause_physics", Empty)
    sim = turtlebot_simulation()
    for _ in range(SETTLE_STEPS):
        sim.step()
    physics_rtfs, node_rtfs = [], []
    for _ in range(turns):
        pause()
        physics_rtfs.append(sustained_steps_per_second(sim.step, window_s) * sim.physics.time_step)
        unpause()
        time.sleep(warmup_s)
        start = time.monotonic()
        time.sleep(window_s)
        wall_s, sim_s = spans(clock_window(clock, start, time.monotonic()))
        node_rtfs.append(sim_s / wall_s)
    ratios = [node / physics for node, physics in zip(node_rtfs, physics_rtfs)]
    return {
        "window_s": window_s,
        "physics_rtf": physics_rtfs,
        "node_rtf": node_rtfs,
        "ratios": ratios,
        "median_ratio": statistics.median(ratios),
    }


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
