"""The TurtleBot demo: drive a circle, show progress, and plot wheel odometry against ground truth."""
from __future__ import annotations

import math
import os
import sys
import threading
import time
from dataclasses import dataclass
from typing import Any, List, Mapping, Optional, Tuple

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from turtle_sim_ode.analysis.trajectory_plot import plot_paths
from turtle_sim_ode.ros.settings import SettingsError, number_param, typed_param

# Beyond this the lap takes longer than anyone waits for a demo; a typo, more likely.
MAX_DURATION_S = 3600.0
# A lap measured by the heading ends by this many nominal laps (2 pi / angular) of sim time at the latest.
LAP_TIME_LIMIT = 3.0


@dataclass(frozen=True)
class DemoSettings:
    linear: float  # m/s
    angular: float  # rad/s
    duration: float  # sim s: how long to drive, or (one_lap) the longest a lap may take
    output: str  # the plot's path
    one_lap: bool = False  # drive until the robot's own heading (ground truth) has turned a full circle


def demo_settings(params: Mapping[str, Any]) -> DemoSettings:
    """The demo's private parameters, checked (SettingsError names the bad one and its value). Without ~duration
    the demo drives one lap: until the robot has turned a full circle (the commanded rate is reached only after
    the wheels spin up and the turn runs a little slower than commanded, so the lap takes longer than 2 pi /
    angular), at most LAP_TIME_LIMIT nominal laps; 10 s when driving straight."""
    linear = number_param(params, "linear", 0.5)
    angular = number_param(params, "angular", 0.5)
    one_lap = "duration" not in params and angular != 0
    default_duration = min(LAP_TIME_LIMIT * 2 * math.pi / abs(angular), MAX_DURATION_S) if angular else 10.0
    duration = number_param(params, "duration", default_duration, 0.0, True, MAX_DURATION_S)
    output = typed_param(params, "output", "~/.ros/turtle_sim_ode_demo.png", str)
    if not output.strip():
        raise SettingsError("parameter ~output must name a file, got [%r]" % output)
    return DemoSettings(linear, angular, duration, os.path.expanduser(output), one_lap)


class CircleDemo:
    def __init__(self, settings: DemoSettings) -> None:
        self.settings = settings
        self.odom: List[Tuple[float, float]] = []
        self.truth: List[Tuple[float, float]] = []
        self._lock = threading.Lock()
        self._heading = HeadingTurn()
        self._cmd = rospy.Publisher("mobile_base/commands/velocity", Twist, queue_size=1)
        rospy.Subscriber("odom", Odometry, self._record, (self.odom,), queue_size=50)
        rospy.Subscriber("ground_truth/odom", Odometry, self._record, (self.truth,), queue_size=50)

    def _record(self, msg: Odometry, args) -> None:
        with self._lock:
            args[0].append((msg.pose.pose.position.x, msg.pose.pose.position.y))
            if args[0] is self.truth:
                q = msg.pose.pose.orientation
                self._heading.add(math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z)))

    def run(self) -> str:
        rospy.wait_for_message("odom", Odometry, timeout=30)
        twist = Twist()
        twist.linear.x, twist.angular.z = self.settings.linear, self.settings.angular
        start_sim, start_wall = rospy.Time.now(), time.monotonic()
        rate = rospy.Rate(10)
        interactive = sys.stdout.isatty()
        last_line = elapsed = turned = 0.0
        lap_done = False
        while not rospy.is_shutdown():
            elapsed = (rospy.Time.now() - start_sim).to_sec()
            with self._lock:
                turned = abs(self._heading.turned)
            lap_done = self.settings.one_lap and turned >= 2 * math.pi
            done = lap_done or elapsed >= self.settings.duration  # the lap's last line is printed too: its summary
            if not done:
                self._cmd.publish(twist)
            wall = time.monotonic() - start_wall
            if interactive or done or wall - last_line >= 1.0:
                last_line = wall
                with self._lock:
                    x, y = self.truth[-1] if self.truth else (math.nan, math.nan)
                line = "sim %6.2f s | real-time factor %5.1f | x %6.3f y %6.3f m" % (
                    elapsed,
                    elapsed / wall if wall > 0 else 0.0,
                    x,
                    y,
                )
                sys.stdout.write(("\r" + line) if interactive else (line + "\n"))
                sys.stdout.flush()
            if done:
                break
            try:
                rate.sleep()
            except rospy.ROSTimeMovedBackwardsException:
                # /gazebo/reset_simulation sent sim time back to 0: start the lap again.
                start_sim, start_wall = rospy.Time.now(), time.monotonic()
                with self._lock:
                    self._heading = HeadingTurn()
        self._cmd.publish(Twist())
        if interactive:
            sys.stdout.write("\n")
        with self._lock:
            paths = {"wheel odometry (/odom)": list(self.odom), "ground truth": list(self.truth)}
        title = "%s: %.0f° turned in %.1f s of sim time\nv=%.2f m/s, w=%.2f rad/s" % (
            "one lap" if lap_done else "circle",
            math.degrees(turned),
            elapsed,
            self.settings.linear,
            self.settings.angular,
        )
        return plot_paths(paths, self.settings.output, title)


class HeadingTurn:
    """How far a heading has turned since its first sample (rad, signed, over many turns): each step between two
    samples is taken as the shorter way round."""

    def __init__(self) -> None:
        self.turned = 0.0
        self._last: Optional[float] = None

    def add(self, heading: float) -> None:
        if self._last is not None:
            self.turned += math.remainder(heading - self._last, 2 * math.pi)
        self._last = heading


def main() -> int:
    rospy.init_node("circle_demo")
    try:
        settings = demo_settings(rospy.get_param("~", {}))
    except SettingsError as error:
        rospy.logfatal(str(error))
        return 1
    try:
        path = CircleDemo(settings).run()
    except (rospy.ROSInterruptException, rospy.ROSException) as error:
        rospy.logerr("demo stopped: %s", error)
        return 1
    print("trajectory plot written to %s" % path)
    return 0
