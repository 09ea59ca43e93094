"""The event messages must be wire-compatible with kobuki_msgs (Noetic), so that a node written for a real
Kobuki, subscribing with kobuki_msgs types, hears the simulator: ROS 1 peers refuse a connection when the
md5sums differ. The expected values are those of kobuki_msgs 0.7 as generated upstream."""
from pathlib import Path

import genmsg.gentools
import genmsg.msg_loader
import pytest

PACKAGE_ROOT = Path(__file__).resolve().parents[2]

KOBUKI_MSGS = {
    "BumperEvent": "ffe360cd50f14f9251d9844083e72ac5",
    "CliffEvent": "c5b106efbb1427a94f517c5e05f06295",
}


@pytest.mark.parametrize("name", sorted(KOBUKI_MSGS))
def test_event_matches_kobuki_msgs(name):
    context = genmsg.msg_loader.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_from_file(
        context, str(PACKAGE_ROOT / "msg" / (name + ".msg")), "turtle_sim_ode_msgs/" + name
    )
    assert genmsg.gentools.compute_md5(context, spec) == KOBUKI_MSGS[name]


def test_step_simulation_fields():
    context = genmsg.msg_loader.MsgContext.create_default()
    spec = genmsg.msg_loader.load_srv_from_file(
        context, str(PACKAGE_ROOT / "srv" / "StepSimulation.srv"), "turtle_sim_ode_msgs/StepSimulation"
    )
    assert spec.request.names == ["steps"] and spec.request.types == ["uint32"]
    assert spec.response.names == ["sim_time", "success", "status_message"]
    assert spec.response.types == ["time", "bool", "string"]
