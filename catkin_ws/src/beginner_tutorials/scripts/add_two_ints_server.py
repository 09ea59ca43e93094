#!/usr/bin/env python3
import sys

from beginner_tutorials.add_two_ints import add_two_ints_server
from beginner_tutorials.params import run_node

if __name__ == "__main__":
    sys.exit(run_node(add_two_ints_server))
