"""The sections of scripts/bench_rqt.py: rqt_plot with injected data (faster than real time), rqt_plot on
turtlesim's pose in real time, rqt_console at 1,000 messages a second. Each runs the tool's widget in this
process (Qt's offscreen platform unless DISPLAY is used), where this process is the ROS node."""
from __future__ import annotations

import os
import statistics
import time
from typing import Any, Callable, Dict, List

from ros_run.process_stats import rss_bytes
from ros_run.processes import Processes, ToolError

PLOT_RATE_HZ = 62.5  # turtlesim's pose rate
PLOT_FIELDS = ("x", "y", "theta")
FRAME_PERIOD_S = 0.04  # rqt_plot's redraw interval
PROBE_PERIOD_MS = 10  # the event-loop probe of the console section
IDLE_PROBE_S = 5.0  # the probe's run before the flood, for the machine's own latency


def summary_ms(samples_s: List[float]) -> Dict[str, float]:
    """median, 95th percentile and maximum of durations in seconds, as milliseconds."""
    if not samples_s:
        return {"median_ms": float("nan"), "p95_ms": float("nan"), "max_ms": float("nan"), "count": 0}
    ordered = sorted(samples_s)
    return {
        "median_ms": 1e3 * statistics.median(ordered),
        "p95_ms": 1e3 * ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))],
        "max_ms": 1e3 * ordered[-1],
        "count": len(ordered),
    }


def mib(value: int) -> float:
    return value / 1048576.0


def pump_events(app, seconds: float) -> None:
    """Runs the Qt event loop for `seconds` (the tools run it themselves; here the benchmark owns the loop)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        app.processEvents()
        time.sleep(0.001)


def timed_frame(app, widget) -> float:
    """One redraw as the widget's timer does it, and the paint it asks for, which the event loop then does."""
    start = time.perf_counter()
    widget.update_plot()
    app.processEvents()
    return time.perf_counter() - start


def make_plot(app, argv: List[str], topic_types: Callable[[], Dict[str, str]]):
    from rqt_plot.plot_widget import PlotWidget

    widget = PlotWidget(argv, topic_types=topic_types)
    widget._redraw_timer.stop()  # the benchmark draws the frames itself, timed
    widget.resize(800, 600)
    widget.show()
    app.processEvents()
    return widget


class FramePair:
    """The plot that runs the whole time and a twin on the same data that is cleared every minute, drawn one after
    the other each frame: the twin's frames at the end are what a fresh plot costs at that moment, so the
    comparison with the long-running plot holds however the machine's load drifts (other work on the 2 cores)."""

    def __init__(self, app, argv: List[str], topic_types: Callable[[], Dict[str, str]], minutes: float) -> None:
        self.app = app
        self.plots = (make_plot(app, argv, topic_types), make_plot(app, argv, topic_types))
        self.minutes = minutes
        self.frames: Dict[str, List[float]] = {"first_minute": [], "last_minute": [], "fresh_last_minute": []}
        self._cleared_minute = 0
        self._count = 0

    def frame(self, elapsed_s: float) -> None:
        """Draws both at `elapsed_s` into the run (data time or wall time)."""
        long_running, fresh = self.plots
        if int(elapsed_s // 60) > self._cleared_minute:
            self._cleared_minute = int(elapsed_s // 60)
            fresh.clear()
        self._count += 1
        order = self.plots if self._count % 2 else self.plots[::-1]  # neither always gets the events queued first
        durations = {id(plot): timed_frame(self.app, plot) for plot in order}
        if elapsed_s < 60.0:
            self.frames["first_minute"].append(durations[id(long_running)])
        if elapsed_s >= self.minutes * 60.0 - 60.0:  # both, on a run shorter than two minutes
            self.frames["last_minute"].append(durations[id(long_running)])
            self.frames["fresh_last_minute"].append(durations[id(fresh)])

    def summary(self) -> Dict[str, Any]:
        return {"frame_" + when: summary_ms(samples) for when, samples in self.frames.items()}

    def close(self) -> None:
        for plot in self.plots:
            plot.shutdown()
            plot.close()


def plot_injected(app, minutes: float, buffer_size: int) -> Dict[str, Any]:
    """`minutes` of three fields at 62.5 Hz pushed into the data windows as fast as frames can be drawn, one frame
    per 40 ms of data time: redraw time in the first and the last minute and of a fresh twin at the end, memory."""
    topic = "/injected/pose"
    argv = ["--buffer-size", str(buffer_size), "%s/x:y:theta" % topic]
    pair = FramePair(app, argv, lambda: {topic: "geometry_msgs/Pose2D"}, minutes)
    curves = ["%s/%s" % (topic, field) for field in PLOT_FIELDS]
    ticks = int(minutes * 60 * PLOT_RATE_HZ)
    ticks_per_frame = PLOT_RATE_HZ * FRAME_PERIOD_S
    rss_start, wall_start, next_frame = rss_bytes(os.getpid()), time.monotonic(), 0.0
    for tick in range(ticks):
        data_time = tick / PLOT_RATE_HZ
        for plot in pair.plots:
            for index, curve in enumerate(curves):
                plot.window.push(curve, data_time, (index + 1) * ((tick % 500) / 50.0))
        if tick + 1 >= next_frame:
            next_frame += ticks_per_frame
            pair.frame(data_time)
    result = {
        "data_minutes": minutes,
        "fields": len(curves),
        "rate_hz": PLOT_RATE_HZ,
        "buffer_size": buffer_size,
        "points_per_curve_at_end": len(pair.plots[0].window.series[curves[0]]),
        "rss_mib_start": mib(rss_start),
        "rss_mib_end": mib(rss_bytes(os.getpid())),
        "wall_s": time.monotonic() - wall_start,
    }
    result.update(pair.summary())
    pair.close()
    return result


def plot_real_time(app, minutes: float, processes: Processes, ros_env: Dict[str, str]) -> Dict[str, Any]:
    """turtlesim_node (headless) driven in a circle, `rqt_plot /turtle1/pose/x:y:theta` in this process for
    `minutes` of wall time, frames every 40 ms: redraw time in the first and the last minute and of a fresh twin
    at the end, points received against 3 x 62.5 Hz, memory, and how late the frames came."""
    env = dict(os.environ, **ros_env)
    env.pop("DISPLAY", None)
    processes.start(["rosrun", "turtlesim", "turtlesim_node"], env, "turtlesim.log")
    twist = "{linear: {x: 1.5}, angular: {z: 1.0}}"
    processes.start(["rostopic", "pub", "-r", "10", "/turtle1/cmd_vel", "geometry_msgs/Twist", twist], env, "cmd.log")
    from rqt_plot.ros_plot_data import published_topic_types

    deadline = time.monotonic() + 30.0
    while "/turtle1/pose" not in published_topic_types():
        if time.monotonic() > deadline:
            raise ToolError("turtlesim never published /turtle1/pose:\n" + processes.log_tail("turtlesim.log"))
        time.sleep(0.1)
    pair = FramePair(app, ["/turtle1/pose/x:y:theta"], published_topic_types, minutes)
    long_running = pair.plots[0]
    if len(long_running.canvas.curve_names()) != 3:
        raise ToolError("the plot has curves %s" % long_running.canvas.curve_names())
    seconds = minutes * 60.0
    lateness: List[float] = []
    start = time.monotonic()
    drained_at_start = long_running.window.points_drained
    rss_start = rss_bytes(os.getpid())
    next_frame = start
    while True:
        now = time.monotonic()
        if now - start >= seconds:
            break
        if now < next_frame:
            app.processEvents()
            time.sleep(min(0.002, next_frame - now))
            continue
        lateness.append(now - next_frame)
        next_frame += FRAME_PERIOD_S
        pair.frame(now - start)
    elapsed = time.monotonic() - start
    result = {
        "wall_minutes": elapsed / 60.0,
        "points_received": long_running.window.points_drained - drained_at_start,
        "points_expected": int(3 * PLOT_RATE_HZ * elapsed),
        "frame_lateness": summary_ms(lateness),
        "rss_mib_start": mib(rss_start),
        "rss_mib_end": mib(rss_bytes(os.getpid())),
    }
    result.update(pair.summary())
    pair.close()
    return result


def console_flood(app, rate: float, seconds: float, processes: Processes, ros_env: Dict[str, str]) -> Dict[str, Any]:
    """rqt_console in this process while a publisher sends `rate` Log messages a second on /rosout_agg for
    `seconds`: how late a 10 ms timer fires (the UI's event-loop latency), how long each batch insert takes, and
    whether every message arrived and the table ends with the newest ones."""
    from python_qt_binding.QtCore import QTimer

    from rqt_console.console_widget import ConsoleWidget
    from rqt_console.filters import MessageFilter

    widget = ConsoleWidget([])
    widget.resize(1000, 600)
    widget.show()
    widget.exclude_panel.add_filter(MessageFilter).filter.set_text("^never seen$", regex=True)  # a regex a row
    widget.proxy.filters_changed()
    inserts: List[float] = []
    original_drain = widget.drain

    def timed_drain() -> int:
        begin = time.perf_counter()
        count = original_drain()
        if count:
            inserts.append(time.perf_counter() - begin)
        return count

    widget._timer.timeout.disconnect()
    widget._timer.timeout.connect(timed_drain)
    idle_lateness: List[float] = []
    lateness = idle_lateness  # the machine's own noise first: the same probe before the flood
    expected_at = [time.monotonic() + PROBE_PERIOD_MS / 1e3]

    def probe() -> None:
        now = time.monotonic()
        lateness.append(max(0.0, now - expected_at[0]))
        expected_at[0] = now + PROBE_PERIOD_MS / 1e3

    probe_timer = QTimer()
    probe_timer.timeout.connect(probe)
    probe_timer.start(PROBE_PERIOD_MS)
    pump_events(app, IDLE_PROBE_S)
    lateness = []
    env = dict(os.environ, **ros_env)
    here = os.path.dirname(os.path.abspath(__file__))
    publisher = processes.start(
        [
            "/usr/bin/python3",
            os.path.join(here, "rqt_log_publisher.py"),
            "--rate",
            str(rate),
            "--seconds",
            str(seconds),
        ],
        env,
        "log_publisher.log",
    )
    rss_start = rss_bytes(os.getpid())
    deadline = time.monotonic() + seconds + 60.0
    while publisher.poll() is None:
        app.processEvents()
        time.sleep(0.001)
        if time.monotonic() > deadline:
            raise ToolError("the log publisher did not finish:\n" + processes.log_tail("log_publisher.log"))
    ended = time.monotonic()
    lines = [line for line in processes.log_tail("log_publisher.log").splitlines() if line.startswith("sent ")]
    if not lines:
        raise ToolError("the log publisher failed:\n" + processes.log_tail("log_publisher.log"))
    sent = int(lines[-1].split()[1])
    newest = "bench message %d" % (sent - 1)
    while time.monotonic() < ended + 10.0:
        record = widget.model.record(0)
        if record is not None and record.message == newest:
            break
        app.processEvents()
        time.sleep(0.005)
    probe_timer.stop()
    record = widget.model.record(0)
    result = {
        "rate_per_s": rate,
        "seconds": seconds,
        "sent": sent,
        "received": widget.queue.received,
        "kept": widget.model.rowCount(),
        "limit": widget.model.limit,
        "newest_on_top": record is not None and record.message == newest,
        "event_loop_latency": summary_ms(lateness),
        "event_loop_latency_idle": summary_ms(idle_lateness),
        "batch_insert": summary_ms(inserts),
        "rss_mib_start": mib(rss_start),
        "rss_mib_end": mib(rss_bytes(os.getpid())),
    }
    widget.shutdown()
    widget.close()
    return result
