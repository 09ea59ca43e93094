"""kobuki_msgs must be wire-compatible with yujinrobot's: ROS 1 peers refuse a connection when the md5sums differ,
so a node built against the real package would not hear the simulator.

The expected md5sums were computed with genmsg.gentools.compute_md5 from the .msg and .action files of
github.com/yujinrobot/kobuki_msgs, branch noetic (0.7.0, commit ec50979); the action's seven messages from
upstream's action/AutoDocking.action expanded by actionlib_msgs' genaction.py.
"""
import subprocess
import sys
from pathlib import Path

import genmsg.gentools
import genmsg.msg_loader
import pytest

PACKAGE_ROOT = Path(__file__).resolve().parents[2]

UPSTREAM_MSG_MD5 = {
    "BumperEvent": "ffe360cd50f14f9251d9844083e72ac5",
    "ButtonEvent": "49eca512765dbdec759a79083ffcec8d",
    "CliffEvent": "c5b106efbb1427a94f517c5e05f06295",
    "ControllerInfo": "46af38e72f0640f41ed22174d43a2550",
    "DigitalInputEvent": "93da823c8b121f8a3940ef3830c58e44",
    "DigitalOutput": "1e97cd7f196a0270516b506e8bf29ca2",
    "DockInfraRed": "a3d77f7d15e50579473dcc24e9b97b34",
    "ExternalPower": "95149d524971a4c6d19e64c827307194",
    "KeyboardInput": "9288b95cb32b48719d84d696be253401",
    "Led": "4391183b0cf05f8f25d04220401b9f43",
    "MotorPower": "8f77c0161e0f2021493136bb5f3f0e51",
    "PowerSystemEvent": "f6464657d6c911b00c7bc7b43a154bf8",
    "RobotStateEvent": "c6eccd4cb1f95df95635b56d6226ea32",
    "ScanAngle": "06e2c839dc5c7f5c13ac09a8b4ff0a6a",
    "SensorState": "430a4bfd78449c8740bfef32b26613a6",
    "Sound": "dfeab0daae67749c426c1db741a4f420",
    "VersionInfo": "3dc0ce6edd49be1fc86730f4a4a21861",
    "WheelDropEvent": "e102837d89384d67669a0df86b63f33b",
}
UPSTREAM_ACTION_MD5 = {
    "AutoDockingAction": "44be114f3afc06365a090db0a5e982b5",
    "AutoDockingActionFeedback": "6f7132467beab5153587d9ebb8d8262d",
    "AutoDockingActionGoal": "4b30be6cd12b9e72826df56b481f40e0",
    "AutoDockingActionResult": "3fb2b9cd9cec6b4cb23b224521dd7679",
    "AutoDockingFeedback": "03343b6aa0067ce6251bcc08bf318388",
    "AutoDockingGoal": "d41d8cd98f00b204e9800998ecf8427e",
    "AutoDockingResult": "74697ed3d931f6eede8bf3a8dfeca160",
}
GENACTION = Path("/usr/lib/actionlib_msgs/genaction.py")
SYSTEM_SHARE = Path("/opt/ros/noetic/share") if Path("/opt/ros/noetic/share").is_dir() else Path("/usr/share")


def md5_of(msg_dir: Path, name: str) -> str:
    search = {
        "kobuki_msgs": [str(msg_dir)],
        "std_msgs": [str(SYSTEM_SHARE / "std_msgs" / "msg")],
        "actionlib_msgs": [str(SYSTEM_SHARE / "actionlib_msgs" / "msg")],
    }
    context = genmsg.msg_loader.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_by_type(context, "kobuki_msgs/" + name, search)
    genmsg.msg_loader.load_depends(context, spec, search)
    return genmsg.gentools.compute_md5(context, spec)


def test_every_upstream_message_is_here_and_nothing_else():
    assert sorted(p.stem for p in (PACKAGE_ROOT / "msg").glob("*.msg")) == sorted(UPSTREAM_MSG_MD5)


@pytest.mark.parametrize("name", sorted(UPSTREAM_MSG_MD5))
def test_message_md5_matches_upstream(name):
    assert md5_of(PACKAGE_ROOT / "msg", name) == UPSTREAM_MSG_MD5[name]


@pytest.mark.skipif(not GENACTION.is_file(), reason="actionlib_msgs' genaction.py is elsewhere on this platform")
def test_action_md5s_match_upstream(tmp_path):
    subprocess.run(
        [sys.executable, str(GENACTION), "-o", str(tmp_path), str(PACKAGE_ROOT / "action" / "AutoDocking.action")],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    assert {name: md5_of(tmp_path, name) for name in UPSTREAM_ACTION_MD5} == UPSTREAM_ACTION_MD5
