"""What Gazebo's world API answers (gazebo_msgs fields as plain Python types) and the loads it schedules."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, List, Tuple, TypedDict

from turtle_sim_ode.models.transforms import Vec3

QuatXYZW = Tuple[float, float, float, float]


class OdeConfig(TypedDict):
    """gazebo_msgs/ODEPhysics."""

    auto_disable_bodies: bool
    sor_pgs_precon_iters: int
    sor_pgs_iters: int
    sor_pgs_w: float
    sor_pgs_rms_error_tol: float
    contact_surface_layer: float
    contact_max_correcting_vel: float
    cfm: float
    erp: float
    max_contacts: int


class PhysicsProperties(TypedDict):
    """gazebo_msgs/GetPhysicsProperties without ``pause`` (which the node knows)."""

    time_step: float
    max_update_rate: float
    gravity: Vec3
    ode_config: OdeConfig


class ModelProperties(TypedDict):
    """gazebo_msgs/GetModelProperties."""

    parent_model_name: str
    canonical_body_name: str
    body_names: List[str]
    geom_names: List[str]
    joint_names: List[str]
    child_model_names: List[str]
    is_static: bool


class LinkProperties(TypedDict):
    """gazebo_msgs/GetLinkProperties with ``com`` as a position and a quaternion (x, y, z, w)."""

    com_position: Vec3
    com_orientation: QuatXYZW
    gravity_mode: bool
    mass: float
    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float


class JointProperties(TypedDict):
    """gazebo_msgs/GetJointProperties; ``type`` is one of its constants (REVOLUTE, ...)."""

    type: int
    damping: List[float]
    position: List[float]
    rate: List[float]


class WorldProperties(TypedDict):
    """gazebo_msgs/GetWorldProperties."""

    sim_time: float
    model_names: List[str]
    rendering_enabled: bool


@dataclass(frozen=True)
class Load:
    """A force added before every step whose start time is in [start, end) (at least one)."""

    kind: str  # "wrench" (target "model::link") or "effort" (target: the joint's name)
    model: str
    target: str
    apply: Callable[[], None]
    start: float
    end: float
