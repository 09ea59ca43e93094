"""controller_manager_msgs must be wire-compatible with ros_control's (ros-controls/ros_control, noetic-devel,
controller_manager_msgs/{msg,srv}, release 0.20.0): a spawner or rqt_controller_manager built against the real
package talks to our controller manager, and ours to a real one.

UPSTREAM: the md5sums genmsg computes from the upstream package's own .msg/.srv files (read from the repository
at noetic-devel; the same values appear in public generated code, e.g. ListControllers 1341feb2...).
"""
import sys
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import md5_tests  # noqa: E402

PACKAGE = "controller_manager_msgs"
UPSTREAM = {
    "msg/ControllerState": "aeb6b261d97793ab74099a3740245272",
    "msg/ControllerStatistics": "697780c372c8d8597a1436d0e2ad3ba8",
    "msg/ControllersStatistics": "a154c347736773e3700d1719105df29d",
    "msg/HardwareInterfaceResources": "f25b55cbf1d1f76e82e5ec9e83f76258",
    "srv/ListControllerTypes": "c1d4cd11aefa9f97ba4aeb5b33987f4e",
    "srv/ListControllers": "1341feb2e63fa791f855565d0da950d8",
    "srv/LoadController": "647e5c54b8d6468952d8d31f1efe96c0",
    "srv/ReloadControllerLibraries": "40e8c411fd1797d2e2c486018f846040",
    "srv/SwitchController": "b29a7abc673b2c54c14b54e50f8d06a5",
    "srv/UnloadController": "647e5c54b8d6468952d8d31f1efe96c0",
}


globals().update(md5_tests(PACKAGE_ROOT, PACKAGE, ["std_msgs"], UPSTREAM))


def test_switch_strictness_constants():
    """BEST_EFFORT=1, STRICT=2 (upstream srv/SwitchController.srv): spawner and rqt send these numbers."""
    text = (PACKAGE_ROOT / "srv" / "SwitchController.srv").read_text()
    assert "int32 BEST_EFFORT=1" in text and "int32 STRICT=2" in text
