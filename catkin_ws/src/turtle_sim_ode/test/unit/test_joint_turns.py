"""Continuous joints' turns counted in C (physics.joint_turns, src/contact_kernel.c's tso_count_turns) read the same
angles as the Python path (models.built.JointHandle.track_turns), double for double, through steps, a
set_model_configuration and a reset_world (issue #33: a 1000-link chain spent 12 % of its step counting turns in
Python)."""
from __future__ import annotations

import math
from typing import List, Tuple

import ode
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.physics.world import PhysicsWorld, seed_ode_random
from turtle_sim_ode.world.simulation import Simulation

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def chain_urdf(links: int, axis: str = "0 1 0") -> str:
    """0.1 m boxes end to end on continuous joints (the chain of bench_sim's section 9, shorter)."""
    parts = [
        '<link name="l%d">%s<collision><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry>'
        "</collision></link>" % (i, INERTIAL)
        for i in range(links)
    ]
    parts += [
        '<joint name="j%d" type="continuous"><parent link="l%d"/><child link="l%d"/><origin xyz="0 0 0.1"/>'
        '<axis xyz="%s"/></joint>' % (i, i - 1, i, axis)
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
    assert (model.joints["j1"]._counter is not None) == kernel
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
