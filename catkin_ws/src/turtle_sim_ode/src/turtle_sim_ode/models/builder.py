"""Build ODE bodies, geoms and joints from a parsed URDF, merging fixed joints like Gazebo."""
from __future__ import annotations

import math
from typing import Dict, List, Sequence, Tuple

import ode

from turtle_sim_ode.models.built import BuiltModel, JointHandle, LinkFrame, remove_static_geoms
from turtle_sim_ode.models.inertia import inertia_about_com, rotated_inertia
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.transforms import (
    Transform,
    Vec3,
    compose,
    inverse,
    pose_transform,
    quat_from_rpy,
    quat_rotate,
)
from turtle_sim_ode.models.description import Box, Cylinder, Geometry, Joint, Mesh, RobotModel, Sphere
from turtle_sim_ode.models.urdf import MAX_LENGTH, WORLD_LINK
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.trimesh import MeshGeom
from turtle_sim_ode.physics.surfaces import SurfaceParams
from turtle_sim_ode.physics.world import PhysicsWorld


def _plane_params(box: Box, transform: Transform) -> Tuple[Vec3, float]:
    """(unit normal, offset) of the plane holding the top face of a <plane>'s thin ``box`` placed at ``transform``."""
    normal = quat_rotate(transform[1], (0.0, 0.0, 1.0))
    top = [c + n * box.size[2] / 2 for c, n in zip(transform[0], normal)]
    return normal, sum(t * n for t, n in zip(top, normal))


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
        remove_static_geoms(physics, space, geoms)
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
                parts.append((inertial.mass, position, rotated_inertia(rotation, inertial.matrix())))
            if not parts:
                raise ModelError(
                    f"link '{body_link}' and the links fixed to it have no " f"<inertial>; a moving body needs mass"
                )
            mass, com, inertia = inertia_about_com(parts)
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
