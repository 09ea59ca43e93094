"""The compiled contact kernel steps a world bitwise like physics.world's Python path.

Each scenario runs twice from a freshly seeded ODE, once per path, and every step's body states, contact counts and
watched contacts must be identical, float for float.
"""
from __future__ import annotations

from typing import Callable, List, Tuple

import ode
import pytest
from conftest import TURTLEBOT_URDF
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from turtle_sim_ode.physics import contact_kernel
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.surfaces import SurfaceParams
from turtle_sim_ode.physics.world import PhysicsWorld, seed_ode_random
from turtle_sim_ode.world.simulation import Simulation

Trace = List[Tuple]


def _state(bodies) -> Tuple:
    return tuple(
        body.getPosition() + body.getQuaternion() + body.getLinearVel() + body.getAngularVel() for body in bodies
    )


def _watched(watches, names) -> Tuple:
    """Each watch's contacts, geoms by name (the two runs have geoms of their own)."""
    return tuple(
        tuple((names[c.geom], names[c.other], c.position, c.normal, c.depth) for c in watch.contacts)
        for watch in watches
    )


def test_the_kernel_is_built_and_used_by_default():
    assert contact_kernel.library() is not None, "libturtle_sim_ode_contacts.so not found: build the workspace"
    assert PhysicsWorld().uses_contact_kernel
    assert not PhysicsWorld(contact_kernel=False).uses_contact_kernel


def _turtlebot_circle(kernel: bool) -> Trace:
    seed_ode_random()
    sim = Simulation(contact_kernel=kernel)
    sim.spawn_urdf("mobile_base", TURTLEBOT_URDF, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    robot = sim.robots["mobile_base"]
    robot.params.cmd_timeout = 0.0
    robot.drive.set_command(0.5, 0.5, sim.sim_time)
    wheel = robot.model.geoms["wheel_left_link"]
    names = {geom: "wheel" for geom in wheel}
    names[sim.physics.ground] = "ground"
    watch = sim.physics.watch_contacts(wheel)
    trace: Trace = []
    for _ in range(2000):
        sim.step()
        trace.append((_state(robot.model.bodies), sim.physics.contact_count, _watched([watch], names)))
    assert sim.physics.uses_contact_kernel == kernel
    return trace


def test_turtlebot_circle_is_bitwise_equal():
    with_kernel, in_python = _turtlebot_circle(True), _turtlebot_circle(False)
    _, contacts, (wheel_contacts,) = with_kernel[-1]
    assert contacts == 4  # two merged wheel line contacts, two casters
    assert wheel_contacts  # the watched wheel touches the ground
    assert with_kernel == in_python


def tilted_body(physics: PhysicsWorld, geom: ode.GeomObject, position, surface) -> ode.Body:
    """A body of 1 kg (a 0.1 m ball's inertia), tilted, carrying ``geom`` with ``surface``: the scenarios' pieces."""
    body = ode.Body(physics.world)
    mass = ode.Mass()
    mass.setSphereTotal(1.0, 0.1)
    body.setMass(mass)
    body.setPosition(position)
    body.setQuaternion((0.96, 0.1, 0.2, 0.1))
    geom.setBody(body)
    physics.register_geom(geom, surface)
    return body


def _pile(kernel: bool, change: Callable[[PhysicsWorld, dict], None]) -> Trace:
    """Boxes (up to 8 contact points a pair, cut to max_contacts), spheres and a capsule dropped onto a static
    table and each other, one model self-colliding with an excluded pair, a watched box and watched ground;
    ``change`` runs at step 200."""
    seed_ode_random()
    physics = PhysicsWorld(PhysicsParams(max_contacts=3), contact_kernel=kernel)
    table = ode.GeomBox(physics.static_space, (1.0, 1.0, 0.2))
    table.setPosition((0.0, 0.0, 0.1))
    physics.register_geom(table, SurfaceParams(mu=0.3, kp=1e6, kd=10.0))
    parts = {"table": table}
    bodies = []
    names = {physics.ground: "ground", table: "table"}

    def add(space, geom, position, surface=None):
        body = tilted_body(physics, geom, position, surface)
        bodies.append(body)
        names[geom] = "geom %d" % len(bodies)
        return body, geom

    pile = physics.create_model_space(self_collide=True)
    first, parts["box_a"] = add(pile, ode.GeomBox(pile, (0.2, 0.2, 0.2)), (0.0, 0.0, 0.32), SurfaceParams(mu=0.5))
    second, parts["box_b"] = add(pile, ode.GeomBox(pile, (0.2, 0.2, 0.2)), (0.05, 0.0, 0.55))
    third, _ = add(pile, ode.GeomSphere(pile, 0.1), (0.12, 0.05, 0.7), SurfaceParams(kp=1e5, kd=50.0))
    physics.exclude_collision(second, third)
    other = physics.create_model_space()
    add(other, ode.GeomCapsule(other, 0.05, 0.3), (-0.1, 0.1, 0.6))
    add(other, ode.GeomCylinder(other, 0.1, 0.05), (0.55, 0.0, 0.3))  # rolls off the table onto the ground
    parts["other"] = other
    parts["pile"] = pile
    watches = [physics.watch_contacts([parts["box_a"]]), physics.watch_contacts([physics.ground])]
    parts["watches"] = watches
    trace: Trace = []
    for step in range(400):
        if step == 200:
            change(physics, parts)
        physics.step()
        trace.append((_state(bodies), physics.contact_count, _watched(watches, names)))
    assert physics.uses_contact_kernel == kernel
    return trace


def _no_change(physics: PhysicsWorld, parts: dict) -> None:
    pass


def _table_changes(physics: PhysicsWorld, parts: dict) -> None:
    """Every kind of table change between steps: new surface, unregistered geom, watch dropped, new time step
    (pair softness depends on it), a space deleted, an exclusion lifted by forgetting a body."""
    physics.register_geom(parts["box_b"], SurfaceParams(mu=0.05, mu2=0.02))
    physics.unregister_geom(parts["table"])
    physics.unwatch_contacts(parts["watches"][1])
    physics.set_params(PhysicsParams(max_contacts=2, time_step=0.002))
    physics.destroy_model_space(parts["other"])
    physics.forget_body(parts["box_b"].getBody())


@pytest.mark.parametrize("change", [_no_change, _table_changes])
def test_pile_of_shapes_is_bitwise_equal(change):
    with_kernel, in_python = _pile(True, change), _pile(False, change)
    assert max(count for _, count, _ in with_kernel) > 5
    assert any(watched[0] for _, _, watched in with_kernel)
    if change is _no_change:  # the cylinder rolls onto the watched ground (the change stops that watch before)
        assert any(watched[1] for _, _, watched in with_kernel)
    assert [entry[1:] for entry in with_kernel] == [entry[1:] for entry in in_python]  # first: clearer message
    assert with_kernel == in_python


@pytest.mark.parametrize("kernel", [True, False])
def test_watched_contacts_are_the_last_steps_whenever_read(kernel):
    """The kernel hands contacts over only when read: what is read must still be the last step's, once, for the
    watches that were there during that step."""
    physics = PhysicsWorld(contact_kernel=kernel)
    space = physics.create_model_space()
    body = ode.Body(physics.world)
    mass = ode.Mass()
    mass.setSphereTotal(1.0, 0.1)
    body.setMass(mass)
    body.setPosition((0.0, 0.0, 0.095))  # resting on the ground: one contact a step
    ball = ode.GeomSphere(space, 0.1)
    ball.setBody(body)
    physics.register_geom(ball)
    kept, dropped = physics.watch_contacts([ball]), physics.watch_contacts([ball])
    for _ in range(5):
        physics.step()
    physics.unwatch_contacts(dropped)
    late = physics.watch_contacts([ball])
    assert len(kept.contacts) == 1 and kept.contacts[0].other is physics.ground
    assert kept.contacts is kept.contacts  # read once, then kept
    assert late.contacts == []  # not there during the step
    physics.step()
    assert len(late.contacts) == len(kept.contacts) == 1


def _gazebo_surfaces(kernel: bool) -> Trace:
    """Per-link Gazebo surfaces on every pair kind: a wheel-like cylinder with fdir1 (turned as it rolls), min_depth
    and max_vel; a box with slip and a lower max_vel than the world's; a sphere with fdir1 and the smaller mu1
    against the box's; body-less table with min_depth (ignored: no body), in a world with a 1 cm surface layer."""
    seed_ode_random()
    params = PhysicsParams(contact_surface_layer=0.01, contact_max_correcting_vel=2000.0, solver_iterations=150)
    physics = PhysicsWorld(params, contact_kernel=kernel)
    table = ode.GeomBox(physics.static_space, (1.0, 1.0, 0.2))
    table.setPosition((0.6, 0.0, 0.1))
    physics.register_geom(table, SurfaceParams(mu=0.5, min_depth=0.05))
    bodies = []
    names = {physics.ground: "ground", table: "table"}

    def add(geom, position, surface, velocity=(0.0, 0.0, 0.0)):
        body = tilted_body(physics, geom, position, surface)
        body.setLinearVel(velocity)
        bodies.append(body)
        names[geom] = "geom %d" % len(bodies)
        return geom

    space = physics.create_model_space(self_collide=True)
    wheel = SurfaceParams(mu=0.1, mu2=0.1, kp=5e5, kd=10.0, min_depth=0.001, max_vel=0.1, fdir1=(1.0, 0.0, 0.0))
    watched = add(ode.GeomCylinder(space, 0.05, 0.03), (0.0, 0.0, 0.06), wheel, (0.5, 0.1, 0.0))
    slippery = SurfaceParams(mu=0.8, kp=1e6, kd=100.0, max_vel=0.05, slip1=0.01, slip2=0.02)
    add(ode.GeomBox(space, (0.1, 0.1, 0.1)), (0.3, 0.0, 0.3), slippery, (0.2, 0.0, 0.0))
    add(ode.GeomSphere(space, 0.05), (0.32, 0.02, 0.5), SurfaceParams(mu=0.3, fdir1=(0.0, 1.0, 0.0), min_depth=0.002))
    watch = physics.watch_contacts([watched])
    trace: Trace = []
    for _ in range(600):
        physics.step()
        trace.append((_state(bodies), physics.contact_count, _watched([watch], names)))
    assert physics.uses_contact_kernel == kernel
    return trace


def test_gazebo_surfaces_are_bitwise_equal():
    with_kernel, in_python = _gazebo_surfaces(True), _gazebo_surfaces(False)
    assert max(count for _, count, _ in with_kernel) >= 3
    assert [entry[1:] for entry in with_kernel] == [entry[1:] for entry in in_python]
    assert with_kernel == in_python


# A dropped piece: (shape, size, x, y, z, vx, vy, mu).
pieces = st.tuples(
    st.sampled_from(["box", "sphere", "cylinder", "capsule"]),
    st.floats(0.03, 0.15),
    st.floats(-0.3, 0.3),
    st.floats(-0.3, 0.3),
    st.floats(0.05, 0.6),
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
    st.floats(0.0, 2.0),
)


def _generated(kernel: bool, solver: str, time_step: float, items) -> Trace:
    """``items`` dropped in one self-colliding space, stepped with ``solver``; a pre-step hook reads each body's
    force and velocity (as plugins.f3d's does) into the trace: the kernel's whole step runs after the hooks, the
    Python path's hooks run between colliding and integrating, and both must see the same."""
    seed_ode_random()
    physics = PhysicsWorld(PhysicsParams(solver=solver, time_step=time_step), contact_kernel=kernel)
    space = physics.create_model_space(self_collide=True)
    shapes = {
        "box": lambda size: ode.GeomBox(space, (size, 1.5 * size, size)),
        "sphere": lambda size: ode.GeomSphere(space, size),
        "cylinder": lambda size: ode.GeomCylinder(space, size, 0.5 * size),
        "capsule": lambda size: ode.GeomCapsule(space, 0.5 * size, size),
    }
    bodies = []
    for shape, size, x, y, z, vx, vy, mu in items:
        body = tilted_body(physics, shapes[shape](size), (x, y, z), SurfaceParams(mu=mu))
        body.setLinearVel((vx, vy, 0.0))
        body.addForce((vx, 0.0, 0.0))
        bodies.append(body)
    seen: List[Tuple] = []
    physics.add_pre_step_hook(lambda: seen.append(tuple(b.getForce() + b.getLinearVel() for b in bodies)))
    trace: Trace = []
    for _ in range(150):
        physics.step()
        trace.append((_state(bodies), physics.contact_count, seen[-1]))
    assert physics.uses_contact_kernel == kernel
    return trace


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    solver=st.sampled_from(["quick", "world"]),
    time_step=st.sampled_from([0.001, 0.0025, 0.01]),
    items=st.lists(pieces, min_size=1, max_size=6),
)
def test_generated_piles_are_bitwise_equal(solver, time_step, items):
    """The kernel's one-call step (collide and integrate without the GIL) against the Python path, with either
    solver."""
    with_kernel = _generated(True, solver, time_step, items)
    in_python = _generated(False, solver, time_step, items)
    assert len(with_kernel) == 150
    for state, _, _ in with_kernel:  # invariant: no solver blew up
        assert all(value == value for body in state for value in body)
    assert with_kernel == in_python
