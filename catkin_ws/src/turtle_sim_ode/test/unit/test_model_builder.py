"""Fixed-joint merging, COM-centred bodies, link poses, joints, teleport and removal."""
import gc
import math

import pytest
from conftest import TURTLEBOT_URDF

from turtle_sim_ode.models.builder import build_model
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.surfaces import SurfaceParams
from turtle_sim_ode.physics.world import PhysicsWorld

NO_GRAVITY = PhysicsParams(gravity=(0.0, 0.0, 0.0))
BOX = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'


def inertial(mass, xyz="0 0 0", ixx=0.1, iyy=0.1, izz=0.1):
    return (
        f'<inertial><mass value="{mass}"/><origin xyz="{xyz}"/>'
        f'<inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/></inertial>'
    )


# "b" is fixed to "a" 1 m ahead and turned 90 degrees; its COM is 0.5 m along its own x.
MERGED = f"""<robot name="merged">
  <link name="a">{inertial(1.0)}</link>
  <link name="b">{inertial(3.0, "0.5 0 0", 0.2, 0.4, 0.6)}{BOX}</link>
  <link name="c">{inertial(0.5)}</link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/>
    <origin xyz="1 0 0" rpy="0 0 {math.pi / 2}"/></joint>
  <joint name="bc" type="revolute"><parent link="b"/><child link="c"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <gazebo reference="b"><mu1>0.25</mu1><kp>1e5</kp></gazebo>
</robot>"""


def test_fixed_joint_merges_mass_com_and_inertia():
    physics = PhysicsWorld(NO_GRAVITY)
    model = build_model(physics, parse_urdf(MERGED))
    assert len(model.bodies) == 2  # a+b merged, c separate
    body = model.links["a"].body
    assert model.links["b"].body is body
    mass = body.getMass()
    assert mass.mass == pytest.approx(4.0)
    # COM: a at (0,0,0) with 1 kg, b's COM at (1, 0.5, 0) with 3 kg.
    assert body.getPosition() == pytest.approx((0.75, 0.375, 0.0))
    # b's inertia rotated 90 deg about z, plus the parallel-axis terms about the COM.
    (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = mass.I
    assert ixx == pytest.approx(0.1 + 0.4 + 1 * 0.375**2 + 3 * 0.125**2)
    assert iyy == pytest.approx(0.1 + 0.2 + 1 * 0.75**2 + 3 * 0.25**2)
    assert izz == pytest.approx(0.1 + 0.6 + 1 * (0.75**2 + 0.375**2) + 3 * (0.25**2 + 0.125**2))
    assert ixy == pytest.approx(-(1 * 0.75 * 0.375 + 3 * 0.25 * 0.125))
    assert (ixz, iyz) == (pytest.approx(0.0), pytest.approx(0.0))


def test_link_poses_geoms_and_surfaces_follow_the_model_pose():
    physics = PhysicsWorld(NO_GRAVITY)
    model = build_model(physics, parse_urdf(MERGED), (2.0, 0.0, 1.0, 0.0, 0.0, math.pi / 2))
    position, quaternion = model.link_pose("b")
    assert position == pytest.approx((2.0, 1.0, 1.0))
    assert quaternion == pytest.approx((0.0, 0.0, 1.0, 0.0), abs=1e-12)  # yaw pi, xyzw
    assert model.link_pose("c")[0] == pytest.approx((2.0, 1.0, 2.0))
    geom = model.geoms["b"][0]
    assert geom.getPosition() == pytest.approx((2.0, 1.0, 1.0))
    assert physics.surface(geom) == SurfaceParams(mu=0.25, mu2=1.0, kp=1e5, kd=1.0)


def test_link_twist_of_offset_link_includes_rotation():
    physics = PhysicsWorld(NO_GRAVITY)
    model = build_model(physics, parse_urdf(MERGED))
    body = model.links["a"].body
    body.setAngularVel((0.0, 0.0, 1.0))
    linear, angular = model.link_twist("a")  # a's origin is 0.75 m behind the COM in x
    assert angular == pytest.approx((0.0, 0.0, 1.0))
    assert linear == pytest.approx((0.375, -0.75, 0.0))


def test_revolute_joint_sign_and_limits():
    physics = PhysicsWorld(NO_GRAVITY)
    model = build_model(physics, parse_urdf(MERGED))
    joint = model.joint("bc")
    joint.joint.setParam(oc.PARAM_VEL, 1.0)
    joint.joint.setParam(oc.PARAM_FMAX, 10.0)
    for _ in range(200):
        physics.step()
    assert joint.rate() == pytest.approx(1.0, rel=1e-3)
    assert joint.angle() == pytest.approx(0.2, abs=0.01)
    # The child really turned counter-clockwise about +z relative to the parent.
    relative_yaw = 2 * math.atan2(model.link_pose("c")[1][2], model.link_pose("c")[1][3]) - 2 * math.atan2(
        model.link_pose("b")[1][2], model.link_pose("b")[1][3]
    )
    assert relative_yaw == pytest.approx(joint.angle(), abs=1e-6)
    for _ in range(1000):
        physics.step()
    assert joint.angle() == pytest.approx(0.5, abs=0.02)


SPINNER = f"""<robot name="spinner">
  <link name="base">{inertial(10.0, ixx=10, iyy=10, izz=10)}</link>
  <link name="wheel">{inertial(0.1)}</link>
  <link name="slide">{inertial(0.1)}</link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="push" type="prismatic"><parent link="base"/><child link="slide"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <dynamics damping="0.5"/></joint>
</robot>"""


def test_continuous_joint_angle_counts_whole_turns():
    physics = PhysicsWorld(NO_GRAVITY)
    model = build_model(physics, parse_urdf(SPINNER))
    spin = model.joint("spin")
    spin.joint.setParam(oc.PARAM_VEL, 10.0)
    spin.joint.setParam(oc.PARAM_FMAX, 100.0)
    for _ in range(1000):
        physics.step()
    assert spin.angle() == pytest.approx(10.0, abs=0.05)  # > pi: unwrapped


def test_prismatic_joint_sign_and_damping():
    physics = PhysicsWorld(NO_GRAVITY)
    model = build_model(physics, parse_urdf(SPINNER))
    push = model.joint("push")
    model.links["slide"].body.setLinearVel((0.1, 0.0, 0.0))
    physics.step()
    assert push.rate() > 0
    for _ in range(1000):
        physics.step()
    # Damping 0.5 N s/m on 0.1 kg (and 10 kg pushed back): velocity decays like exp(-5 t).
    assert 0.0 < push.rate() < 0.1 * math.exp(-4.0)
    assert push.angle() > 0.0


def test_set_pose_teleports_keeping_joints_and_zeroing_velocity():
    physics = PhysicsWorld()
    model = build_model(physics, parse_urdf(TURTLEBOT_URDF))
    wheel = model.joint("wheel_left_joint")
    wheel.joint.setParam(oc.PARAM_VEL, 5.0)
    wheel.joint.setParam(oc.PARAM_FMAX, 1.0)
    for _ in range(300):
        physics.step()
    angle = wheel.angle()
    scan_offset = model.link_pose("base_scan")[0][2] - model.link_pose("base_footprint")[0][2]
    model.set_pose(1.0, 2.0, 0.0, 0.0, 0.0, 1.0)
    position, quaternion = model.link_pose("base_footprint")
    assert position == pytest.approx((1.0, 2.0, 0.0), abs=1e-12)
    assert quaternion == pytest.approx((0.0, 0.0, math.sin(0.5), math.cos(0.5)), abs=1e-9)
    assert model.link_pose("base_scan")[0][2] - position[2] == pytest.approx(scan_offset)
    assert wheel.angle() == pytest.approx(angle, abs=1e-9)
    for body in model.bodies:
        assert body.getLinearVel() == (0.0, 0.0, 0.0)
        assert body.getAngularVel() == (0.0, 0.0, 0.0)


def test_remove_destroys_everything():
    physics = PhysicsWorld()
    model = build_model(physics, parse_urdf(TURTLEBOT_URDF))
    physics.step()
    assert physics.contact_count > 0
    model.remove()
    physics.step()
    assert physics.contact_count == 0
    assert physics.space.getNumGeoms() == 0
    with pytest.raises(RuntimeError, match="removed"):
        model.link_pose("base_link")
    build_model(physics, parse_urdf(TURTLEBOT_URDF))  # the world is still usable
    physics.step()
    assert physics.contact_count > 0


def test_link_lookup_errors_name_the_link():
    model = build_model(PhysicsWorld(), parse_urdf(TURTLEBOT_URDF))
    with pytest.raises(KeyError, match="nope"):
        model.link_pose("nope")
    with pytest.raises(KeyError, match="base_joint"):
        model.joint("base_joint")  # fixed joints are merged away


def test_massless_moving_link_is_rejected_and_leaves_world_clean():
    physics = PhysicsWorld()
    urdf = f"""<robot name="r"><link name="a">{inertial(1.0)}{BOX}</link><link name="b">{BOX}</link>
      <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>"""
    with pytest.raises(ModelError, match="'b'.*no <inertial>"):
        build_model(physics, parse_urdf(urdf))
    assert physics.space.getNumGeoms() == 0


def test_bad_pose_is_rejected():
    with pytest.raises(ValueError, match="pose"):
        build_model(PhysicsWorld(), parse_urdf(TURTLEBOT_URDF), (0.0, 0.0, math.nan, 0, 0, 0))


def test_worlds_in_reference_cycles_are_garbage_collected_safely():
    for _ in range(5):  # a crash here would take the interpreter down
        physics = PhysicsWorld()
        model = build_model(physics, parse_urdf(TURTLEBOT_URDF))
        for _ in range(10):
            physics.step()
        physics.model, model.physics = model, physics  # a cycle through both
        del physics, model
        gc.collect()
