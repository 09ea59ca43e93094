"""The TurtleBot demo: drive a circle, show progress, and plot wheel odometry against ground truth."""
from __future__ import annotations

import math
import os
import sys
import threading
import time
from dataclasses import dataclass
from typing import Any, List, Mapping, Tuple

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from turtle_sim_ode.analysis.trajectory_plot import plot_paths
from turtle_sim_ode.ros.settings import SettingsError, number_param, typed_param

# Beyond this the lap takes longer than anyone waits for a demo; a typo, more likely.
MAX_DURATION_S = 3600.0


@dataclass(frozen=True)
class DemoSettings:
    linear: float  # m/s
    angular: float  # rad/s
    duration: float  # sim s
    output: str  # the plot's path


def demo_settings(params: Mapping[str, Any]) -> DemoSettings:
    """The demo's private parameters, checked (SettingsError names the bad one and its value). The lap lasts one
    turn by default, 10 s when driving straight."""
    linear = number_param(params, "linear", 0.5)
    angular = number_param(params, "angular", 0.5)
    default_duration = min(2 * math.pi / abs(angular), MAX_DURATION_S) if angular else 10.0
    duration = number_param(params, "duration", default_duration, 0.0, True, MAX_DURATION_S)
    output = typed_param(params, "output", "~/.ros/turtle_sim_ode_demo.png", str)
    if not output.strip():
        raise SettingsError("parameter ~output must name a file, got [%r]" % output)
    return DemoSettings(linear, angular, duration, os.path.expanduser(output))


class CircleDemo:
    def __init__(self, settings: DemoSettings) -> None:
        self.settings = settings
        self.odom: List[Tuple[float, float]] = []
        self.truth: List[Tuple[float, float]] = []
        self._lock = threading.Lock()
        self._cmd = rospy.Publisher("mobile_base/commands/velocity", Twist, queue_size=1)
        rospy.Subscriber("odom", Odometry, self._record, (self.odom,), queue_size=50)
        rospy.Subscriber("ground_truth/odom", Odometry, self._record, (self.truth,), queue_size=50)

    def _record(self, msg: Odometry, args) -> None:
        with self._lock:
            args[0].append((msg.pose.pose.position.x, msg.pose.pose.position.y))

    def run(self) -> str:
        rospy.wait_for_message("odom", Odometry, timeout=30)
        twist = Twist()
        twist.linear.x, twist.angular.z = self.settings.linear, self.settings.angular
        start_sim, start_wall = rospy.Time.now(), time.monotonic()
        rate = rospy.Rate(10)
        interactive = sys.stdout.isatty()
        last_line = 0.0
        while not rospy.is_shutdown():
            elapsed = (rospy.Time.now() - start_sim).to_sec()
            done = elapsed >= self.settings.duration  # the lap's last line is printed too: its summary
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
        self._cmd.publish(Twist())
        if interactive:
            sys.stdout.write("\n")
        with self._lock:
            paths = {"wheel odometry (/odom)": list(self.odom), "ground truth": list(self.truth)}
        title = "circle v=%.2f m/s, w=%.2f rad/s, %.1f s of sim time" % (
            self.settings.linear,
            self.settings.angular,
            self.settings.duration,
        )
        return plot_paths(paths, self.settings.output, title)


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
