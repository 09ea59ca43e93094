"""The simulator's ROS interface: node `gazebo` stepping a Simulation and publishing what falls due.

Everything is stamped with the simulation's own time, which this node also publishes on /clock, so it never
waits on ROS time itself.
"""
from __future__ import annotations

import ctypes
import gc
import math
import os
import signal
import threading
import time
from typing import Dict, List, Optional, Sequence

import rospkg
import rospy
from rosgraph_msgs.msg import Clock
from rospy.impl import simtime
from tf2_msgs.msg import TFMessage
from turtle_sim_ode_msgs.srv import StepSimulation, StepSimulationRequest, StepSimulationResponse

from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.description import Pose
from turtle_sim_ode.ros.resource_paths import resource_paths
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.ros.gazebo_api import GazeboApi
from turtle_sim_ode.ros.spawn import MAX_RAYS_PER_MODEL, TopicTypes, known_topic_types, summarise
from turtle_sim_ode.ros.pacing import MAX_PACING_WAIT_S, Pacing, pacing_problem
from turtle_sim_ode.ros.performance import PerformanceMetricsPublisher
from turtle_sim_ode.ros.periodic import Periodic, TopicCheck, ros_time, sim_stamp
from turtle_sim_ode.ros.plugins import model_interfaces
from turtle_sim_ode.ros.scene_markers import SceneMarkers
from turtle_sim_ode.ros.settings import SettingsError, SimulatorSettings, settings_from_params
from turtle_sim_ode.ros.wire import OUTBOX, ClockPacker, PackedPublisher, release, stamp_parts
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

# One /gazebo/step_simulation call holds the world for at most this many steps (about a minute of wall time).
MAX_LOCKSTEP_STEPS = 1000000
# The run loop holds the world for at most this many steps that publish nothing (a few ms): services get in between.
MAX_QUIET_STEPS = 100
# Added to the count of steps to the next due time before truncating it (see SimulatorNode._step_quietly).
DUE_STEPS_ROUNDING = 1e-6


class SimulatorNode:
    """Owns the simulation, its clock and the ROS interfaces of the spawned robots."""

    def __init__(self, settings: SimulatorSettings) -> None:
        self.settings = settings
        max_update_rate = settings.real_time_factor / settings.physics.time_step
        self.sim = Simulation(settings.physics, settings.drive_overrides, max_update_rate)
        # Service calls and topic callbacks run in rospy's threads; the world changes only under this lock.
        self.lock = threading.Lock()
        self._unpaused = threading.Event()
        # Set by what changes the pacing (rate, pause, reset, a lockstep call ending, shutdown): the loop re-anchors.
        self._wake = threading.Event()
        # Held by a /gazebo/step_simulation call while it steps: the loop does not step in between, even if unpaused.
        self._lockstep = threading.Lock()
        # Set by SIGINT/SIGTERM (see main): the loop ends between steps.
        self.stop_requested = threading.Event()
        if not settings.paused:
            self._unpaused.set()
        # Published at step rates: packed and written synchronously (see ros.wire). No tf2_ros broadcaster: rospy
        # shares one publisher per topic in a process, and the broadcaster's queue would make /tf queued again.
        self._clock_pub = PackedPublisher("/clock", Clock)
        self._clock_packer = ClockPacker()
        # Advertised with the first model whose plugin publishes tf (Gazebo has no /tf publisher before).
        self._tf: Optional[PackedPublisher] = None
        self.interfaces: Dict[str, List[Periodic]] = {}
        self._interfaces: List[Periodic] = []  # all of them, in that order: the loop runs through them
        self.api: Optional[GazeboApi] = None
        self.metrics: Optional[PerformanceMetricsPublisher] = None
        self.scene_markers: Optional[SceneMarkers] = None  # what the viewer (gzclient) draws
        self._step_service: Optional[rospy.Service] = None
        # Sim time of the last step and of the next /clock message (a reset of the simulation goes below both).
        self._now = self.sim.sim_time
        self._next_clock = self._now
        # The earliest next_due of all interfaces: most steps publish nothing and need not ask each of them.
        self._next_due = math.inf
        # Whether this node's own ROS time follows its /clock (see stop_hearing_own_clock).
        self.sets_ros_time = False

    def advertise(self) -> None:
        """Offer the /gazebo services and topics: only once the world file and start-up model are in, so that
        no client (spawn_model in a launch file) can put a model in first; none with enable_ros_network false."""
        if not self.settings.enable_ros_network:
            rospy.loginfo("enable_ros_network is false: no /gazebo services and topics")
            return
        self.api = GazeboApi(
            self.sim,
            self.lock,
            self.add_interface,
            self._remove_interface,
            self._set_paused,
            lambda: self.paused,
            self.settings.model_states_rate,
            self.settings.pub_clock_frequency,
            self._on_time_change,
        )
        self.metrics = PerformanceMetricsPublisher(self.sim)
        self.scene_markers = SceneMarkers(self.sim, self.lock)
        if self.settings.step_simulation_service:
            self._step_service = rospy.Service("~step_simulation", StepSimulation, self._on_step_simulation)

    # --- models -------------------------------------------------------------------------------------------
    def add_interface(self, name: str, robot_namespace: str, check_topic: Optional[TopicCheck] = None) -> None:
        """The ROS side of a freshly spawned model's plugins (called under the lock); all or nothing: on an error
        none of its topics stays advertised. ``check_topic`` sees each topic before it is advertised (default: the
        topics in use, see TopicTypes); WorldError for a model over the ray limit. The caller removes the model on an
        error (the spawn service does; at start-up the node exits)."""
        rays = sum(laser.samples for laser in self.sim.plugins[name].lasers) if name in self.sim.plugins else 0
        if rays > MAX_RAYS_PER_MODEL:
            raise WorldError(
                "model '%s' asks for %d rays per scan (laser samples): at most %d per model"
                % (name, rays, MAX_RAYS_PER_MODEL)
            )
        if check_topic is None:
            check_topic = TopicTypes(name, known_topic_types())
        plugins = self.sim.plugins.get(name)
        publishes_tf = plugins is not None and any(broadcasts_tf(config) for config in plugins.configs)
        if self._tf is None and self.settings.publish_tf and publishes_tf:
            self._tf = PackedPublisher("/tf", TFMessage)
        # pace_from_now: the run loop re-anchors its pacing after the step (see _run_paced), not catching it up.
        interfaces = model_interfaces(
            name, self.sim, self.settings, self._tf, robot_namespace, check_topic, self._wake.set
        )
        self.interfaces[name] = interfaces
        self._interfaces = self._all_interfaces()
        for interface in interfaces:
            interface.restart(self.sim.sim_time)
        self._schedule()

    def _remove_interface(self, name: str) -> None:
        for interface in self.interfaces.pop(name, []):
            interface.close()
        self._interfaces = self._all_interfaces()
        self._schedule()
        release_memory()

    def _schedule(self) -> None:
        self._next_due = min([interface.next_due for interface in self._interfaces], default=math.inf)

    def spawn_urdf(self, name: str, urdf: str, pose) -> List[str]:
        """Spawn a model at start-up; ModelError on a bad name or model."""
        with self.lock:
            warnings = self.sim.spawn_urdf(name, urdf, pose)
            self.add_interface(name, "")
        if warnings:
            rospy.logwarn("spawn %s: %s", name, "; ".join(summarise(warnings)))
        rospy.loginfo("spawned model [%s] at x %.3f y %.3f z %.3f yaw %.3f", name, pose[0], pose[1], pose[2], pose[5])
        return warnings

    def _set_paused(self, paused: bool) -> None:
        if paused:
            self._unpaused.clear()
        else:
            self._unpaused.set()
        self._wake.set()

    def _on_time_change(self, what: str) -> None:
        """After /gazebo/set_physics_properties or a reset (called under the lock): the loop re-anchors its pacing;
        after reset_simulation every topic restarts and /clock tells the new time at once, even while paused."""
        if what == "reset_simulation":
            self._restart_time()
            self._publish_clock(self._now)
        self._wake.set()

    def stop(self) -> None:
        """Ask the loop to end (from a signal handler)."""
        self.stop_requested.set()
        self._wake.set()

    @property
    def paused(self) -> bool:
        return not self._unpaused.is_set()

    # --- stepping -----------------------------------------------------------------------------------------
    def _advance(self) -> None:
        """One physics step, then /clock and every topic that fell due (call under the lock)."""
        sim = self.sim
        if sim.sim_time < self._now:  # /gazebo/reset_simulation: time starts again
            self._restart_time()
        sim.step()
        now = self._now = sim.sim_time
        if now >= self._next_due - 1e-9:  # as Periodic.publish_due decides
            stamp = sim_stamp(now)
            for interface in self._interfaces:
                interface.publish_due(now, stamp)
            self._schedule()
        if self.api is not None:
            self.api.publish_states(now)
        if self.metrics is not None:
            self.metrics.publish_due(now)
        if now >= self._next_clock - 1e-9:
            self._next_clock = max(self._next_clock + 1.0 / self.settings.pub_clock_frequency, now)
            self._publish_clock(now)

    def _restart_time(self) -> None:
        """Sim time went back (reset_simulation): every schedule starts again from it (call under the lock)."""
        now = self._now = self.sim.sim_time
        self._next_clock = now
        for interface in self._all_interfaces():
            interface.restart(now)
        self._schedule()

    def _publish_clock(self, now: float) -> None:
        secs, nsecs = stamp_parts(now)
        self._clock_pub.publish(self._clock_packer.pack, secs, nsecs)
        if self.sets_ros_time:
            set_ros_time(secs, nsecs)

    def _step_quietly(self) -> None:
        """Step through the steps at which nothing falls due without _advance's checks (call unpaced, under the lock,
        after a reset has been seen): up to the step before the next due time, so that _advance makes the due step."""
        due = min(self._next_due, self._next_clock, self.api.states_due() if self.api is not None else math.inf)
        quiet = min(quiet_steps(self._now, due, self.sim.physics.time_step), MAX_QUIET_STEPS)
        if quiet > 0:
            step = self.sim.step
            for _ in range(quiet):
                step()
            self._now = self.sim.sim_time

    def _on_step_simulation(self, request: StepSimulationRequest) -> StepSimulationResponse:
        """Lockstep: exactly `steps` steps of a paused simulation, each publishing what it makes due."""
        if not self.paused:
            message = "the simulation is running: pause it (/gazebo/pause_physics) before stepping it"
        elif request.steps > MAX_LOCKSTEP_STEPS:
            message = "steps [%d] is more than one call may take (%d): split it" % (request.steps, MAX_LOCKSTEP_STEPS)
        else:
            # One call at a time, and the run loop waits for it even if unpaused meanwhile: the answer is the sim
            # time after exactly these steps.
            with self._lockstep:
                for _ in range(request.steps):
                    with self.lock:  # taken per step so that services and topics are served in between
                        self._advance()
                        now = self._now
                self._wake.set()
            if request.steps == 0:
                now = self.sim.sim_time
            return StepSimulationResponse(sim_stamp(now), True, "stepped %d" % request.steps)
        rospy.logwarn("step_simulation: %s", message)
        return StepSimulationResponse(sim_stamp(self.sim.sim_time), False, message)

    # --- main loop ----------------------------------------------------------------------------------------
    def run(self) -> None:
        """Step until shutdown, paced to the simulation's real-time factor (which /gazebo/set_physics_properties
        may change); while paused, only /gazebo/step_simulation steps."""
        with self.lock:
            self._publish_clock(self._now)
            self._next_clock = self._now + 1.0 / self.settings.pub_clock_frequency
        pacing = Pacing(time.monotonic(), self._now, self.sim.real_time_factor)
        OUTBOX.period_s = self.settings.write_batch_period
        OUTBOX.hold(OUTBOX.period_s > 0)  # this loop's messages written a connection at a time: see ros.wire
        try:
            self._run_paced(pacing)
        finally:
            OUTBOX.hold(False)

    def _run_paced(self, pacing: Pacing) -> None:
        while not rospy.is_shutdown() and not self.stop_requested.is_set():
            if self._wake.is_set():
                self._wake.clear()
                pacing.restart(time.monotonic(), self.sim.sim_time, self.sim.real_time_factor)
            if not self._unpaused.is_set() or self._lockstep.locked():
                OUTBOX.flush()  # nothing waits while the loop does
                self._wake.wait(MAX_PACING_WAIT_S)
                self._wake.set()  # re-anchor once running again
                continue
            rtf = self.sim.real_time_factor
            if rtf != pacing.rtf:
                pacing.restart(time.monotonic(), self.sim.sim_time, rtf)
            wait = pacing.wait(time.monotonic(), self._now)
            if wait > 0:
                OUTBOX.flush()
                self._wake.wait(min(wait, MAX_PACING_WAIT_S))
                continue
            with self.lock:
                if self._lockstep.locked():  # a step_simulation call began meanwhile: its steps alone
                    continue
                if self.sim.sim_time < self._now:  # reset_simulation: pace from the new time
                    self._restart_time()
                    pacing.restart(time.monotonic(), self._now, rtf)
                elif rtf == 0:  # unpaced, each step keeps its own wall time: sim time never runs ahead
                    self._step_quietly()
                self._advance()
            OUTBOX.flush_due()

    def _all_interfaces(self) -> List[Periodic]:
        return [interface for interfaces in self.interfaces.values() for interface in interfaces]

    def close(self) -> None:
        if self.scene_markers is not None:
            self.scene_markers.close()
        if self._step_service is not None:
            self._step_service.shutdown()
        for interface in self._all_interfaces():
            interface.close()


def quiet_steps(now: float, due: float, time_step: float) -> int:
    """How many steps from ``now`` end before the step that reaches ``due`` (0 or less: none). (due - now) / step is
    mostly a hair under a whole number (0.01 / 0.001 = 9.999...): truncated as it is, it stopped two steps short and
    cost the loop a turn with nothing due; with DUE_STEPS_ROUNDING the quiet steps still end at least 0.999999 of a
    step before ``due``, so none of them is due (publish_due's tolerance is 1e-9 s, time steps >= 1e-7 s)."""
    return int((due - now) / time_step + DUE_STEPS_ROUNDING) - 1


def broadcasts_tf(config) -> bool:  # type: ignore[no-untyped-def]
    """Whether a plugin's config asks for odometry on /tf (diff drive, Kobuki and smb_gazebo's odometry source:
    publishTf/publish_tf, skid steer: broadcastTF)."""
    return bool(getattr(config, "publish_tf", False) or getattr(config, "broadcast_tf", False))


def release_memory() -> None:
    """Hand freed heap back to the system after a model is deleted: glibc keeps the memory of a large model's many
    small objects (ODE ray geoms) otherwise, ~300 MB for 800,000 rays."""
    gc.collect()
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):  # not glibc
        pass


def stop_hearing_own_clock() -> bool:
    """With /use_sim_time set, rospy subscribes every node to /clock, this one too: flat out, deserialising its own
    /clock took about a sixth of its CPU. Drop that subscriber; the node sets its ROS time as it publishes /clock
    (what the subscriber did). True if it was subscribed."""
    subscriber = getattr(simtime, "_clock_sub", None)
    if subscriber is None:
        return False
    release(subscriber)
    simtime._clock_sub = None
    return True


def set_ros_time(secs: int, nsecs: int) -> None:
    """What rospy's /clock subscriber does (rospy.rostime._set_rostime) without its Condition.notifyAll, which
    warns of its deprecation on every call since Python 3.10: ~6 us a /clock message."""
    rospy.rostime._rostime_current = ros_time(secs, nsecs)
    with rospy.rostime._rostime_cond:
        rospy.rostime._rostime_cond.notify_all()


def resolve_world(world_name: str) -> str:
    """A world file given as a path, or by file name in this package's worlds/ (as Gazebo's worlds/x.world)."""
    if os.path.isfile(world_name):
        return world_name
    packaged = os.path.join(rospkg.RosPack().get_path("turtle_sim_ode"), "worlds", os.path.basename(world_name))
    if os.path.isfile(packaged):
        return packaged
    raise ModelError("world file '%s' not found (nor %s)" % (world_name, packaged))


def load_world(node: SimulatorNode, world_name: str) -> None:
    path = resolve_world(world_name)
    with open(path) as world_file:
        world = parse_sdf_world(world_file.read())
    time_step = world.physics.apply(node.sim.physics.params).time_step
    problem = pacing_problem(time_step, node.settings.real_time_factor / time_step, node.settings.pub_clock_frequency)
    if problem:
        raise ModelError("real_time_factor [%g] with the world's %s" % (node.settings.real_time_factor, problem))
    with node.lock:
        warnings = node.sim.load_world(world)
        # The node's real_time_factor parameter (the launch argument) wins over the world's pacing.
        node.sim.max_update_rate = node.settings.real_time_factor / node.sim.physics.time_step
        for name in list(node.sim.models):  # the included and plugin-made models' plugins too
            node.add_interface(name, "")
        node._restart_time()  # a world's <state> may start sim time elsewhere than 0
    publish_user_camera(world.user_camera)
    if warnings:  # one line, at most MAX_SHOWN_WARNINGS of them
        rospy.logwarn("world %s: %s", path, "; ".join(summarise(warnings)))
    rospy.loginfo("loaded world [%s] from %s: models %s", world.name, path, list(node.sim.models))


def publish_user_camera(pose: Optional[Pose]) -> None:
    """~user_camera_pose: the world's <gui><camera><pose> [x, y, z, roll, pitch, yaw] for the viewer's first view;
    unset where the world has none (the viewer then looks from Gazebo's default)."""
    if pose is not None:
        rospy.set_param("~user_camera_pose", list(pose.xyz) + list(pose.rpy))
    elif rospy.has_param("~user_camera_pose"):
        rospy.delete_param("~user_camera_pose")


def main(overrides: Optional[Dict[str, object]] = None, notes: Sequence[str] = (), claim_sim_time: bool = False) -> int:
    """Run node `gazebo`. ``overrides``: private parameters that win over the parameter server's (gazebo_ros's
    gzserver command line); ``notes``: warnings to log once the node is up (options without effect here);
    ``claim_sim_time``: set /use_sim_time true unless it is set, as gazebo_ros's API plugin does (launch files
    of this package set it themselves)."""
    # rospy's own SIGINT handler shuts rospy down inside whatever the main thread is doing; in the middle of a
    # publish it can deadlock on the publisher's lock (seen flat out). Here a signal only asks the loop to stop.
    rospy.init_node("gazebo", disable_signals=True)
    for note in notes:
        rospy.logwarn(note)
    if claim_sim_time and not rospy.has_param("/use_sim_time"):
        rospy.set_param("/use_sim_time", True)
    try:
        settings = settings_from_params(dict(rospy.get_param("~", {}), **(overrides or {})))
    except SettingsError as error:
        rospy.logfatal(str(error))
        return 1
    node = SimulatorNode(settings)
    node.sim.resources = resource_paths()
    rospy.loginfo(
        "model and mesh files are read from under %s; Gazebo model path %s",
        node.sim.resources.allowed_roots(),
        node.sim.resources.model_paths,
    )
    node.sets_ros_time = stop_hearing_own_clock()
    if settings.world_name:
        try:
            load_world(node, settings.world_name)
        except (ModelError, WorldError, OSError) as error:
            rospy.logfatal("cannot load world [%s]: %s" % (settings.world_name, error))
            return 1
    else:
        publish_user_camera(None)  # no world: an earlier server's first view is not this one's
    if settings.spawn_model_name:
        urdf = rospy.get_param(settings.spawn_robot_description, None)
        if not isinstance(urdf, str):
            rospy.logfatal(
                "parameter %s holds no URDF to spawn model [%s]"
                % (rospy.resolve_name(settings.spawn_robot_description), settings.spawn_model_name)
            )
            return 1
        try:
            node.spawn_urdf(settings.spawn_model_name, urdf, settings.spawn_pose)
        except (ModelError, WorldError, ValueError) as error:
            rospy.logfatal("cannot spawn model [%s]: %s" % (settings.spawn_model_name, error))
            return 1
    node.advertise()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: node.stop())
    try:
        node.run()
    except rospy.ROSInterruptException:
        pass
    finally:
        node.close()
        rospy.signal_shutdown("simulator stopped")
    return 0
