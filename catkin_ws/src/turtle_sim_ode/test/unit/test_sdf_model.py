"""SDF models and worlds: parsing, conversion to the URDF-style tree, and building them."""
import dataclasses
import math
import random

import pytest
from conftest import PACKAGE_ROOT, TURTLEBOT_URDF

from turtle_sim_ode.models.builder import build_model
from turtle_sim_ode.models.transforms import compose, inverse, pose_transform, quat_from_rpy
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_parts import PLANE_THICKNESS
from turtle_sim_ode.models.sdf_world import Include, parse_sdf_world
from turtle_sim_ode.models.description import Box, GazeboSurface, Mesh, Pose
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.surfaces import SurfaceParams
from turtle_sim_ode.physics.world import PhysicsWorld

NO_GRAVITY = PhysicsParams(gravity=(0.0, 0.0, 0.0))
WORLDS = PACKAGE_ROOT / "worlds"


def sdf(body, version="1.6"):
    return f'<?xml version="1.0"?>\n<sdf version="{version}">\n{body}\n</sdf>'


def inertial(mass=1.0, inertia=0.1):
    return (
        f"<inertial><mass>{mass}</mass><inertia><ixx>{inertia}</ixx><iyy>{inertia}</iyy>"
        f"<izz>{inertia}</izz></inertia></inertial>"
    )


def link(name, pose="0 0 0 0 0 0", extra=inertial()):
    return f'<link name="{name}"><pose>{pose}</pose>{extra}</link>'


def box_collision(size, surface=""):
    return f'<collision name="c"><geometry><box><size>{size}</size></box></geometry>' f"{surface}</collision>"


def model(name, *parts, static=False):
    return f'<model name="{name}"><static>{str(static).lower()}</static>{"".join(parts)}</model>'


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


# --- worlds ------------------------------------------------------------------------------
def test_empty_world():
    world = parse_sdf_world((WORLDS / "empty.world").read_text())
    assert (world.ground_plane, world.sun, world.models) == (True, True, [])
    assert world.includes == [Include("model://ground_plane")]  # a model like any other, built in (includes.py)
    assert world.warnings == []
    physics = world.physics
    assert (physics.max_step_size, physics.solver, physics.iterations) == (0.001, "quick", 50)
    assert (physics.real_time_factor, physics.real_time_update_rate) == (1.0, 1000.0)
    params = physics.apply(PhysicsParams(time_step=0.002, solver="world", erp=0.5))
    assert (params.time_step, params.solver, params.solver_iterations) == (0.001, "quick", 50)
    assert params.gravity == (0.0, 0.0, -9.81)
    assert params.erp == 0.5  # not set by the world: the simulator's value stays


def test_room_world_parses():
    world = parse_sdf_world((WORLDS / "room.world").read_text())
    assert world.ground_plane and world.warnings == []
    models = {m.name: m for m in world.models}
    assert list(models) == ["walls", "obstacle_box", "obstacle_cylinder", "push_box"]
    walls = models["walls"].model
    assert walls.static and len(walls.links) == 4
    sizes = sorted(walls.links[name].collisions[0].geometry.size for name in walls.links)
    assert sizes == [(6.0, 0.1, 0.5)] * 2 + [(6.2, 0.1, 0.5)] * 2
    assert models["obstacle_box"].model.static and models["obstacle_cylinder"].model.static
    box = models["push_box"]
    assert not box.model.static
    assert box.model.links["link"].inertial.mass == 2.0
    assert box.model.surfaces["link"] == GazeboSurface(mu1=0.5, mu2=0.5, kp=1e6, kd=100.0)
    assert box.spawn_pose == (1.0, -1.5, 0.15, 0.0, 0.0, 0.0)


def test_room_world_walls_stop_the_pushed_box_and_static_models_have_no_bodies():
    world = parse_sdf_world((WORLDS / "room.world").read_text())
    physics = PhysicsWorld(world.physics.apply(PhysicsParams()))
    built = {m.name: build_model(physics, m.model, m.spawn_pose) for m in world.models}
    assert [name for name, b in built.items() if b.bodies] == ["push_box"]
    assert built["walls"].link_pose("wall_east")[0] == pytest.approx((3.05, 0.0, 0.25))
    box = built["push_box"]
    for _ in range(200):
        physics.step()
    assert box.link_pose("link")[0][2] == pytest.approx(0.15, abs=1e-3)
    box.links["link"].body.setLinearVel((0.0, -6.0, 0.0))  # would slide 3.7 m without the wall
    for _ in range(1500):
        physics.step()
    position, _ = box.link_pose("link")
    assert position[1] == pytest.approx(-3.0 + 0.15, abs=0.02)  # against the south wall
    assert position[2] == pytest.approx(0.15, abs=2e-3)
    assert built["walls"].link_twist("wall_south") == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def test_static_model_teleports_and_removes_only_its_geoms():
    world = parse_sdf_world((WORLDS / "room.world").read_text())
    physics = PhysicsWorld()
    built = {m.name: build_model(physics, m.model, m.spawn_pose) for m in world.models}
    assert physics.static_space.getNumGeoms() == 6
    obstacle = built["obstacle_box"]
    obstacle.set_pose(-1.0, 2.0, 0.25)
    position, quaternion = obstacle.link_pose("link")
    assert position == pytest.approx((-1.0, 2.0, 0.25)) and quaternion == pytest.approx((0, 0, 0, 1))
    assert obstacle.geoms["link"][0].getPosition() == pytest.approx((-1.0, 2.0, 0.25))
    built["walls"].remove()
    assert physics.static_space.getNumGeoms() == 2
    physics.step()  # still consistent


def test_world_includes_plugins_and_ignored_parts():
    world = parse_sdf_world(
        sdf(
            """<world name="w">
      <light name="l" type="directional"/>
      <include><uri>model://turtlebot3_burger</uri><name>robot</name>
        <pose>1 2 0 0 0 1.5</pose><static>false</static></include>
      <include><uri>model://table</uri></include>
      <plugin name="state" filename="libgazebo_ros_state.so"><ros_ns>/g</ros_ns></plugin>
      <actor name="walker"/>
      <physics type="ode"><gravity>0 0 -1</gravity></physics>
      <model name="ground_plane"><static>true</static><link name="link"><collision name="c">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
      </collision></link></model>
    </world>""",
            "1.4",
        )
    )
    assert world.includes == [
        Include("model://turtlebot3_burger", "robot", Pose((1.0, 2.0, 0.0), (0.0, 0.0, 1.5)), False),
        Include("model://table"),
    ]
    assert [include.index for include in world.includes] == [1, 2]  # after the <light>
    assert world.plugins[0].params == {"ros_ns": "/g"}
    assert world.physics.gravity == (0.0, 0.0, -1.0)  # SDF 1.4 puts it in <physics>
    assert world.ground_plane and not world.sun and [model.name for model in world.models] == ["ground_plane"]
    assert world.models[0].index == 6  # after the includes, plugin, actor and physics, as written
    assert world.warnings == ["<world> <actor> is not supported, ignored"]


def test_world_physics_default_block_and_range():
    world = parse_sdf_world(
        sdf(
            '<world name="w"><physics type="ode"><max_step_size>0.01'
            '</max_step_size></physics><physics type="bullet" default="1">'
            "<ode><constraints><erp>2</erp></constraints></ode></physics>"
            "</world>"
        )
    )
    assert world.physics.max_step_size is None  # the default block is the second one
    # A world without a ground plane has no ground (Gazebo's World::Load adds none): no warning either.
    assert len(world.warnings) == 1 and "only its ODE settings" in world.warnings[0]
    with pytest.raises(ModelError, match="erp"):
        world.physics.apply(PhysicsParams())


def test_world_gravity_beyond_the_bound_is_refused():
    world = parse_sdf_world(sdf('<world name="w"><gravity>0 0 -1e6</gravity></world>'))
    with pytest.raises(ModelError, match=r"gravity .*-1000000"):
        world.physics.apply(PhysicsParams())


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


# --- errors -------------------------------------------------------------------------------
def test_bad_xml_reports_line():
    with pytest.raises(ModelError, match="line 4, column 2: mismatched tag"):
        parse_sdf_model('<sdf version="1.6">\n<model name="m">\n<link name="a">\n</model></sdf>')


@pytest.mark.parametrize(
    "doctype",
    [
        '<!DOCTYPE m [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">'
        '<!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;"><!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">]>',
        '<!DOCTYPE m [<!ENTITY d SYSTEM "file:///etc/passwd">]>',
    ],
)
def test_entities_are_refused(doctype):
    with pytest.raises(ModelError, match="XML guard"):
        parse_sdf_model(f'<?xml version="1.0"?>{doctype}<model name="m"><link name="&d;"/></model>')
    with pytest.raises(ModelError, match="XML guard"):
        parse_sdf_world(f'<?xml version="1.0"?>{doctype}<sdf version="1.6"><world name="&d;"/></sdf>')


def joint(parent, child, joint_type="revolute", extra="", name="j"):
    return (
        f'<joint name="{name}" type="{joint_type}"><parent>{parent}</parent><child>{child}</child>' f"{extra}</joint>"
    )


@pytest.mark.parametrize(
    "body, message",
    [
        (model("m", link("a"), joint("missing", "a")), "parent link 'missing' does not exist"),
        (model("m", link("a"), joint("a", "missing")), "child link 'missing' does not exist"),
        (model("m", link("a"), joint("world", "a", "fixed")), "joints to the world"),
        (model("m", link("a"), link("b"), joint("a", "b", "ball")), "unsupported type 'ball'"),
        (
            model("m", link("a"), link("b"), joint("a", "b", extra="<axis><xyz>0 0 0</xyz></axis>")),
            "axis must not be zero",
        ),
        (model("m", link("a"), link("a")), "duplicate link name 'a'"),
        (model("m", link("a"), link("b"), link("c"), joint("a", "c"), joint("b", "c", name="k")), "two parents"),
        (model("m", link("a"), link("b"), joint("a", "b"), joint("a", "b", name="j")), "duplicate joint name 'j'"),
        (model("m", link("r"), link("a"), link("b"), joint("a", "b"), joint("b", "a", name="k")), "cycle"),
        (model("m", '<link name="a"><pose relative_to="b">0 0 0 0 0 0</pose></link>'), "relative_to"),
        (model("m", '<link name="a"><pose>0 0 0</pose></link>'), "expected 6 numbers"),
        (model("m", link("a", extra="<inertial><mass>0</mass></inertial>")), "mass must be > 0"),
        (
            model("m", link("a", extra='<collision name="c"><geometry><heightmap/></geometry>' "</collision>")),
            "unsupported geometry",
        ),
        (model("m", "<include><uri>model://x</uri></include>", link("a")), "an <include> inside a model"),
        (model("m", '<model><link name="a"/></model>', link("a")), "a nested <model> needs a name"),
        (model("m"), "has no <link>"),
        (
            model("m", link("a"), link("b"), '<joint name="j" type="fixed"><parent>a</parent></joint>'),
            "needs <parent> and <child>",
        ),
        (
            model(
                "m",
                link("a"),
                link("b"),
                joint("a", "b", extra="<axis><limit><lower>1</lower><upper>0</upper></limit></axis>"),
            ),
            "lower 1.0 > upper 0.0",
        ),
        (
            model(
                "m",
                link(
                    "a", extra='<collision name="c"><geometry><plane><size>1</size></plane>' "</geometry></collision>"
                ),
                static=True,
            ),
            "expected 2 numbers",
        ),
        (
            model(
                "m",
                link(
                    "a",
                    extra='<collision name="c"><geometry><sphere><radius>-1</radius>'
                    "</sphere></geometry></collision>",
                ),
            ),
            "must be > 0",
        ),
        ('<model name="m"><static>maybe</static><link name="a"/></model>', "expected true or false"),
        ('<world name="w"/>', "world_name launch argument"),
    ],
)
def test_model_errors(body, message):
    with pytest.raises(ModelError, match=message):
        parse_sdf_model(sdf(body))


@pytest.mark.parametrize(
    "text, message",
    [
        (sdf(model("m", link("a")), "1.8"), "version 1.8 is not supported"),
        (sdf(model("m", link("a")), "one"), "expected a version"),
        (
            sdf(
                model(
                    "m", link("a"), link("b"), joint("a", "b", extra='<axis><xyz expressed_in="f">1 0 0</xyz></axis>')
                ),
                "1.7",
            ),
            "expressed_in='f'",
        ),
        ('<robot name="r"/>', "root element"),
        (sdf(model("m", link("a")) + model("n", link("a"))), "expected one <model>"),
    ],
)
def test_document_errors(text, message):
    with pytest.raises(ModelError, match=message):
        parse_sdf_model(text)


def test_unsupported_parts_are_warned_about():
    surface = "<surface><friction><ode><mu>{}</mu></ode></friction></surface>"
    robot = parse_sdf_model(
        sdf(
            model(
                "m",
                "<self_collide>true</self_collide>",
                link(
                    "a",
                    extra=inertial()
                    + "<kinematic>true</kinematic>"
                    + box_collision("1 1 1", surface.format(0.5))
                    + box_collision("1 1 1", surface.format(0.7)),
                ),
                link("b"),
                joint("a", "b", extra="<axis><dynamics><spring_stiffness>5</spring_stiffness>" "</dynamics></axis>"),
            )
        )
    )
    assert robot.surfaces["a"].mu1 == 0.7
    for expected in (
        "<kinematic> is not supported",
        "different <surface> values",
        "<spring_stiffness> is not supported",
        "<self_collide> is not applied",
    ):
        assert any(expected in w for w in robot.warnings), expected


def test_bad_surface_leaves_the_static_space_clean():
    physics = PhysicsWorld()
    text = sdf(
        model(
            "m",
            link(
                "a",
                extra=box_collision("1 1 1")
                + box_collision("1 1 1", "<surface><friction><ode><mu>-1</mu></ode></friction></surface>"),
            ),
            static=True,
        )
    )
    with pytest.raises(ModelError, match=r"link 'a'.*friction/ode/mu"):  # the parser refuses it (issue 14)
        parse_sdf_model(text)
    robot = parse_sdf_model(text.replace("<mu>-1</mu>", "<mu>1</mu>"))
    robot.surfaces["a"] = GazeboSurface(mu1=-1.0)  # past the parser: the builder must still clean up
    with pytest.raises(ValueError, match="mu"):
        build_model(physics, robot)
    assert physics.static_space.getNumGeoms() == 0


def test_world_errors():
    with pytest.raises(ModelError, match="two models are named 'm'"):
        parse_sdf_world(sdf(f'<world name="w">{model("m", link("a"))}{model("m", link("a"))}' f"</world>"))
    for physics, message in (
        ("<max_step_size>0</max_step_size>", "must be > 0"),
        ("<ode><solver><iters>2.5</iters></solver></ode>", "positive integer"),
    ):
        with pytest.raises(ModelError, match=message):
            parse_sdf_world(sdf(f'<world name="w"><physics type="ode">{physics}</physics></world>'))
    with pytest.raises(ModelError, match="quick or world"):
        parse_sdf_world(
            sdf('<world name="w"><physics type="ode"><ode><solver><type>pgs</type>' "</solver></ode></physics></world>")
        )


def test_a_world_without_gravity_gets_sdfs_default():
    """Issue 14: SDF's -9.8 as Gazebo gives it, not the simulator's own -9.81; a given <gravity> wins."""
    assert parse_sdf_world(sdf('<world name="w"></world>')).physics.apply(PhysicsParams()).gravity == (0, 0, -9.8)
    given = parse_sdf_world(sdf('<world name="w"><gravity>0 0 -9.81</gravity></world>'))
    assert given.physics.apply(PhysicsParams()).gravity == (0.0, 0.0, -9.81)


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


def test_a_world_model_with_a_nested_model_spawns_as_one_model():
    from turtle_sim_ode.world.simulation import Simulation

    nested = model("table", link("top", "0 0 0.5 0 0 0"), '<model name="leg">' + link("foot") + "</model>", static=True)
    sim = Simulation()
    sim.load_world(parse_sdf_world(sdf(f'<world name="w">{nested}</world>')))
    assert list(sim.models) == ["table"]
    assert set(sim.models["table"].robot.links) == {"top", "leg::foot"}
    sim.get_link_state("table::leg::foot")  # Gazebo's scoped name resolves
