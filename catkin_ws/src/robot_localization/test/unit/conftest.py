"""Let the unit tests import the package's Python code from the source tree when the workspace is not sourced."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src"))
