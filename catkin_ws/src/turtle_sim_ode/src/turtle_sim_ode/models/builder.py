"""Build ODE bodies, geoms and joints from a parsed URDF, merging fixed joints like Gazebo."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import ode

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.urdf import WORLD_LINK, MAX_LENGTH, Box, Cylinder, Geometry, Joint, Mesh, RobotModel, Sphere
from turtle_sim_ode.models.transforms import (  # noqa: F401 (the names other modules import from here)
    Matrix3,
    Quat,
    Transform,
    Vec3,
    compose,
    inverse,
    pose_transform,
    quat_from_rpy,
    quat_matrix,
    quat_multiply,
    quat_rotate,
    rpy_of,
)
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.trimesh import MeshGeom, remove_geom
from turtle_sim_ode.physics.world import PhysicsWorld, SurfaceParams

_TWO_PI = 2 * math.pi
_NO_ROTATION: Quat = (1.0, 0.0, 0.0, 0.0)


# --- handles -------------------------------------------------------------------------
@dataclass(frozen=True)
class LinkFrame:
    """Where a URDF link frame sits on its ODE body (whose frame is at the body's COM).

    Links of a static model have no body; their offset is their world pose.
    """

    body: Optional[ode.Body]
    offset: Transform


class JointHandle:
    """A non-fixed URDF joint: position and velocity with URDF sign conventions."""

    __slots__ = ("name", "type", "joint", "_read_wrapped", "_last_wrapped", "_unwrapped")

    def __init__(self, name: str, joint_type: str, joint: ode.Joint) -> None:
        self.name = name
        self.type = joint_type
        self.joint = joint
        self._read_wrapped = joint.getAngle if joint_type == "continuous" else None
        self._last_wrapped = 0.0
        self._unwrapped = 0.0

    def angle(self) -> float:
        """Joint position (rad or m); continuous joints are unwrapped (multi-turn)."""
        if self.type == "continuous":
            return self._unwrapped
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


def _after_step_hook(continuous: List[JointHandle], damping: List[Tuple[JointHandle, float]]) -> Callable[[], None]:
    def after_step() -> None:
        for handle in continuous:
            handle.track_turns()
        for handle, coefficient in damping:
            # Added now, this acts during the next step (ODE clears forces after each step).
            effort = -coefficient * handle.rate()
            if handle.type == "prismatic":
                handle.joint.addForce(effort)
            else:
                handle.joint.addTorque(effort)

    return after_step


def _remove_static_geoms(physics: PhysicsWorld, space: ode.SpaceBase, geoms: Dict[str, List[ode.GeomObject]]) -> None:
    """Take a static model's geoms out of the shared static space (and the ground away if it is one of them)."""
    for link_geoms in geoms.values():
        for geom in link_geoms:
            if geom is physics.ground:
                physics.remove_ground()
                continue
            physics.unregister_geom(geom)
            remove_geom(space, geom)


def _plane_params(box: Box, transform: Transform) -> Tuple[Vec3, float]:
    """(unit normal, offset) of the plane holding the top face of a <plane>'s thin ``box`` placed at ``transform``."""
    normal = quat_rotate(transform[1], (0.0, 0.0, 1.0))
    top = [c + n * box.size[2] / 2 for c, n in zip(transform[0], normal)]
    return normal, sum(t * n for t, n in zip(top, normal))


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
        # Shared with the hook: set_damping edits it in place.
        self._damping = damping
        self._hook: Optional[Callable[[], None]] = None
        if continuous or damping:
            # A closure, not a bound method: the world must not reference this model back,
            # since a reference cycle lets the garbage collector free PyODE objects in an
            # order that crashes.
            self._hook = _after_step_hook(continuous, damping)
            physics.add_post_step_hook(self._hook)

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
            if self._hook is None:  # no continuous joints, no damping until now
                self._hook = _after_step_hook([], self._damping)
                self._physics.add_post_step_hook(self._hook)

    def set_mass(self, link: str, mass: float, com: Vec3, inertia: Matrix3) -> None:
        """Give the body carrying ``link`` this mass, centre of mass and inertia about it (both
        in the link frame). The body's origin follows its COM; links, geoms and joint frames
        stay where they are, joints keep their positions."""
        frame = self._frame(link)
        body = frame.body
        if body is None:
            raise ValueError(f"link '{link}' of static model '{self.name}' has no body")
        (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = _rotated_inertia(frame.offset[1], inertia)
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
            _remove_static_geoms(self._physics, self._space, self.geoms)
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


# --- building -----------------------------------------------------------------------
def _inertia_about_com(parts: Sequence[Tuple[float, Vec3, Matrix3]]) -> Tuple[float, Vec3, Matrix3]:
    """Total mass, COM and inertia about the COM of point-mass-plus-inertia parts."""
    mass = sum(m for m, _, _ in parts)
    com = tuple(sum(m * c[i] for m, c, _ in parts) / mass for i in range(3))
    inertia = [[0.0] * 3 for _ in range(3)]
    for m, c, local in parts:
        d = [c[i] - com[i] for i in range(3)]
        d2 = d[0] ** 2 + d[1] ** 2 + d[2] ** 2
        for r in range(3):
            for k in range(3):
                # Parallel-axis theorem: I + m(|d|^2 E - d d^T).
                inertia[r][k] += local[r][k] + m * ((d2 if r == k else 0.0) - d[r] * d[k])
    return mass, com, tuple(tuple(row) for row in inertia)  # type: ignore[return-value]


def _rotated_inertia(q: Quat, inertia: Matrix3) -> Matrix3:
    """R I R^T."""
    rot = quat_matrix(q)
    return tuple(  # type: ignore[return-value]
        tuple(sum(rot[r][a] * inertia[a][b] * rot[k][b] for a in range(3) for b in range(3)) for k in range(3))
        for r in range(3)
    )


def _create_geom(space: ode.SpaceBase, geometry: Geometry) -> ode.GeomObject:
    if isinstance(geometry, Box):
        return ode.GeomBox(space, geometry.size)
    if isinstance(geometry, Cylinder):
        return ode.GeomCylinder(space, geometry.radius, geometry.length)
    if isinstance(geometry, Sphere):
        return ode.GeomSphere(space, geometry.radius)
    if isinstance(geometry, Mesh):
        if geometry.vertices is None or geometry.faces is None:
            raise ModelError(f"mesh '{geometry.uri}' is not loaded (models.meshes.load_meshes reads it)")
        return MeshGeom(space, geometry.vertices, geometry.faces, geometry.prepared)  # type: ignore[arg-type,return-value]
    raise ModelError(f"unsupported geometry {geometry!r}")


def _on_body(geometry: Geometry, robot: RobotModel, link: str) -> Tuple[Geometry, Transform]:
    """The geometry a moving link's collision gets, and its centre in the collision frame: a mesh becomes the box
    that bounds it (meshes are body-less, see physics.trimesh), with a warning."""
    if not isinstance(geometry, Mesh):
        return geometry, ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))
    if geometry.vertices is None:
        raise ModelError(f"mesh '{geometry.uri}' is not loaded (models.meshes.load_meshes reads it)")
    low = [min(v[axis] for v in geometry.vertices) for axis in range(3)]
    high = [max(v[axis] for v in geometry.vertices) for axis in range(3)]
    size = tuple(max(h - l, 1e-4) for l, h in zip(low, high))
    centre = tuple((l + h) / 2 for l, h in zip(low, high))
    robot.warnings.append(
        f"link '{link}': mesh '{geometry.uri}' on a moving link collides as its bounding box "
        f"{size[0]:.3g} x {size[1]:.3g} x {size[2]:.3g} m (meshes collide as meshes on static models)"
    )
    return Box(size), (centre, (1.0, 0.0, 0.0, 0.0))  # type: ignore[arg-type]


def _surface_for(robot: RobotModel, link: str, default: SurfaceParams) -> SurfaceParams:
    tags = robot.surfaces.get(link)
    if tags is None:
        return default
    return SurfaceParams(
        mu=default.mu if tags.mu1 is None else tags.mu1,
        mu2=default.mu2 if tags.mu2 is None else tags.mu2,
        kp=default.kp if tags.kp is None else tags.kp,
        kd=default.kd if tags.kd is None else tags.kd,
        min_depth=default.min_depth if tags.min_depth is None else tags.min_depth,
        max_vel=default.max_vel if tags.max_vel is None else tags.max_vel,
        fdir1=default.fdir1 if tags.fdir1 is None else tags.fdir1,
        slip1=default.slip1 if tags.slip1 is None else tags.slip1,
        slip2=default.slip2 if tags.slip2 is None else tags.slip2,
    )


def _build_static(physics: PhysicsWorld, robot: RobotModel, world_of: Dict[str, Transform]) -> BuiltModel:
    """Body-less collision geoms in the physics' static space, at the links' world poses."""
    space = physics.static_space
    links: Dict[str, LinkFrame] = {}
    geoms: Dict[str, List[ode.GeomObject]] = {}
    try:
        for link, transform in world_of.items():
            links[link] = LinkFrame(None, transform)
            surface = _surface_for(robot, link, physics.params.default_surface)
            geoms[link] = []
            for collision in robot.links[link].collisions:
                placed = compose(transform, pose_transform(collision.origin))
                if collision.plane and isinstance(collision.geometry, Box) and not physics.has_ground:
                    # Gazebo's ODE plane is infinite: the world's ground (one a world; a second plane is its box).
                    geoms[link].append(physics.place_ground(*_plane_params(collision.geometry, placed), surface))
                    continue
                geom = _create_geom(space, collision.geometry)
                geoms[link].append(geom)
                position, quaternion = placed
                geom.setPosition(position)
                geom.setQuaternion(quaternion)
                physics.register_geom(geom, surface)
    except Exception:
        _remove_static_geoms(physics, space, geoms)
        raise
    return BuiltModel(physics, robot, space, [], links, geoms, {}, [])


def build_model(
    physics: PhysicsWorld,
    robot: RobotModel,
    pose: Sequence[float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    self_collide: bool = False,
) -> BuiltModel:
    """Create the model with its model frame (a URDF's root link) at pose (x, y, z, roll,
    pitch, yaw), x, y, z within MAX_LENGTH of the world origin.

    Links attached by fixed joints are merged into their parent's body (mass, COM and
    inertia combined, collisions kept); a "floating" joint leaves its child a free body.
    ODE bodies sit at their COM, oriented like the link that owns them; each link
    remembers its offset on the body. A static model gets no bodies: its collision geoms
    are fixed in the world, in ``physics.static_space``.
    """
    if len(pose) != 6 or not all(math.isfinite(v) for v in pose):
        raise ValueError(f"pose must be 6 finite numbers (x, y, z, roll, pitch, yaw), got {pose!r}")
    if any(abs(v) > MAX_LENGTH for v in pose[:3]):
        raise ValueError(f"pose x, y, z must be within {MAX_LENGTH:g} m of the world origin, got {tuple(pose[:3])!r}")
    world_of: Dict[str, Transform] = {
        robot.root: compose(((pose[0], pose[1], pose[2]), quat_from_rpy(*pose[3:])), pose_transform(robot.root_pose))
    }
    owner: Dict[str, str] = {robot.root: robot.root}  # link -> link whose body carries it
    members_of: Dict[str, List[str]] = {robot.root: [robot.root]}  # the reverse, in BFS order
    child_joints: Dict[str, List[Joint]] = {}
    for joint in robot.joints.values():
        child_joints.setdefault(joint.parent, []).append(joint)
    order, world = [robot.root], (WORLD_LINK if robot.root == WORLD_LINK else None)
    for link in order:  # breadth-first; ``order`` grows while iterating
        for joint in child_joints.get(link, []):
            world_of[joint.child] = compose(world_of[link], pose_transform(joint.origin))
            owner[joint.child] = owner[link] if joint.type == "fixed" and link != world else joint.child
            members_of.setdefault(owner[joint.child], []).append(joint.child)
            order.append(joint.child)
    if robot.static:
        return _build_static(physics, robot, world_of)

    space = physics.create_model_space(self_collide)
    bodies: Dict[str, ode.Body] = {}
    links: Dict[str, LinkFrame] = {}
    if members_of.pop(world, None):  # the world frame itself, where the model was placed: no body
        links[WORLD_LINK] = LinkFrame(None, world_of[WORLD_LINK])
    welds: List[ode.FixedJoint] = []
    geoms: Dict[str, List[ode.GeomObject]] = {}
    try:
        for body_link, members in members_of.items():
            to_body_link = inverse(world_of[body_link])
            relative = {m: compose(to_body_link, world_of[m]) for m in members}
            parts = []
            for member in members:
                inertial = robot.links[member].inertial
                if inertial is None:
                    continue
                position, rotation = compose(relative[member], pose_transform(inertial.origin))
                parts.append((inertial.mass, position, _rotated_inertia(rotation, inertial.matrix())))
            if not parts:
                raise ModelError(
                    f"link '{body_link}' and the links fixed to it have no " f"<inertial>; a moving body needs mass"
                )
            mass, com, inertia = _inertia_about_com(parts)
            body = ode.Body(physics.world)
            ode_mass = ode.Mass()
            i = inertia
            ode_mass.setParameters(mass, 0.0, 0.0, 0.0, i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2])
            body.setMass(ode_mass)
            body_pose = compose(world_of[body_link], (com, (1.0, 0.0, 0.0, 0.0)))
            body.setPosition(body_pose[0])
            body.setQuaternion(body_pose[1])
            bodies[body_link] = body
            for member in members:
                offset = compose(((-com[0], -com[1], -com[2]), (1.0, 0.0, 0.0, 0.0)), relative[member])
                links[member] = LinkFrame(body, offset)
                geoms[member] = []
                surface = _surface_for(robot, member, physics.params.default_surface)
                for collision in robot.links[member].collisions:
                    geometry, centre = _on_body(collision.geometry, robot, member)
                    geom = _create_geom(space, geometry)
                    geom.setBody(body)
                    geom_offset = compose(compose(offset, pose_transform(collision.origin)), centre)
                    geom.setOffsetPosition(geom_offset[0])
                    geom.setOffsetQuaternion(geom_offset[1])
                    physics.register_geom(geom, surface)
                    geoms[member].append(geom)

        joints: Dict[str, JointHandle] = {}
        damping: List[Tuple[JointHandle, float]] = []
        stop_warnings: List[str] = []
        for joint in robot.joints.values():
            if joint.type == "floating" or (joint.type == "fixed" and owner[joint.child] != joint.child):
                continue
            # None: the world (SDF's <parent>world</parent>, or a URDF root link named world, as sdformat's
            # URDF to SDF conversion makes it: no link, its joints joints to the world).
            child = bodies[joint.child]
            parent = None if joint.parent == WORLD_LINK else bodies.get(owner[joint.parent])
            if joint.type == "fixed":  # from the world link: welded where it was placed
                welds.append(ode.FixedJoint(physics.world))
                welds[-1].attach(child, None)
                welds[-1].setFixed()
                continue
            anchor, rotation = compose(world_of[joint.child], pose_transform(joint.frame))
            axis = quat_rotate(rotation, joint.axis)
            if joint.type == "prismatic":
                ode_joint = ode.SliderJoint(physics.world)
            else:
                ode_joint = ode.HingeJoint(physics.world)
            # ODE measures body1 relative to body2: child first gives URDF's sign.
            ode_joint.attach(child, parent)
            if joint.type != "prismatic":
                ode_joint.setAnchor(anchor)
            ode_joint.setAxis(axis)
            if joint.type != "continuous" and joint.limits is not None:
                reach = sanity.MAX_HINGE_STOP if joint.type == "revolute" else sanity.MAX_LENGTH
                if max(abs(joint.limits.lower), abs(joint.limits.upper)) <= reach:
                    ode_joint.setParam(oc.PARAM_LO_STOP, joint.limits.lower)
                    ode_joint.setParam(oc.PARAM_HI_STOP, joint.limits.upper)
                else:
                    stop_warnings.append(
                        f"joint '{joint.name}': limits [{joint.limits.lower:g}, {joint.limits.upper:g}] are beyond "
                        f"±{reach:.4g} and not enforced (ODE's hinge angle wraps at ±π)"
                    )
            if joint.dynamics.friction > 0:
                # Gazebo's joint friction: a zero-velocity motor limited to the friction force.
                ode_joint.setParam(oc.PARAM_VEL, 0.0)
                ode_joint.setParam(oc.PARAM_FMAX, joint.dynamics.friction)
            if parent is not None:
                physics.exclude_collision(child, parent)
            handle = JointHandle(joint.name, joint.type, ode_joint)
            joints[joint.name] = handle
            if joint.dynamics.damping > 0:
                damping.append((handle, joint.dynamics.damping))
    except Exception:
        physics.destroy_model_space(space)
        for body in bodies.values():
            physics.forget_body(body)
            body.disable()
        raise
    model = BuiltModel(physics, robot, space, list(bodies.values()), links, geoms, joints, damping)
    model.welds = welds
    model.warnings = stop_warnings + _keep_sane(model, bodies, physics.time_step)
    return model


def _keep_sane(model: BuiltModel, bodies: Dict[str, ode.Body], time_step: float) -> List[str]:
    """Raise moments of inertia too small for a body's reach and lower joint damping the step cannot integrate
    (physics.sanity's bounds), as ODE would otherwise spin the body up or let it sink through the ground; a warning
    for each change."""
    warnings = []
    for link, body in bodies.items():
        mass = body.getMass()
        reach = model.extent(body)
        floor = sanity.min_moment(mass.mass, reach)
        lowest = sanity.principal_moments(mass.I)[0]
        if lowest < floor:
            diagonal = all(mass.I[i][j] == 0 for i in range(3) for j in range(3) if i != j)
            # Principal axes on the body's: only the moments below the bound move; else all by the shortfall.
            raised = [
                [
                    (max(mass.I[i][i], floor) if diagonal else mass.I[i][i] + floor - lowest)
                    if i == j
                    else mass.I[i][j]
                    for j in range(3)
                ]
                for i in range(3)
            ]
            adjusted = ode.Mass()
            adjusted.setParameters(
                mass.mass,
                0.0,
                0.0,
                0.0,
                raised[0][0],
                raised[1][1],
                raised[2][2],
                raised[0][1],
                raised[0][2],
                raised[1][2],
            )
            body.setMass(adjusted)
            warnings.append(
                f"link '{link}': smallest moment of inertia {lowest:.3g} kg m^2 is too small for a {mass.mass:g} kg "
                f"body reaching {reach:.3g} m (ODE would spin it up); raised to {floor:.3g}"
            )
    for index, (handle, coefficient) in enumerate(model.damping_entries()):
        stable = sanity.stable_damping(coefficient, handle.moved_inertia(), time_step)
        if stable < coefficient:
            model.set_damping(handle.name, stable)
            warnings.append(
                f"joint '{handle.name}': damping {coefficient:g} is unstable at a {time_step:g} s step on what it "
                f"moves; lowered to {stable:.3g}"
            )
    return warnings
