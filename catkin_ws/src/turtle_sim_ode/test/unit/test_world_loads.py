"""Gazebo's world API on Simulation: body wrenches and joint efforts held in time, cleared, refused."""
import math

import pytest
from world_helpers import ARM, BOX, floating, run

from turtle_sim_ode.world.values import WorldError


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
