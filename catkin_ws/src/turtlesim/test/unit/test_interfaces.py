"""The messages and services are the originals field for field: their md5sums equal ros_tutorials' turtlesim."""
from __future__ import annotations

import os

import genmsg
import genmsg.msg_loader
import pytest

PACKAGE = os.path.join(os.path.dirname(__file__), "..", "..")
# md5sums of ros_tutorials' turtlesim (noetic-devel) definitions, as genmsg computes them.
ORIGINAL_MD5 = {
    "msg/Color": "353891e354491c51aabe32df673fb446",
    "msg/Pose": "863b248d5016ca62ea2e895ae5265cf9",
    "srv/Kill": "c1f3d28f1b044c871e6eff2e9fc3c667",
    "srv/SetPen": "9f452acce566bf0c0954594f69a8e41b",
    "srv/Spawn": "0b2d2e872a8e2887d5ed626f2bf2c561",
    "srv/TeleportAbsolute": "a130bc60ee6513855dc62ea83fcc5b20",
    "srv/TeleportRelative": "9d5c2dcd348ac8f76ce2a4307bd63a13",
}


@pytest.mark.parametrize("name", sorted(ORIGINAL_MD5))
def test_definition_md5_equals_original(name):
    context = genmsg.msg_loader.MsgContext.create_default()
    kind, type_name = name.split("/")
    path = os.path.join(PACKAGE, kind, type_name + "." + kind)
    load = genmsg.msg_loader.load_msg_from_file if kind == "msg" else genmsg.msg_loader.load_srv_from_file
    spec = load(context, path, "turtlesim/" + type_name)
    assert genmsg.compute_md5(context, spec) == ORIGINAL_MD5[name]


@pytest.mark.parametrize("name", sorted(ORIGINAL_MD5))
def test_generated_python_md5_equals_original(name):
    kind, type_name = name.split("/")
    module = pytest.importorskip("turtlesim." + kind, reason="the workspace is not built and sourced")
    assert getattr(module, type_name)._md5sum == ORIGINAL_MD5[name]
