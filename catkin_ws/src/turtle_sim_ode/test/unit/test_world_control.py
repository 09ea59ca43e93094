"""Gazebo's world API on Simulation: names and errors, model and link states in reference frames, model
configurations, spawning, worlds and resets (properties: test_world_properties.py; loads: test_world_loads.py)."""
import math

import pytest
from conftest import PACKAGE_ROOT, TURTLEBOT_URDF
from world_helpers import ARM, BOX, YAW_90, floating, run, same_rotation, snapshot

from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.transforms import quat_rotate
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

SDF_BOX = """<sdf version="1.6"><model name="crate"><link name="link"><inertial><mass>2</mass>
<inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
<collision name="c"><geometry><box><size>0.3 0.3 0.3</size></box></geometry></collision>
</link></model></sdf>"""


# --- names and errors --------------------------------------------------------------------------
@pytest.mark.parametrize(
    "call, message",
    [
        (lambda s: s.get_model_state("nobody"), "model 'nobody' does not exist"),
        (lambda s: s.get_model_state("box", "nowhere"), "reference frame 'nowhere' is not a model or link"),
        (lambda s: s.get_link_state("box"), "link 'box' does not exist (links are named 'model::link')"),
        (lambda s: s.get_link_state("box::nolink"), "link 'box::nolink' does not exist"),
        (
            lambda s: s.set_link_state("arm::tip", (0, 0, 0), (0, 0, 0, 1), reference_frame="arm::x"),
            "reference frame 'arm::x' is not a model or link",
        ),
        (lambda s: s.joint_properties("elbow"), "joint 'elbow' does not exist"),
        (lambda s: s.set_model_state("box", (0, 0, math.nan), (0, 0, 0, 1)), "position must be 3 finite numbers"),
        (lambda s: s.set_model_state("box", (0, 0, 1), (0, 0, math.inf, 1)), "orientation must be 4 finite numbers"),
        (
            lambda s: s.set_model_state("box", (0, 0, 1), (0, 0, 0, 1), (1, 2)),
            "linear velocity must be 3 finite numbers",
        ),
        (lambda s: s.model_properties("arm::base"), "model 'arm::base' does not exist"),
        (lambda s: s.delete("ghost"), "model 'ghost' does not exist"),
    ],
)
def test_unknown_names_and_bad_values_raise_and_change_nothing(call, message):
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)), ("arm", ARM, (3, 0, 1, 0, 0, 0)))
    run(sim, 0.01)
    before = snapshot(sim)
    with pytest.raises(WorldError) as error:
        call(sim)
    assert message in str(error.value)
    assert snapshot(sim) == before


def test_world_properties_list_models_in_spawn_order():
    sim = floating(("b", BOX, (0, 0, 1, 0, 0, 0)), ("a", BOX, (1, 0, 1, 0, 0, 0)))
    run(sim, 0.005)
    properties = sim.world_properties()
    assert properties["model_names"] == ["b", "a"] and not properties["rendering_enabled"]
    assert properties["sim_time"] == pytest.approx(0.005)


def test_model_properties_of_the_turtlebot():
    sim = Simulation()
    sim.spawn_urdf("mobile_base", TURTLEBOT_URDF)
    properties = sim.model_properties("mobile_base")
    assert properties["canonical_body_name"] == "base_footprint"
    assert {"base_footprint", "base_link", "wheel_left_link", "caster_back_link"} <= set(properties["body_names"])
    assert properties["joint_names"] == ["wheel_left_joint", "wheel_right_joint"]
    assert properties["geom_names"] and not properties["is_static"]
    assert properties["parent_model_name"] == "" and properties["child_model_names"] == []


# --- states and reference frames -------------------------------------------------------------------
def test_model_state_in_the_world():
    sim = floating(("box", BOX, (1, 2, 3, 0, 0, math.pi / 2)))
    position, quaternion, linear, angular = sim.get_model_state("box", "world")
    assert position == pytest.approx((1, 2, 3)) and same_rotation(quaternion, YAW_90)
    assert linear == pytest.approx((0, 0, 0)) and angular == pytest.approx((0, 0, 0))
    assert sim.get_model_state("box", "/map") == sim.get_model_state("box")


def test_set_model_state_normalises_the_quaternion_and_zero_means_identity():
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)))
    sim.set_model_state("box", (1, 0, 1), (0, 0, 2, 2))
    assert same_rotation(sim.get_model_state("box")[1], YAW_90)
    sim.set_model_state("box", (1, 0, 1), (0, 0, 0, 0))
    assert same_rotation(sim.get_model_state("box")[1], (0, 0, 0, 1))


def test_state_relative_to_a_moving_model_follows_gazebo_ros():
    sim = floating(("a", BOX, (0, 0, 1, 0, 0, math.pi / 2)), ("b", BOX, (1, 0, 1, 0, 0, 0)))
    sim.set_model_state("a", (0, 0, 1), YAW_90, (0, 1, 0), (0, 0, 0.5))
    sim.set_model_state("b", (1, 0, 1), (0, 0, 0, 1), (1, 0, 0), (0, 0, 0))
    position, quaternion, linear, angular = sim.get_model_state("b", "a")
    assert position == pytest.approx((0, -1, 0), abs=1e-12)
    assert same_rotation(quaternion, (0, 0, -math.sqrt(0.5), math.sqrt(0.5)))
    # (v_b - v_a) = (1, -1, 0) and (w_b - w_a) = (0, 0, -0.5), in a's axes.
    assert linear == pytest.approx((-1, -1, 0), abs=1e-12)
    assert angular == pytest.approx((0, 0, -0.5), abs=1e-12)


@pytest.mark.parametrize("frame", ["a", "a::box", "arm::tip"])
def test_set_then_get_relative_to_a_frame_round_trips(frame):
    sim = floating(("a", BOX, (0, 0, 1, 0.3, 0, 1.0)), ("b", BOX, (1, 0, 1, 0, 0, 0)), ("arm", ARM, (3, 0, 1, 0, 0, 0)))
    sim.set_model_state("a", (0, 0, 1), (0.1, 0, 0.3, 1), (0.2, 0.1, 0), (0.1, 0, 0.4))
    state = ((0.5, -0.2, 0.1), (0.0, 0.0, math.sin(0.2), math.cos(0.2)), (0.3, 0.0, -0.1), (0.0, 0.2, 0.1))
    sim.set_model_state("b", *state, reference_frame=frame)
    got = sim.get_model_state("b", frame)
    for value, expected in zip(got[:2], state[:2]):
        assert value == pytest.approx(expected, abs=1e-12)
    # gazebo_ros_api_plugin.cpp, setModelState: the twist is turned into world axes with the frame's rotation only
    # (the frame's own velocity is not added).
    frame_state = sim.get_model_state(frame) if frame == "a" else sim.get_link_state(frame)
    (fx, fy, fz, fw), world = frame_state[1], sim.get_model_state("b")
    for given, value in zip(state[2:], world[2:]):
        assert value == pytest.approx(quat_rotate((fw, fx, fy, fz), given), abs=1e-12)


def test_set_model_state_moves_all_bodies_rigidly():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.set_model_configuration("arm", ["shoulder"], [0.4])
    sim.set_model_state("arm", (2, 0, 1), (0, 0, 0, 1), (0.5, 0, 0), (0, 0, 1.0))
    tip = sim.get_link_state("arm::tip")
    expected_tip = (2 + math.cos(0.4), math.sin(0.4), 1.5)
    assert tip[0] == pytest.approx(expected_tip)
    # v + w x r at the tip's origin.
    assert tip[2] == pytest.approx((0.5 - math.sin(0.4), math.cos(0.4), 0.0))
    assert tip[3] == pytest.approx((0, 0, 1.0))
    run(sim, 0.2)  # spins as one body: the joint does not move
    assert sim.joint_properties("shoulder")["position"][0] == pytest.approx(0.4, abs=1e-4)


def test_set_link_state_of_a_merged_link_moves_its_body_only():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    base_before = sim.get_link_state("arm::base")
    sim.set_link_state("arm::tip", (0.5, 0.5, 2.0), YAW_90, (0, 0, 1), reference_frame="world")
    tip = sim.get_link_state("arm::tip")
    assert tip[0] == pytest.approx((0.5, 0.5, 2.0)) and same_rotation(tip[1], YAW_90)
    assert tip[2] == pytest.approx((0, 0, 1))
    upper = sim.get_link_state("arm::upper")  # fixed to tip: moved with it, turned back, 1 m behind
    assert upper[0] == pytest.approx((-0.5, 0.5, 2.0)) and same_rotation(upper[1], (0, 0, 0, 1))
    assert sim.get_link_state("arm::base") == base_before


def test_link_state_relative_to_its_own_model():
    sim = floating(("arm", ARM, (1, 1, 1, 0, 0, math.pi / 2)))
    position, quaternion, linear, angular = sim.get_link_state("arm::tip", "arm")
    assert position == pytest.approx((1, 0, 0.5)) and same_rotation(quaternion, YAW_90)
    sim.set_link_state("arm::upper", (0, 0, 0.5), (0, 0, 0, 1), (0, 0, 0), (0, 0, 0.2), "arm")
    assert sim.get_link_state("arm::upper", "arm")[3] == pytest.approx((0, 0, 0.2))


def test_static_models_move_but_have_no_bodies_to_push():
    sim = Simulation()
    world = parse_sdf_world((PACKAGE_ROOT / "worlds" / "room.world").read_text())
    sim.load_world(world)
    sim.set_model_state("obstacle_box", (-1, 2, 0.25), (0, 0, 0, 1), (1, 0, 0))
    position, _, linear, _ = sim.get_model_state("obstacle_box")
    assert position == pytest.approx((-1, 2, 0.25)) and linear == (0.0, 0.0, 0.0)
    assert sim.model_properties("walls")["is_static"]
    for call in (
        lambda: sim.link_properties("walls::wall_east"),
        lambda: sim.apply_body_wrench("walls::wall_east", "", (0, 0, 0), (1, 0, 0), (0, 0, 0)),
        lambda: sim.set_link_state("walls::wall_east", (0, 0, 0), (0, 0, 0, 1)),
    ):
        with pytest.raises(WorldError, match="belongs to static model 'walls'"):
            call()


# --- model configuration ---------------------------------------------------------------------
def test_set_model_configuration_moves_the_links_below_the_joints():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    base = sim.get_link_state("arm::base")
    sim.set_model_configuration("arm", ["shoulder", "arm::rail"], [0.7, 0.3])
    c, s = math.cos(0.7), math.sin(0.7)
    assert sim.get_link_state("arm::tip")[0] == pytest.approx((c, s, 1.5))
    assert sim.get_link_state("arm::slide")[0] == pytest.approx((0.8 * c, 0.8 * s, 1.5))
    assert sim.joint_properties("shoulder")["position"][0] == pytest.approx(0.7)
    assert sim.joint_properties("rail")["position"][0] == pytest.approx(0.3)
    assert sim.get_link_state("arm::base") == base
    run(sim, 0.05)
    assert sim.get_link_state("arm::tip")[0] == pytest.approx((c, s, 1.5), abs=1e-6)


def test_set_model_configuration_counts_continuous_turns():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.set_model_configuration("arm", ["spin"], [7.0])
    assert sim.joint_properties("spin")["position"][0] == pytest.approx(7.0)
    assert same_rotation(sim.get_link_state("arm::wheel")[1], (0, math.sin(3.5), 0, math.cos(3.5)))
    run(sim, 0.05)
    assert sim.joint_properties("spin")["position"][0] == pytest.approx(7.0, abs=1e-6)
    sim.set_model_configuration("arm", ["spin"], [-1.0])
    assert sim.joint_properties("spin")["position"][0] == pytest.approx(-1.0)


def test_set_model_configuration_keeps_drive_odometry():
    sim = Simulation()
    sim.spawn_urdf("robot", TURTLEBOT_URDF)
    sim.set_model_configuration("robot", ["wheel_left_joint", "wheel_right_joint"], [1.0, 2.0])
    sim.robots["robot"].update_odometry(sim.sim_time)
    assert sim.robots["robot"].odometry.pose == (0.0, 0.0, 0.0)


@pytest.mark.parametrize(
    "names, positions, message",
    [
        (["shoulder", "elbow"], [0.1, 0.2], "model 'arm' has no joint 'elbow'"),
        (["shoulder"], [0.1, 0.2], "different lengths"),
        (["shoulder"], [math.nan], "position of joint 'shoulder' must be a finite number"),
    ],
)
def test_set_model_configuration_errors_change_nothing(names, positions, message):
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    before = snapshot(sim)
    with pytest.raises(WorldError, match=message):
        sim.set_model_configuration("arm", names, positions)
    assert snapshot(sim) == before


# --- spawning, worlds and resets -------------------------------------------------------------------
def test_spawn_with_a_quaternion_pose_relative_to_a_model():
    sim = floating(("a", BOX, (1, 0, 1, 0, 0, math.pi / 2)))
    warnings = sim.spawn_sdf("crate", SDF_BOX, ((1, 0, 0), (0, 0, 0, 1)), reference_frame="a")
    assert warnings == []
    position, quaternion, _, _ = sim.get_model_state("crate")
    assert position == pytest.approx((1, 1, 1)) and same_rotation(quaternion, YAW_90)
    assert sim.link_properties("crate::link")["mass"] == pytest.approx(2.0)
    with pytest.raises(WorldError, match="reference frame 'b' is not a model or link"):
        sim.spawn_urdf("box", BOX, (0, 0, 0, 0, 0, 0), reference_frame="b")
    with pytest.raises(ModelError, match="must not contain '::'"):
        sim.spawn_urdf("a::b", BOX)
    assert list(sim.models) == ["a", "crate"]


WORLD = """<sdf version="1.6"><world name="w">
  <include><uri>model://ground_plane</uri></include>
  <include><uri>model://table</uri><name>table1</name></include>
  <physics type="ode"><max_step_size>0.002</max_step_size><real_time_factor>2</real_time_factor>
    <ode><solver><iters>30</iters></solver></ode></physics>
  <plugin name="p" filename="libworld_thing.so"/>
  <model name="crate"><pose>1 0 0.5 0 0 0</pose><link name="link"><inertial><mass>2</mass></inertial>
    <collision name="c"><geometry><box><size>0.3 0.3 0.3</size></box></geometry></collision></link></model>
  <model name="MODEL2"><pose>0 1 0.5 0 0 0</pose><link name="link"><inertial><mass>1</mass></inertial>
    </link></model>
</world></sdf>"""


def test_load_world_sets_physics_and_pacing_and_spawns_inline_models():
    sim = Simulation()
    warnings = sim.load_world(parse_sdf_world(WORLD))
    assert warnings == [
        "cannot resolve model://table (model 'table1'): not spawned",
        "world plugin libworld_thing.so (p) is not supported: ignored",
    ]
    properties = sim.physics_properties()
    assert properties["time_step"] == 0.002 and properties["ode_config"]["sor_pgs_iters"] == 30
    assert properties["max_update_rate"] == pytest.approx(1000.0) and sim.real_time_factor == pytest.approx(2.0)
    assert list(sim.models) == ["ground_plane", "crate", "MODEL2"]  # the world's order; the ground plane built in
    assert sim.get_model_state("crate")[0] == pytest.approx((1, 0, 0.5))
    with pytest.raises(WorldError, match=r"load_world needs an empty world, but models \['ground_plane', 'crate'"):
        sim.load_world(parse_sdf_world(WORLD))


def test_load_world_that_fails_leaves_the_world_empty():
    sim = Simulation()
    with pytest.raises(ModelError, match="must not contain"):
        sim.load_world(parse_sdf_world(WORLD.replace("MODEL2", "bad::name")))
    assert sim.models == {} and sim.physics_properties() == Simulation().physics_properties()


def test_reset_world_restores_poses_joints_odometry_and_clears_loads():
    sim = Simulation()
    sim.spawn_urdf("robot", TURTLEBOT_URDF, (1, 0, 0, 0, 0, math.pi / 2))
    sim.spawn_urdf("box", BOX, (0, 2, 0.1, 0, 0, 0))
    start = {name: sim.get_model_state(name) for name in sim.models}
    robot = sim.robots["robot"]
    robot.drive.set_command(0.3, 0.5, sim.sim_time)
    sim.apply_body_wrench("box::box", "", (0, 0, 0), (0, 0, 20), (0, 0, 0))
    run(sim, 0.5)
    robot.update_odometry(sim.sim_time)
    assert robot.odometry.x > 0.05 and sim.joint_properties("wheel_left_joint")["position"][0] > 1
    wheel = sim.joint_properties("wheel_left_joint")["position"][0]
    sim.set_link_properties("robot::base_footprint", (0, 0, 0.05), (0, 0, 0, 1), True, 3.0, (0.05, 0, 0, 0.05, 0, 0.05))
    assert sim.joint_properties("wheel_left_joint")["position"][0] == pytest.approx(wheel, abs=1e-12)
    sim.reset_world()
    for name, (position, quaternion, _, _) in start.items():
        state = sim.get_model_state(name)
        assert state[0] == pytest.approx(position, abs=1e-12) and same_rotation(state[1], quaternion)
        assert state[2] == pytest.approx((0, 0, 0)) and state[3] == pytest.approx((0, 0, 0))
    assert sim.joint_properties("wheel_left_joint")["position"][0] == pytest.approx(0.0, abs=1e-9)
    assert robot.drive.command == (0.0, 0.0) and sim.loads == []
    assert sim.sim_time == pytest.approx(0.5)
    run(sim, 0.3)
    robot.update_odometry(sim.sim_time)
    assert abs(robot.odometry.x) < 1e-3 and abs(robot.odometry.yaw) < 1e-3


def test_reset_simulation_also_restarts_time():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.set_model_configuration("arm", ["spin", "shoulder"], [9.0, 1.0])
    run(sim, 0.1)
    sim.reset_simulation()
    assert sim.sim_time == 0.0
    assert sim.joint_properties("spin")["position"][0] == pytest.approx(0.0, abs=1e-9)
    assert sim.get_link_state("arm::tip")[0] == pytest.approx((1, 0, 1.5), abs=1e-12)
    run(sim, 0.01)
    assert sim.sim_time == pytest.approx(0.01)
