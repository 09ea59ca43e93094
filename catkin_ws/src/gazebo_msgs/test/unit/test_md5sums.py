"""gazebo_msgs must be wire-compatible with ROS Noetic's gazebo_msgs (ros-simulation/gazebo_ros_pkgs, noetic-devel).

ROS 1 peers refuse a connection when the md5sums of the two sides differ, so every message and service here must
hash to the value the upstream package produces. The checks run twice: on the .msg/.srv sources through genmsg
(needs no build, only the dependencies' .msg files) and on the generated Python classes (needs a built devel space
sourced; skipped otherwise, the source check still runs).

Where the expected values come from:
* PUBLISHED: the md5sums the project was given for the upstream package.
* UPSTREAM_GENERATED: the md5sums found in public code generated from the upstream package (rosserial ros_lib
  headers, gennodejs/genlisp output, C# and Swift bindings, and `rosbag info` of a Noetic Gazebo recording).
  LinkStates and ModelStates share one md5sum upstream too: their fields are identical.
"""
import re
import sys
from pathlib import Path

import pytest

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import installed_msg_dir  # noqa: E402

PACKAGE = "gazebo_msgs"
DEPENDENCIES = ("std_msgs", "geometry_msgs", "sensor_msgs", "trajectory_msgs")

PUBLISHED = {
    "srv/SpawnModel": "9ed9c82c96abe1a00c3e8cdaeee24413",
    "srv/GetModelState": "4c515e936d3319c9610c559c60bfc3d4",
    "srv/SetModelState": "5b3ab0281d4f5445def017e3a2e4a07b",
    "msg/ModelState": "9330fd35f2fcd82d457e54bd54e10593",
    "msg/ModelStates": "48c080191eb15c41858319b4d8a609c2",
    "srv/DeleteModel": "9ce56b4e9e54616de25d796dc972a262",
    "srv/GetWorldProperties": "36bb0f2eccf4d8be971410c22818ba3f",
    "srv/GetPhysicsProperties": "575a5e74786981b7df2e3afc567693a6",
    "srv/SetPhysicsProperties": "97e2057080558ce4730434b5fae75c91",
    "srv/ApplyBodyWrench": "585b9f9618aa0581b207e2f2d90866bc",
}

UPSTREAM_GENERATED = {
    "msg/ContactState": "48c0ffb054b8c444f870cecea1ee50d9",
    "msg/ContactsState": "acbcb1601a8e525bf72509f18e6f668d",
    "msg/LinkState": "0818ebbf28ce3a08d48ab1eaa7309ebe",
    "msg/LinkStates": "48c080191eb15c41858319b4d8a609c2",
    "msg/ODEJointProperties": "1b744c32a920af979f53afe2f9c3511f",
    "msg/ODEPhysics": "667d56ddbd547918c32d1934503dc335",
    "msg/PerformanceMetrics": "884f71fd5037b886ec5e126b83c4425a",
    "msg/SensorPerformanceMetric": "01762ded18cfe9ebc7c8222667c99547",
    "msg/WorldState": "de1a9de3ab7ba97ac0e9ec01a4eb481e",
    "srv/ApplyJointEffort": "c0039811b8cc919490b3cff748cdf46b",
    "srv/BodyRequest": "5eade9afe7f232d78005bd0cafeab755",
    "srv/DeleteLight": "ae11ea8100d536d5b92c2b5917abf912",
    "srv/GetJointProperties": "7b30be900f50aa21efec4a0ec92d91c9",
    "srv/GetLightProperties": "df2cef87e13e2e6990e81e8aaa454c19",
    "srv/GetLinkProperties": "0e06a70386d0ee3fb880c02f23fcd821",
    "srv/GetLinkState": "09d6c98cce97b35f7ab9bd70300657ab",
    "srv/GetModelProperties": "5717f7bd34ed990fa80e28b3015027a3",
    "srv/JointRequest": "0be1351618e1dc030eb7959d9a4902de",
    "srv/SetJointProperties": "15a76e921b1410c698d82782ea5fa370",
    "srv/SetJointTrajectory": "88f5c10979e3f9649d5ae87a3b12aa65",
    "srv/SetLightProperties": "e6f13430c57278bb364aca53a1bf5ebf",
    "srv/SetLinkProperties": "d534ce1b36ee99de0ffa806c3a6348f0",
    "srv/SetLinkState": "8a5146eb66ae4d26b0860b08f3f271be",
    "srv/SetModelConfiguration": "10e3139d3b669c40afc057d38956fff7",
}

EXPECTED_MD5 = dict(PUBLISHED, **UPSTREAM_GENERATED)

# The interface files of gazebo_msgs 2.9.2, the last release on noetic-devel.
UPSTREAM_FILES = {
    "msg": [
        "ContactState",
        "ContactsState",
        "LinkState",
        "LinkStates",
        "ModelState",
        "ModelStates",
        "ODEJointProperties",
        "ODEPhysics",
        "PerformanceMetrics",
        "SensorPerformanceMetric",
        "WorldState",
    ],
    "srv": [
        "ApplyBodyWrench",
        "ApplyJointEffort",
        "BodyRequest",
        "DeleteLight",
        "DeleteModel",
        "GetJointProperties",
        "GetLightProperties",
        "GetLinkProperties",
        "GetLinkState",
        "GetModelProperties",
        "GetModelState",
        "GetPhysicsProperties",
        "GetWorldProperties",
        "JointRequest",
        "SetJointProperties",
        "SetJointTrajectory",
        "SetLightProperties",
        "SetLinkProperties",
        "SetLinkState",
        "SetModelConfiguration",
        "SetModelState",
        "SetPhysicsProperties",
        "SpawnModel",
    ],
}
UPSTREAM_TYPES = sorted("%s/%s" % (kind, name) for kind, names in UPSTREAM_FILES.items() for name in names)


def package_files(kind):
    return sorted(p.stem for p in (PACKAGE_ROOT / kind).iterdir() if p.suffix == "." + kind)


def dependency_msg_dir(package):
    try:
        return installed_msg_dir(package)
    except FileNotFoundError as error:
        pytest.fail(str(error))


def test_every_upstream_file_is_here_and_no_other():
    for kind, names in UPSTREAM_FILES.items():
        assert package_files(kind) == sorted(names), kind


def test_expected_md5_table_covers_every_type():
    assert sorted(EXPECTED_MD5) == UPSTREAM_TYPES


def test_cmakelists_generates_every_file():
    cmake = (PACKAGE_ROOT / "CMakeLists.txt").read_text()
    for kind, function in (("msg", "add_message_files"), ("srv", "add_service_files")):
        block = re.search(r"%s\((.*?)\)" % function, cmake, re.S).group(1)
        listed = sorted(re.findall(r"(\w+)\.%s\b" % kind, block))
        assert listed == sorted(UPSTREAM_FILES[kind]), function


@pytest.fixture(scope="module")
def genmsg_md5():
    genmsg = pytest.importorskip("genmsg")
    from genmsg import msg_loader

    search_path = {PACKAGE: [str(PACKAGE_ROOT / "msg")]}
    search_path.update((dep, [dependency_msg_dir(dep)]) for dep in DEPENDENCIES)

    def md5(type_key):
        kind, name = type_key.split("/")
        context = genmsg.MsgContext.create_default()
        full_name = "%s/%s" % (PACKAGE, name)
        if kind == "msg":
            spec = msg_loader.load_msg_by_type(context, full_name, search_path)
        else:
            spec = msg_loader.load_srv_from_file(context, str(PACKAGE_ROOT / "srv" / (name + ".srv")), full_name)
        msg_loader.load_depends(context, spec, search_path)
        return genmsg.compute_md5(context, spec)

    return md5


@pytest.mark.parametrize("type_key", sorted(EXPECTED_MD5))
def test_source_md5sum_matches_upstream(genmsg_md5, type_key):
    assert genmsg_md5(type_key) == EXPECTED_MD5[type_key]


@pytest.mark.parametrize("type_key", sorted(EXPECTED_MD5))
def test_generated_python_md5sum_matches_upstream(type_key):
    kind, name = type_key.split("/")
    try:
        module = __import__("%s.%s" % (PACKAGE, kind), fromlist=[name])
    except ImportError as error:
        pytest.skip("generated %s.%s not importable (source a devel space): %s" % (PACKAGE, kind, error))
    generated = getattr(module, name)
    assert generated._md5sum == EXPECTED_MD5[type_key]
    assert generated._type == "%s/%s" % (PACKAGE, name)
    if kind == "srv":
        assert generated._request_class._type == "%s/%sRequest" % (PACKAGE, name)
        assert generated._response_class._type == "%s/%sResponse" % (PACKAGE, name)
