#!/usr/bin/env python3
"""rostest node: passes when ~node logs ~min_count messages matching ~pattern on /rosout within ~timeout s.

It checks what a node says it did (a listener saying "I heard: [...]"), not merely that a topic exists.
"""
import re
import sys
import threading
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log


class ExpectRosout(unittest.TestCase):
    def test_node_logs_pattern(self):
        node = rospy.get_param("~node")
        pattern = re.compile(rospy.get_param("~pattern"))
        min_count = rospy.get_param("~min_count", 5)
        timeout = rospy.get_param("~timeout", 20.0)
        matches, others = [], []
        enough = threading.Event()

        def on_log(log: Log):
            if log.name != node:
                return
            (matches if pattern.search(log.msg) else others).append(log.msg)
            if len(matches) >= min_count:
                enough.set()

        subscriber = rospy.Subscriber("/rosout", Log, on_log, queue_size=100)
        enough.wait(timeout)
        subscriber.unregister()
        self.assertGreaterEqual(
            len(matches),
            min_count,
            "%s logged %d matching messages in %s s; others: %s" % (node, len(matches), timeout, others[:5]),
        )


if __name__ == "__main__":
    rospy.init_node("expect_rosout", anonymous=True)
    rostest.rosrun("beginner_tutorials", "expect_rosout", ExpectRosout, sys.argv)
