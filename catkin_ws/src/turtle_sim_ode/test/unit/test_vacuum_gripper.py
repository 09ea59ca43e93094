"""libgazebo_ros_vacuum_gripper.so (gazebo_plugins/src/gazebo_ros_vacuum_gripper.cpp): GazeboRosVacuumGripper::Load
needs <bodyName> and <topicName>; UpdateChild, while on, holds every link of another model whose origin is within
0.05 m of the gripper link's: it gets the gripper link's velocity, within 0.01 m it is put on the gripper's origin,
and min(1/distance, 20) N pull it along Pose3d's ``gripper - link`` position (in the link's frame, added in the
world's); off, nothing is touched. The forces are read from the ODE bodies' accumulators after the hook ran, before
the physics step clears them."""
from __future__ import annotations

import math
from pathlib import Path
from typing import Tuple

import pytest
from conftest import PACKAGE_ROOT
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.transforms import quat_from_rpy
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.vacuum_gripper import (
    MAX_FORCE,
    REACH,
    SNAP,
    VACUUM_GRIPPER,
    VacuumGripper,
    VacuumGripperConfig,
)
from turtle_sim_ode.world.simulation import Simulation

MODELS = Path(PACKAGE_ROOT) / "test" / "models"
ARM_URDF = (MODELS / "vacuum_gripper_arm.urdf").read_text()
SMALL_BOX_SDF = (MODELS / "small_box.sdf").read_text()
GRIPPER_AT = (0.0, 0.0, 1.0)  # the static gripper's link origin

# A static gripper: its link at GRIPPER_AT, no collision (as upstream's example end effector), so boxes near it
# are only moved by the plugin.
STATIC_GRIPPER_SDF = """<sdf version="1.6"><model name="hand"><static>true</static>
  <link name="gripper"><visual name="v"><geometry><box><size>0.01 0.01 0.01</size></box></geometry></visual></link>
</model></sdf>"""
# A box whose link frame is 0.1 m off its centre of mass (the plugin measures from link origins); no collision.
OFFSET_BOX_URDF = """<robot name="offset_box"><link name="lid">
  <inertial><origin xyz="0.1 0 0"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0"
  iyz="0"/></inertial></link></robot>"""
FREE_BOX_SDF = """<sdf version="1.6"><model name="b"><link name="link">
  <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
</link></model></sdf>"""

Vec3 = Tuple[float, float, float]


def plugin(**tags: str) -> GazeboPlugin:
    return GazeboPlugin(VACUUM_GRIPPER, "gazebo_ros_vacuum_gripper", dict(tags))


def gripper_world(*box_positions: Vec3, yaw: float = 0.0) -> Tuple[Simulation, VacuumGripper]:
    """The static gripper at GRIPPER_AT and a free 1 kg box (link at its centre) at each position."""
    sim = Simulation()
    sim.spawn_sdf("hand", STATIC_GRIPPER_SDF, GRIPPER_AT + (0.0, 0.0, 0.0))
    for index, position in enumerate(box_positions):
        sim.spawn_sdf(f"box{index}", FREE_BOX_SDF, tuple(position) + (0.0, 0.0, yaw))
    gripper = VacuumGripper(sim.models["hand"], "gripper", sim.models)
    sim.step_hooks["hand::vacuum_gripper"] = gripper
    return sim, gripper


def box_body(sim: Simulation, index: int = 0):  # type: ignore[no-untyped-def]
    return sim.models[f"box{index}"].links["link"].body


def below(distance: float) -> Vec3:
    return (GRIPPER_AT[0], GRIPPER_AT[1], GRIPPER_AT[2] - distance)


# --- tags -------------------------------------------------------------------------------------------------------
def test_body_and_topic_are_required_and_namespace_defaults_to_none() -> None:
    """GazeboRosVacuumGripper::Load: no <bodyName> or no <topicName> stops loading; without <robotNamespace>, the spawn's
    (gazebo_ros_api_plugin.cpp walkChildAddRobotNamespace gives it one): None here."""
    with pytest.raises(ModelError, match="needs <bodyName>"):
        read_plugins("m", [plugin(topicName="grasping")], {}, [])
    with pytest.raises(ModelError, match="needs <topicName>"):
        read_plugins("m", [plugin(bodyName="tip")], {}, [])
    (config,) = read_plugins("m", [plugin(bodyName="tip", topicName="grasping")], {}, []).configs
    assert config == VacuumGripperConfig("tip", "grasping", None)
    tags = plugin(bodyName=" m::tip ", topicName="/left/grasping", robotNamespace="/robot/left_vacuum_gripper")
    (config,) = read_plugins("m", [tags], {}, []).configs
    assert config == VacuumGripperConfig("m::tip", "/left/grasping", "/robot/left_vacuum_gripper")


def test_the_gripper_link_must_be_one_gazebo_keeps() -> None:
    """Load: link_ = model->GetLink(bodyName); a missing link (or one lumped by a fixed joint) is fatal, the links
    found named."""
    sim = Simulation()
    sim.spawn_urdf("arm", ARM_URDF)
    with pytest.raises(ModelError, match=r"\[post\] does not exist.*found links are: base boom vacuum_gripper"):
        VacuumGripper(sim.models["arm"], "post", sim.models)  # fixed to the base
    with pytest.raises(ModelError, match=r"\[suction\] does not exist"):
        VacuumGripper(sim.models["arm"], "suction", sim.models)
    assert VacuumGripper(sim.models["arm"], "arm::vacuum_gripper", sim.models).link == "vacuum_gripper"


# --- the force law ----------------------------------------------------------------------------------------------
def test_off_touches_nothing() -> None:
    """UpdateChild: while status_ is false it only publishes false."""
    sim, gripper = gripper_world(below(0.03))
    body = box_body(sim)
    body.setLinearVel((0.1, 0.2, 0.3))
    gripper.step(0.0, 0.001)
    assert body.getForce() == (0.0, 0.0, 0.0) and body.getLinearVel() == (0.1, 0.2, 0.3)
    assert not gripper.grasping


def test_a_link_within_reach_is_pulled_with_20_newtons() -> None:
    """UpdateChild: norm 0.03 < 0.05: force 1/norm = 33.3 capped at 20 (max_force), toward the gripper; the link
    gets the gripper link's velocity (0 for a static one); grasping true."""
    sim, gripper = gripper_world(below(0.03))
    body = box_body(sim)
    body.setLinearVel((0.1, 0.2, 0.3))
    body.setAngularVel((1.0, 0.0, 0.0))
    assert gripper.switch_on() and not gripper.switch_on()  # a second "on" is refused (upstream warns)
    gripper.step(0.0, 0.001)
    assert body.getForce() == pytest.approx((0.0, 0.0, MAX_FORCE), abs=1e-9)
    assert body.getLinearVel() == (0.0, 0.0, 0.0) and body.getAngularVel() == (0.0, 0.0, 0.0)
    assert body.getPosition() == pytest.approx(below(0.03), abs=1e-12)  # beyond 0.01: not moved
    assert gripper.grasping


@pytest.mark.parametrize("distance", [0.0499, 0.02, 0.011])
def test_the_pull_is_20_newtons_everywhere_within_reach(distance: float) -> None:
    """UpdateChild: norm_force = 1/norm, capped at 20; 1/norm > 20 for every norm < 0.05."""
    sim, gripper = gripper_world((distance, 0.0, GRIPPER_AT[2]))  # along +x of the gripper: pulled along -x
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert box_body(sim).getForce() == pytest.approx((-MAX_FORCE, 0.0, 0.0), abs=1e-9)


@pytest.mark.parametrize("distance", [REACH, 0.0501, 0.2])
def test_nothing_at_or_beyond_reach(distance: float) -> None:
    """UpdateChild: only norm < 0.05 is held."""
    sim, gripper = gripper_world(below(distance))
    body = box_body(sim)
    body.setLinearVel((0.0, 0.0, -1.0))
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert body.getForce() == (0.0, 0.0, 0.0) and body.getLinearVel() == (0.0, 0.0, -1.0)
    assert not gripper.grasping


def test_the_force_is_the_offset_in_the_links_frame_added_in_the_worlds() -> None:
    """UpdateChild: diff = parent_pose - link_pose (ignition Pose3 CoordPositionSub: the gripper's offset rotated
    into the link's frame), force = 20 diff.Normalize() given to Link::AddForce (world frame). A box yawed by 90°
    0.03 m along -x of the gripper: offset (+0.03, 0, 0) in the world is (0, -0.03, 0) in the box's frame."""
    sim, gripper = gripper_world((-0.03, 0.0, GRIPPER_AT[2]), yaw=math.pi / 2)
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert box_body(sim).getForce() == pytest.approx((0.0, -MAX_FORCE, 0.0), abs=1e-9)


def test_a_link_within_a_centimetre_is_put_on_the_gripper() -> None:
    """UpdateChild: norm < 0.01: link_pose.Set(parent_pose.Pos(), link_pose.Rot()); SetWorldPose: the link's origin
    on the gripper's, its orientation kept; the force still along the offset before the move."""
    sim, gripper = gripper_world((0.003, 0.004, GRIPPER_AT[2]), yaw=0.3)
    body = box_body(sim)
    before = body.getQuaternion()
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert body.getPosition() == pytest.approx(GRIPPER_AT, abs=1e-12)
    assert body.getQuaternion() == pytest.approx(before, abs=1e-12)
    (fx, fy, fz) = body.getForce()
    assert math.hypot(fx, fy) == pytest.approx(MAX_FORCE) and fz == pytest.approx(0.0, abs=1e-9)


def test_a_link_on_the_gripper_gets_no_force() -> None:
    """UpdateChild: norm 0: 1/0 capped at 20, times diff.Normalize() of a zero vector, which ignition leaves zero."""
    sim, gripper = gripper_world(GRIPPER_AT)
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert box_body(sim).getForce() == (0.0, 0.0, 0.0) and gripper.grasping


def test_distance_is_measured_from_link_origins_not_centres_of_mass() -> None:
    """UpdateChild compares link_->WorldPose() and links[j]->WorldPose(): link frames. The lid's frame 0.02 m below
    the gripper, its centre of mass 0.1 m aside: held, and moved as its link frame must be."""
    sim = Simulation()
    sim.spawn_sdf("hand", STATIC_GRIPPER_SDF, GRIPPER_AT + (0.0, 0.0, 0.0))
    sim.spawn_urdf("lid", OFFSET_BOX_URDF, below(0.005) + (0.0, 0.0, 0.0))
    gripper = VacuumGripper(sim.models["hand"], "gripper", sim.models)
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert gripper.grasping
    assert sim.models["lid"].link_pose("lid")[0] == pytest.approx(GRIPPER_AT, abs=1e-12)
    assert sim.models["lid"].links["lid"].body.getForce() == pytest.approx((0.0, 0.0, MAX_FORCE), abs=1e-9)


def test_the_held_link_takes_the_velocity_of_the_gripper_links_origin() -> None:
    """UpdateChild: SetLinearVel(link_->WorldLinearVel()) (Link::WorldLinearVel(): the link origin's velocity, here
    0.1 m from the centre of mass of a spinning gripper), SetAngularVel(link_->WorldAngularVel())."""
    sim = Simulation()
    sim.spawn_urdf(
        "hand", OFFSET_BOX_URDF.replace("offset_box", "hand").replace('"lid"', '"gripper"'), (0, 0, 1, 0, 0, 0)
    )
    sim.spawn_sdf("box0", FREE_BOX_SDF, (0.0, 0.0, 0.97, 0.0, 0.0, 0.0))
    hand = sim.models["hand"].links["gripper"].body
    hand.setLinearVel((0.5, 0.0, 0.0))
    hand.setAngularVel((0.0, 0.0, 2.0))  # the origin sits 0.1 m along -x of the centre: ω × r = (0, -0.2, 0)
    gripper = VacuumGripper(sim.models["hand"], "gripper", sim.models)
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert box_body(sim).getLinearVel() == pytest.approx((0.5, -0.2, 0.0), abs=1e-12)
    assert box_body(sim).getAngularVel() == pytest.approx((0.0, 0.0, 2.0), abs=1e-12)


def test_own_model_static_models_and_a_model_named_as_the_link_are_left_alone() -> None:
    """UpdateChild skips models named as the gripper's model or (sic) as its link; a static model's links do not
    move (they have no body here)."""
    sim, gripper = gripper_world()
    sim.spawn_sdf("gripper", FREE_BOX_SDF, below(0.02) + (0.0, 0.0, 0.0))  # named as the gripper link
    sim.spawn_sdf("shelf", STATIC_GRIPPER_SDF.replace("gripper", "board"), below(0.02) + (0.0, 0.0, 0.0))
    gripper.switch_on()
    gripper.step(0.0, 0.001)
    assert sim.models["gripper"].links["link"].body.getForce() == (0.0, 0.0, 0.0)
    assert not gripper.grasping
    assert sim.models["shelf"].link_pose("board")[0] == pytest.approx(below(0.02))


def test_off_again_lets_go() -> None:
    sim, gripper = gripper_world(below(0.03))
    gripper.switch_on()
    assert gripper.switch_off() and not gripper.switch_off()  # a second "off" is refused (upstream warns)
    gripper.step(0.0, 0.001)
    assert box_body(sim).getForce() == (0.0, 0.0, 0.0) and not gripper.grasping


def test_deleting_a_model_drops_its_hooks_and_the_gripper_forgets_deleted_models() -> None:
    """Simulation.step_hooks: keys "model" or "model::what"; delete drops both kinds."""
    sim, gripper = gripper_world(below(0.03))
    gripper.switch_on()
    sim.step()
    assert gripper.grasping
    sim.delete("box0")
    sim.step()
    assert not gripper.grasping
    sim.delete("hand")
    assert sim.step_hooks == {}


# --- the arm of the rostest, without ROS ------------------------------------------------------------------------
def test_the_arm_lifts_the_box_and_drops_it() -> None:
    """The rostest's scene stepped here: on, the box is drawn up to the end effector (grasping); 40 N on the lift
    raises boom and box to the 0.2 m stop; off, the box falls back to the ground. Tolerances: 2 mm on heights."""
    sim = Simulation()
    sim.spawn_urdf("arm", ARM_URDF)
    sim.spawn_sdf("box", SMALL_BOX_SDF, (0.45, 0.0, 0.02, 0.0, 0.0, 0.0))
    gripper = VacuumGripper(sim.models["arm"], "vacuum_gripper", sim.models)
    sim.step_hooks["arm::vacuum_gripper"] = gripper

    def heights() -> Tuple[float, float]:
        tip = sim.models["arm"].link_pose("vacuum_gripper")[0][2]
        return tip, sim.models["box"].link_pose("link")[0][2]

    for _ in range(300):
        sim.step()
    assert not gripper.grasping and heights() == pytest.approx((0.052, 0.02), abs=0.002)
    gripper.switch_on()
    for _ in range(300):
        sim.step()
    tip, box = heights()
    assert gripper.grasping and tip == pytest.approx(0.052, abs=0.002)  # the boom stays on its stop
    assert box == pytest.approx(tip - 0.03, abs=0.002)  # against the end effector's underside
    sim.apply_joint_effort("lift", 40.0, sim.sim_time, -1.0)
    for _ in range(700):
        sim.step()
    tip, box = heights()
    assert gripper.grasping and tip == pytest.approx(0.252, abs=0.002)
    assert box == pytest.approx(tip - 0.03, abs=0.002)
    gripper.switch_off()
    for _ in range(500):
        sim.step()
    assert not gripper.grasping and heights() == pytest.approx((0.252, 0.02), abs=0.002)


# --- generated inputs -------------------------------------------------------------------------------------------
coordinate = st.floats(-0.12, 0.12, allow_nan=False, allow_subnormal=False)  # spawn refuses subnormals
angle = st.floats(-math.pi, math.pi, allow_nan=False, allow_subnormal=False)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    offsets=st.lists(st.tuples(coordinate, coordinate, coordinate), min_size=1, max_size=4),
    yaw=angle,
    on=st.booleans(),
)
def test_generated_positions_keep_the_invariants(offsets, yaw, on) -> None:  # type: ignore[no-untyped-def]
    """Any boxes around the gripper: forces finite and at most 20 N; off, or 0.05 m or farther, a box is untouched;
    within reach, its velocity is the gripper's (0); a few physics steps stay finite."""
    positions = [tuple(g + o for g, o in zip(GRIPPER_AT, offset)) for offset in offsets]
    sim, gripper = gripper_world(*positions, yaw=yaw)
    for index in range(len(positions)):
        box_body(sim, index).setLinearVel((0.0, 0.0, -0.5))
    if on:
        gripper.switch_on()
    gripper.step(0.0, 0.001)
    held = False
    for index, offset in enumerate(offsets):
        body = box_body(sim, index)
        force = body.getForce()
        assert all(math.isfinite(f) for f in force) and math.sqrt(sum(f * f for f in force)) <= MAX_FORCE + 1e-9
        distance = math.sqrt(sum(o * o for o in offset))
        if not on or distance >= REACH:
            assert force == (0.0, 0.0, 0.0) and body.getLinearVel() == (0.0, 0.0, -0.5)
            assert body.getPosition() == pytest.approx(positions[index], abs=1e-12)
        else:
            held = True
            assert body.getLinearVel() == (0.0, 0.0, 0.0)
            if distance >= SNAP:
                assert body.getPosition() == pytest.approx(positions[index], abs=1e-12)
            else:
                assert body.getPosition() == pytest.approx(GRIPPER_AT, abs=1e-9)
    assert gripper.grasping == held
    for _ in range(20):
        sim.step()
    for index in range(len(positions)):
        position = sim.models[f"box{index}"].link_pose("link")[0]
        assert all(math.isfinite(v) for v in position)


tag_text = st.one_of(st.none(), st.text(max_size=12))


@settings(max_examples=80, deadline=None)
@given(body=tag_text, topic=tag_text, namespace=tag_text)
def test_generated_tags_read_or_are_refused(body, topic, namespace) -> None:  # type: ignore[no-untyped-def]
    """Any tag texts: a config (non-empty body and topic, stripped) or a ModelError naming the missing tag."""
    tags = {k: v for k, v in (("bodyName", body), ("topicName", topic), ("robotNamespace", namespace)) if v is not None}
    try:
        (config,) = read_plugins("m", [plugin(**tags)], {}, []).configs
    except ModelError as error:
        assert "<bodyName>" in str(error) or "<topicName>" in str(error)
        assert not (body or "").strip() or not (topic or "").strip()
        return
    assert config.body == body.strip() and config.topic == topic.strip()
    assert config.robot_namespace == (None if namespace is None else namespace.strip())


def test_quat_helper_agrees_with_the_spawn_yaw() -> None:
    """The yawed box of the tests above is yawed as quat_from_rpy makes it (a sanity check of the fixture)."""
    sim, _ = gripper_world((0.5, 0.0, 1.0), yaw=math.pi / 2)
    assert box_body(sim).getQuaternion() == pytest.approx(quat_from_rpy(0.0, 0.0, math.pi / 2), abs=1e-12)
