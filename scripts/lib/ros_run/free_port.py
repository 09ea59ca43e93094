#!/usr/bin/env python3
"""Print a TCP port that is free on the loopback interface (for a master of our own)."""
from ros_run.processes import free_port

print(free_port())
