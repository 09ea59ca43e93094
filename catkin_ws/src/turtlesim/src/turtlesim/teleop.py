"""turtle_teleop_key: arrow keys on the terminal -> turtle1/cmd_vel. The key decoding has no ROS in it."""
from __future__ import annotations

import os
import sys
import termios
from typing import Optional, Tuple

ARROWS = {b"A": "up", b"B": "down", b"C": "right", b"D": "left"}
USAGE = "Reading from keyboard\n---------------------------\nUse arrow keys to move the turtle. 'q' to quit."


class KeyDecoder:
    """Bytes from a terminal -> key names: the arrows' escape sequences (ESC [ A or ESC O A ...) and 'q'."""

    def __init__(self):
        self._pending = b""

    def feed(self, byte: bytes) -> Optional[str]:
        if self._pending:
            self._pending += byte
            if len(self._pending) == 2:
                if byte in (b"[", b"O"):
                    return None
                self._pending = b""
                return None
            self._pending = b""
            return ARROWS.get(byte)
        if byte == b"\x1b":
            self._pending = byte
            return None
        return "quit" if byte == b"q" else None


def velocities(key: str, scale_linear: float, scale_angular: float) -> Tuple[float, float]:
    """(linear.x, angular.z) for an arrow key."""
    return {
        "up": (scale_linear, 0.0),
        "down": (-scale_linear, 0.0),
        "left": (0.0, scale_angular),
        "right": (0.0, -scale_angular),
    }[key]


class RawTerminal:
    """Keys without Enter and without echo while inside the `with`; the terminal's settings restored after."""

    def __init__(self, fd: int):
        self._fd = fd
        self._saved = None

    def __enter__(self) -> "RawTerminal":
        self._saved = termios.tcgetattr(self._fd)
        raw = termios.tcgetattr(self._fd)
        raw[3] &= ~(termios.ICANON | termios.ECHO)
        raw[6][termios.VMIN] = 1
        raw[6][termios.VTIME] = 0
        termios.tcsetattr(self._fd, termios.TCSANOW, raw)
        return self

    def __exit__(self, *_exc) -> None:
        termios.tcsetattr(self._fd, termios.TCSANOW, self._saved)


def main() -> int:
    import rospy
    from geometry_msgs.msg import Twist

    # No rospy signal handler: Ctrl-C must interrupt the blocking read, so the terminal is restored on the way out.
    rospy.init_node("teleop_turtle", disable_signals=True)
    scales = []
    for name in ("scale_linear", "scale_angular"):
        value = rospy.get_param(name, 2.0)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            rospy.logfatal("Parameter [%s] has the wrong type: [%r]", rospy.resolve_name(name), value)
            return 1
        scales.append(float(value))
    fd = sys.stdin.fileno()
    if not os.isatty(fd):
        rospy.logfatal("turtle_teleop_key reads the arrow keys from a terminal, and its input is not one")
        return 1
    pub = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
    print(USAGE, flush=True)
    decoder = KeyDecoder()
    try:
        with RawTerminal(fd):
            while True:
                byte = os.read(fd, 1)
                if not byte:  # end of input
                    break
                key = decoder.feed(byte)
                if key == "quit":
                    break
                if key is not None:
                    twist = Twist()
                    twist.linear.x, twist.angular.z = velocities(key, *scales)
                    pub.publish(twist)
    except KeyboardInterrupt:
        pass
    finally:
        rospy.signal_shutdown("teleop ended")
    return 0
