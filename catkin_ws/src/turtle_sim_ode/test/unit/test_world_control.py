"""Gazebo's world API on Simulation: states, frames, properties, physics, configuration, loads, resets."""
import math

import pytest

from turtle_sim_ode.physics.trimesh import quickstep_w
from conftest import PACKAGE_ROOT, TURTLEBOT_URDF

from turtle_sim_ode.models.transforms import quat_rotate
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.world.properties import CONTINUOUS, PRISMATIC, REVOLUTE
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

NO_GRAVITY = PhysicsParams(gravity=(0.0, 0.0, 0.0))
YAW_90 = (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))  # (x, y, z, w)


def inertial(mass, xyz="0 0 0", moment=0.1):
    return (
        f'<inertial><mass value="{mass}"/><origin xyz="{xyz}"/><inertia ixx="{moment}" ixy="0" '
        f'ixz="0" iyy="{moment}" iyz="0" izz="{moment}"/></inertial>'
    )


BOX = f"""<robot name="box"><link name="box">{inertial(1.0)}
<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>"""

# A heavy base; "upper" turns about z 0.5 m up, with "tip" fixed 1 m along it (turned 90 degrees)
# and "slide" on a rail along it; "wheel" spins about y beside the base.
ARM = f"""<robot name="arm">
  <link name="base">{inertial(10.0, moment=10.0)}</link>
  <link name="upper">{inertial(1.0, "0.5 0 0")}</link>
  <link name="tip">{inertial(0.5)}</link>
  <link name="slide">{inertial(0.3)}</link>
  <link name="wheel">{inertial(0.2, moment=0.01)}</link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="tip_joint" type="fixed"><parent link="upper"/><child link="tip"/>
    <origin xyz="1 0 0" rpy="0 0 {math.pi / 2}"/></joint>
  <joint name="rail" type="prismatic"><parent link="upper"/><child link="slide"/>
    <origin xyz="0.5 0 0"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/>
    <origin xyz="0 -0.5 0"/><axis xyz="0 1 0"/></joint>
</robot>"""

# No continuous joint and no damping: the model starts without a post-step hook.
PENDULUM = f"""<robot name="pendulum">
  <link name="base">{inertial(100.0, moment=100.0)}</link>
  <link name="bar">{inertial(1.0, "0.5 0 0")}</link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="bar"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""

SDF_BOX = """<sdf version="1.6"><model name="crate"><link name="link"><inertial><mass>2</mass>
<inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
<collision name="c"><geometry><box><size>0.3 0.3 0.3</size></box></geometry></collision>
</link></model></sdf>"""


def run(sim, seconds):
    for _ in range(round(seconds / sim.physics.time_step)):
        sim.step()


def same_rotation(q1, q2):
    return abs(sum(a * b for a, b in zip(q1, q2))) == pytest.approx(1.0, abs=1e-9)


def floating(*models):
    """A zero-gravity world with (name, urdf, pose) models."""
    sim = Simulation(NO_GRAVITY)
    for name, urdf, pose in models:
        sim.spawn_urdf(name, urdf, pose)
    return sim


def snapshot(sim):
    """Everything a failed request must leave alone."""
    return (
        {name: [sim.get_link_state(f"{name}::{link}") for link in model.links] for name, model in sim.models.items()},
        sim.physics_properties(),
        list(sim.loads),
        sim.sim_time,
    )


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


# --- link and joint properties -------------------------------------------------------------------
def test_link_properties_are_the_merged_body_in_the_link_frame():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    upper = sim.link_properties("arm::upper")
    assert upper["mass"] == pytest.approx(1.5) and upper["gravity_mode"]
    assert upper["com_position"] == pytest.approx((2 / 3, 0, 0)) and upper["com_orientation"] == (0, 0, 0, 1)
    assert (upper["ixx"], upper["iyy"], upper["izz"]) == pytest.approx(
        (0.2, 0.2 + 1 / 36 + 0.5 / 9, 0.2 + 1 / 36 + 0.5 / 9)
    )
    tip = sim.link_properties("arm::tip")  # same body, seen from a frame turned 90 degrees
    assert tip["mass"] == pytest.approx(1.5)
    assert tip["com_position"] == pytest.approx((0, 1 / 3, 0), abs=1e-12)
    assert (tip["ixx"], tip["iyy"]) == pytest.approx((upper["iyy"], upper["ixx"]))


def test_set_link_properties_moves_the_com_but_not_the_links_or_joints():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.set_model_configuration("arm", ["shoulder", "rail"], [0.5, 0.2])
    links = {link: sim.get_link_state(f"arm::{link}")[:2] for link in sim.models["arm"].links}
    sim.set_link_properties("arm::upper", (0.2, 0.1, 0), YAW_90, False, 2.0, (0.1, 0, 0, 0.3, 0, 0.4))
    upper = sim.link_properties("arm::upper")
    assert upper["mass"] == pytest.approx(2.0) and not upper["gravity_mode"]
    assert upper["com_position"] == pytest.approx((0.2, 0.1, 0))
    assert (upper["ixx"], upper["iyy"], upper["izz"]) == pytest.approx((0.3, 0.1, 0.4))  # turned by the COM frame
    for link, (position, quaternion) in links.items():
        assert sim.get_link_state(f"arm::{link}")[0] == pytest.approx(position, abs=1e-12)
    assert sim.joint_properties("shoulder")["position"][0] == pytest.approx(0.5)
    assert sim.joint_properties("rail")["position"][0] == pytest.approx(0.2)
    run(sim, 0.1)  # joints still hold their frames: nothing drifts
    for link, (position, _) in links.items():
        assert sim.get_link_state(f"arm::{link}")[0] == pytest.approx(position, abs=1e-6)


@pytest.mark.parametrize(
    "mass, inertia, message",
    [
        (0.0, (0.1, 0, 0, 0.1, 0, 0.1), "mass must be > 0"),
        (1.0, (0.1, 0.2, 0, 0.1, 0, 0.1), "inertia must be positive definite"),
        (1.0, (0.1, 0, 0, math.nan, 0, 0.1), "inertia .* must be 6 finite numbers"),
    ],
)
def test_set_link_properties_rejects_bad_mass_properties(mass, inertia, message):
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)))
    before = sim.link_properties("box::box")
    with pytest.raises(WorldError, match=message):
        sim.set_link_properties("box::box", (0, 0, 0), (0, 0, 0, 1), True, mass, inertia)
    assert sim.link_properties("box::box") == before


def test_joint_properties_types_positions_and_rates():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.spawn_urdf("robot", TURTLEBOT_URDF, (5, 0, 0, 0, 0, 0))
    assert sim.joint_properties("shoulder")["type"] == REVOLUTE
    assert sim.joint_properties("arm::rail")["type"] == PRISMATIC
    wheel = sim.joint_properties("robot::wheel_left_joint")
    assert wheel["type"] == CONTINUOUS and wheel["damping"] == [0.0]
    assert wheel["position"] == [pytest.approx(0.0)] and len(wheel["rate"]) == 1


def test_set_joint_properties_sets_ode_params_and_limits_motion():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    # lists as in gazebo_msgs/ODEJointProperties (first entry used) or plain numbers
    sim.set_joint_properties("arm::shoulder", hiStop=[0.2, 9.0], loStop=-0.2, stop_erp=[0.5], fudge_factor=0.5, cfm=[])
    joint = sim.models["arm"].joints["shoulder"].joint
    assert joint.getParam(oc.PARAM_HI_STOP) == 0.2 and joint.getParam(oc.PARAM_LO_STOP) == -0.2
    assert joint.getParam(oc.PARAM_STOP_ERP) == 0.5 and joint.getParam(oc.PARAM_FUDGE_FACTOR) == 0.5
    sim.apply_joint_effort("shoulder", 1.0)
    run(sim, 1.0)
    assert sim.joint_properties("shoulder")["position"][0] == pytest.approx(0.2, abs=0.01)
    sim.set_joint_properties("spin", vel=2.0, fmax=10.0)  # a velocity motor
    run(sim, 0.5)
    assert sim.joint_properties("spin")["rate"][0] == pytest.approx(2.0, abs=1e-3)


def test_set_joint_damping_slows_a_joint_down():
    sim = floating(("pendulum", PENDULUM, (0, 0, 1, 0, 0, 0)))
    sim.apply_joint_effort("hinge", 0.5, duration=0.2)
    run(sim, 0.2)
    rate = sim.joint_properties("hinge")["rate"][0]
    assert rate > 0.1
    sim.set_joint_properties("hinge", damping=[0.5])
    assert sim.joint_properties("hinge")["damping"] == [0.5]
    run(sim, 0.5)
    assert 0 < sim.joint_properties("hinge")["rate"][0] < 0.9 * rate
    sim.set_joint_properties("hinge", damping=[0.0])
    assert sim.joint_properties("hinge")["damping"] == [0.0]


@pytest.mark.parametrize(
    "values, message",
    [
        ({"loStop": [0.5], "hiStop": [0.1]}, "loStop 0.5 must not exceed hiStop 0.1"),
        ({"erp": 2.0}, r"erp must be in \[0, 1\]"),
        ({"fmax": [math.nan]}, "fmax must be a finite number"),
        ({"damping": [-1.0]}, "damping must be >= 0"),
        ({"hiStop": [math.nan]}, "hiStop must be a number"),
    ],
)
def test_set_joint_properties_rejects_bad_values(values, message):
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    joint = sim.models["arm"].joints["shoulder"].joint
    params = [joint.getParam(p) for p in range(14)]
    with pytest.raises(WorldError, match=message):
        sim.set_joint_properties("shoulder", **values)
    assert [joint.getParam(p) for p in range(14)] == params


# --- physics ---------------------------------------------------------------------------------
def physics_arguments(properties, **changes):
    """set_physics_properties keywords from a physics_properties() dict, with ``changes``."""
    config = dict(properties["ode_config"])
    arguments = {
        "time_step": properties["time_step"],
        "max_update_rate": properties["max_update_rate"],
        "gravity": properties["gravity"],
        "iterations": config.pop("sor_pgs_iters"),
    }
    arguments.update(config)
    arguments.update(changes)
    return arguments


def test_physics_properties_report_the_world():
    assert Simulation().physics_properties() == {
        "time_step": 0.001,
        "max_update_rate": 1000.0,
        "gravity": (0.0, 0.0, -9.81),
        "ode_config": {
            "auto_disable_bodies": False,
            "sor_pgs_precon_iters": 0,
            "sor_pgs_iters": 50,
            "sor_pgs_w": 1.3,
            "sor_pgs_rms_error_tol": 0.0,
            "contact_surface_layer": 0.0001,
            "contact_max_correcting_vel": 0.1,
            "cfm": 1e-5,
            "erp": 0.2,
            "max_contacts": 4,
        },
    }


def test_set_physics_properties_applies_to_the_live_world():
    sim = Simulation()
    sim.spawn_urdf("box", BOX, (0, 0, 5, 0, 0, 0))
    arguments = physics_arguments(
        sim.physics_properties(),
        max_update_rate=500.0,
        gravity=(0.0, 0.0, -1.0),
        iterations=20,
        erp=0.5,
        cfm=1e-4,
        max_contacts=10,
    )
    assert sim.set_physics_properties(**arguments) == []
    world = sim.physics.world
    assert world.getGravity() == (0.0, 0.0, -1.0) and world.getQuickStepNumIterations() == 20
    assert world.getERP() == 0.5 and world.getCFM() == pytest.approx(1e-4)
    assert physics_arguments(sim.physics_properties()) == arguments
    assert sim.max_update_rate == 500.0 and sim.real_time_factor == pytest.approx(0.5)
    run(sim, 0.1)
    assert sim.get_model_state("box")[2][2] == pytest.approx(-0.1)


def test_time_step_change_keeps_sim_time_continuous():
    sim = Simulation()
    sim.spawn_urdf("robot", TURTLEBOT_URDF)
    run(sim, 0.01)
    sim.set_physics_properties(**physics_arguments(sim.physics_properties(), time_step=0.002))
    assert sim.sim_time == pytest.approx(0.01) and sim.physics_properties()["time_step"] == 0.002
    for _ in range(5):
        sim.step()
    assert sim.sim_time == pytest.approx(0.02)
    height = sim.get_model_state("robot")[0][2]
    run(sim, 0.2)  # contacts recomputed for the new step: the robot still rests on its wheels
    assert sim.get_model_state("robot")[0][2] == pytest.approx(height, abs=1e-3)
    sim.reset_simulation()
    assert sim.sim_time == 0.0


@pytest.mark.parametrize(
    "change, message",
    [
        ({"time_step": 0.0}, r"time_step must be in \(0, 0.1\]"),
        ({"gravity": (0.0, math.nan, -9.81)}, "gravity must be 3 finite numbers"),
        ({"iterations": 10**6}, r"iterations must be an integer in 1..1000"),
        ({"erp": 2.0}, r"erp must be in \[0, 1\]"),
        ({"max_contacts": 2.5}, "max_contacts must be an integer"),
        ({"max_update_rate": -1.0}, "max_update_rate must be >= 0"),
        ({"sor_pgs_w": math.inf}, "sor_pgs_w must be a finite number"),
    ],
)
def test_set_physics_properties_rejects_bad_values_and_changes_nothing(change, message):
    sim = Simulation()
    sim.spawn_urdf("box", BOX, (0, 0, 0.1, 0, 0, 0))
    before = sim.physics_properties()
    with pytest.raises(WorldError, match=message):
        sim.set_physics_properties(**physics_arguments(before, **change))
    assert sim.physics_properties() == before
    assert sim.physics.world.getGravity() == before["gravity"]


def test_set_physics_properties_warns_about_settings_it_keeps():
    sim = Simulation()
    arguments = physics_arguments(sim.physics_properties(), auto_disable_bodies=True, sor_pgs_w=1.0)
    # Issue 14: the SOR factor is applied (Gazebo's <sor>); it was fixed at 1.3 with a warning.
    assert sim.set_physics_properties(**arguments) == ["auto_disable_bodies is not supported: bodies stay enabled"]
    assert sim.physics_properties()["ode_config"]["sor_pgs_w"] == 1.0 and quickstep_w(sim.physics.world) == 1.0


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


# --- wrenches and efforts ---------------------------------------------------------------------
def test_wrench_of_10_newtons_for_half_a_second_on_1_kg():
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)))
    sim.apply_body_wrench("box::box", "", (0, 0, 0), (10, 0, 0), (0, 0, 0), 0.0, 0.5)
    run(sim, 0.8)
    assert sim.get_model_state("box")[2] == pytest.approx((5.0, 0, 0), abs=1e-9)
    assert sim.get_model_state("box")[3] == pytest.approx((0, 0, 0), abs=1e-12)
    assert sim.loads == []  # ended: dropped, so steps do no load work again


def test_wrench_frame_axes_and_reference_point():
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, math.pi / 2)))
    # +x of the yawed box is world +y; 0.1 m to the side of the COM the push also turns it.
    sim.apply_body_wrench("box::box", "box", (0, 0.1, 0), (10, 0, 0), (0, 0, 0.5), duration=0.1)
    run(sim, 0.1)
    _, _, linear, angular = sim.get_model_state("box", "world")
    assert linear == pytest.approx((0, 1.0, 0), abs=1e-9)
    # torque (0, 0, 0.5) + r x F = (0, 0, 0.5 - 1) in the box frame, about world z; I = 0.1
    assert angular == pytest.approx((0, 0, -0.5), abs=1e-9)


def test_wrench_in_another_frame_adds_its_lever():
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)), ("marker", BOX, (0, 1, 1, 0, 0, 0)))
    sim.apply_body_wrench("box::box", "marker", (0, 0, 0), (1, 0, 0), (0, 0, 0), duration=0.1)
    run(sim, 0.1)
    # force at the marker's origin, 1 m beside the box: torque (0, 1, 0) x (1, 0, 0) = (0, 0, -1)
    assert sim.get_model_state("box")[3] == pytest.approx((0, 0, -1.0), abs=1e-9)


def test_wrench_scheduling_start_time_zero_duration_and_clearing():
    sim = floating(
        ("late", BOX, (0, 0, 1, 0, 0, 0)), ("once", BOX, (2, 0, 1, 0, 0, 0)), ("forever", BOX, (4, 0, 1, 0, 0, 0))
    )
    sim.apply_body_wrench("late::box", "", (0, 0, 0), (10, 0, 0), (0, 0, 0), 0.05, 0.05)
    sim.apply_body_wrench("once::box", "", (0, 0, 0), (10, 0, 0), (0, 0, 0), 0.0, 0.0)
    sim.apply_body_wrench("forever::box", "world", (0, 0, 0), (10, 0, 0), (0, 0, 0), -3.0, -1.0)
    run(sim, 0.05)
    assert sim.get_model_state("late")[2][0] == 0.0
    assert sim.get_model_state("once")[2][0] == pytest.approx(0.01)  # one step
    run(sim, 0.15)
    assert sim.get_model_state("late")[2][0] == pytest.approx(0.5)
    sim.clear_body_wrenches("forever::box")
    run(sim, 0.1)
    assert sim.get_model_state("forever")[2][0] == pytest.approx(2.0)
    assert sim.loads == []


def test_joint_effort_spins_a_wheel_for_its_duration():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.apply_joint_effort("arm::spin", 0.01, start_time=0.0, duration=0.2)
    run(sim, 0.2)
    rate = sim.joint_properties("spin")["rate"][0]
    assert rate == pytest.approx(0.2, rel=0.05)  # 0.01 N m on about 0.01 kg m^2, for 0.2 s
    run(sim, 0.2)
    assert sim.joint_properties("spin")["rate"][0] == pytest.approx(rate, rel=1e-3)  # no effort now
    assert sim.joint_properties("spin")["position"][0] > 0.05


def test_prismatic_effort_pushes_along_the_rail():
    sim = floating(("arm", ARM, (0, 0, 1, 0, 0, 0)))
    sim.apply_joint_effort("rail", 0.3, duration=0.1)
    run(sim, 0.1)
    assert sim.joint_properties("rail")["rate"][0] > 0.05


def test_clear_joint_forces_unscoped_clears_every_model():
    sim = floating(("a", ARM, (0, 0, 1, 0, 0, 0)), ("b", ARM, (5, 0, 1, 0, 0, 0)))
    sim.apply_joint_effort("a::spin", 0.01)
    sim.apply_joint_effort("b::spin", 0.01)
    sim.clear_joint_forces("b::spin")
    assert [(load.model, load.target) for load in sim.loads] == [("a", "spin")]
    sim.apply_joint_effort("b::spin", 0.01)
    sim.clear_joint_forces("spin")
    assert sim.loads == []


@pytest.mark.parametrize(
    "call, message",
    [
        (
            lambda s: s.apply_body_wrench("box::box", "", (0, 0, 0), (math.nan, 0, 0), (0, 0, 0)),
            "force must be 3 finite numbers",
        ),
        (
            lambda s: s.apply_body_wrench("box::box", "", (0, 0, 0), (1, 0, 0), (0, 0, 0), math.inf),
            "start_time must be a finite number",
        ),
        (
            lambda s: s.apply_body_wrench("box::box", "sky", (0, 0, 0), (1, 0, 0), (0, 0, 0)),
            "reference frame 'sky' is not a model or link",
        ),
        (lambda s: s.apply_body_wrench("box", "", (0, 0, 0), (1, 0, 0), (0, 0, 0)), "link 'box' does not exist"),
        (lambda s: s.apply_joint_effort("arm::spin", 1.0, 0.0, math.nan), "duration must be a finite number"),
        (lambda s: s.apply_joint_effort("wheel", 1.0), "joint 'wheel' does not exist"),
        (lambda s: s.clear_joint_forces("nothing"), "joint 'nothing' does not exist"),
        (lambda s: s.clear_body_wrenches("arm::nothing"), "link 'arm::nothing' does not exist"),
    ],
)
def test_bad_loads_are_refused(call, message):
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)), ("arm", ARM, (3, 0, 1, 0, 0, 0)))
    sim.apply_joint_effort("arm::spin", 0.01)
    before = list(sim.loads)
    with pytest.raises(WorldError, match=message):
        call(sim)
    assert sim.loads == before


def test_huge_duration_lasts_and_delete_drops_the_loads():
    sim = floating(("box", BOX, (0, 0, 1, 0, 0, 0)), ("arm", ARM, (3, 0, 1, 0, 0, 0)))
    sim.apply_body_wrench("box::box", "", (0, 0, 0), (1, 0, 0), (0, 0, 0), 1e9, 1e300)
    sim.apply_joint_effort("arm::spin", 0.01, 0.0, 1e300)
    run(sim, 0.01)
    assert len(sim.loads) == 2
    sim.delete("arm")
    assert [load.model for load in sim.loads] == ["box"]
    sim.delete("box")
    assert sim.loads == []
    sim.step()


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
