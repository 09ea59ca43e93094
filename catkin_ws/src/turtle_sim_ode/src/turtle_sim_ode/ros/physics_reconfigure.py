"""The physics settings through dynamic_reconfigure, as gazebo_ros offers them: /gazebo/set_parameters,
parameter_descriptions and parameter_updates with the fields of gazebo_ros's PhysicsConfig (cfg/Physics.cfg).

gazebo_ros generates its config type from Physics.cfg at build time; the same description is written out here
(dynamic_reconfigure's Python server takes any object with the generated module's attributes), so that this
package needs no build-time generator and no package named gazebo_ros.
"""
from __future__ import annotations

from typing import Any, Callable, Dict, List, Tuple

import rospy
from dynamic_reconfigure.server import Server
from gazebo_msgs.msg import ODEPhysics
from gazebo_msgs.srv import (
    GetPhysicsPropertiesRequest,
    GetPhysicsPropertiesResponse,
    SetPhysicsPropertiesRequest,
    SetPhysicsPropertiesResponse,
)
from geometry_msgs.msg import Vector3

# name, type, default, min, max, description. Names, types, defaults and bounds are gazebo_ros's
# (noetic-devel gazebo_ros/cfg/Physics.cfg); every field is at reconfiguration level 1 there.
PHYSICS_FIELDS: Tuple[Tuple[str, str, Any, Any, Any, str], ...] = (
    ("time_step", "double", 0.001, 0.0, 10.0, "Physics step (s)."),
    ("max_update_rate", "double", 60.0, 0.0, 1000.0, "Steps per wall second; 0 as fast as possible."),
    ("gravity_x", "double", 0.0, -100.0, 100.0, "Gravity along x (m/s^2)."),
    ("gravity_y", "double", 0.0, -100.0, 100.0, "Gravity along y (m/s^2)."),
    ("gravity_z", "double", -9.8, -100.0, 100.0, "Gravity along z (m/s^2)."),
    ("auto_disable_bodies", "bool", False, False, True, "Disable bodies at rest."),
    ("sor_pgs_precon_iters", "int", 0, 0, 10000, "Preconditioning iterations of ODE's quickstep."),
    ("sor_pgs_iters", "int", 20, 0, 10000, "Iterations of ODE's quickstep."),
    ("sor_pgs_w", "double", 1.3, 0.0, 5.0, "Successive over-relaxation factor of ODE's quickstep."),
    ("sor_pgs_rms_error_tol", "double", -1.0, -1.0, 10000.0, "RMS error tolerance of ODE's quickstep."),
    ("cfm", "double", 0.0, 0.0, 10.0, "Global constraint force mixing."),
    ("erp", "double", 0.2, 0.0, 10.0, "Global error reduction parameter."),
    ("contact_surface_layer", "double", 0.001, 0.0, 10.0, "Penetration allowed without correction (m)."),
    ("contact_max_correcting_vel", "double", 100.0, 0.0, 10000000.0, "Fastest penetration correction (m/s)."),
    ("max_contacts", "int", 100, 0, 10000000, "Most contacts between two geoms."),
)
LEVEL = 1
C_TYPES = {"double": "double", "int": "int", "bool": "bool"}


class PhysicsConfig:
    """The attributes dynamic_reconfigure's generator writes into a <Name>Config.py module."""

    config_description: Dict[str, Any] = {
        "name": "Default",
        "type": "",
        "state": True,
        "cstate": "true",
        "id": 0,
        "parent": 0,
        "parameters": [
            {
                "name": name,
                "type": kind,
                "default": default,
                "level": LEVEL,
                "description": description,
                "min": low,
                "max": high,
                "edit_method": "",
                "ctype": C_TYPES[kind],
                "cconsttype": "const " + C_TYPES[kind],
            }
            for name, kind, default, low, high, description in PHYSICS_FIELDS
        ],
        "groups": [],
        "class": "DEFAULT",
        "parentclass": "",
        "parentname": "Default",
        "field": "default",
        "upper": "DEFAULT",
        "lower": "groups",
    }
    defaults = {name: default for name, _, default, _, _, _ in PHYSICS_FIELDS}
    min = {name: low for name, _, _, low, _, _ in PHYSICS_FIELDS}
    max = {name: high for name, _, _, _, high, _ in PHYSICS_FIELDS}
    level = {name: LEVEL for name, *_ in PHYSICS_FIELDS}
    type = {name: kind for name, kind, *_ in PHYSICS_FIELDS}
    all_level = LEVEL


def config_of(physics: GetPhysicsPropertiesResponse) -> Dict[str, Any]:
    """The PhysicsConfig fields of a get_physics_properties answer (gazebo_ros's physicsReconfigureCallback)."""
    ode = physics.ode_config
    return {
        "time_step": physics.time_step,
        "max_update_rate": physics.max_update_rate,
        "gravity_x": physics.gravity.x,
        "gravity_y": physics.gravity.y,
        "gravity_z": physics.gravity.z,
        "auto_disable_bodies": ode.auto_disable_bodies,
        "sor_pgs_precon_iters": ode.sor_pgs_precon_iters,
        "sor_pgs_iters": ode.sor_pgs_iters,
        "sor_pgs_w": ode.sor_pgs_w,
        "sor_pgs_rms_error_tol": ode.sor_pgs_rms_error_tol,
        "cfm": ode.cfm,
        "erp": ode.erp,
        "contact_surface_layer": ode.contact_surface_layer,
        "contact_max_correcting_vel": ode.contact_max_correcting_vel,
        "max_contacts": ode.max_contacts,
    }


def request_of(config: Dict[str, Any]) -> SetPhysicsPropertiesRequest:
    ode = ODEPhysics(
        auto_disable_bodies=bool(config["auto_disable_bodies"]),
        sor_pgs_precon_iters=int(config["sor_pgs_precon_iters"]),
        sor_pgs_iters=int(config["sor_pgs_iters"]),
        sor_pgs_w=config["sor_pgs_w"],
        sor_pgs_rms_error_tol=config["sor_pgs_rms_error_tol"],
        contact_surface_layer=config["contact_surface_layer"],
        contact_max_correcting_vel=config["contact_max_correcting_vel"],
        cfm=config["cfm"],
        erp=config["erp"],
        max_contacts=int(config["max_contacts"]),
    )
    gravity = Vector3(config["gravity_x"], config["gravity_y"], config["gravity_z"])
    return SetPhysicsPropertiesRequest(config["time_step"], config["max_update_rate"], gravity, ode)


class PhysicsReconfigure:
    """A dynamic_reconfigure server (in the node's namespace) over the get/set_physics_properties handlers: its
    first configuration is the world's physics; a later one that differs is applied through
    set_physics_properties (with its checks); a refused one is logged and the world's values are published."""

    def __init__(
        self,
        get_physics: Callable[[GetPhysicsPropertiesRequest], GetPhysicsPropertiesResponse],
        set_physics: Callable[[SetPhysicsPropertiesRequest], SetPhysicsPropertiesResponse],
    ) -> None:
        self._get = get_physics
        self._set = set_physics
        self._initialised = False
        self._server = Server(PhysicsConfig, self._on_config)

    def _current(self) -> Dict[str, Any]:
        return config_of(self._get(GetPhysicsPropertiesRequest()))

    def _on_config(self, config: Dict[str, Any], _level: int) -> Dict[str, Any]:
        current = self._current()
        if not self._initialised:
            self._initialised = True
            config.update(current)
            return config
        if changed_fields(config, current):
            answer = self._set(request_of(config))
            if not answer.success:
                rospy.logwarn("physics reconfigure refused: %s", answer.status_message)
                config.update(self._current())
            else:
                rospy.loginfo("physics dynamic reconfigure update complete")
        return config


def changed_fields(config: Dict[str, Any], current: Dict[str, Any]) -> List[str]:
    return [name for name in PhysicsConfig.defaults if config[name] != current[name]]
