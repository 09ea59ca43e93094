"""rospy glue shared by the exercise nodes (twin of ros_helpers.h): checked parameters and conversions."""
import math

import rospy
from beginner_tutorials.params import ParamError, read_param
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from my_first_rospkg.motion import Pose2D, Velocity, yaw_from_quaternion

VELOCITY_TOPIC = "mobile_base/commands/velocity"


def read_positive(name: str, default: float) -> float:
    """A float parameter, a ParamError unless it is a finite number > 0."""
    value = read_param(name, default, (int, float))
    if not (math.isfinite(value) and value > 0.0):
        raise ParamError("Parameter [%s] must be a finite number > 0, got [%g]" % (rospy.resolve_name(name), value))
    return float(value)


def read_positive_int(name: str, default: int) -> int:
    """An int parameter, a ParamError unless it is >= 1."""
    value = read_param(name, default, int)
    if value < 1:
        raise ParamError("Parameter [%s] must be an integer >= 1, got [%d]" % (rospy.resolve_name(name), value))
    return value


def read_non_empty(name: str, default: str) -> str:
    """A string parameter, a ParamError when it is empty."""
    value = read_param(name, default, str)
    if not value:
        raise ParamError("Parameter [%s] must not be empty, got [%s]" % (rospy.resolve_name(name), value))
    return value


def to_twist(velocity: Velocity) -> Twist:
    twist = Twist()
    twist.linear.x = velocity.linear
    twist.angular.z = velocity.angular
    return twist


def to_pose2d(odometry: Odometry) -> Pose2D:
    p, q = odometry.pose.pose.position, odometry.pose.pose.orientation
    return Pose2D(p.x, p.y, yaw_from_quaternion(q.x, q.y, q.z, q.w))


def velocity_publisher() -> rospy.Publisher:
    return rospy.Publisher(VELOCITY_TOPIC, Twist, queue_size=1)


def publish_stop(publisher: rospy.Publisher) -> None:
    """Publish a zero Twist and give the publisher's thread a moment to send it before the node exits."""
    publisher.publish(Twist())
    rospy.rostime.wallsleep(0.2)  # rospy sends from a queue thread and offers no flush


def wait_for_robot(publisher: rospy.Publisher) -> bool:
    """Wait (wall time) until a subscriber is connected and sim time runs; False on shutdown."""
    while not rospy.is_shutdown() and (publisher.get_num_connections() == 0 or rospy.Time.now().is_zero()):
        rospy.rostime.wallsleep(0.05)
    return not rospy.is_shutdown()
