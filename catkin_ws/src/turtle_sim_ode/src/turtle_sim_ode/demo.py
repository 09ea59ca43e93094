"""The TurtleBot demo: drive a circle, show progress, and plot wheel odometry against ground truth."""
from __future__ import annotations

import math
import os
import sys
import threading
import time
from typing import List, Tuple

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from .trajectory_plot import plot_paths


class CircleDemo:
    def __init__(self) -> None:
        self.linear = float(rospy.get_param("~linear", 0.5))
        self.angular = float(rospy.get_param("~angular", 0.5))
        self.duration = float(rospy.get_param("~duration", 2 * math.pi / abs(self.angular) if self.angular else 10.0))
        self.output = os.path.expanduser(rospy.get_param("~output", "~/.ros/turtle_sim_ode_demo.png"))
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
        twist.linear.x, twist.angular.z = self.linear, self.angular
        start_sim, start_wall = rospy.Time.now(), time.monotonic()
        rate = rospy.Rate(10)
        interactive = sys.stdout.isatty()
        last_line = 0.0
        while not rospy.is_shutdown():
            elapsed = (rospy.Time.now() - start_sim).to_sec()
            if elapsed >= self.duration:
                break
            self._cmd.publish(twist)
            wall = time.monotonic() - start_wall
            if interactive or wall - last_line >= 1.0:
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
        title = "circle v=%.2f m/s, w=%.2f rad/s, %.1f s of sim time" % (self.linear, self.angular, self.duration)
        return plot_paths(paths, self.output, title)


def main() -> int:
    rospy.init_node("circle_demo")
    try:
        path = CircleDemo().run()
    except (rospy.ROSInterruptException, rospy.ROSException) as error:
        rospy.logerr("demo stopped: %s", error)
        return 1
    print("trajectory plot written to %s" % path)
    return 0
