#!/usr/bin/env python3
import os
import sys

# This script bears the library's name (as upstream's executable does): the folders holding it (its own, and the
# devel space's relay folder) would otherwise shadow the library on `import teleop_twist_keyboard`.
sys.path = [p for p in sys.path if not os.path.isfile(os.path.join(p or os.curdir, "teleop_twist_keyboard.py"))]

from teleop_twist_keyboard.node import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
