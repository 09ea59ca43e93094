"""Per-joint work after each step done in C for a model's joints at once (physics.joint_batch, src/contact_kernel.c)
steps as the Python path of models.built does it joint by joint, double for double (issue #33: a 1000-link chain spent
12 % of its step counting turns in Python): continuous joints' turns (tso_count_turns) through steps, a
set_model_configuration and a reset_world; viscous damping of hinges and sliders (tso_damp_joints), also when
set_damping changes it."""
from __future__ import annotations

import math
from typing import List, Tuple

import ode
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.physics.world import PhysicsWorld, seed_ode_random
from turtle_sim_ode.world.simulation import Simulation

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def chain_urdf(links: int, axis: str = "0 1 0", kind: str = "continuous", damping: float = 0.0) -> str:
    """0.1 m boxes end to end on ``kind`` joints with viscous ``damping`` (the chain of bench_sim's section 9,
    shorter)."""
    parts = [
        '<link name="l%d">%s<collision><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry>'
        "</collision></link>" % (i, INERTIAL)
        for i in range(links)
    ]
    parts += [
        '<joint name="j%d" type="%s"><parent link="l%d"/><child link="l%d"/><origin xyz="0 0 0.1"/>'
        '<axis xyz="%s"/><limit lower="-0.05" upper="0.05" effort="1" velocity="1"/><dynamics damping="%r"/></joint>'
        % (i, kind, i - 1, i, axis, damping)
        for i in range(1, links)
    ]
    return '<robot name="chain">%s</robot>' % "".join(parts)


def _run(kernel: bool, links: int, pose: Tuple[float, ...], spin: float, steps: int) -> List[List[float]]:
    """The joint angles after ``steps`` steps with the root spun at ``spin`` rad/s about the joints' axis, after a
    set_model_configuration, after as many steps spun again, after a reset_world, after more steps spun again."""
    seed_ode_random()
    sim = Simulation(contact_kernel=kernel)
    sim.spawn_urdf("chain", chain_urdf(links), pose)
    model = sim.models["chain"]
    assert (model.joints["j1"]._counter is not None) == kernel and model._hook._damper is None
    model.links["l0"].body.setAngularVel((0.0, spin, 0.0))
    angles = []
    for change in (lambda: sim.set_model_configuration("chain", ["j1", "j2"], [7.5, -3.0]), sim.reset_world):
        for _ in range(steps):
            sim.step()
        angles.append([handle.angle() for handle in model.joints.values()])
        change()
        angles.append([handle.angle() for handle in model.joints.values()])
        model.links["l0"].body.setAngularVel((0.0, spin, 0.0))
    for _ in range(steps):
        sim.step()
    return angles + [[handle.angle() for handle in model.joints.values()]]


def test_a_spun_chain_reads_the_same_turns_in_c_as_in_python():
    counted = _run(True, 12, (0.0, 0.0, 3.0, 0.0, 0.0, 0.0), 40.0, 400)
    assert counted == _run(False, 12, (0.0, 0.0, 3.0, 0.0, 0.0, 0.0), 40.0, 400)
    assert max(abs(angle) for angle in counted[0]) > 2 * math.pi  # turns were counted across the wrap
    assert counted[1][:2] == [7.5, -3.0]  # set_model_configuration reads back exactly
    assert counted[3] == [0.0] * 11  # reset_world: the spawn's
    assert counted[4] != counted[3]


@settings(max_examples=8, deadline=None)
@given(
    links=st.integers(3, 8),
    pose=st.tuples(st.just(0.0), st.just(0.0), *(st.integers(-300, 300).map(lambda n: n / 100) for _ in range(4))),
    spin=st.integers(-80, 80).map(float),
)
def test_generated_chains_read_the_same_turns_in_c_as_in_python(links, pose, spin):
    counted = _run(True, links, pose, spin, 150)
    assert counted == _run(False, links, pose, spin, 150)
    assert all(math.isfinite(angle) for phase in counted for angle in phase)


def test_a_hinge_without_a_unique_id_falls_back_to_python():
    """Two hinges between the same two bodies cannot be told apart by their bodies: no counter, the Python path."""
    physics = PhysicsWorld()
    first, second = ode.Body(physics.world), ode.Body(physics.world)
    hinges = [ode.HingeJoint(physics.world), ode.HingeJoint(physics.world)]
    for hinge in hinges:
        hinge.attach(first, second)
    assert physics.turn_counter(hinges) is None
    assert physics.turn_counter(hinges[:1]) is None
    lone = ode.HingeJoint(physics.world)
    lone.attach(second, None)
    assert physics.turn_counter([lone]) is not None
    assert PhysicsWorld(contact_kernel=False).turn_counter([lone]) is None


def _damped(kernel: bool, kind: str, axis: str, damping: float, spin: Tuple[float, float, float]) -> List[Tuple]:
    """Every body's state after each of 300 steps of a 6-link chain of damped ``kind`` joints, spun by ``spin``; its
    damping changed twice on the way (set_damping: one joint off, then one joint on again, doubled)."""
    seed_ode_random()
    sim = Simulation(contact_kernel=kernel)
    sim.spawn_urdf("chain", chain_urdf(6, axis, kind, damping), (0.0, 0.0, 2.0, 0.4, 0.0, 0.0))
    model = sim.models["chain"]
    assert (model._hook is not None and model._hook._damper is not None) == (kernel and damping > 0)
    model.links["l0"].body.setAngularVel(spin)
    model.links["l0"].body.setLinearVel(spin)
    trace = []
    for step in range(300):
        if step == 100:
            model.set_damping("j2", 0.0)
        if step == 200:
            model.set_damping("j2", 2 * damping)
        sim.step()
        trace.append(tuple(body.getPosition() + body.getLinearVel() + body.getAngularVel() for body in model.bodies))
    return trace


def test_damped_hinges_and_sliders_step_the_same_in_c_as_in_python():
    for kind, axis in (("continuous", "0 1 0"), ("revolute", "1 0 0"), ("prismatic", "0 0 1"), ("prismatic", "1 0 0")):
        assert _damped(True, kind, axis, 0.3, (2.0, -3.0, 1.0)) == _damped(False, kind, axis, 0.3, (2.0, -3.0, 1.0))


@settings(max_examples=10, deadline=None)
@given(
    kind=st.sampled_from(["continuous", "revolute", "prismatic"]),
    damping=st.sampled_from([0.0, 0.01, 0.5, 3.0]),
    spin=st.tuples(*(st.integers(-20, 20).map(float) for _ in range(3))),
)
def test_generated_damped_chains_step_the_same_in_c_as_in_python(kind, damping, spin):
    counted = _damped(True, kind, "0 1 0", damping, spin)
    assert counted == _damped(False, kind, "0 1 0", damping, spin)
    assert all(math.isfinite(value) for state in counted[-1] for value in state)


def test_set_damping_adds_the_hook_once_damping_starts():
    """A model without continuous or damped joints has no hook until set_damping gives one damping; 0 adds none."""
    sim = Simulation()
    sim.spawn_urdf("chain", chain_urdf(3, kind="revolute"), (0.0, 0.0, 2.0, 0.0, 0.0, 0.0))
    model = sim.models["chain"]
    assert model._hook is None
    model.set_damping("j1", 0.0)
    assert model._hook is None
    model.set_damping("j1", 0.2)
    assert model._hook is not None and model._hook._damper is not None
