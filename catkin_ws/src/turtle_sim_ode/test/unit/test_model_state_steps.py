"""A pioneer2dx-like robot stepped through /gazebo/set_model_state relative to its own chassis, as gazebo_plugins'
set_model_state_test does (noetic-devel gazebo_plugins/test/set_model_state_test/set_model_state_test.cpp,
TEST(ModelStateTest, FrameTest)): turns of quaternion (0, 0, 0.04018, 1) until the heading is pi/4 within 0.05 rad,
then 0.1 m steps forward until 5 m from the origin, where x and y are sqrt(25/2) within 0.2; then (0, 0) in the
world within 0.01 m. Between two commands the world runs 0.2 s, as the test sleeps. The robot (test/worlds/
caster_robot.world) is our own, in the style of Gazebo's pioneer2dx."""
import math

import pytest
from conftest import PACKAGE_ROOT

from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.world.simulation import Simulation

WORLD = PACKAGE_ROOT / "test" / "worlds" / "caster_robot.world"
TURN = (0.0, 0.0, 0.04018, 1.0)  # not unit length: gazebo_ros normalises it (Quaterniond::Normalize)
STEP_TURN = 2 * math.atan(0.04018)  # 4.6 degrees
LEVEL = math.radians(1.0)  # the chassis stays within a degree of level after every step


def heading_and_tilt(sim: Simulation):
    (x, y, z), (qx, qy, qz, qw), _, _ = sim.get_model_state("caster_bot")
    yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
    roll = math.atan2(2 * (qw * qx + qy * qz), 1 - 2 * (qx * qx + qy * qy))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (qw * qy - qz * qx))))
    return (x, y), yaw, max(abs(roll), abs(pitch))


def command(sim: Simulation, position, quaternion, frame: str) -> None:
    sim.set_model_state("caster_bot", position, quaternion, reference_frame=frame)
    for _ in range(200):
        sim.step()


@pytest.fixture(scope="module")
def sim() -> Simulation:
    sim = Simulation()
    sim.load_world(parse_sdf_world(WORLD.read_text()))
    for _ in range(500):  # settle on wheels and caster
        sim.step()
    return sim


def test_turns_forward_steps_and_return(sim: Simulation) -> None:
    turns = 0
    while True:
        command(sim, (0, 0, 0), TURN, "caster_bot::chassis")
        turns += 1
        (x, y), yaw, tilt = heading_and_tilt(sim)
        assert tilt < LEVEL and math.hypot(x, y) < 0.01, (turns, x, y, tilt)
        assert yaw == pytest.approx(turns * STEP_TURN, abs=0.005)
        if abs(yaw - math.pi / 4) < 0.05:
            break
        assert turns < 12, "the heading never came within 0.05 rad of pi/4"
    assert turns == 10  # 46.0 degrees
    steps = 0
    while math.hypot(x, y) < 5.0:
        command(sim, (0.1, 0, 0), (0, 0, 0, 1), "caster_bot::chassis")
        steps += 1
        (x, y), step_yaw, tilt = heading_and_tilt(sim)
        assert tilt < LEVEL and step_yaw == pytest.approx(yaw, abs=0.005), (steps, tilt, step_yaw)
        assert math.hypot(x, y) == pytest.approx(0.1 * steps, abs=0.01)
        assert steps < 60
    assert x == pytest.approx(math.sqrt(12.5), abs=0.2) and y == pytest.approx(math.sqrt(12.5), abs=0.2)
    command(sim, (0, 0, 0), (0, 0, 0, 1), "world")
    (x, y), yaw, tilt = heading_and_tilt(sim)
    assert abs(x) < 0.01 and abs(y) < 0.01 and abs(yaw) < 0.01 and tilt < LEVEL


def test_a_state_relative_to_a_moving_link_leaves_the_model_at_rest(sim: Simulation) -> None:
    """The twist is taken in the frame's axes, without the frame's own velocity (setModelState rotates it only),
    and every link gets it: a model commanded relative to itself while it moves stops."""
    sim.set_model_state("caster_bot", (1, 1, 0.3), (0, 0, 0, 1), (0.5, 0, 0), (0, 0, 2.0))
    assert sim.get_model_state("caster_bot")[3] == pytest.approx((0, 0, 2.0))
    sim.set_model_state("caster_bot", (0, 0, 0), (0, 0, 0, 2), reference_frame="caster_bot::chassis")
    for body in sim.models["caster_bot"].bodies:
        assert body.getLinearVel() == pytest.approx((0, 0, 0)) and body.getAngularVel() == pytest.approx((0, 0, 0))
