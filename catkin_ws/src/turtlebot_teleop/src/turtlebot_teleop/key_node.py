"""Node turtlebot_teleop_key: the keyboard on the terminal -> geometry_msgs/Twist on ~cmd_vel, ten times a second."""
from __future__ import annotations

import os
import select
import sys
import termios
import tty

from turtlebot_teleop.keyboard import KeyboardTeleop, speeds_line, USAGE

KEY_WAIT_S = 0.1


def read_key(fd: int, saved: list) -> str:
    """One key within KEY_WAIT_S ('' if none), the terminal raw only while waiting, as upstream reads it."""
    tty.setraw(fd)
    try:
        ready, _, _ = select.select([fd], [], [], KEY_WAIT_S)
        return os.read(fd, 1).decode("latin-1") if ready else ""
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)


def main() -> int:
    import rospy
    from geometry_msgs.msg import Twist

    # Ctrl-C arrives as a byte while the terminal is raw; between reads it is a KeyboardInterrupt, handled below.
    rospy.init_node("turtlebot_teleop", disable_signals=True)
    fd = sys.stdin.fileno()
    if not os.isatty(fd):
        rospy.logfatal("turtlebot_teleop_key reads keys from a terminal, and its input is not one")
        return 1
    saved = termios.tcgetattr(fd)
    pub = rospy.Publisher("~cmd_vel", Twist, queue_size=5)
    teleop = KeyboardTeleop()
    print(USAGE)
    print(speeds_line(teleop.speed, teleop.turn), flush=True)
    try:
        while not rospy.is_shutdown():
            lines = teleop.step(read_key(fd, saved))
            for line in lines:
                print(line, flush=True)
            if teleop.quit:
                break
            twist = Twist()
            twist.linear.x, twist.angular.z = teleop.twist()
            pub.publish(twist)
    except KeyboardInterrupt:
        pass
    finally:
        pub.publish(Twist())  # the robot must not keep the last speed
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        rospy.signal_shutdown("teleop ended")
    return 0
