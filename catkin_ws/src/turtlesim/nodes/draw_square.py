#!/usr/bin/env python3
import sys

from turtlesim.square import main

if __name__ == "__main__":
    sys.exit(main())
