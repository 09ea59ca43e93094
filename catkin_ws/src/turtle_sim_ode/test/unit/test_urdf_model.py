"""URDF parsing into dataclasses and every validation error."""
import pytest
from conftest import TURTLEBOT_URDF

from turtle_sim_ode.models.description import Cylinder, GazeboSurface, Mesh, Sphere
from turtle_sim_ode.models.urdf import MAX_LINKS, parse_urdf
from turtle_sim_ode.models.text import ModelError

INERTIA = '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'


def link(name, mass="1", inertia=INERTIA, body=""):
    inertial = f'<inertial><mass value="{mass}"/>{inertia}</inertial>' if mass else ""
    return f'<link name="{name}">{inertial}{body}</link>'


def joint(name, parent, child, kind="fixed", extra=""):
    return f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>' f'<child link="{child}"/>{extra}</joint>'


def robot(*parts):
    return '<robot name="r">' + "".join(parts) + "</robot>"


def test_turtlebot_parses():
    model = parse_urdf(TURTLEBOT_URDF)
    assert model.name == "turtlebot" and model.root == "base_footprint"
    assert model.warnings == []
    assert model.links["base_footprint"].inertial is None
    assert model.links["base_link"].inertial.mass == 2.4
    wheel = model.joints["wheel_left_joint"]
    assert (wheel.type, wheel.parent, wheel.child, wheel.axis) == (
        "continuous",
        "base_link",
        "wheel_left_link",
        (0.0, 1.0, 0.0),
    )
    assert model.joints["wheel_right_joint"].origin.xyz == (0.0, -0.115, 0.0248)
    assert model.links["wheel_left_link"].collisions[0].geometry == Cylinder(0.035, 0.0206)
    assert isinstance(model.links["caster_front_link"].collisions[0].geometry, Sphere)
    assert model.surfaces["wheel_left_link"] == GazeboSurface(1.0, 1.0, 1e6, 100.0, 1.0, 0.001)
    assert model.surfaces["caster_back_link"].mu1 == 0.0
    plugin = model.plugin("libgazebo_ros_kobuki.so")
    assert plugin.name == "kobuki_controller"
    assert plugin.params["left_wheel_joint_name"] == "wheel_left_joint"
    assert plugin.params["wheel_diameter"] == "0.070"


def test_joint_details_and_old_style_gazebo_tags():
    model = parse_urdf(
        robot(
            link("a"),
            link("b"),
            joint(
                "j",
                "a",
                "b",
                "revolute",
                '<origin xyz="1 2 3" rpy="0 0 1.5"/><axis xyz="0 0 2"/>'
                '<limit lower="-1" upper="1" effort="5" velocity="2"/>'
                '<dynamics damping="0.5" friction="0.1"/>',
            ),
            '<gazebo reference="b"><mu1 value="0.3"/><kp>1e5</kp></gazebo>',
        )
    )
    j = model.joints["j"]
    assert j.origin.xyz == (1, 2, 3) and j.origin.rpy == (0, 0, 1.5)
    assert j.axis == (0, 0, 1)  # normalised
    assert (j.limits.lower, j.limits.upper, j.limits.effort, j.limits.velocity) == (-1, 1, 5, 2)
    assert (j.dynamics.damping, j.dynamics.friction) == (0.5, 0.1)
    assert model.surfaces["b"] == GazeboSurface(mu1=0.3, kp=1e5)


def test_bad_xml_reports_line():
    with pytest.raises(ModelError, match="line 4, column 2: mismatched tag"):
        parse_urdf('<robot name="r">\n<link name="a"/>\n<link name="b">\n</robot>')


def test_entity_expansion_is_refused():
    bomb = '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;">]>' '<robot name="r">&b;</robot>'
    with pytest.raises(ModelError):
        parse_urdf(bomb)


@pytest.mark.parametrize(
    "urdf, message",
    [
        (robot(link("a"), joint("j", "missing", "a")), "parent link 'missing' does not exist"),
        (robot(link("a"), joint("j", "a", "missing")), "child link 'missing' does not exist"),
        (robot(link("a"), link("b")), "2 root links"),
        (robot(link("r"), link("a"), link("b"), joint("j1", "a", "b"), joint("j2", "b", "a")), "cycle"),
        (robot(link("a"), link("b"), joint("j1", "a", "b"), joint("j2", "b", "a")), "cycle"),
        (robot(link("a"), link("b"), link("c"), joint("j1", "a", "c"), joint("j2", "b", "c")), "two parents"),
        (robot(link("a", mass="0")), "mass must be > 0"),
        (robot(link("a", mass="-2")), "mass must be > 0"),
        (
            robot(link("a", inertia='<inertia ixx="1" ixy="2" ixz="0" iyy="1" iyz="0" izz="1"/>')),
            "not positive definite",
        ),
        (
            robot(link("a", inertia='<inertia ixx="0" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>')),
            "not positive definite",
        ),
        (robot(link("a", mass="nan")), "finite"),
        (
            robot(
                link("a", body='<collision><origin xyz="0 0"/><geometry><sphere radius="1"/>' "</geometry></collision>")
            ),
            "expected 3 numbers",
        ),
        (
            robot(link("a", body='<collision><geometry><sphere radius="-1"/></geometry></collision>')),
            "radius must be > 0",
        ),
        (robot(link("a"), link("b"), joint("j", "a", "b", "floating")), "unsupported type"),
        (robot(link("a"), link("b"), joint("j", "a", "b", "revolute")), "needs <limit>"),
        (robot(link("a"), link("a")), "duplicate link"),
        ('<robot name="r"></robot>', "no <link>"),
        ('<model name="r"><link name="a"/></model>', "must be <robot>"),
        (robot(*(link(f"l{i}") for i in range(MAX_LINKS + 1))), "too large"),
    ],
)
def test_invalid_models_raise_model_error(urdf, message):
    with pytest.raises(ModelError, match=message):
        parse_urdf(urdf)


def test_model_error_is_a_value_error():
    assert issubclass(ModelError, ValueError)


def test_mesh_collision_is_kept_unopened():
    model = parse_urdf(
        robot(
            link(
                "a",
                body=(
                    '<collision><geometry><mesh filename="package://x/base.stl" scale="2 2 1"/>'
                    "</geometry></collision>"
                ),
            )
        )
    )
    # Issue 14: a mesh, read at spawn from under the ROS package path (test_meshes_and_worlds); it was a 1 cm box.
    assert model.links["a"].collisions[0].geometry == Mesh("package://x/base.stl", (2.0, 2.0, 1.0))
    assert model.warnings == []


def test_gazebo_reference_to_unknown_link_warns():
    model = parse_urdf(robot(link("a"), '<gazebo reference="nope"><mu1>1</mu1></gazebo>'))
    assert model.surfaces == {} and "nope" in model.warnings[0]
