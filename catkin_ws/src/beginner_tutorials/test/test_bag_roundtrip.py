#!/usr/bin/env python3
"""rostest node: the bag that record.launch wrote holds ~count chatter messages, and playing it delivers them."""
import os
import subprocess
import sys
import threading
import time
import unittest

import rosbag
import rospy
import rostest
from std_msgs.msg import String


def wait_for_file(path: str, timeout: float) -> bool:
    """rosbag record renames <bag>.active to <bag> when it closes the file: nothing to subscribe to, so poll."""
    deadline = time.monotonic() + timeout
    while not os.path.exists(path):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.1)
    return True


class BagRoundTrip(unittest.TestCase):
    def test_record_and_play(self):
        bag_path = rospy.get_param("~bag")
        count = rospy.get_param("~count")
        self.assertTrue(wait_for_file(bag_path, 60.0), "record.launch wrote no %s" % bag_path)
        try:
            with rosbag.Bag(bag_path) as bag:
                # The bag keeps the name as recorded: relative, so that it plays back into any namespace.
                recorded = [msg.data for _, msg, _ in bag.read_messages(topics=["chatter"])]
            self.assertEqual(len(recorded), count)
            numbers = [int(text.rsplit(" ", 1)[1]) for text in recorded]
            self.assertEqual(numbers, list(range(numbers[0], numbers[0] + count)), "messages lost or reordered")

            played, all_played = [], threading.Event()

            def on_message(msg: String):
                played.append(msg.data)
                if len(played) == count:
                    all_played.set()

            rospy.Subscriber("replayed_chatter", String, on_message, queue_size=count)
            player = subprocess.run(
                ["rosbag", "play", "--wait-for-subscribers", "--quiet", bag_path, "chatter:=replayed_chatter"],
                timeout=60,
            )
            self.assertEqual(player.returncode, 0)
            all_played.wait(10.0)
            self.assertEqual(played, recorded)
        finally:
            os.remove(bag_path)


if __name__ == "__main__":
    rospy.init_node("test_bag_roundtrip")
    rostest.rosrun("beginner_tutorials", "bag_roundtrip", BagRoundTrip, sys.argv)
