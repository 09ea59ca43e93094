"""Gazebo's world, model, link, joint and physics properties (the /gazebo/get_*_properties and set_*_properties
services), ROS-free."""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Dict, List, Sequence, Union

from turtle_sim_ode.models.inertia import rotated_inertia
from turtle_sim_ode.models.transforms import inverse
from turtle_sim_ode.models.urdf import MAX_INERTIA, MAX_LENGTH, MAX_MASS, _is_positive_definite
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.settings import MAX_GRAVITY
from turtle_sim_ode.world.entities import EntityLookup
from turtle_sim_ode.world.records import (
    JointProperties,
    LinkProperties,
    ModelProperties,
    OdeConfig,
    PhysicsProperties,
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

# A gazebo_msgs/ODEJointProperties value: a number, or a list whose first entry is used;
# None or an empty list leaves the parameter alone.
JointParam = Union[None, float, Sequence[float]]

# gazebo_msgs/GetJointProperties type constants.
REVOLUTE, CONTINUOUS, PRISMATIC, FIXED, BALL, UNIVERSAL = range(6)
JOINT_TYPES = {"revolute": REVOLUTE, "continuous": CONTINUOUS, "prismatic": PRISMATIC}

# ODE's successive over-relaxation factor, which PyODE cannot change.
SOR_PGS_W = 1.3

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


class PropertyControl(EntityLookup):
    """Properties read and set by name (mixed into WorldControl)."""

    def world_properties(self) -> WorldProperties:
        return WorldProperties(sim_time=self.physics.sim_time, model_names=list(self.models), rendering_enabled=False)

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
        (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = rotated_inertia(rotation, mass.I)
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
        model.set_mass(link, mass, com, rotated_inertia(rotation, matrix))
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
