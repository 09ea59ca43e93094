#!/usr/bin/env python3
import sys

from turtlesim.mimic import main

if __name__ == "__main__":
    sys.exit(main())
