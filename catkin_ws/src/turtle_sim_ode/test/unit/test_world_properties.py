"""Gazebo's world API on Simulation: link, joint and physics properties, read and set."""
import math

import pytest
from conftest import TURTLEBOT_URDF
from world_helpers import ARM, BOX, YAW_90, floating, inertial, run

from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.trimesh import quickstep_w
from turtle_sim_ode.world.properties import CONTINUOUS, PRISMATIC, REVOLUTE
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

# No continuous joint and no damping: the model starts without a post-step hook.
PENDULUM = f"""<robot name="pendulum">
  <link name="base">{inertial(100.0, moment=100.0)}</link>
  <link name="bar">{inertial(1.0, "0.5 0 0")}</link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="bar"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""


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
