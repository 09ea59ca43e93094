"""SDF models: parsing, conversion to the URDF-style tree (joint axes, link poses, nested models), and building them
(errors: test_sdf_errors.py; worlds: test_sdf_world.py)."""
import dataclasses
import math
import random

import pytest
from conftest import TURTLEBOT_URDF
from sdf_helpers import box_collision, inertial, link, model, sdf

from turtle_sim_ode.models.builder import build_model
from turtle_sim_ode.models.description import Box, Mesh, Pose
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_parts import PLANE_THICKNESS
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.transforms import compose, inverse, pose_transform, quat_from_rpy
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.surfaces import SurfaceParams
from turtle_sim_ode.physics.world import PhysicsWorld

NO_GRAVITY = PhysicsParams(gravity=(0.0, 0.0, 0.0))

# base at the model origin; arm 1 m ahead, hinged 0.5 m behind its origin (joint pose).
ARM = model(
    "arm",
    link("base", extra=inertial(10.0, 10.0)),
    link("arm", "1 0 0 0 0 0"),
    '<joint name="hinge" type="revolute"><parent>base</parent><child>arm</child>'
    "<pose>-0.5 0 0 0 0 0</pose><axis><xyz>0 0 1</xyz>"
    "<limit><lower>-0.5</lower><upper>0.5</upper><effort>3</effort></limit>"
    "<dynamics><damping>0.1</damping><friction>0</friction></dynamics></axis></joint>",
)


# --- models ------------------------------------------------------------------------------
def test_two_link_revolute_model_moves_and_stops_at_its_limit():
    robot = parse_sdf_model(sdf(ARM))
    hinge = robot.joints["hinge"]
    assert (hinge.type, hinge.limits.upper, hinge.limits.effort) == ("revolute", 0.5, 3.0)
    assert hinge.origin.xyz == (1.0, 0.0, 0.0) and hinge.frame.xyz == (-0.5, 0.0, 0.0)
    physics = PhysicsWorld(NO_GRAVITY)
    built = build_model(physics, robot, (0.0, 0.0, 1.0, 0.0, 0.0, math.pi / 2))
    joint = built.joint("hinge")
    assert joint.joint.getAnchor() == pytest.approx((0.0, 0.5, 1.0))  # the joint pose
    assert joint.joint.getAxis() == pytest.approx((0.0, 0.0, 1.0))
    joint.joint.setParam(oc.PARAM_VEL, 1.0)
    joint.joint.setParam(oc.PARAM_FMAX, 100.0)
    for _ in range(200):
        physics.step()
    assert joint.rate() == pytest.approx(1.0, rel=1e-3)
    assert joint.angle() == pytest.approx(0.2, abs=0.01)
    # In the base frame, the arm origin swings about the anchor 0.5 m ahead of the base.
    arm = compose(inverse(built.link_transform("base")), built.link_transform("arm"))[0]
    angle = joint.angle()
    assert arm == pytest.approx((0.5 + 0.5 * math.cos(angle), 0.5 * math.sin(angle), 0.0), abs=1e-5)
    for _ in range(1000):
        physics.step()
    assert joint.angle() == pytest.approx(0.5, abs=0.02)


@pytest.mark.parametrize("limit", ["", "<limit><lower>-1e16</lower><upper>1e16</upper></limit>"])
def test_unlimited_revolute_is_continuous(limit):
    robot = parse_sdf_model(
        sdf(
            model(
                "m",
                link("a"),
                link("b"),
                f'<joint name="j" type="revolute"><parent>a</parent><child>b</child>'
                f"<axis><xyz>0 1 0</xyz>{limit}</axis></joint>",
            )
        )
    )
    assert robot.joints["j"].type == "continuous"


# The child link is yawed 90 degrees and the joint frame rolled 90 degrees in it, so the
# model's x axis is the joint frame's z axis; spawned yawed 90 degrees, that is world y.
@pytest.mark.parametrize(
    "version, axis",
    [
        ("1.4", "<xyz>1 0 0</xyz>"),
        ("1.5", "<xyz>1 0 0</xyz><use_parent_model_frame>true</use_parent_model_frame>"),
        ("1.5", "<xyz>0 0 1</xyz>"),
        ("1.6", "<xyz>0 0 1</xyz>"),
        ("1.7", "<xyz>0 0 1</xyz>"),
        ("1.7", '<xyz expressed_in="__model__">1 0 0</xyz>'),
        ("1.7", '<xyz expressed_in="b">0 -1 0</xyz>'),
    ],
)
def test_axis_conventions_of_sdf_versions_give_the_same_world_axis(version, axis):
    text = sdf(
        model(
            "m",
            link("a"),
            link("b", f"1 0 0 0 0 {math.pi / 2}"),
            f'<joint name="j" type="revolute"><parent>a</parent><child>b</child>'
            f"<pose>0 0 0 {math.pi / 2} 0 0</pose><axis>{axis}"
            f"<limit><lower>-1</lower><upper>1</upper></limit></axis></joint>",
        ),
        version,
    )
    built = build_model(PhysicsWorld(NO_GRAVITY), parse_sdf_model(text), (0.0, 0.0, 0.0, 0.0, 0.0, math.pi / 2))
    assert built.joint("j").joint.getAxis() == pytest.approx((0.0, 1.0, 0.0), abs=1e-9)


def test_link_poses_survive_the_conversion_to_a_joint_tree():
    rng = random.Random(4)
    poses = [[rng.uniform(-2, 2) for _ in range(6)] for _ in range(4)]
    poses[2][4] = math.pi / 2  # gimbal lock in the parent-to-child rotation
    poses[1][3:] = [0.0, 0.0, 0.0]
    texts = [" ".join(str(v) for v in p) for p in poses]
    chain = "".join(
        f'<joint name="j{i}" type="fixed"><parent>l{i}</parent><child>l{i + 1}</child>' f"</joint>" for i in range(3)
    )
    robot = parse_sdf_model(sdf(model("m", *(link(f"l{i}", t) for i, t in enumerate(texts)), chain)))
    spawn = (0.5, -1.0, 2.0, 0.1, 0.2, 0.3)
    built = build_model(PhysicsWorld(NO_GRAVITY), robot, spawn)
    model_frame = (spawn[:3], quat_from_rpy(*spawn[3:]))
    for i, p in enumerate(poses):
        position, quaternion = built.link_transform(f"l{i}")
        expected_position, expected = compose(model_frame, pose_transform(Pose(p[:3], p[3:])))
        assert position == pytest.approx(expected_position, abs=1e-9)
        sign = 1.0 if sum(a * b for a, b in zip(quaternion, expected)) > 0 else -1.0
        assert [sign * q for q in quaternion] == pytest.approx(expected, abs=1e-9)


def test_sphere_dropped_on_static_box_rests_on_top():
    physics = PhysicsWorld()
    table = parse_sdf_model(sdf(model("table", link("top", "0 0 0.25 0 0 0", box_collision("1 1 0.5")), static=True)))
    assert table.links["top"].inertial is None
    build_model(physics, table, (2.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    ball = build_model(
        physics,
        parse_sdf_model(
            sdf(
                model(
                    "ball",
                    link(
                        "ball",
                        extra=inertial(1.0, 0.004)
                        + '<collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry>'
                        "</collision>",
                    ),
                )
            )
        ),
        (2.0, 0.0, 1.0, 0.0, 0.0, 0.0),
    )
    for _ in range(1500):
        physics.step()
    assert ball.link_pose("ball")[0] == pytest.approx((2.0, 0.0, 0.6), abs=1e-3)


def test_free_links_of_a_model_are_separate_bodies():
    physics = PhysicsWorld(NO_GRAVITY)
    robot = parse_sdf_model(sdf(model("pair", link("a", "0 0 1 0 0 0"), link("b", "1 0 1 0 0 0"))))
    assert robot.root == "a" and robot.root_pose.xyz == (0.0, 0.0, 1.0)
    built = build_model(physics, robot, (0.0, 2.0, 0.0, 0.0, 0.0, 0.0))
    assert len(built.bodies) == 2 and built.joints == {}
    assert built.link_pose("b")[0] == pytest.approx((1.0, 2.0, 1.0))
    built.links["b"].body.setLinearVel((1.0, 0.0, 0.0))
    for _ in range(100):
        physics.step()
    assert built.link_pose("a")[0] == pytest.approx((0.0, 2.0, 1.0))
    assert built.link_pose("b")[0] == pytest.approx((1.1, 2.0, 1.0))
    built.set_pose(0.0, 0.0, 0.0)  # places the model frame, the links keep their offsets
    assert built.link_pose("b")[0] == pytest.approx((1.1, 0.0, 1.0))


def test_surface_goes_onto_the_link_geoms():
    physics = PhysicsWorld()
    surface = (
        "<surface><friction><ode><mu>0.2</mu></ode></friction>"
        "<contact><ode><kp>1e5</kp><kd>3</kd></ode></contact></surface>"
    )
    built = build_model(
        physics, parse_sdf_model(sdf(model("m", link("a", extra=inertial() + box_collision("0.1 0.1 0.1", surface)))))
    )
    assert physics.surface(built.geoms["a"][0]) == SurfaceParams(mu=0.2, mu2=1.0, kp=1e5, kd=3.0)


def test_plane_becomes_a_box_below_it_in_static_models_only():
    plane = (
        '<collision name="c"><geometry><plane><normal>0 1 0</normal><size>4 2</size>' "</plane></geometry></collision>"
    )
    robot = parse_sdf_model(sdf(model("wall", link("l", "0 3 0 0 0 0", plane), static=True)))
    collision = robot.links["l"].collisions[0]
    assert collision.geometry == Box((4.0, 2.0, PLANE_THICKNESS))
    built = build_model(PhysicsWorld(), robot)
    assert built.geoms["l"][0].getPosition() == pytest.approx((0.0, 3.0 - PLANE_THICKNESS / 2, 0.0))
    with pytest.raises(ModelError, match="only supported in static models"):
        parse_sdf_model(sdf(model("m", link("l", extra=inertial() + plane))))


def test_mesh_is_kept_for_spawn_time():
    robot = parse_sdf_model(
        sdf(
            model(
                "m",
                link(
                    "a",
                    extra=inertial()
                    + (
                        '<collision name="c"><geometry><mesh><uri>model://m/base.dae</uri><scale>2 2 2</scale>'
                        "</mesh></geometry></collision>"
                    ),
                ),
            )
        )
    )
    # Issue 14: the mesh itself, read at spawn (test_meshes_and_worlds); it was a 2 cm box with a warning.
    assert robot.links["a"].collisions[0].geometry == Mesh("model://m/base.dae", (2.0, 2.0, 2.0))


def test_bare_model_plugins_and_missing_inertial():
    robot = parse_sdf_model(
        '<model name="m"><link name="a"/><plugin name="drive" filename="libdrive.so">'
        "<wheel>left</wheel></plugin></model>"
    )
    assert robot.plugin("libdrive.so").params == {"wheel": "left"}
    assert robot.links["a"].inertial.mass == 1.0  # SDF's default
    assert "no <inertial>" in robot.warnings[0]


def test_static_flag_on_a_urdf_model_builds_fixed_geoms():
    physics = PhysicsWorld()
    robot = dataclasses.replace(parse_urdf(TURTLEBOT_URDF), static=True)
    built = build_model(physics, robot, (1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    assert built.bodies == [] and built.joints == {}
    count = physics.static_space.getNumGeoms()
    assert count == sum(len(g) for g in built.geoms.values()) > 0
    scan = built.link_pose("base_scan")[0]
    for _ in range(100):
        physics.step()
    assert built.link_pose("base_scan")[0] == scan
    built.remove()
    assert physics.static_space.getNumGeoms() == 0


def test_nested_models_are_flattened_with_gazebos_scoped_names():
    """Issue 14: a nested model's links and joints join the outer model as 'inner::name', posed in its frame."""
    inner = (
        '<model name="inner"><pose>1 0 0 0 0 1.5707963267948966</pose>'
        + link("a", "0 0 0 0 0 0")
        + link("b", "0.5 0 0 0 0 0")
        + '<joint name="hinge" type="revolute"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz>'
        "<limit><lower>-1</lower><upper>1</upper></limit></axis></joint>"
        '<model name="deep">' + link("c", "0 0 1 0 0 0") + "</model></model>"
    )
    outer = model(
        "outer",
        link("base"),
        inner,
        '<joint name="mount" type="fixed"><parent>base</parent><child>inner::a</child></joint>'
        '<joint name="deep_mount" type="fixed"><parent>base</parent><child>inner::deep::c</child></joint>',
    )
    robot = parse_sdf_model(sdf(outer))
    assert set(robot.links) == {"base", "inner::a", "inner::b", "inner::deep::c"}
    assert set(robot.joints) == {"mount", "deep_mount", "inner::hinge"}
    assert (robot.joints["inner::hinge"].parent, robot.joints["inner::hinge"].child) == ("inner::a", "inner::b")
    physics = PhysicsWorld()
    built = build_model(physics, robot, (0, 0, 2, 0, 0, 0))
    b = built.link_pose("inner::b")[0]
    assert b == pytest.approx((1.0, 0.5, 2.0), abs=1e-9)  # inner turned 90 degrees: its x is the world's y
    assert built.link_pose("inner::deep::c")[0] == pytest.approx((1.0, 0.0, 3.0), abs=1e-9)
