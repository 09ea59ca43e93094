"""A model built in the physics world: its links on their bodies, its geoms and joints, moved as a whole or joint
by joint, its masses and damping changed, removed again (models.builder builds it)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

import ode

from turtle_sim_ode.models.inertia import rotated_inertia
from turtle_sim_ode.models.transforms import (
    Matrix3,
    Quat,
    Transform,
    Vec3,
    compose,
    inverse,
    pose_transform,
    quat_from_rpy,
    quat_multiply,
    quat_rotate,
)
from turtle_sim_ode.models.description import RobotModel
from turtle_sim_ode.physics.joint_batch import JointDamper, TurnCounter
from turtle_sim_ode.physics.trimesh import remove_geom
from turtle_sim_ode.physics.world import PhysicsWorld

_TWO_PI = 2 * math.pi
_NO_ROTATION: Quat = (1.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True)
class LinkFrame:
    """Where a URDF link frame sits on its ODE body (whose frame is at the body's COM).

    Links of a static model have no body; their offset is their world pose.
    """

    body: Optional[ode.Body]
    offset: Transform


class JointHandle:
    """A non-fixed URDF joint: position and velocity with URDF sign conventions."""

    __slots__ = ("name", "type", "joint", "_read_wrapped", "_last_wrapped", "_unwrapped", "_counter", "_slot")

    def __init__(self, name: str, joint_type: str, joint: ode.Joint) -> None:
        self.name = name
        self.type = joint_type
        self.joint = joint
        self._read_wrapped = joint.getAngle if joint_type == "continuous" else None
        self._last_wrapped = 0.0
        self._unwrapped = 0.0
        self._counter: Optional[TurnCounter] = None  # counting the turns in C instead, in slot _slot
        self._slot = 0

    def count_in(self, counter: TurnCounter, slot: int) -> None:
        """Count the turns of this continuous joint in ``counter``'s ``slot`` from now on."""
        counter.last[slot], counter.unwrapped[slot] = self._last_wrapped, self._unwrapped
        self._counter, self._slot = counter, slot

    def angle(self) -> float:
        """Joint position (rad or m); continuous joints are unwrapped (multi-turn)."""
        if self.type == "continuous":
            return self._unwrapped if self._counter is None else self._counter.unwrapped[self._slot]
        if self.type == "prismatic":
            return self.joint.getPosition()
        return self.joint.getAngle()

    def moved_inertia(self) -> float:
        """The inertia the joint's effort accelerates (kg m^2 about a hinge's axis, kg along a slider): its two
        bodies in series, a static side counting as infinite."""
        axis = self.joint.getAxis()
        inverse_sum = 0.0
        for index in (0, 1):
            body = self.joint.getBody(index)
            if body is None:
                continue
            mass = body.getMass()
            if self.type == "prismatic":
                inverse_sum += 1.0 / mass.mass
                continue
            w, x, y, z = body.getQuaternion()
            local = quat_rotate((w, -x, -y, -z), axis)
            moment = sum(local[i] * mass.I[i][j] * local[j] for i in range(3) for j in range(3))
            inverse_sum += 1.0 / moment
        return 1.0 / inverse_sum if inverse_sum > 0 else math.inf

    def rate(self) -> float:
        """Joint velocity (rad/s or m/s)."""
        if self.type == "prismatic":
            return self.joint.getPositionRate()
        return self.joint.getAngleRate()

    def track_turns(self) -> None:
        """Accumulate ODE's [-pi, pi] hinge angle; called after every step."""
        if self._counter is not None:
            self._counter.count_one(self._slot)
            return
        wrapped = self._read_wrapped()
        delta = wrapped - self._last_wrapped
        if delta > math.pi:
            delta -= _TWO_PI
        elif delta < -math.pi:
            delta += _TWO_PI
        self._unwrapped += delta
        self._last_wrapped = wrapped

    def resync(self, position: float) -> None:
        """The bodies were moved so the joint is at ``position``: continuous joints count
        turns from there (others read their position from ODE anyway)."""
        if self._read_wrapped is not None:
            self._unwrapped = position
            self._last_wrapped = self._read_wrapped()
            if self._counter is not None:
                self.count_in(self._counter, self._slot)


class _AfterStep:
    """The hook a model's joints need after every step: the turns of continuous joints counted (``counter``'s in C,
    those of ``continuous`` apart) and the damping of the next step added (by ``damper`` in C if there is one). It
    references neither the model nor the world: a cycle through the world lets the garbage collector free PyODE
    objects in an order that crashes."""

    def __init__(self, counter: Optional[TurnCounter], continuous: List[JointHandle]) -> None:
        self._counter, self._continuous = counter, continuous
        self._damping: List[Tuple[JointHandle, float]] = []
        self._damper: Optional[JointDamper] = None

    def set_damping(self, damping: List[Tuple[JointHandle, float]], damper: Optional[JointDamper]) -> None:
        """(joint, coefficient) of each damped joint, and ``damper`` applying the same in C (None: in Python)."""
        self._damping, self._damper = list(damping), damper

    def __call__(self) -> None:
        if self._counter is not None:
            self._counter.count()
        for handle in self._continuous:
            handle.track_turns()
        # Added now, the damping acts during the next step (ODE clears forces after each step).
        if self._damper is not None:
            self._damper.apply()
            return
        for handle, coefficient in self._damping:
            effort = -coefficient * handle.rate()
            if handle.type == "prismatic":
                handle.joint.addForce(effort)
            else:
                handle.joint.addTorque(effort)


def remove_static_geoms(physics: PhysicsWorld, space: ode.SpaceBase, geoms: Dict[str, List[ode.GeomObject]]) -> None:
    """Take a static model's geoms out of the shared static space (and the ground away if it is one of them)."""
    for link_geoms in geoms.values():
        for geom in link_geoms:
            if geom is physics.ground:
                physics.remove_ground()
                continue
            physics.unregister_geom(geom)
            remove_geom(space, geom)


class BuiltModel:
    """One URDF model in a PhysicsWorld: link poses, joints, teleport and removal."""

    def __init__(
        self,
        physics: PhysicsWorld,
        robot: RobotModel,
        space: ode.SpaceBase,
        bodies: List[ode.Body],
        links: Dict[str, LinkFrame],
        geoms: Dict[str, List[ode.GeomObject]],
        joints: Dict[str, JointHandle],
        damping: List[Tuple[JointHandle, float]],
    ) -> None:
        self.name = robot.name
        self.robot = robot
        self.root_link = robot.root
        self.links = links
        self.geoms = geoms  # link name -> its collision geoms, in URDF order
        self.joints = joints
        self.bodies = bodies
        self.warnings: List[str] = []  # what building changed to keep the model sane, for the spawn's answer
        self.welds: List[ode.FixedJoint] = []  # joints from a URDF link named "world": to the world
        self._physics = physics
        self._space: Optional[ode.SpaceBase] = space
        continuous = [j for j in joints.values() if j.type == "continuous"]
        counter = physics.turn_counter([handle.joint for handle in continuous]) if continuous else None
        if counter is not None:
            for slot, handle in enumerate(continuous):
                handle.count_in(counter, slot)
            continuous = []
        self._damping = damping
        self._hook: Optional[_AfterStep] = None
        if counter is not None or continuous or damping:
            self._add_hook(counter, continuous)

    def _frame(self, link: str) -> LinkFrame:
        if self._space is None:
            raise RuntimeError(f"model '{self.name}' was removed")
        try:
            return self.links[link]
        except KeyError:
            raise KeyError(f"model '{self.name}' has no link '{link}'") from None

    def joint(self, name: str) -> JointHandle:
        try:
            return self.joints[name]
        except KeyError:
            raise KeyError(f"model '{self.name}' has no movable joint '{name}'") from None

    def link_transform(self, link: str) -> Transform:
        """World pose of a URDF link frame as (position, quaternion wxyz)."""
        frame = self._frame(link)
        if frame.body is None:
            return frame.offset
        return compose((frame.body.getPosition(), frame.body.getQuaternion()), frame.offset)

    def link_pose(self, link: str) -> Tuple[Vec3, Quat]:
        """World pose of a URDF link frame as (position, quaternion xyzw as in ROS)."""
        position, (w, x, y, z) = self.link_transform(link)
        return position, (x, y, z, w)

    def link_twist(self, link: str) -> Tuple[Vec3, Vec3]:
        """World-frame (linear velocity of the link origin, angular velocity)."""
        frame = self._frame(link)
        if frame.body is None:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        position, _ = self.link_transform(link)
        return frame.body.getPointVel(position), frame.body.getAngularVel()

    def model_transform(self) -> Transform:
        """World pose of the model frame (a URDF's root link) as (position, quaternion wxyz)."""
        return compose(self.link_transform(self.root_link), inverse(pose_transform(self.robot.root_pose)))

    def set_pose(self, x: float, y: float, z: float, roll: float = 0.0, pitch: float = 0.0, yaw: float = 0.0) -> None:
        """Teleport so the model frame (a URDF's root link) is at this pose; joints keep their
        positions, velocities become zero."""
        self.set_transform(((x, y, z), quat_from_rpy(roll, pitch, yaw)))

    def set_transform(self, target: Transform) -> None:
        """``set_pose`` with the model frame's pose as (position, unit quaternion wxyz)."""
        move = compose(target, inverse(self.model_transform()))
        for body in self.bodies:
            position, quaternion = compose(move, (body.getPosition(), body.getQuaternion()))
            body.setPosition(position)
            body.setQuaternion(quaternion)
            body.setLinearVel((0.0, 0.0, 0.0))
            body.setAngularVel((0.0, 0.0, 0.0))
        if self.robot.static:
            for geom in (geom for link_geoms in self.geoms.values() for geom in link_geoms):
                if geom is self._physics.ground:
                    normal, offset = geom.getParams()
                    point = compose(move, (tuple(n * offset for n in normal), _NO_ROTATION))[0]
                    turned = quat_rotate(move[1], normal)
                    geom.setParams(turned, sum(p * n for p, n in zip(point, turned)))
                    continue
                position, quaternion = compose(move, (geom.getPosition(), geom.getQuaternion()))
                geom.setPosition(position)
                geom.setQuaternion(quaternion)
            self.links = {name: LinkFrame(None, compose(move, frame.offset)) for name, frame in self.links.items()}

    def extent(self, body: ode.Body) -> float:
        """How far the collisions of ``body`` reach from its centre of mass (m; 0 without collisions)."""
        centre = body.getPosition()
        reach = 0.0
        for geom in (geom for link_geoms in self.geoms.values() for geom in link_geoms):
            if geom.getBody() is not body:
                continue
            x0, x1, y0, y1, z0, z1 = geom.getAABB()
            reach = max(
                reach,
                math.sqrt(
                    max((x0 - centre[0]) ** 2, (x1 - centre[0]) ** 2)
                    + max((y0 - centre[1]) ** 2, (y1 - centre[1]) ** 2)
                    + max((z0 - centre[2]) ** 2, (z1 - centre[2]) ** 2)
                ),
            )
        return reach

    def damping_entries(self) -> List[Tuple[JointHandle, float]]:
        """(joint, viscous damping coefficient) of every damped joint."""
        return list(self._damping)

    def damping(self, joint: str) -> float:
        """Viscous damping coefficient of a movable joint (0 if none)."""
        handle = self.joint(joint)
        return next((c for h, c in self._damping if h is handle), 0.0)

    def set_damping(self, joint: str, coefficient: float) -> None:
        """Damping torque (force) = -coefficient * joint rate, from the next step on."""
        handle = self.joint(joint)
        self._damping[:] = [(h, c) for h, c in self._damping if h is not handle]
        if coefficient > 0:
            self._damping.append((handle, coefficient))
        if self._hook is not None:
            self._hook.set_damping(self._damping, self._damper())
        elif self._damping:  # no continuous joints, no damping until now
            self._add_hook(None, [])

    def _add_hook(self, counter: Optional[TurnCounter], continuous: List[JointHandle]) -> None:
        self._hook = _AfterStep(counter, continuous)
        self._hook.set_damping(self._damping, self._damper())
        self._physics.add_post_step_hook(self._hook)

    def _damper(self) -> Optional[JointDamper]:
        damped = [(handle.joint, coefficient) for handle, coefficient in self._damping]
        return self._physics.joint_damper(damped) if damped else None

    def set_mass(self, link: str, mass: float, com: Vec3, inertia: Matrix3) -> None:
        """Give the body carrying ``link`` this mass, centre of mass and inertia about it (both
        in the link frame). The body's origin follows its COM; links, geoms and joint frames
        stay where they are, joints keep their positions."""
        frame = self._frame(link)
        body = frame.body
        if body is None:
            raise ValueError(f"link '{link}' of static model '{self.name}' has no body")
        (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = rotated_inertia(frame.offset[1], inertia)
        ode_mass = ode.Mass()
        ode_mass.setParameters(mass, 0.0, 0.0, 0.0, ixx, iyy, izz, ixy, ixz, iyz)
        shift = compose(frame.offset, (com, _NO_ROTATION))[0]  # the new COM in the body frame
        attached = [h for h in self.joints.values() if h.joint.getBody(0) is body or h.joint.getBody(1) is body]
        # (handle, anchor, axis, position) in the world before the move.
        before = [
            (
                h,
                h.joint.getAnchor() if h.type != "prismatic" else None,
                h.joint.getAxis(),
                h.joint.getPosition() if h.type == "prismatic" else h.joint.getAngle(),
            )
            for h in attached
        ]
        moved = compose((body.getPosition(), body.getQuaternion()), (shift, _NO_ROTATION))[0]
        velocity = body.getPointVel(moved)
        body.setMass(ode_mass)
        body.setPosition(moved)
        body.setLinearVel(velocity)
        for name, link_frame in list(self.links.items()):
            if link_frame.body is body:
                offset = (
                    (
                        link_frame.offset[0][0] - shift[0],
                        link_frame.offset[0][1] - shift[1],
                        link_frame.offset[0][2] - shift[2],
                    ),
                    link_frame.offset[1],
                )
                self.links[name] = LinkFrame(body, offset)
                for geom, collision in zip(self.geoms[name], self.robot.links[name].collisions):
                    geom.setOffsetPosition(compose(offset, pose_transform(collision.origin))[0])
        for handle, anchor, axis, position in before:
            _reanchor(handle, anchor, axis, position)

    def remove(self) -> None:
        """Destroy all bodies, geoms and joints of this model."""
        if self._space is None:
            return
        if self._hook is not None:
            self._physics.remove_post_step_hook(self._hook)
        if self.robot.static:
            remove_static_geoms(self._physics, self._space, self.geoms)
        else:
            self._physics.destroy_model_space(self._space)
        for joint in [handle.joint for handle in self.joints.values()] + self.welds:
            joint.attach(None, None)
        for body in self.bodies:
            self._physics.forget_body(body)
            body.disable()
        # Dropping the last references lets PyODE destroy the ODE objects.
        self._space = None
        self.joints = {}
        self.links = {}
        self.geoms = {}
        self.bodies = []
        self._hook = None


def _reanchor(handle: JointHandle, anchor: Optional[Vec3], axis: Vec3, position: float) -> None:
    """Recompute a joint's body-relative frames from its world ``anchor`` and ``axis`` after a
    body moved under it, so that it still reads ``position``.

    ODE takes the current pose as the joint's zero when its anchor (hinge) or axis (slider)
    is set, so the child body is briefly moved back to the joint's zero for that.
    """
    child = handle.joint.getBody(0)
    (x, y, z), orientation = child.getPosition(), child.getQuaternion()
    if anchor is None:  # slider
        child.setPosition((x - axis[0] * position, y - axis[1] * position, z - axis[2] * position))
        handle.joint.setAxis(axis)
    else:
        sine = math.sin(-position / 2)
        turn = (math.cos(-position / 2), sine * axis[0], sine * axis[1], sine * axis[2])
        arm = quat_rotate(turn, (x - anchor[0], y - anchor[1], z - anchor[2]))
        child.setPosition((anchor[0] + arm[0], anchor[1] + arm[1], anchor[2] + arm[2]))
        child.setQuaternion(quat_multiply(turn, orientation))
        handle.joint.setAnchor(anchor)
    child.setPosition((x, y, z))
    child.setQuaternion(orientation)
