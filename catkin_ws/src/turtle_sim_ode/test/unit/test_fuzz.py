"""Property-based tests (issue #16): generated model texts and world requests, careless and hostile, thrown at a
world holding a TurtleBot and a reference box. After each input, whatever it was: the answer came within
ANSWER_WITHIN_REFERENCES times the time of spawning a TurtleBot in a new world (measured in the same run) and
was a clean refusal (ModelError, WorldError, ValueError: what the services turn into success false) or a success;
the world steps on with sim time advancing exactly; every pose is finite and on or near the ground; the
reference box has not moved.

CI runs a bounded number of examples with a fixed seed (derandomize); scripts/fuzz_sim.sh runs many more."""
from __future__ import annotations

import functools
import math
import os
import sys
from typing import Callable, List, Optional

import pytest
from conftest import PACKAGE_ROOT, TURTLEBOT_URDF
from hypothesis import HealthCheck, event, given, seed, settings
from hypothesis import strategies as st
from workspace_testing.timing import assert_within, best_seconds, timed

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

EXAMPLES = int(os.environ.get("TURTLE_SIM_FUZZ_EXAMPLES", "40"))
SEED = os.environ.get("TURTLE_SIM_FUZZ_SEED")  # scripts/fuzz_sim.sh: fresh inputs; CI: the fixed derandomized ones
FUZZ = settings(
    max_examples=EXAMPLES,
    derandomize=SEED is None,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
)
ANSWER_WITHIN_REFERENCES = 50  # an answer may take this many times reference_seconds()
STEPS_AFTER = 300
CLEAN_REFUSALS = (ModelError, WorldError, ValueError)
BOX = (PACKAGE_ROOT / "test" / "models" / "box.urdf").read_text()
FUZZ_POSE = (30.0, 0.0, 0.5, 0.0, 0.0, 0.0)  # far from the reference box and the TurtleBot

HOSTILE_NUMBERS = [0.0, -0.0, 5e-324, 1e-320, 1e-310, 1e-300, 1e-12, 1e12, 1e300, 1e308, -1e308, math.pi, 7.0, -1.0]
HOSTILE_TEXTS = ["", " ", "nan", "-inf", "inf", "abc", "1e", "0x10", "1,5", "１", "1 2", "--1"]

# Mostly plausible values, so that inputs get past parsing and into the physics, with hostile ones mixed in.
plausible = st.floats(min_value=0.001, max_value=2.0).map(repr)
hostile = st.one_of(
    st.sampled_from(HOSTILE_NUMBERS).map(repr),
    st.sampled_from(HOSTILE_TEXTS),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
)


def rarely(usual: st.SearchStrategy, unusual: st.SearchStrategy, odds: int = 30) -> st.SearchStrategy:
    """``unusual`` once in ``odds`` draws, else ``usual``."""
    return st.integers(min_value=1, max_value=odds).flatmap(lambda n: unusual if n == 1 else usual)


# A model has about thirty numbers, so about two models in three carry a hostile one.
number_text = rarely(plausible, hostile)


def normal_floats(low: float, high: float) -> st.SearchStrategy:
    """Floats in [low, high], subnormals as 0 (Hypothesis 5, Ubuntu 20.04's, has no allow_subnormal)."""
    return st.floats(min_value=low, max_value=high).map(lambda v: 0.0 if abs(v) < sys.float_info.min else v)


signed_text = rarely(normal_floats(-2.0, 2.0).map(repr), hostile)
names = rarely(st.sampled_from(["a", "b", "c", "wheel", "base"]), st.text(max_size=6), 20)
mostly = st.integers(min_value=0, max_value=9).map(lambda n: n > 0)  # True nine times in ten


@st.composite
def geometries(draw: Callable) -> str:
    kind = draw(rarely(st.sampled_from(["box", "cylinder", "sphere", "mesh"]), st.just("capsule"), 20))
    if kind == "box":
        return f'<box size="{draw(number_text)} {draw(number_text)} {draw(number_text)}"/>'
    if kind == "cylinder":
        return f'<cylinder radius="{draw(number_text)}" length="{draw(number_text)}"/>'
    if kind == "sphere":
        return f'<sphere radius="{draw(number_text)}"/>'
    if kind == "mesh":
        return f'<mesh filename="package://nowhere/m.stl" scale="{draw(number_text)} 1 1"/>'
    return "<capsule/>"


@st.composite
def links(draw: Callable, name: str) -> str:
    inertia = draw(number_text)
    inertial = (
        f'<inertial><origin xyz="{draw(signed_text)} 0 0"/><mass value="{draw(number_text)}"/>'
        f'<inertia ixx="{inertia}" ixy="{draw(rarely(st.just("0"), hostile))}" ixz="0" iyy="{draw(number_text)}" '
        f'iyz="0" izz="{draw(number_text)}"/></inertial>'
    )
    collision = f"<collision><geometry>{draw(geometries())}</geometry></collision>"
    return f'<link name="{name}">{inertial if draw(mostly) or name == "l0" else ""}{collision}</link>'


@st.composite
def joints(draw: Callable, parent: str, child: str) -> str:
    kind = draw(st.sampled_from(["continuous"] * 3 + ["revolute"] * 2 + ["prismatic", "fixed", "floating", "planar"]))
    parts = [f'<parent link="{parent}"/><child link="{child}"/>']
    parts.append(f'<origin xyz="{draw(signed_text)} {draw(signed_text)} 0" rpy="0 0 {draw(signed_text)}"/>')
    parts.append(f'<axis xyz="{draw(signed_text)} {draw(signed_text)} {draw(signed_text)}"/>')
    if draw(mostly):
        parts.append(
            f'<limit lower="{draw(signed_text)}" upper="{draw(signed_text)}" effort="{draw(number_text)}" '
            f'velocity="{draw(number_text)}"/>'
        )
    if draw(st.booleans()):
        parts.append(f'<dynamics damping="{draw(number_text)}" friction="{draw(number_text)}"/>')
    if draw(st.booleans()):
        parts.append(f'<mimic joint="j0" multiplier="{draw(signed_text)}" offset="{draw(signed_text)}"/>')
    return f'<joint name="j{child}" type="{kind}">{"".join(parts)}</joint>'


@st.composite
def gazebo_blocks(draw: Callable, link_names: List[str]) -> str:
    blocks = []
    reference = draw(st.sampled_from(link_names * 5 + ["ghost"]))
    tags = draw(st.lists(st.sampled_from(["mu1", "mu2", "kp", "kd", "maxVel", "minDepth"]), max_size=4))
    blocks.append(f'<gazebo reference="{reference}">' + "".join(f"<{t}>{draw(number_text)}</{t}>" for t in tags))
    if draw(st.booleans()):
        blocks.append(
            f'<sensor type="{draw(st.sampled_from(["ray", "ray", "imu", "contact", "camera", "gps"]))}" name="s">'
            f"<update_rate>{draw(number_text)}</update_rate><ray><scan><horizontal>"
            f"<samples>{draw(st.sampled_from(['1', '10', '360', '360', '0', '-5', 'x']))}</samples>"
            f"<min_angle>{draw(signed_text)}</min_angle><max_angle>{draw(signed_text)}</max_angle>"
            f"</horizontal></scan><range><min>{draw(number_text)}</min><max>{draw(number_text)}</max></range></ray>"
            f'<plugin name="p" filename="libgazebo_ros_laser.so"><topicName>scan</topicName></plugin></sensor>'
        )
    blocks.append("</gazebo>")
    if len(link_names) > 2 and draw(st.booleans()):
        params = "".join(
            f"<{tag}>{draw(number_text)}</{tag}>"
            for tag in ("wheelSeparation", "wheelDiameter", "wheelTorque", "wheelAcceleration", "updateRate")
        )
        blocks.append(
            '<gazebo><plugin name="drive" filename="libgazebo_ros_diff_drive.so">'
            f"<leftJoint>j{link_names[1]}</leftJoint><rightJoint>j{link_names[2]}</rightJoint>{params}</plugin></gazebo>"
        )
    return "".join(blocks)


@st.composite
def urdf_texts(draw: Callable) -> str:
    count = draw(st.integers(min_value=1, max_value=4))
    link_names = [f"l{i}" for i in range(count)]
    parts = [draw(links(name)) for name in link_names]
    parts += [draw(joints(link_names[0], name)) for name in link_names[1:]]
    parts.append(draw(gazebo_blocks(link_names)))
    return f'<robot name="{draw(names)}">{"".join(parts)}</robot>'


@st.composite
def sdf_texts(draw: Callable) -> str:
    pose = " ".join(draw(signed_text) for _ in range(6))
    surface = (
        f"<surface><friction><ode><mu>{draw(number_text)}</mu><mu2>{draw(number_text)}</mu2></ode></friction>"
        f"<contact><ode><kp>{draw(number_text)}</kp><kd>{draw(number_text)}</kd>"
        f"<min_depth>{draw(number_text)}</min_depth><max_vel>{draw(number_text)}</max_vel></ode></contact></surface>"
    )
    return (
        f'<sdf version="{draw(st.sampled_from(["1.4", "1.6", "1.7", "2.0", "x"]))}"><model name="m">'
        f"<static>{draw(st.sampled_from(['false', 'true', 'maybe']))}</static>"
        f'<link name="a"><pose>{pose}</pose><inertial><mass>{draw(number_text)}</mass><inertia>'
        f"<ixx>{draw(number_text)}</ixx><iyy>{draw(number_text)}</iyy><izz>{draw(number_text)}</izz></inertia>"
        f'</inertial><collision name="c"><geometry>'
        f"<box><size>{draw(number_text)} {draw(number_text)} {draw(number_text)}</size></box>"
        f"</geometry>{surface if draw(st.booleans()) else ''}</collision></link></model></sdf>"
    )


def new_world() -> Simulation:
    sim = Simulation()
    sim.spawn_urdf("reference", BOX, (-2.0, 0.0, 0.1, 0.0, 0.0, 0.0))
    sim.spawn_urdf("mobile_base", TURTLEBOT_URDF)
    for _ in range(200):
        sim.step()
    return sim


@functools.lru_cache(maxsize=None)
def reference_seconds() -> float:
    """Spawning a TurtleBot in a new world: the machine's speed at a typical request, measured in this run."""
    return best_seconds(lambda: Simulation().spawn_urdf("mobile_base", TURTLEBOT_URDF))


def assert_answered_in_time(seconds: float) -> None:
    assert_within(seconds, reference_seconds(), ANSWER_WITHIN_REFERENCES, "the answer")


def accepted(action: Callable[[], object]) -> bool:
    try:
        action()
        event("accepted")
        return True
    except CLEAN_REFUSALS as error:
        event(f"refused ({type(error).__name__})")
        return False


def answered(action: Callable[[], object]) -> bool:
    """Run one input: a clean refusal or a success, in time; True if it was accepted."""
    result, seconds = timed(lambda: accepted(action))
    assert_answered_in_time(seconds)
    return result


def assert_world_goes_on(sim: Simulation, reference_position: Optional[tuple]) -> None:
    """``reference_position`` None: the input was meant to move the reference box (world physics, its own mass)."""
    start = sim.sim_time
    for _ in range(STEPS_AFTER):
        sim.step()
    assert sim.sim_time == pytest.approx(start + STEPS_AFTER * sim.physics.time_step, rel=1e-9)
    for name in sim.models:
        position, orientation, linear, angular = sim.get_model_state(name)
        values = (*position, *orientation, *linear, *angular)
        assert all(math.isfinite(v) for v in values), (name, values)
        assert position[2] > -1.0, (name, position)
    if reference_position is not None:
        assert sim.get_model_state("reference")[0] == pytest.approx(reference_position, abs=1e-6)


@pytest.fixture(scope="module")
def world() -> Simulation:
    return new_world()


@FUZZ
@seed(int(SEED or 0))
@given(text=st.one_of(urdf_texts(), sdf_texts()))
def test_generated_models_are_refused_cleanly_or_spawned_sane(world: Simulation, text: str) -> None:
    reference = world.get_model_state("reference")[0]
    answered(
        lambda: world.spawn_sdf("fuzz", text, FUZZ_POSE)
        if text.startswith("<sdf")
        else world.spawn_urdf("fuzz", text, FUZZ_POSE)
    )
    try:
        assert_world_goes_on(world, reference)
    finally:
        if "fuzz" in world.models:
            world.delete("fuzz")


request_values = st.one_of(
    st.floats(min_value=-5.0, max_value=5.0),
    st.sampled_from(HOSTILE_NUMBERS),
    st.floats(allow_nan=True, allow_infinity=True),
)
joint_names = st.sampled_from(["wheel_left_joint", "wheel_right_joint", "mobile_base::wheel_left_joint", "ghost"])
requests = st.one_of(
    st.builds(
        lambda name, key, value: ("set_joint_properties", name, {key: [value]}),
        joint_names,
        st.sampled_from(["damping", "hiStop", "loStop", "erp", "cfm", "stop_erp", "stop_cfm", "fudge_factor"]),
        request_values,
    ),
    st.builds(
        lambda name, effort, duration: ("apply_joint_effort", name, effort, 0.0, duration),
        joint_names,
        request_values,
        st.sampled_from([0.05, 0.5, -1.0]),
    ),
    st.builds(
        lambda link, mass, moments: ("set_link_properties", link, (0, 0, 0), (0, 0, 0, 1), True, mass, moments),
        st.sampled_from(["reference::box_link", "mobile_base::base_link", "mobile_base::wheel_left_link"]),
        request_values,
        st.tuples(request_values, st.just(0.0), st.just(0.0), request_values, st.just(0.0), request_values),
    ),
    st.builds(
        lambda name, value: ("set_model_configuration", "mobile_base", [name], [value]), joint_names, request_values
    ),
    st.builds(
        lambda step, rate, z: ("set_physics_properties", step, rate, (0.0, 0.0, z), 50, 0.2, 1e-5, 1e-4, 0.1, 4),
        st.one_of(st.just(0.001), request_values),
        st.one_of(st.just(0.0), request_values),
        st.one_of(st.just(-9.81), request_values),
    ),
    st.builds(
        lambda link, force: ("apply_body_wrench", link, "", (0, 0, 0), force, (0, 0, 0), 0.0, 0.1),
        st.sampled_from(["mobile_base::base_link", "reference::box_link"]),
        st.tuples(request_values, request_values, request_values),
    ),
)

SCRATCH_ROBOT_POSE = (0.0, 5.0, 0.0, 0.0, 0.0, 0.0)


@FUZZ
@seed(int(SEED or 0))
@given(sequence=st.lists(requests, min_size=1, max_size=4))
def test_generated_world_requests_are_refused_cleanly_or_leave_a_sane_world(sequence: list) -> None:
    sim = new_world()
    sim.delete("mobile_base")  # requests go to a robot of their own, away from the reference box
    sim.spawn_urdf("mobile_base", TURTLEBOT_URDF, SCRATCH_ROBOT_POSE)
    reference = sim.get_model_state("reference")[0]
    for request in sequence:
        method, *arguments = request
        keywords = arguments.pop() if method == "set_joint_properties" else {}
        accepted = answered(lambda: getattr(sim, method)(*arguments, **keywords))
        meant_to_move_it = method == "set_physics_properties" or str(arguments[0]).startswith("reference")
        if accepted and meant_to_move_it:
            reference = None
    sim.clear_body_wrenches("mobile_base::base_link")
    assert_world_goes_on(sim, reference)
