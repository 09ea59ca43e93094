#!/usr/bin/env python3
import sys

from beginner_tutorials.params import run_node
from my_first_rospkg.nodes import main_spiral

if __name__ == "__main__":
    sys.exit(run_node(main_spiral))
