"""The rospy interface classes of the exercise nodes (twins of src/nodes/*.cpp); scripts/ only call main_*()."""
import math

import rospy
import tf2_ros
from beginner_tutorials.params import ParamError, read_param, read_rate
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Float64

from my_first_rospkg.motion import (
    Bouncer,
    CircleTrajectory,
    SpiralTrajectory,
    SquareController,
    SquareParams,
    TimedTrajectory,
    Velocity,
)
from my_first_rospkg.ros_helpers import (
    publish_stop,
    read_non_empty,
    read_positive,
    read_positive_int,
    to_pose2d,
    to_twist,
    velocity_publisher,
    wait_for_robot,
)
from my_first_rospkg.scan import find_scan_minimum


def _sleep(rate: rospy.Rate) -> None:
    try:
        rate.sleep()
    except rospy.ROSTimeMovedBackwardsException:
        pass  # the simulator was reset: carry on with the new clock


def main_spin() -> None:
    """Turn in place: angular.z = ~angular_speed at ~rate Hz."""
    rospy.init_node("my_first_rospkg_node")
    rate_hz = read_rate("~rate", 10.0)
    angular_speed = float(read_param("~angular_speed", 0.5, (int, float)))
    publisher = velocity_publisher()
    rospy.on_shutdown(lambda: publisher.publish(Twist()))
    twist = to_twist(Velocity(0.0, angular_speed))
    rospy.loginfo("Turning in place at [%g] rad/s", angular_speed)
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        publisher.publish(twist)
        _sleep(rate)


class TrajectoryDriver:
    """Plays a TimedTrajectory on the velocity topic at a fixed rate of ROS time (sim time under /use_sim_time)."""

    def __init__(self, trajectory: TimedTrajectory, rate_hz: float, name: str):
        self._trajectory, self._rate_hz, self._name = trajectory, rate_hz, name
        self._publisher = velocity_publisher()
        rospy.on_shutdown(lambda: self._publisher.publish(Twist()))

    def run(self) -> bool:
        """Wait for the robot, drive the trajectory to its end and stop the robot. False on shutdown."""
        if not wait_for_robot(self._publisher):
            return False
        start = rospy.Time.now()
        rospy.loginfo("%s: driving for [%.2f] s", self._name, self._trajectory.duration())
        rate = rospy.Rate(self._rate_hz)
        while not rospy.is_shutdown():
            elapsed = (rospy.Time.now() - start).to_sec()
            if elapsed >= self._trajectory.duration():
                publish_stop(self._publisher)
                rospy.loginfo("%s: done, robot stopped", self._name)
                return True
            self._publisher.publish(to_twist(self._trajectory.velocity_at(elapsed)))
            _sleep(rate)
        return False


def main_circle() -> None:
    rospy.init_node("circle")
    trajectory = CircleTrajectory(
        read_positive("~radius", 1.0), read_positive("~speed", 0.3), read_positive("~laps", 1.0)
    )
    TrajectoryDriver(trajectory, read_rate("~rate", 10.0), "circle").run()


def main_spiral() -> None:
    rospy.init_node("spiral")
    initial_radius = read_positive("~initial_radius", 0.2)
    growth_rate = read_positive("~growth_rate", 0.04)
    angular_speed = read_positive("~angular_speed", 0.5)
    max_radius = read_positive("~max_radius", 1.0)
    rate_hz = read_rate("~rate", 10.0)
    if max_radius <= initial_radius:
        raise ParamError(
            "Parameter [%s] must be > ~initial_radius [%g], got [%g]"
            % (rospy.resolve_name("~max_radius"), initial_radius, max_radius)
        )
    TrajectoryDriver(SpiralTrajectory(initial_radius, growth_rate, angular_speed, max_radius), rate_hz, "spiral").run()


class BounceNode:
    """Drives forwards and backwards inside the limits: one command per odometry message."""

    def __init__(self, speed: float, limit_x: float, limit_y: float):
        self._bouncer = Bouncer(speed, limit_x, limit_y)
        self._publisher = velocity_publisher()
        self._subscriber = rospy.Subscriber("odom", Odometry, self._on_odometry, queue_size=1)
        rospy.on_shutdown(self._stop)

    def _on_odometry(self, odometry: Odometry) -> None:
        pose = to_pose2d(odometry)
        before = self._bouncer.direction
        velocity = self._bouncer.update(pose)
        if self._bouncer.direction != before:
            rospy.loginfo("Reversing at x [%.3f], y [%.3f]", pose.x, pose.y)
        self._publisher.publish(to_twist(velocity))

    def _stop(self) -> None:
        self._subscriber.unregister()
        self._publisher.publish(Twist())


def main_bounce() -> None:
    rospy.init_node("bounce")
    BounceNode(read_positive("~speed", 0.5), read_positive("~limit_x", 2.0), read_positive("~limit_y", 2.0))
    rospy.spin()


class SquareNode:
    """Drives a square closed-loop on odometry, then stops the robot."""

    def __init__(self, params: SquareParams):
        self._controller = SquareController(params)
        self._publisher = velocity_publisher()
        self._subscriber = rospy.Subscriber("odom", Odometry, self._on_odometry, queue_size=1)
        rospy.on_shutdown(lambda: self._publisher.publish(Twist()))

    def done(self) -> bool:
        return self._controller.done()

    def _on_odometry(self, odometry: Odometry) -> None:
        if self._controller.done():
            return
        pose = to_pose2d(odometry)
        before = self._controller.state
        velocity = self._controller.update(pose, odometry.header.stamp.to_sec())
        if self._controller.state != before:
            rospy.loginfo(
                "Square: %s at x [%.3f], y [%.3f], yaw [%.3f] (sides done [%d])",
                self._controller.state.value,
                pose.x,
                pose.y,
                pose.yaw,
                self._controller.sides_done,
            )
        self._publisher.publish(to_twist(velocity))

    def stop(self) -> None:
        self._subscriber.unregister()
        publish_stop(self._publisher)


def main_square() -> None:
    rospy.init_node("square")
    defaults = SquareParams()
    params = SquareParams(**{name: read_positive("~" + name, getattr(defaults, name)) for name in SquareParams._fields})
    node = SquareNode(params)
    while not rospy.is_shutdown() and not node.done():
        rospy.rostime.wallsleep(0.01)
    if node.done():
        node.stop()
        rospy.loginfo("Square: done, robot stopped")


class ScanMonitor:
    """Logs the closest return of each scan on `topic`."""

    def __init__(self, topic: str, queue_size: int):
        self._subscriber = rospy.Subscriber(topic, LaserScan, self._on_scan, queue_size=queue_size)
        rospy.loginfo("Monitoring scans on [%s]", self._subscriber.resolved_name)

    def _on_scan(self, scan: LaserScan) -> None:
        minimum = find_scan_minimum(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max)
        if not minimum.found:
            rospy.logwarn_throttle(5.0, "No valid beam in a scan of [%d] ranges" % len(scan.ranges))
        elif minimum.too_close:
            rospy.loginfo("Smallest distance: closer than [%g] m at angle [%g] rad", minimum.distance, minimum.angle)
        else:
            rospy.loginfo("Smallest distance: [%g] m at angle [%g] rad", minimum.distance, minimum.angle)


def main_scan_monitor() -> None:
    rospy.init_node("scan_monitor")
    ScanMonitor(read_non_empty("~topic", "scan"), read_positive_int("~queue_size", 1))
    rospy.spin()


class TfListenerNode:
    """Looks up fixed_frame -> robot_frame with tf2 and publishes the distance from the first pose found."""

    def __init__(self, fixed_frame: str, robot_frame: str, rate_hz: float):
        self._fixed_frame, self._robot_frame = fixed_frame, robot_frame
        self._buffer = tf2_ros.Buffer()
        self._listener = tf2_ros.TransformListener(self._buffer)
        self._publisher = rospy.Publisher("distance_from_start", Float64, queue_size=10)
        self._start = None
        self._timer = rospy.Timer(rospy.Duration(1.0 / rate_hz), self._on_timer)

    def _on_timer(self, _event) -> None:
        try:
            transform = self._buffer.lookup_transform(self._fixed_frame, self._robot_frame, rospy.Time(0))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException) as error:
            rospy.logwarn_throttle(
                5.0, "No transform [%s] -> [%s] yet: %s" % (self._fixed_frame, self._robot_frame, error)
            )
            return
        t = transform.transform.translation
        if self._start is None:
            self._start = (t.x, t.y)
            rospy.loginfo("Start point in [%s]: x [%.3f], y [%.3f]", self._fixed_frame, t.x, t.y)
        distance = math.hypot(t.x - self._start[0], t.y - self._start[1])
        self._publisher.publish(Float64(distance))
        rospy.loginfo_throttle(1.0, "Distance from start: [%.3f] m" % distance)


def main_tf_listener() -> None:
    rospy.init_node("tf_listener")
    TfListenerNode(
        read_non_empty("~fixed_frame", "odom"),
        read_non_empty("~robot_frame", "base_footprint"),
        read_rate("~rate", 10.0),
    )
    rospy.spin()
