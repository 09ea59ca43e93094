#!/usr/bin/env python3
import sys

import rospy

from beginner_tutorials.add_two_ints import add_two_ints_client

if __name__ == "__main__":
    sys.exit(add_two_ints_client(rospy.myargv()[1:]))
