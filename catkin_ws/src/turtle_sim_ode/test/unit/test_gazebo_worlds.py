"""The worlds behind gazebo_ros's world launch files (worlds/*.world, models/), against gazebo-classic's
worlds/shapes.world, mud.world, willowgarage.world, rubble.world and gazebo_ros_pkgs' gazebo_plugins/test/
test_worlds/elevator.world (model names and poses), plugins/RubblePlugin.cc (RubblePlugin::Load) and
plugins/ElevatorPlugin.cc (MoveToFloor's five states, DoorController and LiftController's PIDs and tolerances,
gazebo::common::PID::Update) and gazebo_ros_elevator.cpp (OnElevator: std::stoi of the message); SDF joints to the world (<parent>world</parent>) as the elevator's lift uses one."""
from __future__ import annotations

import math
import random

import pytest
from conftest import PACKAGE_ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.ros.plugins.elevator import floor_number
from turtle_sim_ode.world.plugins.elevator import Elevator, GazeboPid
from turtle_sim_ode.world.rubble import BOARD_LENGTH, BOARD_SECTION, CINDER_BLOCK, RUBBLE, rubble
from turtle_sim_ode.world.simulation import Simulation

PATHS = ResourcePaths({}, [str(PACKAGE_ROOT / "models")], [str(PACKAGE_ROOT)])


def loaded(name: str) -> Simulation:
    sim = Simulation()
    sim.resources = PATHS
    sim.load_world(parse_sdf_world((PACKAGE_ROOT / "worlds" / name).read_text()))
    return sim


def run(sim: Simulation, seconds: float) -> None:
    for _ in range(int(round(seconds / sim.physics.time_step))):
        sim.step()


# name -> (x, y, z) of the model frame as the Gazebo world places it
WORLDS = {
    "shapes.world": {
        "ground_plane": (0, 0, 0),
        "box": (0, 0, 0.5),
        "sphere": (0, 1.5, 0.5),
        "cylinder": (0, -1.5, 0.5),
    },
    "mud.world": {
        "ground_plane": (0, 0, 0),
        "pendulum_thick_mud": (-2, 0, 0),
        "pendulum_thin_mud": (0, 0, 0),
        "pendulum_no_mud": (2, 0, 0),
        "mud_pit_thin": (0, -1, 0.7),
        "mud_pit_thick": (0, -1, 1.0),
    },
    "willowgarage.world": {"ground_plane": (0, 0, 0), "willowgarage": (0, 0, 0)},
    "elevator_ros.world": {
        "ground_plane": (0, 0, 0),
        "elevator": (0, 0, 0.075),
        "elevator_shaft": (0, 0, 0),
        "floor0": (2.25, 0, 0.075),
        "floor1": (2.25, 0, 3.075),
    },
}


@pytest.mark.parametrize("world", sorted(WORLDS))
def test_each_world_holds_gazebos_models_by_name_and_pose(world: str) -> None:
    sim = loaded(world)
    assert list(sim.models) == list(WORLDS[world])  # in the world's order, as Gazebo loads them
    for name, position in WORLDS[world].items():
        assert sim.get_model_state(name)[0] == pytest.approx(position, abs=1e-6), name
    run(sim, 0.5)  # and they stand: the shapes rest where they are
    for name in ("box", "sphere"):
        if name in sim.models:
            assert sim.get_model_state(name)[0] == pytest.approx(WORLDS[world][name], abs=2e-3)


def test_the_pendulums_swing() -> None:
    sim = loaded("mud.world")
    joint = sim.models["pendulum_no_mud"].joint("upper_joint")
    run(sim, 0.5)
    assert abs(joint.angle()) > 0.1 and math.isfinite(joint.angle())


# --- the elevator ------------------------------------------------------------------------------
def test_the_elevator_rides_to_floor_1_opens_waits_and_closes() -> None:
    sim = loaded("elevator_ros.world")
    (config,) = sim.plugins["elevator"].configs
    assert (config.lift_joint, config.door_joint, config.floor_height, config.door_wait_time, config.topic) == (
        "lift",
        "door",
        3.075,
        10.0,
        "elevator",
    )
    elevator = Elevator(sim.models["elevator"], config)
    sim.step_hooks["elevator"] = elevator
    assert elevator.move_to_floor(1) and not elevator.move_to_floor(0)  # MoveToFloor: ignored while busy
    opened = None
    while elevator.busy and sim.sim_time < 40.0:
        run(sim, 0.1)
        if opened is None and elevator.door.handle.angle() > 1.0 - 0.05:
            opened = sim.sim_time
            # the car at floor 1 within the lift's 0.15 m, sagging by weight / p (800 kg x 9.8 / 100000)
            assert elevator.lift.handle.angle() == pytest.approx(3.075 - 800 * 9.8 / 100000.0, abs=0.02)
    assert opened is not None, "the door never opened"
    assert sim.sim_time - opened >= 10.0  # the door held open door_wait_time
    assert abs(elevator.door.handle.angle()) < 0.05  # closed again
    assert sim.get_model_state("elevator")[0][2] == pytest.approx(0.075 + 3.075, abs=0.15)


def test_reset_forgets_the_ride() -> None:
    sim = loaded("elevator_ros.world")
    elevator = Elevator(sim.models["elevator"], sim.plugins["elevator"].configs[0])
    sim.step_hooks["elevator"] = elevator
    elevator.move_to_floor(1)
    run(sim, 0.2)
    sim.reset_world()
    assert not elevator.busy and elevator.move_to_floor(0)


@settings(max_examples=50, deadline=None)
@given(
    gains=st.tuples(*(st.floats(0, 1e5, allow_subnormal=False) for _ in range(3))),
    errors=st.lists(
        st.tuples(st.floats(-10, 10, allow_subnormal=False), st.one_of(st.just(0.0), st.floats(1e-6, 0.1))),
        min_size=1,
        max_size=8,
    ),
)
def test_the_pid_is_gazebos(gains, errors) -> None:
    """common::PID::Update: 0 for dt 0; else -(p e + i sum(e dt) + d (e - last e) / dt), the last error 0 at first."""
    pid, last, integral = GazeboPid(gains), 0.0, 0.0
    for error, dt in errors:
        command = pid.update(error, dt)
        if dt <= 0:
            assert command == 0.0
            continue
        integral += dt * error
        expected = -(gains[0] * error + gains[1] * integral + gains[2] * (error - last) / dt)
        last = error
        assert command == pytest.approx(expected, rel=1e-9, abs=1e-9)


# --- joints to the world -------------------------------------------------------------------------
LIFT = """<sdf version="1.6"><model name="lift"><pose>0 0 0.5 0 0 0</pose>
  <link name="car"><inertial><mass>10</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.4 0.4 0.4</size></box></geometry></collision></link>
  <joint name="rail" type="%s"><parent>world</parent><child>car</child>
    <axis><xyz>0 0 1</xyz><limit><lower>-0.2</lower><upper>1</upper></limit></axis></joint></model></sdf>"""


def test_a_prismatic_joint_to_the_world_holds_the_root_link_on_its_axis() -> None:
    sim = Simulation()
    sim.spawn_sdf("lift", LIFT % "prismatic", (1, 2, 0.5, 0, 0, 0))
    body = sim.models["lift"].bodies[0]
    body.addForce((50.0, -30.0, 0.0))  # sideways: the rail holds it
    run(sim, 0.5)
    x, y, z = sim.get_model_state("lift")[0]
    assert (x, y) == pytest.approx((1, 2), abs=1e-3)
    assert z == pytest.approx(0.5 - 0.2, abs=0.02)  # fell along the rail to its lower limit, above the ground
    assert sim.joint_properties("rail")["position"] == [pytest.approx(-0.2, abs=0.02)]


def test_fixed_joints_to_the_world_and_ones_that_hold_no_root_are_refused() -> None:
    with pytest.raises(ModelError, match="fixed joints to the world"):
        parse_sdf_model(LIFT % "fixed")
    two = (LIFT % "prismatic").replace(
        "</model>",
        '<link name="top"><inertial><mass>1</mass></inertial></link><joint name="j" type="revolute">'
        "<parent>car</parent><child>top</child></joint>"
        '<joint name="rail2" type="prismatic"><parent>world</parent><child>top</child></joint></model>',
    )
    with pytest.raises(ModelError, match="must hold the root link"):
        parse_sdf_model(two)


# --- RubblePlugin ----------------------------------------------------------------------------------
def plugin(**tags: str) -> GazeboPlugin:
    given = {"bottom_right": "2 -3 0", "top_left": "8 3 0.5", "min_mass": "0.1", "max_mass": "2", "count": "20"}
    given.update(tags)
    return GazeboPlugin(RUBBLE, "rubble", given)


def test_the_rubble_world_strews_named_pieces() -> None:
    sim = loaded("rubble.world")
    assert list(sim.models) == ["ground_plane"] + [f"rubble_{i}" for i in range(20)]
    run(sim, 1.0)
    assert all(sim.get_model_state(f"rubble_{i}")[0][2] > -0.01 for i in range(20))  # on the ground


@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    low=st.tuples(*(st.floats(-10, 10, allow_subnormal=False) for _ in range(3))),
    extent=st.tuples(*(st.floats(0, 5, allow_subnormal=False) for _ in range(3))),
    count=st.integers(0, 12),
)
def test_every_piece_is_a_board_or_a_cinder_block_inside_the_region(seed, low, extent, count) -> None:
    high = tuple(a + b for a, b in zip(low, extent))
    tags = {"bottom_right": "%r %r %r" % low, "top_left": "%r %r %r" % high, "count": str(count)}
    pieces = rubble(plugin(**tags), random.Random(seed))
    assert [name for name, _, _ in pieces] == [f"rubble_{i}" for i in range(count)]
    for name, model, (x, y, z, roll, pitch, yaw) in pieces:
        (collision,) = model.links["link"].collisions
        size = collision.geometry.size
        assert size == CINDER_BLOCK or (BOARD_LENGTH[0] <= size[0] <= BOARD_LENGTH[1] and size[1:] == BOARD_SECTION)
        assert low[0] <= x <= high[0] and low[1] <= y <= high[1]
        assert z >= low[2] + size[2] / 2 - 1e-12 and z <= max(high[2], low[2] + size[2] / 2)
        assert 0 <= roll <= 3.1415 and -0.1 <= pitch <= 0.1 and 0 <= yaw <= 3.1415
        assert 0.1 <= model.links["link"].inertial.mass <= 2.0


@pytest.mark.parametrize(
    "tags, message",
    [
        ({"count": "2.5"}, "whole number"),
        ({"count": "100000"}, "whole number"),
        ({"min_mass": "3"}, "masses"),
        ({"min_mass": "0"}, "masses"),
        ({"top_left": "1 2"}, "3 numbers"),
        ({"bottom_right": "a b c"}, "bottom_right"),
    ],
)
def test_bad_rubble_tags_are_refused_by_name(tags, message) -> None:
    with pytest.raises(ModelError, match=message):
        rubble(plugin(**tags))


@settings(max_examples=100, deadline=None)
@given(
    floor=st.integers(-(2**31), 2**31 - 1),
    blanks=st.sampled_from(["", " ", "\t "]),
    tail=st.sampled_from(["", "x", " 3"]),
)
def test_floor_numbers_are_read_as_std_stoi_reads_them(floor: int, blanks: str, tail: str) -> None:
    """GazeboRosElevator::OnElevator hands the message to std::stoi: blanks, a sign, digits; the rest ignored."""
    assert floor_number(f"{blanks}{floor}{tail}") == floor
    assert floor_number(f"+{floor}") == (floor if floor >= 0 else None)


@pytest.mark.parametrize("text", ["", "abc", "-", "one", str(2**31), str(-(2**31) - 1)])
def test_text_std_stoi_refuses_is_no_floor(text: str) -> None:
    assert floor_number(text) is None
