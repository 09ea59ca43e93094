"""Node joint_state_publisher_gui: joint_state_publisher's node with this window on top (as upstream's script)."""
from __future__ import annotations

import signal
import sys
import threading


def main() -> int:
    import rospy
    from python_qt_binding.QtWidgets import QApplication

    import joint_state_publisher
    from joint_state_publisher_gui.window import JointStatePublisherGui

    rospy.init_node("joint_state_publisher_gui")
    app = QApplication(sys.argv)
    app.setApplicationDisplayName("Joint State Publisher")
    try:
        jsp = joint_state_publisher.JointStatePublisher()
    except RuntimeError as error:  # no robot_description
        rospy.logfatal("joint_state_publisher_gui: %s", error)
        return 1
    window = JointStatePublisherGui("Node: " + rospy.get_name(), jsp, joint_state_publisher.get_param("num_rows", 0))
    window.show()
    window.sliderUpdateTrigger.emit()
    # joint_state_publisher's publishing loop; it ends with ROS, and must not keep the process once Qt has ended
    threading.Thread(target=jsp.loop, daemon=True).start()
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # Ctrl-C ends the window at once, as upstream's does
    code = app.exec_()
    rospy.signal_shutdown("window closed")
    return code
