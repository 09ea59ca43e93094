"""Node teleop_twist_keyboard: keys on the terminal -> geometry_msgs/Twist on cmd_vel.

As upstream's 1.0.0: each key publishes once, from a thread that also repeats the last twist at ~repeat_rate
(when > 0); with ~key_timeout > 0, a moving robot is stopped when no key came for that long; the last message is
a zero twist.
"""
from __future__ import annotations

import math
import os
import select
import sys
import termios
import threading
import tty
from typing import Optional

import rospy
from geometry_msgs.msg import Twist

from teleop_twist_keyboard.keys import USAGE, KeyTeleop, speeds_line

# How often the wait for a subscriber says so (s).
WAITING_NOTICE_S = 2.5


class TwistRepeater(threading.Thread):
    """Publishes the newest twist when it changes, and again every 1/rate s if rate > 0."""

    def __init__(self, publisher: rospy.Publisher, rate: float) -> None:
        super().__init__(daemon=True)
        self._publisher = publisher
        self._period = 1.0 / rate if rate > 0.0 else None
        self._twist = Twist()
        self._changed = threading.Condition()
        self._pending = False  # a twist came while this thread was publishing: not to be missed
        self._done = False
        self.start()

    def update(self, twist: Twist) -> None:
        with self._changed:
            self._twist, self._pending = twist, True
            self._changed.notify()

    def stop(self) -> None:
        """Publish a zero twist last, then end."""
        with self._changed:
            self._done, self._twist, self._pending = True, Twist(), True
            self._changed.notify()
        self.join()

    def run(self) -> None:
        while True:
            with self._changed:
                self._changed.wait_for(lambda: self._pending, self._period)
                twist, done, self._pending = self._twist, self._done, False
            self._publisher.publish(twist)
            if done:
                return


def read_key(fd: int, saved: list, timeout: Optional[float]) -> str:
    """One key, or '' when ``timeout`` s pass without one (None: wait for a key); raw mode only while waiting."""
    tty.setraw(fd, termios.TCSANOW)  # not TCSAFLUSH (setraw's default): keys typed between reads are kept
    try:
        ready, _, _ = select.select([fd], [], [], timeout)
        return os.read(fd, 1).decode("latin-1") if ready else ""
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)


def read_params() -> dict:
    """~speed, ~turn, ~repeat_rate, ~key_timeout with upstream's defaults; rospy.ROSException naming a bad one."""
    params = {}
    for name, default, least in (
        ("speed", 0.5, None),
        ("turn", 1.0, None),
        ("repeat_rate", 0.0, 0.0),
        ("key_timeout", 0.0, 0.0),
    ):
        value = rospy.get_param("~" + name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise rospy.ROSException("~%s [%r] is not a finite number" % (name, value))
        if least is not None and value < least:
            raise rospy.ROSException("~%s [%r] is negative (0 turns it off)" % (name, value))
        params[name] = float(value)
    return params


def wait_for_subscriber(publisher: rospy.Publisher) -> None:
    waited = 0.0
    while publisher.get_num_connections() == 0 and not rospy.is_shutdown():
        rospy.rostime.wallsleep(0.1)  # rospy has no event for a new subscriber
        waited += 0.1
        if waited >= WAITING_NOTICE_S:
            print("Waiting for a subscriber on %s" % publisher.resolved_name, flush=True)
            waited = 0.0


def main() -> int:
    # Ctrl-C comes as a key while the terminal is raw; between reads it is a KeyboardInterrupt, handled below.
    rospy.init_node("teleop_twist_keyboard", disable_signals=True)
    fd = sys.stdin.fileno()
    if not os.isatty(fd):
        rospy.logfatal("teleop_twist_keyboard reads keys from a terminal, and its input is not one")
        return 1
    try:
        params = read_params()
    except rospy.ROSException as error:
        rospy.logfatal("teleop_twist_keyboard: %s", error)
        return 1
    saved = termios.tcgetattr(fd)
    publisher = rospy.Publisher("cmd_vel", Twist, queue_size=1)
    repeater = TwistRepeater(publisher, params["repeat_rate"])
    teleop = KeyTeleop(params["speed"], params["turn"])
    key_timeout = params["key_timeout"] or None
    try:
        wait_for_subscriber(publisher)
        repeater.update(to_twist(teleop))  # a zero twist first, as upstream's
        print(USAGE)
        print(speeds_line(teleop.speed, teleop.turn), flush=True)
        while not teleop.quit and not rospy.is_shutdown():
            publish, lines = teleop.press(read_key(fd, saved, key_timeout))
            for line in lines:
                print(line, flush=True)
            if publish:
                repeater.update(to_twist(teleop))
    except KeyboardInterrupt:
        pass
    finally:
        repeater.stop()
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        rospy.signal_shutdown("teleop ended")
    return 0


def to_twist(teleop: KeyTeleop) -> Twist:
    twist = Twist()
    (twist.linear.x, twist.linear.y, twist.linear.z), twist.angular.z = teleop.twist()
    return twist
