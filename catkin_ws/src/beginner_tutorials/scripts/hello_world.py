#!/usr/bin/env python3
import sys

from beginner_tutorials.hello_world import hello_world
from beginner_tutorials.params import run_node

if __name__ == "__main__":
    sys.exit(run_node(hello_world))
