"""mimic: one turtle copies another's motion, input/pose in, output/cmd_vel out (twin of src/mimic.cpp)."""
from __future__ import annotations

import rospy
from geometry_msgs.msg import Twist

from turtlesim.msg import Pose


class Mimic:
    def __init__(self):
        self._pub = rospy.Publisher("output/cmd_vel", Twist, queue_size=1)
        self._sub = rospy.Subscriber("input/pose", Pose, self._on_pose, queue_size=1)

    def _on_pose(self, pose: Pose) -> None:
        twist = Twist()
        twist.linear.x = pose.linear_velocity
        twist.angular.z = pose.angular_velocity
        self._pub.publish(twist)


def main() -> int:
    rospy.init_node("turtle_mimic")
    Mimic()
    rospy.spin()
    return 0
