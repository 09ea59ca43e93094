"""The viewer (gazebo_ros's gzclient, `gazebo`, gui:=true): rviz on a configuration written at start-up (see
viewer_config) showing the world as Gazebo's client does, and beside it a small control window with what Gazebo's
client shows under its view: sim time, real time, real-time factor, whether the world is paused; play/pause, step
and the two resets.

The control window follows rqt's pattern: ROS callbacks only write a WorldClock (under a lock), a Qt timer reads it
into the widgets; service calls run in threads of their own, never in Qt's."""
from __future__ import annotations

import os
import subprocess
import tempfile
import threading
import time
from collections import deque
from typing import Callable, Deque, List, Optional, Sequence, Set, Tuple

import rosgraph
import rospy
import yaml
from gazebo_msgs.srv import GetPhysicsProperties
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty
from turtle_sim_ode_msgs.srv import StepSimulation

from turtle_sim_ode.ros.viewer_config import FIXED_FRAME, WINDOW, rviz_config

# Real-time factor over this much wall time, as Gazebo's client averages it.
RTF_WINDOW_S = 1.0
# How often the pause state is asked for (gazebo_msgs/GetPhysicsProperties).
STATE_POLL_S = 0.5
UI_PERIOD_MS = 100
SERVICE_TIMEOUT_S = 2.0
STATE_FAILURES = 3
CONTROL_WINDOW_WIDTH = 250
WORLD_WAIT_S = 15.0
ADOPT_PERIOD_S = 0.1  # tf from `world` to the robots' trees, at rviz's pace
TIE_FRESH_S = 1.0  # s of sim time: another viewer's tie to `world` this recent is kept up by it


class WorldClock:
    """Sim time, real time (wall time while the world runs, since the viewer started) and the real-time factor,
    from /clock readings with the wall time they arrived at."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.sim_time = 0.0
        self.real_time = 0.0
        self.paused: Optional[bool] = None  # None until the server answered
        self.can_step = False
        self._samples: Deque[Tuple[float, float]] = deque()  # (wall, sim)

    def on_clock(self, sim: float, wall: float) -> None:
        with self.lock:
            if self._samples:
                last_wall, last_sim = self._samples[-1]
                if sim < last_sim:  # reset_simulation: time starts again
                    self._samples.clear()
                elif sim > last_sim:
                    self.real_time += wall - last_wall
            self.sim_time = sim
            self._samples.append((wall, sim))
            while len(self._samples) > 2 and self._samples[0][0] < wall - RTF_WINDOW_S:
                self._samples.popleft()

    def real_time_factor(self, wall: float) -> float:
        """Sim seconds per wall second over the last RTF_WINDOW_S (0 when /clock stood still that long)."""
        with self.lock:
            if len(self._samples) < 2 or wall - self._samples[-1][0] > RTF_WINDOW_S:
                return 0.0
            (wall0, sim0), (wall1, sim1) = self._samples[0], self._samples[-1]
            return (sim1 - sim0) / (wall1 - wall0) if wall1 > wall0 else 0.0


def format_time(seconds: float) -> str:
    """Gazebo's client style: 00 00:01:02.345 (days hours:minutes:seconds)."""
    days, rest = divmod(max(seconds, 0.0), 86400)
    hours, rest = divmod(rest, 3600)
    minutes, rest = divmod(rest, 60)
    return "%02d %02d:%02d:%06.3f" % (days, hours, minutes, rest)


class ServerLink:
    """The simulator's services the control window uses, and the /clock and pause state it reads."""

    def __init__(self, clock: WorldClock) -> None:
        self.clock = clock
        self._clock_sub = rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=10)
        self._stop = threading.Event()
        threading.Thread(target=self._poll_state, name="viewer_state", daemon=True).start()

    def close(self) -> None:
        self._stop.set()
        self._clock_sub.unregister()

    def _on_clock(self, message: Clock) -> None:
        self.clock.on_clock(message.clock.to_sec(), time.monotonic())

    def _poll_state(self) -> None:
        failures = 0
        while not self._stop.is_set() and not rospy.is_shutdown():
            paused = self.clock.paused
            try:
                rospy.wait_for_service("/gazebo/get_physics_properties", SERVICE_TIMEOUT_S)
                paused = rospy.ServiceProxy("/gazebo/get_physics_properties", GetPhysicsProperties)().pause
                failures = 0
            except (rospy.ROSException, rospy.ServiceException):
                failures += 1  # a busy server may miss one answer: "no server" only when it keeps silent
                if failures >= STATE_FAILURES:
                    paused = None
            try:
                can_step = bool(rosgraph.Master(rospy.get_name()).lookupService("/gazebo/step_simulation"))
            except (rosgraph.MasterException, OSError):  # not offered (gzserver's default), or no master
                can_step = False
            with self.clock.lock:
                self.clock.paused, self.clock.can_step = paused, can_step
            self._stop.wait(STATE_POLL_S)

    def call(self, service: str, done: Callable[[str], None]) -> None:
        """Call one of the world-control services in a thread; ``done`` gets "" or what went wrong."""

        def run() -> None:
            try:
                rospy.wait_for_service(service, SERVICE_TIMEOUT_S)
                if service.endswith("step_simulation"):
                    answer = rospy.ServiceProxy(service, StepSimulation)(1)
                    done("" if answer.success else answer.status_message)
                else:
                    rospy.ServiceProxy(service, Empty)()
                    done("")
            except (rospy.ROSException, rospy.ServiceException) as error:
                done("%s: %s" % (service, error))

        threading.Thread(target=run, daemon=True).start()


class FrameAdopter:
    """Ties each tf tree without the `world` frame (a robot's `odom`, or `map` under amcl) to `world` at identity,
    as Gazebo's robots start with odometry at the world's origin, so that the robots' laser scans and point clouds
    show among the scene's models; a frame that gets a parent other than `world` is left alone from then on."""

    def __init__(self) -> None:
        import tf2_ros
        from tf2_msgs.msg import TFMessage

        self._buffer = tf2_ros.Buffer()
        self._listener = tf2_ros.TransformListener(self._buffer)
        self._publisher = rospy.Publisher("/tf", TFMessage, queue_size=1)
        self._message = TFMessage
        self._parented: Set[str] = set()  # frames others gave a parent: never tied to `world` by the viewer
        self._last_stamp = rospy.Time(0)
        self._timer = rospy.Timer(rospy.Duration(ADOPT_PERIOD_S), self._adopt)

    def close(self) -> None:
        self._timer.shutdown()
        self._listener.unregister()

    def roots(self) -> List[str]:
        """The frames to tie to `world`: parents in others' transforms that are nobody else's child."""
        frames = yaml.safe_load(self._buffer.all_frames_as_yaml()) or {}
        # Ties to `world` are this viewer's or another viewer's (any may close): they do not count as parents; one
        # another viewer keeps up to date is left to it (two would send the same stamps).
        others = {frame: about for frame, about in frames.items() if about.get("parent") != FIXED_FRAME}
        self._parented.update(others)
        recent = rospy.Time.now().to_sec() - TIE_FRESH_S
        tied_by_others = {
            frame
            for frame, about in frames.items()
            if about.get("parent") == FIXED_FRAME
            and about.get("broadcaster") != rospy.get_name()
            and float(about.get("most_recent_transform", 0.0)) >= recent
        }
        parents = {about.get("parent") for about in others.values()}
        return sorted(frame for frame in parents - self._parented - tied_by_others if frame and frame != FIXED_FRAME)

    def _adopt(self, _event) -> None:  # type: ignore[no-untyped-def]
        from geometry_msgs.msg import TransformStamped

        now = rospy.Time.now()
        if now <= self._last_stamp:  # sim time stood still (paused, or /clock slower than the timer): sent already
            return
        self._last_stamp = now
        transforms = []
        for root in self.roots():
            transform = TransformStamped()
            transform.header.stamp = now
            transform.header.frame_id = FIXED_FRAME
            transform.child_frame_id = root
            transform.transform.rotation.w = 1.0
            transforms.append(transform)
        if transforms:
            try:
                self._publisher.publish(self._message(transforms))
            except rospy.ROSException:  # shutting down: the topic closed under the timer
                pass


def control_window(link: ServerLink):  # type: ignore[no-untyped-def]
    """The control window (Qt widgets; imported here so that the node without a display needs no Qt)."""
    from python_qt_binding.QtCore import QTimer
    from python_qt_binding.QtWidgets import QFormLayout, QGridLayout, QLabel, QPushButton, QVBoxLayout, QWidget

    window = QWidget()
    window.setWindowTitle("Gazebo: world")
    window.setGeometry(WINDOW["X"] + WINDOW["Width"] + 10, WINDOW["Y"], CONTROL_WINDOW_WIDTH, 240)
    layout = QVBoxLayout(window)
    form = QFormLayout()
    labels = {name: QLabel("-") for name in ("Sim time", "Real time", "Real time factor", "State")}
    for name, label in labels.items():
        form.addRow(name + ":", label)
    layout.addLayout(form)
    buttons = QGridLayout()
    play = QPushButton("Pause")
    step = QPushButton("Step")
    reset_models = QPushButton("Reset models")
    reset_world = QPushButton("Reset world")
    for index, button in enumerate((play, step, reset_models, reset_world)):
        buttons.addWidget(button, index // 2, index % 2)
    layout.addLayout(buttons)
    message = QLabel("")
    message.setWordWrap(True)
    layout.addWidget(message)
    problems: Deque[str] = deque(maxlen=1)  # written by service threads, shown by the timer

    def report(problem: str) -> None:
        problems.append(problem)

    def toggle() -> None:
        paused = link.clock.paused
        link.call("/gazebo/unpause_physics" if paused else "/gazebo/pause_physics", report)

    play.clicked.connect(toggle)
    step.clicked.connect(lambda: link.call("/gazebo/step_simulation", report))
    # Gazebo's Edit menu: "Reset Model Poses" is gazebo_ros's reset_world, "Reset World" its reset_simulation.
    reset_models.clicked.connect(lambda: link.call("/gazebo/reset_world", report))
    reset_world.clicked.connect(lambda: link.call("/gazebo/reset_simulation", report))

    def refresh() -> None:
        clock = link.clock
        with clock.lock:
            sim, real, paused, can_step = clock.sim_time, clock.real_time, clock.paused, clock.can_step
        labels["Sim time"].setText(format_time(sim))
        labels["Real time"].setText(format_time(real))
        labels["Real time factor"].setText("%.2f" % clock.real_time_factor(time.monotonic()))
        labels["State"].setText({None: "no server", True: "paused", False: "running"}[paused])
        play.setText("Play" if paused else "Pause")
        play.setEnabled(paused is not None)
        step.setEnabled(bool(paused) and can_step)
        step.setToolTip("" if can_step else "the server offers no /gazebo/step_simulation")
        if problems:
            message.setText(problems.pop())

    timer = QTimer(window)
    timer.timeout.connect(refresh)
    timer.start(UI_PERIOD_MS)
    refresh()
    return window


def write_config(user_camera: Optional[Sequence[float]]) -> str:
    """The generated rviz configuration in a temporary file (the caller removes it)."""
    handle, path = tempfile.mkstemp(prefix="gazebo_viewer_", suffix=".rviz")
    with os.fdopen(handle, "w") as config:
        yaml.safe_dump(rviz_config(user_camera), config, default_flow_style=False, sort_keys=False)
    return path


def user_camera_pose() -> Optional[Sequence[float]]:
    """The world's first view, as the simulator published it (None: Gazebo's default). As gzclient waits for its
    server, this waits (at most WORLD_WAIT_S) for the simulator's services, which it offers once the world is in."""
    try:
        rospy.wait_for_service("/gazebo/get_physics_properties", WORLD_WAIT_S)
    except rospy.ROSException:
        rospy.logwarn(
            "no simulator answers yet (/gazebo/get_physics_properties): the viewer starts on the default view"
        )
    pose = rospy.get_param("/gazebo/user_camera_pose", None)
    if isinstance(pose, list) and len(pose) == 6 and all(isinstance(v, (int, float)) for v in pose):
        return [float(v) for v in pose]
    return None


def run_viewer(rviz_config_path: Optional[str] = None, rviz_args: Sequence[str] = ()) -> int:
    """Run the viewer until rviz or the control window is closed, or ROS shuts down (rospy is initialised)."""
    from python_qt_binding.QtCore import QTimer
    from python_qt_binding.QtWidgets import QApplication

    generated = None
    if rviz_config_path is None:
        generated = rviz_config_path = write_config(user_camera_pose())
    rviz_name = "__name:=%s_rviz_%d" % (rospy.get_name().lstrip("/").replace("/", "_"), os.getpid())
    rviz = subprocess.Popen(["rviz", "-d", rviz_config_path, rviz_name] + list(rviz_args), stdin=subprocess.DEVNULL)
    app = QApplication([])
    link = ServerLink(WorldClock())
    adopter = FrameAdopter()
    window = control_window(link)
    window.show()
    watch = QTimer()  # rviz closed or ROS shut down: the viewer ends (and lets Python see signals meanwhile)
    watch.timeout.connect(lambda: app.quit() if rviz.poll() is not None or rospy.is_shutdown() else None)
    watch.start(200)
    try:
        app.exec_()
    finally:
        link.close()
        adopter.close()
        if rviz.poll() is None:
            rviz.terminate()
            try:
                rviz.wait(10)
            except subprocess.TimeoutExpired:
                rviz.kill()
                rviz.wait()
        if generated is not None:
            os.remove(generated)
    return 0
