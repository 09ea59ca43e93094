"""controller_manager_msgs must be wire-compatible with ros_control's (ros-controls/ros_control, noetic-devel,
controller_manager_msgs/{msg,srv}, release 0.20.0): a spawner or rqt_controller_manager built against the real
package talks to our controller manager, and ours to a real one.

UPSTREAM (upstream_md5sums.txt beside this file): the md5sums genmsg computes from the upstream package's own
.msg/.srv files (read from the repository at noetic-devel; the same values appear in public generated code, e.g.
ListControllers 1341feb2...).
"""
import sys
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import md5_tests, read_md5sums  # noqa: E402

UPSTREAM = read_md5sums(Path(__file__).with_name("upstream_md5sums.txt"))


globals().update(md5_tests(PACKAGE_ROOT, "controller_manager_msgs", ["std_msgs"], UPSTREAM))


def test_switch_strictness_constants():
    """BEST_EFFORT=1, STRICT=2 (upstream srv/SwitchController.srv): spawner and rqt send these numbers."""
    text = (PACKAGE_ROOT / "srv" / "SwitchController.srv").read_text()
    assert "int32 BEST_EFFORT=1" in text and "int32 STRICT=2" in text
