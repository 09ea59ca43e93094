"""uuid_msgs must be wire-compatible with ros-geographic-info's (github.com/ros-geographic-info/unique_identifier,
release 1.0.6, uuid_msgs/msg/UniqueID.msg).

UPSTREAM: the md5sum genmsg computes from the upstream file.
"""
import sys
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import md5_tests  # noqa: E402

UPSTREAM = {"msg/UniqueID": "fec2a93b6f5367ee8112c9c0b41ff310"}

globals().update(md5_tests(PACKAGE_ROOT, "uuid_msgs", ["std_msgs"], UPSTREAM))
