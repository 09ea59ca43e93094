#!/usr/bin/env python3
"""rostest node: the add_two_ints service itself, called from rospy: sums, overflow refusal, md5 check."""
import sys
import unittest

import rospy
import rostest

from beginner_tutorials.srv import AddTwoInts

INT64_MAX = 2**63 - 1
INT64_MIN = -(2**63)


class WrongMd5AddTwoInts(AddTwoInts):
    """The same type name with another md5sum, as an out-of-date client build would send."""

    _md5sum = "0123456789abcdef0123456789abcdef"


class AddTwoIntsService(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service("add_two_ints", timeout=30)
        cls.add = rospy.ServiceProxy("add_two_ints", AddTwoInts)

    def test_sums(self):
        for a, b in ((1, 2), (-7, 3), (0, 0), (INT64_MAX, 0), (INT64_MIN, 0), (INT64_MAX, INT64_MIN)):
            self.assertEqual(self.add(a, b).sum, a + b)

    def test_overflow_refused(self):
        for a, b in ((INT64_MAX, 1), (INT64_MIN, -1)):
            with self.assertRaises(rospy.ServiceException):
                self.add(a, b)
        self.assertEqual(self.add(2, 2).sum, 4, "the server must keep serving after a refusal")

    def test_wrong_md5_refused(self):
        with self.assertRaisesRegex(rospy.ServiceException, "md5"):
            rospy.ServiceProxy("add_two_ints", WrongMd5AddTwoInts)(1, 2)


if __name__ == "__main__":
    rospy.init_node("test_add_two_ints_service")
    rostest.rosrun("beginner_tutorials", "add_two_ints_service", AddTwoIntsService, sys.argv)
