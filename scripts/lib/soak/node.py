"""The soak's ROS node (scripts/soak.py), in the soak's own process: it drives the robot in a circle, listens to /odom,
/scan and /clock, and spawns and deletes models in a thread of its own, counting all of it in ``Stats``."""
from __future__ import annotations

import collections
import contextlib
import math
import os
import subprocess
import threading
import time
import traceback
from typing import Any, Deque, Dict, List, Optional, Tuple

from ros_run.process_stats import process_alive
from ros_run.master import node_pid
from ros_run.processes import ToolError

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
MODELS = os.path.join(REPO, "catkin_ws", "src", "turtle_sim_ode", "test", "models")
SIMULATOR_NODE = "/gazebo"
ROBOT = "mobile_base"
COMMAND_TOPIC = "/mobile_base/commands/velocity"
COMMAND_PERIOD_S = 0.1  # 10 Hz wall
CIRCLE = (0.25, 0.5)  # v (m/s), w (rad/s): a circle of 0.5 m radius
REVERSE_PERIOD_S = 15.0  # wall seconds between reversals (the robot then goes back round the same circle)
STARTUP_TIMEOUT_S = 90.0
CALL_TIMEOUT_S = 30.0  # a service call taking longer counts as a hung simulator
SPAWN_GRID = (6, 4)  # boxes are spawned on a grid of this many slots, from x = 4 m: away from the robot's circle


class SoakError(ToolError):
    """The soak could not be set up or run (the message says why)."""


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
        return node_pid(SIMULATOR_NODE, self.rospy.get_name())

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
