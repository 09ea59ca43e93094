"""gazebo_ros_f3d (``libgazebo_ros_f3d.so``, gazebo_plugins/src/gazebo_ros_f3d.cpp): the force and torque on a link,
in the world frame. Its tags (GazeboRosF3D::Load: <bodyName> and <topicName> required, <frameName> "world", read
but only stamped on the message) and its per-step work (UpdateChild: Link::WorldForce and WorldTorque).

What Gazebo's WorldForce is under ODE: ODELink::MoveCallback keeps dBodyGetForce/dBodyGetTorque, called from
dxStepBody while gazebo-classic's bundled ODE steps (deps/opende/src/quickstep.cpp, dxQuickStepper, and
quickstep_update_bodies.cpp, dxUpdateBodies). By then the accumulators hold the forces added for the step, plus the
weight (m g, "add the gravity force to all bodies"), minus the gyroscopic torque ω × (I ω) (dxBodyGyroscopic), plus
the constraint forces of the step's joints and contacts (m × caccel, and the body-frame inertia × caccel's angular
part: "so dBodyGetForce and dBodyGetTorque returns total force and torque on the body"); they are zeroed after.
So f3d reports the total force on the body: a link at rest reads about zero, a free one F + m g.

PyODE cannot reach inside a step, and its ODE zeroes the accumulators before the step returns, so this reads the
same sum from the step's ends: a pre-step hook (PhysicsWorld.add_pre_step_hook) keeps the accumulators (every force
is in by then) and the body's velocities and orientation; after the step the total force is m Δv / Δt (ODE's own
update: Δv = Δt (facc / m + caccel)). The constraint's angular acceleration is what of Δω / Δt the accumulated torque
does not explain, with the gyroscopic torque as Debian's ODE 0.16 applies it (implicitly, Lacoursière's form in its
quickstep: (I Ĩ⁻¹ − 1) L / Δt, Ĩ = I − Δt [L]×, L = I ω); the torque reported is then upstream's: the accumulated
torque − ω × (I ω) + the body-frame inertia × that acceleration."""
from __future__ import annotations

from dataclasses import dataclass
from typing import List, Mapping, Optional, Sequence, Tuple

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.inertia import rotated_inertia
from turtle_sim_ode.models.transforms import Matrix3, Vec3
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.world.kinematics import cross
from turtle_sim_ode.world.plugins.tags import text

F3D = "libgazebo_ros_f3d.so"
MODEL_PLUGINS = (F3D,)


@dataclass(frozen=True)
class F3dConfig:
    body: str
    topic: str
    frame: str = "world"
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> F3dConfig:
    body, topic = text(plugin, "bodyName", ""), text(plugin, "topicName", "")
    if not body or not topic:
        raise ModelError(f"{plugin.filename} needs <bodyName> and <topicName>")
    return F3dConfig(body, topic, text(plugin, "frameName", "world"), robot_namespace_tag(plugin.params))


def _times(m: Sequence[Sequence[float]], v: Sequence[float]) -> Vec3:
    return tuple(m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2] for r in range(3))  # type: ignore[return-value]


def _inverse(m: Matrix3) -> Optional[Matrix3]:
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    if det == 0:
        return None
    return (
        ((e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det),
        ((f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det),
        ((d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det),
    )


def _implicit_gyroscopic(inertia: Matrix3, spin: Vec3, time_step: float) -> Vec3:
    """The gyroscopic torque ODE 0.16's quickstep adds for a step (zero where its matrix is singular, as there)."""
    lx, ly, lz = _times(inertia, spin)
    h = time_step
    tilde = tuple(
        tuple(inertia[r][c] - h * cross for c, cross in enumerate(row))
        for r, row in enumerate(((0.0, -lz, ly), (lz, 0.0, -lx), (-ly, lx, 0.0)))
    )
    tilde_inverse = _inverse(tilde)  # type: ignore[arg-type]
    if tilde_inverse is None:
        return (0.0, 0.0, 0.0)
    ratio = [[sum(inertia[r][k] * tilde_inverse[k][c] for k in range(3)) for c in range(3)] for r in range(3)]
    scaled = _times(ratio, (lx / h, ly / h, lz / h))
    return (scaled[0] - lx / h, scaled[1] - ly / h, scaled[2] - lz / h)


class LinkForce:
    """The total force and torque on a link's body in the last step (world frame, about its centre of mass), as
    Gazebo's ODELink keeps them; zero before the first step. ``close`` takes its hook out of the physics again."""

    def __init__(self, physics: PhysicsWorld, model: BuiltModel, link: str) -> None:
        body = model.links[link].body
        if body is None:
            raise ModelError(f"model '{model.name}': link '{link}' has no body for an f3d plugin")
        self._physics = physics
        self._body = body
        mass = body.getMass()
        self._mass, self._inertia = mass.mass, mass.I
        start: List[Optional[tuple]] = [None]  # (force, torque, velocity, angular velocity, quaternion) at the start

        def before_step() -> None:  # a closure: the world must not hold this object (see models.built)
            start[0] = (
                body.getForce(),
                body.getTorque(),
                body.getLinearVel(),
                body.getAngularVel(),
                body.getQuaternion(),
            )

        self._start = start
        self._hook = before_step
        physics.add_pre_step_hook(before_step)

    def wrench(self, time_step: float) -> Tuple[Vec3, Vec3]:
        """(force, torque) of the step just taken, of length ``time_step``."""
        if self._start[0] is None:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        _, torque0, velocity0, spin0, orientation = self._start[0]
        velocity, spin = self._body.getLinearVel(), self._body.getAngularVel()
        force = tuple(self._mass * (velocity[i] - velocity0[i]) / time_step for i in range(3))
        inertia = rotated_inertia(orientation, self._inertia)
        implicit = _implicit_gyroscopic(inertia, spin0, time_step)
        inverse = _inverse(inertia)  # a body's inertia is positive definite: never None
        explained = _times(inverse, [torque0[i] + implicit[i] for i in range(3)]) if inverse else (0.0, 0.0, 0.0)
        constraint = [(spin[i] - spin0[i]) / time_step - explained[i] for i in range(3)]
        gyroscopic = cross(spin0, _times(inertia, spin0))  # as Gazebo's ODE subtracts it (explicitly)
        added = _times(self._inertia, constraint)  # the body-frame inertia, as dxUpdateBodies weights it
        return force, tuple(torque0[i] - gyroscopic[i] + added[i] for i in range(3))  # type: ignore[return-value]

    def close(self) -> None:
        if self._hook is not None:
            self._physics.remove_pre_step_hook(self._hook)
            self._hook = None
