"""Gazebo's per-link surface parameters (minDepth, maxVel, kp, kd, mu1, mu2, fdir1, slip1, slip2) from URDF
<gazebo reference> blocks and SDF <surface>: read, validated, and acting as Gazebo's ODE makes them act.

The burger (test/models/burger.urdf, written as turtlebot3_description writes its burger) in a world with
TurtleBot3's physics block (test/worlds/tb3_physics.world: a 1 cm contact surface layer) must drive as it does in
Gazebo: its wheels' minDepth 1 mm replaces the world's 1 cm, so it stays on its wheels."""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from conftest import TURTLEBOT_URDF

from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboSurface
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.physics.world import seed_ode_random
from turtle_sim_ode.world.simulation import Simulation

TEST_ROOT = Path(__file__).resolve().parents[1]
BURGER_URDF = (TEST_ROOT / "models" / "burger.urdf").read_text()
TB3_WORLD = (TEST_ROOT / "worlds" / "tb3_physics.world").read_text()
SPEED = 0.2  # m/s, for 5 s
EXPECTED_DISTANCE = 1.0
DISTANCE_TOLERANCE = 0.03


def _drive_burger(urdf: str, kernel: bool = True):
    """Settle 1 s, drive straight at SPEED for 5 s; (distance driven, base_footprint heights, trace of poses)."""
    seed_ode_random()
    sim = Simulation(contact_kernel=kernel)
    assert sim.load_world(parse_sdf_world(TB3_WORLD)) == [
        "<physics> <ode/solver/use_dynamic_moi_rescaling> 1 is not simulated, ignored"
    ]
    assert sim.physics.params.sor == 1.4
    sim.spawn_urdf("burger", urdf)
    robot, model = sim.robots["burger"], sim.models["burger"]
    robot.params.cmd_timeout = 0.0
    for _ in range(1000):
        sim.step()
    start = model.link_pose("base_footprint")[0]
    robot.drive.set_command(SPEED, 0.0, sim.sim_time)
    trace = []
    for _ in range(5000):
        sim.step()
        trace.append(model.link_pose("base_footprint"))
    end = trace[-1][0]
    return math.dist(start[:2], end[:2]), (start[2], end[2]), trace


def test_the_burger_drives_in_turtlebot3s_world_as_in_gazebo():
    distance, heights, _ = _drive_burger(BURGER_URDF)
    assert distance == pytest.approx(EXPECTED_DISTANCE, abs=DISTANCE_TOLERANCE)
    # On its wheels, 1 mm (their minDepth) into the ground, not 1 cm (the world's surface layer).
    assert all(-0.002 < z < 0.0 for z in heights)


def test_without_its_links_min_depth_the_burger_sinks_onto_its_base_and_sticks():
    """What the world's values alone do (the bug of issue 14): the reason the per-link values matter."""
    urdf = re.sub(r"<minDepth>[^<]*</minDepth>|<maxVel>[^<]*</maxVel>", "", BURGER_URDF)
    distance, heights, _ = _drive_burger(urdf)
    assert distance < 0.05
    assert heights[1] < -0.005


def test_burger_in_turtlebot3s_world_is_bitwise_equal_in_kernel_and_python():
    """minDepth, maxVel and fdir1 (turned with the spinning wheel each step) on both paths."""
    assert _drive_burger(BURGER_URDF, True)[2][:1500] == _drive_burger(BURGER_URDF, False)[2][:1500]


def test_urdf_surface_tags_are_read():
    robot = parse_urdf(BURGER_URDF)
    assert robot.surfaces["wheel_left_link"] == GazeboSurface(
        mu1=0.1, mu2=0.1, kp=500000.0, kd=10.0, max_vel=0.1, min_depth=0.001, fdir1=(1.0, 0.0, 0.0)
    )
    urdf = BURGER_URDF.replace("<maxVel>1.0</maxVel>", "<maxVel>1.0</maxVel><slip1>0.5</slip1><slip2>0.25</slip2>")
    caster = parse_urdf(urdf).surfaces["caster_back_link"]
    assert (caster.slip1, caster.slip2, caster.fdir1) == (0.5, 0.25, None)


@pytest.mark.parametrize(
    "tag, value",
    [
        ("minDepth", "-0.001"),
        ("maxVel", "-0.1"),
        ("maxVel", "nan"),
        ("kp", "0"),
        ("kd", "-1"),
        ("mu1", "inf"),
        ("slip1", "-0.5"),
        ("fdir1", "1 0"),
        ("fdir1", "1 nan 0"),
    ],
)
def test_bad_urdf_surface_values_are_refused_naming_link_and_tag(tag, value):
    block = '<gazebo reference="wheel_left_link">'
    urdf = BURGER_URDF.replace(block, f"{block}<{tag}>{value}</{tag}>", 1)
    with pytest.raises(ModelError, match=rf"wheel_left_link.*<{tag}>"):
        parse_urdf(urdf)


def _sdf_link(surface: str) -> str:
    return (
        '<sdf version="1.6"><model name="m"><link name="wheel"><inertial><mass>1</mass></inertial>'
        '<collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry>'
        f"<surface>{surface}</surface></collision></link></model></sdf>"
    )


def test_sdf_surface_values_are_read():
    robot = parse_sdf_model(
        _sdf_link(
            "<friction><ode><mu>0.3</mu><mu2>0.2</mu2><fdir1>0 1 0</fdir1><slip1>0.1</slip1><slip2>0.2</slip2>"
            "</ode></friction><contact><ode><kp>1e6</kp><kd>50</kd><max_vel>0.5</max_vel>"
            "<min_depth>0.002</min_depth></ode></contact>"
        )
    )
    assert robot.surfaces["wheel"] == GazeboSurface(
        mu1=0.3, mu2=0.2, kp=1e6, kd=50.0, max_vel=0.5, min_depth=0.002, fdir1=(0.0, 1.0, 0.0), slip1=0.1, slip2=0.2
    )


@pytest.mark.parametrize(
    "surface, tag",
    [
        ("<contact><ode><min_depth>-1</min_depth></ode></contact>", "min_depth"),
        ("<contact><ode><max_vel>nan</max_vel></ode></contact>", "max_vel"),
        ("<friction><ode><slip2>-1</slip2></ode></friction>", "slip2"),
        ("<friction><ode><fdir1>0 0</fdir1></ode></friction>", "fdir1"),
    ],
)
def test_bad_sdf_surface_values_are_refused_naming_link_and_tag(surface, tag):
    with pytest.raises(ModelError, match=rf"link 'wheel'.*{tag}"):
        parse_sdf_model(_sdf_link(surface))


def test_turtlebot2_keeps_its_links_min_depth():
    """The TurtleBot 2 description's wheels and casters say minDepth 1 mm: it rests 1 mm into the ground."""
    sim = Simulation()
    sim.spawn_urdf("mobile_base", TURTLEBOT_URDF)
    for _ in range(1000):
        sim.step()
    assert sim.models["mobile_base"].link_pose("base_footprint")[0][2] == pytest.approx(-0.001, abs=2e-4)


def test_tags_that_are_not_simulated_are_named_in_warnings():
    urdf = BURGER_URDF.replace(
        '<gazebo reference="caster_back_link">',
        '<gazebo reference="caster_back_link"><material>Gazebo/FlatBlack</material><selfCollide>true</selfCollide>'
        "<dampingFactor>0.1</dampingFactor>",
    ).replace("</robot>", "<gazebo><static>false</static></gazebo></robot>")
    warnings = parse_urdf(urdf).warnings
    assert "<gazebo reference='caster_back_link'> <selfCollide> is not simulated, ignored" in warnings
    assert "<gazebo reference='caster_back_link'> <dampingFactor> is not simulated, ignored" in warnings
    assert "<gazebo> <static> is not simulated, ignored" in warnings
    assert not any("material" in warning for warning in warnings)  # drawing only
    assert parse_urdf(BURGER_URDF).warnings == []
    robot = parse_sdf_model(
        _sdf_link(
            "<bounce><restitution_coefficient>0.5</restitution_coefficient></bounce><friction><ode><mu>1</mu>"
        ).replace("</surface>", "</ode><torsional><coefficient>1</coefficient></torsional></friction></surface>")
    )
    assert robot.warnings == [
        "link 'wheel' collision 'c' <surface> <bounce/restitution_coefficient> is not simulated, ignored",
        "link 'wheel' collision 'c' <surface> <friction/torsional/coefficient> is not simulated, ignored",
    ]
