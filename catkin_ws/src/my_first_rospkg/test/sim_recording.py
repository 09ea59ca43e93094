"""Helpers of the simulator rostests: record the ground truth while a node drives, and shape measurements."""
import math
import threading
from typing import List, NamedTuple, Sequence

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from turtle_sim_ode.analysis import path_fit


class Sample(NamedTuple):
    t: float
    x: float
    y: float
    yaw: float


def planar(odom: Odometry) -> Sample:
    p, q = odom.pose.pose.position, odom.pose.pose.orientation
    yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
    return Sample(odom.header.stamp.to_sec(), p.x, p.y, yaw)


class Recorder:
    """Ground truth samples from the first non-zero command on, and the commands the node under test sent."""

    def __init__(self, truth_topic: str = "/ground_truth/odom", command_topic: str = "/mobile_base/commands/velocity"):
        self.samples: List[Sample] = []
        self.last_command = None
        self.last_command_time = None
        self.started = False
        self._lock = threading.Lock()
        self._truth = rospy.Subscriber(truth_topic, Odometry, self._on_truth, queue_size=100)
        self._commands = rospy.Subscriber(command_topic, Twist, self._on_command, queue_size=100)

    def _on_truth(self, odom: Odometry) -> None:
        with self._lock:
            self.latest = planar(odom)
            if self.started:
                self.samples.append(self.latest)

    def _on_command(self, twist: Twist) -> None:
        with self._lock:
            moving = twist.linear.x != 0.0 or twist.angular.z != 0.0
            if moving and not self.started:
                self.started = True
                if hasattr(self, "latest"):
                    self.samples.append(self.latest)
            self.last_command = twist
            self.last_command_time = rospy.Time.now()

    def finished(self, quiet_seconds: float) -> bool:
        """True once the node sent a zero Twist as its last command, `quiet_seconds` of sim time ago."""
        with self._lock:
            if not self.started or self.last_command is None:
                return False
            stopped = self.last_command.linear.x == 0.0 and self.last_command.angular.z == 0.0
            return stopped and (rospy.Time.now() - self.last_command_time).to_sec() >= quiet_seconds

    def wait_until_finished(self, quiet_seconds: float = 1.5, wall_timeout: float = 120.0) -> List[Sample]:
        waited = 0.0
        while not self.finished(quiet_seconds):
            assert waited < wall_timeout, "the node did not end with a zero Twist within %s s (wall)" % wall_timeout
            rospy.rostime.wallsleep(0.1)
            waited += 0.1
        with self._lock:
            return list(self.samples)

    def record_for(self, sim_seconds: float, wall_timeout: float = 120.0) -> List[Sample]:
        """Samples of `sim_seconds` of sim time from the first non-zero command on."""
        waited = 0.0
        while not self.samples or self.samples[-1].t - self.samples[0].t < sim_seconds:
            assert waited < wall_timeout, "no %s s of driving within %s s (wall)" % (sim_seconds, wall_timeout)
            rospy.rostime.wallsleep(0.1)
            waited += 0.1
        with self._lock:
            return list(self.samples)


def fit_circle(samples: Sequence[Sample]):
    """Least-squares circle through the samples (turtle_sim_ode's path fit): centre x, centre y, radius."""
    (cx, cy), radius = path_fit.fit_circle([(s.x, s.y) for s in samples])
    return cx, cy, radius


def unwrapped_yaw(samples: Sequence[Sample]) -> List[float]:
    yaws = [samples[0].yaw]
    for previous, sample in zip(samples, samples[1:]):
        yaws.append(yaws[-1] + math.atan2(math.sin(sample.yaw - previous.yaw), math.cos(sample.yaw - previous.yaw)))
    return yaws


def straight_runs(samples: Sequence[Sample], min_speed: float = 0.05, window: int = 5) -> List[List[Sample]]:
    """Consecutive samples where the robot moves faster than min_speed (turning in place does not count)."""
    runs: List[List[Sample]] = []
    current: List[Sample] = []
    for i in range(window, len(samples)):
        a, b = samples[i - window], samples[i]
        moving = b.t > a.t and math.hypot(b.x - a.x, b.y - a.y) / (b.t - a.t) > min_speed
        if moving:
            current.append(b)
        elif current:
            runs.append(current)
            current = []
    if current:
        runs.append(current)
    return runs
