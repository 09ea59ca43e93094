"""libgazebo_ros_f3d.so and libgazebo_ros_ft_sensor.so without ROS: their tags (GazeboRosF3D::Load, GazeboRosFT::Load
in gazebo_plugins/src/gazebo_ros_f3d.cpp and gazebo_ros_ft_sensor.cpp) and what they read each step.

f3d's expected values follow gazebo-classic's ODELink::MoveCallback (dBodyGetForce/dBodyGetTorque) read inside its
bundled ODE's step (deps/opende/src/quickstep.cpp dxQuickStepper: gravity added to the force accumulator, ω × (I ω)
taken off the torque; quickstep_update_bodies.cpp dxUpdateBodies: the constraint forces added): the total force. The
ft_sensor's follow ODEJoint::GetForceTorque (gazebo/physics/ode/ODEJoint.cc): body2 = the child's, about the joint,
in the child link's frame, negated."""
from __future__ import annotations

import math
from pathlib import Path
from typing import Dict

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.transforms import quat_matrix
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.f3d import F3D, F3dConfig, LinkForce
from turtle_sim_ode.world.plugins.force import LinkWrench
from turtle_sim_ode.world.plugins.ft_sensor import FT_SENSOR, FtSensorConfig, JointWrench, sensor_joint
from turtle_sim_ode.world.plugins.p3d import noisy
from turtle_sim_ode.world.simulation import Simulation

MODELS = Path(__file__).resolve().parents[1] / "models"
G = 9.81
STEP = 0.001
SLAB = """<robot name="slab"><link name="slab"><inertial><mass value="2"/>
  <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
  <collision><geometry><box size="0.4 0.2 0.05"/></geometry></collision></link></robot>"""


def _read(filename: str, tags: Dict[str, str]):
    (config,) = read_plugins("m", [GazeboPlugin(filename, "p", tags)], {}, []).configs
    return config


def test_f3d_tags_and_defaults() -> None:
    with pytest.raises(ModelError, match="needs <bodyName> and <topicName>"):
        _read(F3D, {"bodyName": "link"})
    assert _read(F3D, {"bodyName": "link", "topicName": "force"}) == F3dConfig("link", "force", "world", None)
    given_ = _read(F3D, {"bodyName": "l", "topicName": "t", "frameName": "map", "robotNamespace": "r"})
    assert (given_.frame, given_.robot_namespace) == ("map", "r")


def test_ft_sensor_tags_and_defaults() -> None:
    with pytest.raises(ModelError, match="needs <jointName> and <topicName>"):
        _read(FT_SENSOR, {"jointName": "j"})
    assert _read(FT_SENSOR, {"jointName": "j", "topicName": "ft"}) == FtSensorConfig("j", "ft", 0.0, 0.0, None)
    for tag, value in (("updateRate", "-1"), ("updateRate", "fast"), ("gaussianNoise", "nan")):
        with pytest.raises(ModelError, match=tag):
            _read(FT_SENSOR, {"jointName": "j", "topicName": "ft", tag: value})


tag_text = st.one_of(
    st.sampled_from(["", " ", "0", "50", "-3", "1e400", "nan", "inf", "x", "link", "/abs", "a::b"]), st.text(max_size=8)
)


@settings(max_examples=300, deadline=None)
@given(
    filename=st.sampled_from([F3D, FT_SENSOR]),
    tags=st.dictionaries(
        st.sampled_from(["bodyName", "jointName", "topicName", "frameName", "updateRate", "gaussianNoise"]), tag_text
    ),
)
def test_any_tags_give_a_config_or_a_model_error(filename: str, tags: Dict[str, str]) -> None:
    try:
        config = _read(filename, tags)
    except ModelError as error:
        assert filename in str(error)
        return
    if isinstance(config, FtSensorConfig):
        assert config.joint and config.topic
        assert math.isfinite(config.update_rate) and config.update_rate >= 0
        assert math.isfinite(config.gaussian_noise) and config.gaussian_noise >= 0
    else:
        assert config.body and config.topic and config.frame


def test_f3d_free_body_reads_the_applied_wrench_plus_weight_less_gyroscopic_torque() -> None:
    """A free body: no constraint, so ODELink's force is F + m g and its torque T − ω × (I ω) (dxQuickStepper)."""
    sim = Simulation()
    sim.spawn_urdf("slab", SLAB, (0, 0, 5, 0.3, 0.2, 0.1))
    model = sim.models["slab"]
    body = model.links["slab"].body
    body.setAngularVel((1.0, 2.0, 3.0))
    reader, push = LinkForce(sim.physics, model, "slab"), LinkWrench(model, "slab")
    assert reader.wrench(STEP) == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))  # before any step
    push.set((1.0, 2.0, 3.0), (0.1, 0.2, 0.3))
    for _ in range(20):
        push.apply()
        spin, rotation = body.getAngularVel(), quat_matrix(body.getQuaternion())
        sim.step()
        inertia = [[sum(rotation[r][k] * body.getMass().I[k][j] for k in range(3)) for j in range(3)] for r in range(3)]
        world = [[sum(inertia[r][k] * rotation[c][k] for k in range(3)) for c in range(3)] for r in range(3)]
        momentum = [sum(world[r][k] * spin[k] for k in range(3)) for r in range(3)]
        gyroscopic = (
            spin[1] * momentum[2] - spin[2] * momentum[1],
            spin[2] * momentum[0] - spin[0] * momentum[2],
            spin[0] * momentum[1] - spin[1] * momentum[0],
        )
        force, torque = reader.wrench(STEP)
        assert force == pytest.approx((1.0, 2.0, 3.0 - 2 * G), abs=1e-6)
        assert torque == pytest.approx([(0.1, 0.2, 0.3)[i] - gyroscopic[i] for i in range(3)], abs=1e-6)


def test_f3d_teleport_between_steps_is_no_force() -> None:
    """The step's own start is kept before it (a pre-step hook): a set_pose that zeroes the velocity reads nothing."""
    sim = Simulation()
    sim.spawn_urdf("slab", SLAB, (0, 0, 5, 0, 0, 0))
    model = sim.models["slab"]
    reader = LinkForce(sim.physics, model, "slab")
    for _ in range(100):
        sim.step()
    model.set_pose(0, 0, 5)
    sim.step()
    assert reader.wrench(STEP)[0] == pytest.approx((0.0, 0.0, -2 * G), abs=1e-6)
    reader.close()
    reader.close()  # twice is fine


def test_f3d_and_ft_sensor_on_a_hanging_arm() -> None:
    """pendulum.urdf: a 0.5 kg arm on a z hinge, its centre of mass 0.15 m out along x, at rest. f3d reads the total
    force, about zero; the ft_sensor the arm's pull on the joint: its weight (0, 0, −m g) and the moment of that
    weight about the joint, (0.15, 0, 0) × (0, 0, −m g) = (0, 0.15 m g, 0)."""
    sim = Simulation()
    sim.spawn_urdf("p", (MODELS / "pendulum.urdf").read_text(), (0, 0, 0.05, 0, 0, 0))
    model = sim.models["p"]
    ft = JointWrench(model, sensor_joint(model, "arm_joint"))
    f3d = LinkForce(sim.physics, model, "arm")
    for _ in range(1500):
        sim.step()
    force, torque = ft.wrench()
    assert force == pytest.approx((0.0, 0.0, -0.5 * G), abs=0.01)
    assert torque == pytest.approx((0.0, 0.15 * 0.5 * G, 0.0), abs=0.01)
    total_force, total_torque = f3d.wrench(STEP)
    assert total_force == pytest.approx((0.0, 0.0, 0.0), abs=0.01)
    assert total_torque == pytest.approx((0.0, 0.0, 0.0), abs=0.01)


@pytest.mark.parametrize("yaw", [0.0, 1.0, -2.5])
def test_ft_sensor_gantry_payload_weight_in_its_frame(yaw: float) -> None:
    """ft_gantry.urdf: the 2 kg payload hangs on the z wrist joint: its weight along the joint axis, (0, 0, −m g) in
    the payload's frame whatever the gantry's yaw, no moment (its centre of mass is on the axis)."""
    sim = Simulation()
    sim.spawn_urdf("g", (MODELS / "ft_gantry.urdf").read_text(), (1.0, -1.0, 0.0, 0, 0, yaw))
    model = sim.models["g"]
    ft = JointWrench(model, sensor_joint(model, "wrist_joint"))
    assert ft.child == "payload"
    for _ in range(1000):
        sim.step()
    force, torque = ft.wrench()
    assert force == pytest.approx((0.0, 0.0, -2.0 * G), abs=0.02)
    assert torque == pytest.approx((0.0, 0.0, 0.0), abs=0.01)


def test_ft_sensor_on_a_fixed_joint_finds_none_and_on_no_joint_refuses() -> None:
    sim = Simulation()
    sim.spawn_urdf("g", (MODELS / "ft_gantry.urdf").read_text())
    model = sim.models["g"]
    assert sensor_joint(model, "beam_joint") is None  # merged into the post's body, as Gazebo lumps it
    with pytest.raises(ModelError, match="no joint 'ghost'"):
        sensor_joint(model, "ghost")


@settings(max_examples=50, deadline=None)
@given(
    values=st.tuples(*[st.floats(-1e6, 1e6)] * 3),
    sigma=st.one_of(st.just(0.0), st.floats(min_value=1e-6, max_value=10.0)),
)
def test_noise_is_none_at_zero_and_finite_otherwise(values, sigma: float) -> None:
    out = noisy(values, sigma)
    assert (out == values) if sigma == 0 else all(math.isfinite(v) for v in out)


@settings(max_examples=25, deadline=None)
@given(
    force=st.tuples(*[st.floats(-50.0, 50.0)] * 3),
    torque=st.tuples(*[st.floats(-1.0, 1.0)] * 3),
)
def test_f3d_force_is_applied_plus_weight_for_any_wrench(force, torque) -> None:
    """Any gazebo_ros_force wrench on a free body: f3d reads F + m g (finite), the sim goes on."""
    sim = Simulation()
    sim.spawn_urdf("slab", SLAB, (0, 0, 50, 0, 0, 0))
    model = sim.models["slab"]
    reader, push = LinkForce(sim.physics, model, "slab"), LinkWrench(model, "slab")
    assert push.set(force, torque)
    for _ in range(5):
        push.apply()
        sim.step()
    read_force, read_torque = reader.wrench(STEP)
    assert read_force == pytest.approx((force[0], force[1], force[2] - 2 * G), abs=1e-6)
    assert all(math.isfinite(v) for v in read_torque)
