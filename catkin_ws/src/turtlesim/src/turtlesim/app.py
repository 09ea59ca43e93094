"""turtlesim_node: the simulator with a window where there is a display, headless where there is not."""
from __future__ import annotations

import rospy

from turtlesim.ros_node import TurtlesimNode
from turtlesim.window import open_window


def main() -> int:
    rospy.init_node("turtlesim")
    try:
        node = TurtlesimNode()
    except rospy.ServiceException as error:  # a bad ~background_* param
        rospy.logfatal(str(error))
        return 1
    node.start()
    try:
        window, why_not = open_window(node.snapshot, rospy.is_shutdown, lambda: rospy.signal_shutdown("window closed"))
        if window is None:
            rospy.loginfo("turtlesim: %s: running headless, every topic and service works as with the window", why_not)
            rospy.spin()
        else:
            window.run()
    except rospy.ROSInterruptException:
        pass
    finally:
        node.stop()
    return 0
