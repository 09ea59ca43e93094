"""turtle_sim_ode_msgs' own service. (The Kobuki's bumper and cliff events use kobuki_msgs: that package's
tests check its md5sums against yujinrobot's.)"""
from pathlib import Path

import genmsg.msg_loader

PACKAGE_ROOT = Path(__file__).resolve().parents[2]


def test_step_simulation_fields():
    context = genmsg.msg_loader.MsgContext.create_default()
    spec = genmsg.msg_loader.load_srv_from_file(
        context, str(PACKAGE_ROOT / "srv" / "StepSimulation.srv"), "turtle_sim_ode_msgs/StepSimulation"
    )
    assert spec.request.names == ["steps"] and spec.request.types == ["uint32"]
    assert spec.response.names == ["sim_time", "success", "status_message"]
    assert spec.response.types == ["time", "bool", "string"]
