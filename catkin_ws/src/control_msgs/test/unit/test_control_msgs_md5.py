"""control_msgs must be wire-compatible with the upstream package (ros-controls/control_msgs, kinetic-devel, the
branch Noetic releases as 1.5.2, control_msgs/{msg,srv,action}): a MoveIt or rqt_joint_trajectory_controller
client built against the real package talks to our trajectory controllers.

UPSTREAM (upstream_md5sums.txt beside this file): the md5sums genmsg computes from the upstream package's own files,
actions expanded by actionlib_msgs' genaction.py as catkin does (FollowJointTrajectoryAction bc4f9b74... is also the
value public clients carry).
"""
import sys
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import md5_tests, read_md5sums  # noqa: E402

UPSTREAM = read_md5sums(Path(__file__).with_name("upstream_md5sums.txt"))


globals().update(
    md5_tests(
        PACKAGE_ROOT, "control_msgs", ["std_msgs", "geometry_msgs", "trajectory_msgs", "actionlib_msgs"], UPSTREAM
    )
)


def test_follow_joint_trajectory_error_codes():
    """The result codes a trajectory controller answers with (upstream action/FollowJointTrajectory.action)."""
    text = (PACKAGE_ROOT / "action" / "FollowJointTrajectory.action").read_text()
    for code in (
        "SUCCESSFUL = 0",
        "INVALID_GOAL = -1",
        "INVALID_JOINTS = -2",
        "OLD_HEADER_TIMESTAMP = -3",
        "PATH_TOLERANCE_VIOLATED = -4",
        "GOAL_TOLERANCE_VIOLATED = -5",
    ):
        assert "int32 " + code in text
