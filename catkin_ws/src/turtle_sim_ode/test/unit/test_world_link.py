"""Issue #31: a URDF link named "world" with a fixed joint to the robot welds the robot to the world, as Gazebo's
URDF to SDF conversion does (sdformat parser_urdf: the root link "world" becomes the world frame, its joint a joint
to the world); an arm on it rests where the tutorial's P gain and gravity put it (test/world_arm_statics.py)."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import yaml
from conftest import PACKAGE_ROOT
from control_helpers import simulated
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.world.simulation import Simulation

sys.path.insert(0, str(PACKAGE_ROOT / "test"))
from world_arm_statics import JOINTS, resting_angles  # noqa: E402

MODELS = Path(PACKAGE_ROOT) / "test" / "models"
ARM = (MODELS / "world_arm.urdf").read_text()
CONTROL = yaml.safe_load((MODELS / "world_arm_control.yaml").read_text())["rrbot"]
P_GAIN = CONTROL["shoulder_position_controller"]["pid"]["p"]
POSITION_CONTROLLERS = {f"{joint}_position_controller": CONTROL[f"{joint}_position_controller"] for joint in JOINTS}
WITHOUT_WORLD = ARM.replace('<link name="world"/>', "").replace(
    '<joint name="world_to_column" type="fixed">\n    <parent link="world"/>\n    <child link="column"/>\n  </joint>',
    "",
)


def run(sim: Simulation, seconds: float) -> None:
    for _ in range(int(round(seconds / sim.physics.time_step))):
        sim.step()


def test_the_world_link_welds_the_column_where_it_was_placed() -> None:
    sim = Simulation()
    sim.spawn_urdf("rrbot", ARM, (1.0, 2.0, 0.0, 0.0, 0.0, 0.3))
    model = sim.models["rrbot"]
    assert model.link_pose("world")[0] == (1.0, 2.0, 0.0)
    start, orientation = model.link_pose("column")
    for _ in range(100):  # a push off the upright arm's unstable rest; then, unheld, it swings down and about
        model.joint("shoulder").joint.addTorque(5.0)
        sim.step()
    run(sim, 3.0)
    position, now = model.link_pose("column")
    assert math.dist(position, start) < 1e-4 and math.dist(now, orientation) < 1e-4
    assert abs(model.joint("shoulder").angle()) > 0.5  # it did swing
    model.remove()


def test_without_the_world_link_the_column_stands_loose() -> None:
    sim = Simulation()
    sim.spawn_urdf("rrbot", WITHOUT_WORLD, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    start, _ = sim.models["rrbot"].link_pose("column")
    run(sim, 3.0)
    assert math.dist(sim.models["rrbot"].link_pose("column")[0], start) > 0.05


@settings(max_examples=8, deadline=None)
@given(st.floats(-1.0, 1.0), st.floats(-1.2, 1.2))
def test_the_arm_rests_where_p_gain_and_gravity_put_it(shoulder: float, elbow: float) -> None:
    sim, control = simulated(ARM, "rrbot", 0.0, POSITION_CONTROLLERS)
    for joint, target in zip(JOINTS, (shoulder, elbow)):
        control.manager.find(f"{joint}_position_controller").controller._on_command(target)
    run(sim, 5.0)
    before = {joint: control.hw.joints[joint].position for joint in JOINTS}
    run(sim, 1.0)
    resting = resting_angles((shoulder, elbow), P_GAIN)
    for joint, expected in zip(JOINTS, resting):
        assert abs(control.hw.joints[joint].position - expected) < 2e-3, (joint, expected)
        # at rest: the mean velocity over the last second (the solver leaves ~1e-3 rad/s of jitter in one step's reading)
        assert abs(control.hw.joints[joint].position - before[joint]) < 1e-3, joint
    assert math.dist(sim.models["rrbot"].link_pose("column")[0], (0.0, 0.0, 0.0)) < 1e-4
