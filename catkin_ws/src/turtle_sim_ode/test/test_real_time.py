#!/usr/bin/env python3
"""rostest node: over ~wall_seconds of wall time, /clock advances ~real_time_factor times as much, within
~tolerance (relative)."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock


class RealTimeFactor(unittest.TestCase):
    def test_clock_keeps_pace(self):
        samples = []
        first = threading.Event()

        def on_clock(msg):
            samples.append((time.monotonic(), msg.clock.to_sec()))
            first.set()

        rospy.Subscriber("/clock", Clock, on_clock, queue_size=100)
        self.assertTrue(first.wait(30.0), "no /clock within 30 s")
        time.sleep(1.0)  # let start-up transients pass: measuring wall time needs the wall clock
        wall0, sim0 = samples[-1]
        time.sleep(rospy.get_param("~wall_seconds"))
        wall1, sim1 = samples[-1]
        achieved = (sim1 - sim0) / (wall1 - wall0)
        wanted = rospy.get_param("~real_time_factor")
        self.assertAlmostEqual(
            achieved,
            wanted,
            delta=wanted * rospy.get_param("~tolerance"),
            msg="real-time factor %.4f, wanted %.2f" % (achieved, wanted),
        )


if __name__ == "__main__":
    rospy.init_node("test_real_time", disable_signals=True)
    rostest.rosrun("turtle_sim_ode", "real_time_factor", RealTimeFactor, sys.argv)
