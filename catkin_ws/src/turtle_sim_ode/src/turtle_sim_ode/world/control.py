"""Gazebo classic's world API (the /gazebo/* services of gazebo_ros), ROS-free.

Entities are named as Gazebo names them: a model "name", a link "model::link", a joint
"joint" (looked up in every model, in spawn order) or "model::joint". Poses are a position
and a ROS quaternion (x, y, z, w); everything is in SI units and plain Python types.
Reference frames "", "world", "map" and "/map" mean the world. Properties are dicts keyed by
the gazebo_msgs field names. Every logical failure raises WorldError, with a message fit for
a service's status_message, before anything in the world changes.
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Dict, List, Optional, Sequence, Tuple, Union

import ode

from turtle_sim_ode.models.builder import (
    BuiltModel,
    JointHandle,
    Transform,
    Vec3,
    _rotated_inertia,
    compose,
    inverse,
    quat_rotate,
)
from turtle_sim_ode.models.urdf import MAX_INERTIA, MAX_LENGTH, MAX_MASS, _is_positive_definite
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.settings import MAX_GRAVITY
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.world.plugins import DriveRobot
from turtle_sim_ode.world.joint_effort import effort_applier
from turtle_sim_ode.world.kinematics import add, conjugate, cross, set_configuration, set_rigid_twist, sub
from turtle_sim_ode.world.records import (
    JointProperties,
    LinkProperties,
    Load,
    ModelProperties,
    OdeConfig,
    PhysicsProperties,
    QuatXYZW,
    WorldProperties,
)
from turtle_sim_ode.world.values import (
    MAX_FORCE,
    MAX_SPEED,
    WorldError,
    finite,
    integer,
    orientation,
    update_rate,
    vec3,
    vector,
)

# position, orientation (x, y, z, w), linear velocity, angular velocity
EntityState = Tuple[Vec3, QuatXYZW, Vec3, Vec3]
# A reference frame's world pose, linear and angular velocity; None is the world.
Frame = Optional[Tuple[Transform, Vec3, Vec3]]
# A gazebo_msgs/ODEJointProperties value: a number, or a list whose first entry is used;
# None or an empty list leaves the parameter alone.
JointParam = Union[None, float, Sequence[float]]

WORLD_FRAMES = ("", "world", "map", "/map")
SCOPE = "::"

# gazebo_msgs/GetJointProperties type constants.
REVOLUTE, CONTINUOUS, PRISMATIC, FIXED, BALL, UNIVERSAL = range(6)
JOINT_TYPES = {"revolute": REVOLUTE, "continuous": CONTINUOUS, "prismatic": PRISMATIC}

# ODE's successive over-relaxation factor, which PyODE cannot change.
SOR_PGS_W = 1.3
# Tolerance on sim-time comparisons when scheduling loads (s).
TIME_EPSILON = 1e-9

# gazebo_msgs/ODEJointProperties fields set with joint.setParam (first axis only).
_JOINT_PARAMS = (
    ("hiStop", oc.PARAM_HI_STOP),
    ("loStop", oc.PARAM_LO_STOP),
    ("erp", oc.PARAM_ERP),
    ("cfm", oc.PARAM_CFM),
    ("stop_erp", oc.PARAM_STOP_ERP),
    ("stop_cfm", oc.PARAM_STOP_CFM),
    ("fudge_factor", oc.PARAM_FUDGE_FACTOR),
    ("fmax", oc.PARAM_FMAX),
    ("vel", oc.PARAM_VEL),
)
# Magnitude limits of the ODEJointProperties fields that drive a joint.
_JOINT_LIMITS = {"fmax": MAX_FORCE, "vel": MAX_SPEED}


class WorldControl:
    """Gazebo's world services over ``models``; mixed into Simulation, which owns the models
    and calls ``apply_loads`` before each physics step while ``loads`` is not empty."""

    physics: PhysicsWorld
    models: Dict[str, BuiltModel]
    robots: Dict[str, DriveRobot]
    max_update_rate: float
    loads: List[Load]

    # --- names ----------------------------------------------------------------------------
    def _model(self, name: str) -> BuiltModel:
        model = self.models.get(name)
        if model is None:
            raise WorldError(f"model '{name}' does not exist")
        return model

    def _scoped_link(self, name: str) -> Optional[Tuple[BuiltModel, str]]:
        model_name, scope, link = name.partition(SCOPE)
        model = self.models.get(model_name) if scope else None
        return (model, link) if model is not None and link in model.links else None

    def _link(self, name: str) -> Tuple[BuiltModel, str]:
        found = self._scoped_link(name)
        if found is None:
            raise WorldError(f"link '{name}' does not exist (links are named 'model::link')")
        return found

    def _link_body(self, name: str) -> Tuple[BuiltModel, str, ode.Body]:
        model, link = self._link(name)
        body = model.links[link].body
        if body is None:
            raise WorldError(f"link '{name}' belongs to static model '{model.name}' and has no body")
        return model, link, body

    def _joint(self, name: str) -> Tuple[BuiltModel, JointHandle]:
        model_name, scope, joint = name.partition(SCOPE)
        scoped = self.models.get(model_name) if scope else None
        if scoped is not None and joint in scoped.joints:
            return scoped, scoped.joints[joint]
        for model in self.models.values():
            if name in model.joints:
                return model, model.joints[name]
        for model, fixed in [(scoped, joint)] if scoped is not None else [(m, name) for m in self.models.values()]:
            if fixed in model.robot.joints:
                raise WorldError(
                    f"joint '{name}' is a fixed joint of model '{model.name}': it was merged into its parent body "
                    f"(as Gazebo does), so it has no position, properties or effort"
                )
        raise WorldError(f"joint '{name}' does not exist")

    def _frame(self, name: str) -> Frame:
        """A reference frame as gazebo_ros takes it: a model's frame with its canonical (root)
        link's velocity, or a link's frame with its origin's velocity."""
        if name in WORLD_FRAMES:
            return None
        model = self.models.get(name)
        if model is not None:
            linear, angular = model.link_twist(model.root_link)
            return model.model_transform(), linear, angular
        found = self._scoped_link(name)
        if found is None:
            raise WorldError(
                f"reference frame '{name}' is not a model or link (use '', 'world', " f"a model name or 'model::link')"
            )
        model, link = found
        linear, angular = model.link_twist(link)
        return model.link_transform(link), linear, angular

    # --- states -----------------------------------------------------------------------------
    @staticmethod
    def _relative(pose: Transform, linear: Vec3, angular: Vec3, frame: Frame) -> EntityState:
        """As gazebo_ros: pose in the frame; velocities minus the frame's, in the frame's axes."""
        if frame is not None:
            frame_pose, frame_linear, frame_angular = frame
            back = conjugate(frame_pose[1])
            pose = compose(inverse(frame_pose), pose)
            linear = quat_rotate(back, sub(linear, frame_linear))
            angular = quat_rotate(back, sub(angular, frame_angular))
        position, (w, x, y, z) = pose
        return position, (x, y, z, w), linear, angular

    def _absolute(
        self,
        position: Sequence[float],
        quaternion: Sequence[float],
        linear: Sequence[float],
        angular: Sequence[float],
        reference_frame: str,
        moving_frame: bool = True,
    ) -> Tuple[Transform, Vec3, Vec3]:
        """Validated world pose and twist from ones relative to ``reference_frame`` (the
        inverse of ``_relative``); the position must be within MAX_LENGTH of the world origin.
        ``moving_frame`` False: the twist is only turned into world axes, the frame's own velocity
        is not added (gazebo_ros's setModelState)."""
        pose: Transform = (vec3(position, "position", MAX_LENGTH), orientation(quaternion, "orientation"))
        velocity = vec3(linear, "linear velocity", MAX_SPEED)
        spin = vec3(angular, "angular velocity", MAX_SPEED)
        frame = self._frame(reference_frame)
        if frame is not None:
            frame_pose, frame_linear, frame_angular = frame
            pose = compose(frame_pose, pose)
            velocity = quat_rotate(frame_pose[1], velocity)
            spin = quat_rotate(frame_pose[1], spin)
            if moving_frame:
                velocity, spin = add(velocity, frame_linear), add(spin, frame_angular)
            vec3(pose[0], f"position relative to the world (from '{reference_frame}')", MAX_LENGTH)
        return pose, velocity, spin

    def get_model_state(self, name: str, reference_frame: str = "") -> EntityState:
        """The model frame's pose and the velocity of its canonical (root) link's origin."""
        model = self._model(name)
        frame = self._frame(reference_frame)
        linear, angular = model.link_twist(model.root_link)
        return self._relative(model.model_transform(), linear, angular, frame)

    def set_model_state(
        self,
        name: str,
        position: Sequence[float],
        quaternion: Sequence[float],
        linear: Sequence[float] = (0.0, 0.0, 0.0),
        angular: Sequence[float] = (0.0, 0.0, 0.0),
        reference_frame: str = "",
    ) -> None:
        """Teleport the model frame; every body then moves with the model as one rigid body
        (``linear`` is its root link origin's velocity). Joints keep their positions; a static
        model ignores the twist. Relative to a model or link, the pose is in that frame and the
        twist in its axes, without the frame's own velocity (gazebo_ros_api_plugin.cpp,
        setModelState: a model stepped relative to itself comes to rest at each step)."""
        model = self._model(name)
        pose, linear, angular = self._absolute(position, quaternion, linear, angular, reference_frame, False)
        model.set_transform(pose)
        set_rigid_twist(model.bodies, model.link_transform(model.root_link)[0], linear, angular)

    def get_link_state(self, name: str, reference_frame: str = "") -> EntityState:
        """The link frame's pose and its origin's velocity."""
        model, link = self._link(name)
        frame = self._frame(reference_frame)
        linear, angular = model.link_twist(link)
        return self._relative(model.link_transform(link), linear, angular, frame)

    def set_link_state(
        self,
        name: str,
        position: Sequence[float],
        quaternion: Sequence[float],
        linear: Sequence[float] = (0.0, 0.0, 0.0),
        angular: Sequence[float] = (0.0, 0.0, 0.0),
        reference_frame: str = "",
    ) -> None:
        """Move the body carrying the link (with every link fixed to it) so the link is at
        this pose and its origin at this velocity; joints pull the other bodies after it."""
        model, link, body = self._link_body(name)
        pose, linear, angular = self._absolute(position, quaternion, linear, angular, reference_frame)
        position, quaternion = compose(pose, inverse(model.links[link].offset))
        body.setPosition(position)
        body.setQuaternion(quaternion)
        set_rigid_twist([body], pose[0], linear, angular)

    # --- properties ---------------------------------------------------------------------
    def world_properties(self) -> WorldProperties:
        return WorldProperties(sim_time=self.physics.sim_time, model_names=list(self.models), rendering_enabled=False)

    def to_world(
        self, reference_frame: str, position: Sequence[float], quaternion: Sequence[float]
    ) -> Tuple[Vec3, QuatXYZW]:
        """A pose given in ``reference_frame`` (as SpawnModel's initial_pose) in the world."""
        (world_position, (w, x, y, z)), _, _ = self._absolute(
            position, quaternion, (0, 0, 0), (0, 0, 0), reference_frame
        )
        return world_position, (x, y, z, w)

    def model_properties(self, name: str) -> ModelProperties:
        """Links (all, in definition order), collisions and movable joints, without scoping."""
        model = self._model(name)
        links = model.robot.links
        return ModelProperties(
            parent_model_name="",
            canonical_body_name=model.root_link,
            body_names=list(links),
            geom_names=[collision.name for link in links.values() for collision in link.collisions],
            joint_names=list(model.joints),
            child_model_names=[],
            is_static=model.robot.static,
        )

    def link_properties(self, name: str) -> LinkProperties:
        """Mass properties of the body carrying the link (links fixed together share one),
        in the link frame."""
        model, link, body = self._link_body(name)
        com, rotation = inverse(model.links[link].offset)
        mass = body.getMass()
        (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = _rotated_inertia(rotation, mass.I)
        return LinkProperties(
            com_position=com,
            com_orientation=(0.0, 0.0, 0.0, 1.0),
            gravity_mode=bool(body.getGravityMode()),
            mass=mass.mass,
            ixx=ixx,
            ixy=ixy,
            ixz=ixz,
            iyy=iyy,
            iyz=iyz,
            izz=izz,
        )

    def set_link_properties(
        self,
        name: str,
        com_position: Sequence[float],
        com_orientation: Sequence[float],
        gravity_mode: bool,
        mass: float,
        inertia: Sequence[float],
    ) -> None:
        """Replace the mass properties of the body carrying the link: COM pose in the link
        frame, ``inertia`` (ixx, ixy, ixz, iyy, iyz, izz) about the COM in the COM's axes.
        The links stay where they are."""
        model, link, body = self._link_body(name)
        com = vec3(com_position, "com position", MAX_LENGTH)
        rotation = orientation(com_orientation, "com orientation")
        mass = finite(mass, "mass", MAX_MASS)
        if mass <= 0:
            raise WorldError(f"mass must be > 0, got {mass}")
        ixx, ixy, ixz, iyy, iyz, izz = vector(inertia, 6, "inertia (ixx, ixy, ixz, iyy, iyz, izz)", MAX_INERTIA)
        matrix = ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))
        if not _is_positive_definite(matrix):
            raise WorldError(
                f"inertia must be positive definite, got ixx={ixx}, ixy={ixy}, "
                f"ixz={ixz}, iyy={iyy}, iyz={iyz}, izz={izz}"
            )
        if mass < sanity.MIN_MASS:
            raise WorldError(f"mass must be at least {sanity.MIN_MASS:g} kg, got {mass}")
        reach = model.extent(body)
        floor = sanity.min_moment(mass, reach)
        lowest = sanity.principal_moments(matrix)[0]
        if lowest < floor:
            raise WorldError(
                f"inertia of link '{name}' is too small for a {mass:g} kg body reaching {reach:.3g} m: "
                f"its smallest principal moment {lowest:.3g} kg m^2 must be at least {floor:.3g} (ODE would spin "
                f"the body up and let it sink through the ground)"
            )
        model.set_mass(link, mass, com, _rotated_inertia(rotation, matrix))
        body.setGravityMode(bool(gravity_mode))

    def joint_properties(self, name: str) -> JointProperties:
        """Type, damping coefficient, position (continuous joints: multi-turn) and rate."""
        model, handle = self._joint(name)
        return JointProperties(
            type=JOINT_TYPES[handle.type],
            damping=[model.damping(handle.name)],
            position=[handle.angle()],
            rate=[handle.rate()],
        )

    def set_joint_properties(
        self,
        name: str,
        damping: JointParam = None,
        hiStop: JointParam = None,
        loStop: JointParam = None,
        erp: JointParam = None,
        cfm: JointParam = None,
        stop_erp: JointParam = None,
        stop_cfm: JointParam = None,
        fudge_factor: JointParam = None,
        fmax: JointParam = None,
        vel: JointParam = None,
    ) -> None:  # noqa: N803 (message names)
        """gazebo_msgs/ODEJointProperties, set through ODE's joint parameters (first axis: a
        list's first entry, as gazebo_ros does for one-axis joints). Stops may be infinite."""
        model, handle = self._joint(name)
        given = {
            "damping": damping,
            "hiStop": hiStop,
            "loStop": loStop,
            "erp": erp,
            "cfm": cfm,
            "stop_erp": stop_erp,
            "stop_cfm": stop_cfm,
            "fudge_factor": fudge_factor,
            "fmax": fmax,
            "vel": vel,
        }
        values: Dict[str, float] = {}
        for key, value in given.items():
            if value is not None and not isinstance(value, (int, float)):
                value = value[0] if len(value) else None
            if value is None:
                continue
            if key in ("hiStop", "loStop"):
                if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value):
                    raise WorldError(f"{key} must be a number, got {value!r}")
                if math.isinf(value) and (value > 0) != (key == "hiStop"):  # +inf as loStop aborted ODE
                    raise WorldError(f"{key} may be infinite only as {'+' if key == 'hiStop' else '-'}inf (no stop)")
                if handle.type == "prismatic":
                    if math.isfinite(value):
                        finite(value, key, MAX_LENGTH)
                else:
                    sanity.hinge_stop(value, key, WorldError)
                values[key] = float(value)
                continue
            values[key] = finite(value, key, _JOINT_LIMITS.get(key, math.inf))
            if key in ("erp", "stop_erp", "fudge_factor") and not 0 <= values[key] <= 1:
                raise WorldError(f"{key} must be in [0, 1], got {values[key]}")
            if key in ("damping", "cfm", "stop_cfm", "fmax") and values[key] < 0:
                raise WorldError(f"{key} must be >= 0, got {values[key]}")
            if key in ("cfm", "stop_cfm") and values[key] > sanity.MAX_CFM:
                raise WorldError(f"{key} must be at most {sanity.MAX_CFM:g}, got {values[key]}")
        driven = [robot for robot in self.robots.values() if handle in robot.wheels]
        overridden = sorted({"vel", "fmax"} & set(values))
        if driven and overridden:
            raise WorldError(
                f"joint '{name}' is a wheel of the drive plugin of model '{driven[0].model.name}', which sets its "
                f"motor ({', '.join(overridden)}) every step: command the drive instead"
            )
        if "damping" in values:
            stable = sanity.stable_damping(values["damping"], handle.moved_inertia(), self.physics.time_step)
            if stable < values["damping"]:
                raise WorldError(
                    f"damping {values['damping']:g} on joint '{name}' is unstable at a {self.physics.time_step:g} s "
                    f"step: at most {stable:.3g} for what the joint moves"
                )
        joint = handle.joint
        low = values.get("loStop", joint.getParam(oc.PARAM_LO_STOP))
        high = values.get("hiStop", joint.getParam(oc.PARAM_HI_STOP))
        if low > high:
            raise WorldError(f"loStop {low} must not exceed hiStop {high}")
        for key, param in _JOINT_PARAMS:
            if key in values:
                joint.setParam(param, values[key])
        if "damping" in values:
            model.set_damping(handle.name, values["damping"])

    # --- physics ----------------------------------------------------------------------------
    def physics_properties(self) -> PhysicsProperties:
        p = self.physics.params
        return PhysicsProperties(
            time_step=p.time_step,
            max_update_rate=self.max_update_rate,
            gravity=(p.gravity[0], p.gravity[1], p.gravity[2]),
            ode_config=OdeConfig(
                auto_disable_bodies=False,
                sor_pgs_precon_iters=0,
                sor_pgs_iters=p.solver_iterations,
                sor_pgs_w=p.sor,
                sor_pgs_rms_error_tol=0.0,
                contact_surface_layer=p.contact_surface_layer,
                contact_max_correcting_vel=p.contact_max_correcting_vel,
                cfm=p.cfm,
                erp=p.erp,
                max_contacts=p.max_contacts,
            ),
        )

    def set_physics_properties(
        self,
        time_step: float,
        max_update_rate: float,
        gravity: Sequence[float],
        iterations: int,
        erp: float,
        cfm: float,
        contact_surface_layer: float,
        contact_max_correcting_vel: float,
        max_contacts: int,
        auto_disable_bodies: bool = False,
        sor_pgs_precon_iters: int = 0,
        sor_pgs_w: float = SOR_PGS_W,
        sor_pgs_rms_error_tol: float = 0.0,
    ) -> List[str]:
        """Apply to the live world between steps (sim time stays continuous); ``iterations`` is
        ode_config.sor_pgs_iters. Returns warnings for the ode_config settings the simulator
        keeps fixed (auto-disable, preconditioning, RMS tolerance)."""
        rate = update_rate(max_update_rate, "max_update_rate")
        integer(sor_pgs_precon_iters, "sor_pgs_precon_iters")
        finite(sor_pgs_w, "sor_pgs_w")
        finite(sor_pgs_rms_error_tol, "sor_pgs_rms_error_tol")
        params = replace(
            self.physics.params,
            time_step=finite(time_step, "time_step"),
            gravity=vec3(gravity, "gravity", MAX_GRAVITY),
            solver_iterations=iterations,
            erp=finite(erp, "erp"),
            cfm=finite(cfm, "cfm"),
            contact_surface_layer=finite(contact_surface_layer, "contact_surface_layer"),
            contact_max_correcting_vel=finite(contact_max_correcting_vel, "contact_max_correcting_vel"),
            max_contacts=max_contacts,
            sor=finite(sor_pgs_w, "sor_pgs_w"),
        )
        try:
            params.validate()
        except ValueError as error:
            message = str(error)
            raise WorldError(
                message.replace("solver_iterations", "iterations", 1)
                if message.startswith("solver_iterations")
                else message
            ) from None
        warnings = []
        if auto_disable_bodies:
            warnings.append("auto_disable_bodies is not supported: bodies stay enabled")
        if sor_pgs_precon_iters != 0:
            warnings.append("sor_pgs_precon_iters is not supported: ignored")
        if sor_pgs_rms_error_tol != 0:
            warnings.append("sor_pgs_rms_error_tol is not supported: ignored")
        self.physics.set_params(params)
        self.max_update_rate = rate
        return warnings

    # --- joints ---------------------------------------------------------------------------
    def set_model_configuration(self, model_name: str, joint_names: Sequence[str], positions: Sequence[float]) -> None:
        """Put the named joints (plain or "model::joint") at these positions by moving the
        bodies below them; the root body stays, the model comes to rest, other joints keep
        their positions. Drive odometry does not count the wheels' jump."""
        model = self._model(model_name)
        if len(joint_names) != len(positions):
            raise WorldError(
                f"joint_names and positions have different lengths " f"({len(joint_names)} and {len(positions)})"
            )
        targets: Dict[str, float] = {}
        for name, position in zip(joint_names, positions):
            joint = name[len(model_name) + len(SCOPE) :] if name.startswith(model_name + SCOPE) else name
            if joint not in model.joints:
                raise WorldError(f"model '{model_name}' has no joint '{name}'")
            targets[joint] = finite(position, f"position of joint '{name}'", MAX_LENGTH)
            handle = model.joints[joint].joint
            if model.joints[joint].type != "continuous":
                low, high = handle.getParam(oc.PARAM_LO_STOP), handle.getParam(oc.PARAM_HI_STOP)
                if not low <= targets[joint] <= high:
                    raise WorldError(
                        f"position {position:g} of joint '{name}' is outside its limits [{low:g}, {high:g}]"
                    )
        if not targets:
            return
        set_configuration(model, targets)
        now = self.physics.sim_time
        for robot in self.robots.values():
            if robot.model is model and any(wheel.name in targets for wheel in robot.wheels):
                robot.wheels_moved(now)

    # --- loads -------------------------------------------------------------------------------
    def _schedule(self, start_time: float, duration: float) -> Tuple[float, float]:
        """(start, end) in sim seconds: a start in the past is now, a negative duration never
        ends."""
        start = max(finite(start_time, "start_time"), self.physics.sim_time)
        duration = finite(duration, "duration")
        return start, math.inf if duration < 0 else start + duration

    def apply_body_wrench(
        self,
        link: str,
        reference_frame: str,
        reference_point: Sequence[float],
        force: Sequence[float],
        torque: Sequence[float],
        start_time: float = 0.0,
        duration: float = -1.0,
    ) -> None:
        """Push the link's body from ``start_time`` for ``duration`` sim seconds (negative:
        until cleared; shorter than a step: one step).

        Force and torque are in the reference frame's axes, taken at the time of the call; the
        force acts at the body's centre of mass plus ``reference_point`` (in those axes) plus,
        for a model or link frame, that frame's origin relative to the link origin. That is
        gazebo_ros' arithmetic, except that the result is applied in world axes as intended
        (gazebo_ros applies body-axis values as world ones), and that wrenches on one body add.
        """
        model, link_name, body = self._link_body(link)
        frame = self._frame(reference_frame)
        lever = vec3(reference_point, "reference_point", MAX_LENGTH)
        push = vec3(force, "force", MAX_FORCE)
        turn = vec3(torque, "torque", MAX_FORCE)
        start, end = self._schedule(start_time, duration)
        if frame is not None:
            (origin, rotation), _, _ = frame
            push = quat_rotate(rotation, push)
            turn = quat_rotate(rotation, turn)
            lever = add(quat_rotate(rotation, lever), sub(origin, model.link_transform(link_name)[0]))
        turn = add(turn, cross(lever, push))
        add_force, add_torque = body.addForce, body.addTorque

        def apply() -> None:
            add_force(push)
            add_torque(turn)

        self.loads.append(Load("wrench", model.name, f"{model.name}{SCOPE}{link_name}", apply, start, end))

    def clear_body_wrenches(self, link: str) -> None:
        """Drop every wrench on this link, scheduled or running."""
        model, link_name = self._link(link)
        target = f"{model.name}{SCOPE}{link_name}"
        self.loads = [load for load in self.loads if not (load.kind == "wrench" and load.target == target)]

    def apply_joint_effort(self, joint: str, effort: float, start_time: float = 0.0, duration: float = -1.0) -> None:
        """Torque (revolute) or force (prismatic) along the joint axis, positive towards
        increasing position, scheduled as ``apply_body_wrench``; held to the joint's velocity
        and effort limits each step as Gazebo does (see world.joint_effort)."""
        model, handle = self._joint(joint)
        effort = finite(effort, "effort", MAX_FORCE)
        limit = sanity.effort_limit(handle.moved_inertia())
        if abs(effort) > limit:
            raise WorldError(
                f"effort {effort:g} on joint '{joint}' must be at most {limit:.3g} in magnitude: it would accelerate "
                f"what the joint moves beyond {sanity.MAX_JOINT_ACCELERATION:g} per s^2"
            )
        start, end = self._schedule(start_time, duration)
        apply = effort_applier(handle, effort, model.robot.joints[handle.name].limits)  # the joint's limits
        self.loads.append(Load("effort", model.name, handle.name, apply, start, end))

    def clear_joint_forces(self, joint: str) -> None:
        """Drop the efforts on this joint; an unscoped name clears that joint in every model
        (as gazebo_ros matches joint names)."""
        model, handle = self._joint(joint)
        everywhere = joint == handle.name
        self.loads = [
            load
            for load in self.loads
            if not (load.kind == "effort" and load.target == handle.name and (everywhere or load.model == model.name))
        ]

    def apply_loads(self) -> None:
        """Add the forces due in the coming step, and drop the loads that end with it."""
        now = self.physics.sim_time
        next_step = now + self.physics.time_step + TIME_EPSILON
        due = []
        for load in self.loads:
            if load.start <= now + TIME_EPSILON:
                load.apply()
                if load.end <= next_step:
                    continue
            due.append(load)
        self.loads = due
