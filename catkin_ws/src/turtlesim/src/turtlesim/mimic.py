"""mimic: one turtle copies another's motion, input/pose in, output/cmd_vel out (twin of src/mimic.cpp)."""
from __future__ import annotations

import rospy
from geometry_msgs.msg import Twist

from turtlesim.msg import Pose


class Mimic:
    def __init__(self):
        # roscpp's NodeHandle("input") remaps the namespace itself; rospy remaps whole names only, so resolve the
        # namespaces first: <remap from="input" to="turtlesim1/turtle1"/> then works as with the C++ mimic.
        self._pub = rospy.Publisher(rospy.resolve_name("output") + "/cmd_vel", Twist, queue_size=1)
        self._sub = rospy.Subscriber(rospy.resolve_name("input") + "/pose", Pose, self._on_pose, queue_size=1)

    def _on_pose(self, pose: Pose) -> None:
        twist = Twist()
        twist.linear.x = pose.linear_velocity
        twist.angular.z = pose.angular_velocity
        self._pub.publish(twist)


def main() -> int:
    try:
        rospy.init_node("turtle_mimic")
        Mimic()
        rospy.spin()
    except rospy.ROSInterruptException:
        pass
    return 0
