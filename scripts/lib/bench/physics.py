"""Section 1 of the benchmark (scripts/bench_sim.py), without ROS: Simulation.step of one TurtleBot, the bare PyODE
floor for the same bodies (``BarePyOde``), the Python collision path the contact kernel replaces, and the radius of the
circle the robot drives."""
from __future__ import annotations

import math
import time
from typing import Any, Callable, Dict, List, Sequence, Tuple

from bench.plan import CIRCLE, MODEL, URDF_PATH, BenchError, Plan

CIRCLE_SAMPLE_PERIOD_S = 0.01
CIRCLE_SAMPLES_FROM_S = 1.0  # leave out the start (the robot accelerates onto the circle)
SETTLE_STEPS = 500


def turtlebot_simulation(contact_kernel: bool = True) -> Any:
    """A Simulation (default physics) with the TurtleBot as MODEL, its drive commanded CIRCLE with no timeout;
    ``contact_kernel`` False collides in Python instead of the compiled kernel."""
    from turtle_sim_ode.world.simulation import Simulation

    sim = Simulation(contact_kernel=contact_kernel)
    with open(URDF_PATH) as urdf:
        sim.spawn_urdf(MODEL, urdf.read(), (0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    robot = sim.robots[MODEL]
    robot.params.cmd_timeout = 0.0
    robot.drive.set_command(CIRCLE[0], CIRCLE[1], sim.sim_time)
    return sim


def best_steps_per_second(steppers: Sequence[Callable[[], None]], steps: int, repeats: int) -> List[float]:
    """Best steps/s of each stepper over ``repeats`` runs of ``steps``, timed in turns so that all see the same load
    of the machine."""
    best = [math.inf] * len(steppers)
    for _ in range(repeats):
        for index, step in enumerate(steppers):
            start = time.perf_counter()
            for _ in range(steps):
                step()
            best[index] = min(best[index], time.perf_counter() - start)
    return [steps / seconds for seconds in best]


# PyODE frees a World's C object with its wrapper and with it every body and joint, which the wrappers that die later
# free again: the bare world lives as long as the process.
_BARE_WORLDS: List[Any] = []


class BarePyOde:
    """The simulation's world, bodies (at their current state), hinge motors, geoms and contact surfaces made again
    directly with PyODE, and stepped by a minimal loop: collide with the ground, contact joints, quickStep."""

    def __init__(self, sim: Any) -> None:
        import ode
        from turtle_sim_ode.physics import ode_constants
        from turtle_sim_ode.models.transforms import compose, inverse
        from turtle_sim_ode.physics.settings import configure_world
        from turtle_sim_ode.physics.surfaces import combine_surfaces

        physics, model = sim.physics, sim.models[MODEL]
        params = physics.params
        self.time_step = params.time_step
        self.world = ode.World()
        _BARE_WORLDS.append(self.world)
        configure_world(self.world, params)
        self.ground = ode.GeomPlane(None, (0.0, 0.0, 1.0), 0.0)
        self.bodies = {}
        for body in model.bodies:
            copy = ode.Body(self.world)
            copy.setMass(body.getMass())
            copy.setPosition(body.getPosition())
            copy.setQuaternion(body.getQuaternion())
            copy.setLinearVel(body.getLinearVel())
            copy.setAngularVel(body.getAngularVel())
            self.bodies[body] = copy
        # (geom, body, surface, contacts kept) of the TurtleBot's cylinders and spheres: one contact per cylinder,
        # since ours merges the two ends of a wheel's line contact into one.
        self.ground_pairs = []
        for geom in (geom for link_geoms in model.geoms.values() for geom in link_geoms):
            if isinstance(geom, ode.GeomCylinder):
                copy, kept = ode.GeomCylinder(None, *geom.getParams()), 1
            else:
                copy, kept = ode.GeomSphere(None, geom.getRadius()), params.max_contacts
            body = geom.getBody()
            copy.setBody(self.bodies[body])
            offset = compose(
                inverse((body.getPosition(), body.getQuaternion())), (geom.getPosition(), geom.getQuaternion())
            )
            copy.setOffsetPosition(offset[0])
            copy.setOffsetQuaternion(offset[1])
            surface = combine_surfaces(physics.surface(physics.ground), physics.surface(geom), self.time_step)
            self.ground_pairs.append((copy, self.bodies[body], surface, kept))
        self.joints = []  # the TurtleBot's wheel hinges
        for handle in model.joints.values():
            joint = ode.HingeJoint(self.world)
            joint.attach(self.bodies[handle.joint.getBody(0)], self.bodies[handle.joint.getBody(1)])
            joint.setAnchor(handle.joint.getAnchor())
            joint.setAxis(handle.joint.getAxis())
            for param in (ode_constants.PARAM_VEL, ode_constants.PARAM_FMAX):
                joint.setParam(param, handle.joint.getParam(param))
            self.joints.append(joint)
        self.contact_joints: List[Any] = []
        self._collide, self._contact_joint = ode.collide, ode.ContactJoint

    def step(self) -> None:
        world, ground, keep = self.world, self.ground, self.contact_joints.append
        collide, contact_joint = self._collide, self._contact_joint
        self.contact_joints.clear()  # dropping a wrapper destroys its joint
        for geom, body, (mode, _side, _adjust, mu, mu2, erp, cfm, *_rest), kept in self.ground_pairs:
            for contact in collide(ground, geom)[:kept]:
                contact.setMode(mode)
                contact.setMu(mu)
                contact.setMu2(mu2)
                contact.setSoftERP(erp)
                contact.setSoftCFM(cfm)
                joint = contact_joint(world, None, contact)
                joint.attach(None, body)
                keep(joint)
        world.quickStep(self.time_step)


def circle_radius(points: Sequence[Sequence[float]]) -> float:
    """Radius of the least-squares circle through (x, y) points."""
    from turtle_sim_ode.analysis.path_fit import fit_circle

    return fit_circle(points)[1]


def circle_track(seconds: float) -> List[Tuple[float, float]]:
    """base_footprint's (x, y) in our simulation driving CIRCLE, sampled as the PyBullet peer samples."""
    sim = turtlebot_simulation()
    model = sim.models[MODEL]
    dt = sim.physics.time_step
    sample_every = max(1, round(CIRCLE_SAMPLE_PERIOD_S / dt))
    track = []
    for step in range(1, round(seconds / dt) + 1):
        sim.step()
        if step % sample_every == 0 and step * dt >= CIRCLE_SAMPLES_FROM_S:
            position, _ = model.link_pose("base_footprint")
            track.append((position[0], position[1]))
    return track


def sustained_steps_per_second(step: Callable[[], None], seconds: float) -> float:
    """Steps/s of ``step`` over ``seconds`` of wall time in one go, as the node's rate is measured (probe.in_turns);
    best_steps_per_second keeps the quickest of short runs instead."""
    steps, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        for _ in range(1000):
            step()
        steps += 1000
    return steps / (time.perf_counter() - start)


def physics_only(plan: Plan) -> Dict[str, Any]:
    """Section 1: our steps/s, the bare PyODE floor's, and the circle radius we drive."""
    sim, in_python = turtlebot_simulation(), turtlebot_simulation(contact_kernel=False)
    if not sim.physics.uses_contact_kernel:
        raise BenchError("the contact kernel (libturtle_sim_ode_contacts.so) is not built: run scripts/build.sh")
    for _ in range(SETTLE_STEPS):
        sim.step()
        in_python.step()
    bare = BarePyOde(sim)
    ours, floor, python_contacts = best_steps_per_second(
        (sim.step, bare.step, in_python.step), plan.physics_steps, plan.physics_repeats
    )
    dt = sim.physics.time_step
    return {
        "time_step": dt,
        "solver": sim.physics.params.solver,
        "solver_iterations": sim.physics.params.solver_iterations,
        "steps_per_s": ours,
        "us_per_step": 1e6 / ours,
        "rtf": ours * dt,
        "contacts_per_step": sim.physics.contact_count,
        "bare_pyode": {
            "steps_per_s": floor,
            "us_per_step": 1e6 / floor,
            "rtf": floor * dt,
            "contacts_per_step": len(bare.contact_joints),
        },
        "overhead_ratio": floor / ours,
        "python_contacts": {  # the Python collision path the kernel replaces (same results, bitwise)
            "steps_per_s": python_contacts,
            "us_per_step": 1e6 / python_contacts,
            "rtf": python_contacts * dt,
        },
        "circle_radius_m": circle_radius(circle_track(plan.circle_seconds)),
        "circle_expected_radius_m": CIRCLE[0] / CIRCLE[1],
    }
