"""gazebo_ros_joint_state_publisher (``libgazebo_ros_joint_state_publisher.so``): the named joints' states."""
from __future__ import annotations

from dataclasses import dataclass
from typing import List, Mapping, Optional, Tuple

from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins.tags import number, text

JOINT_STATE_PUBLISHER = "libgazebo_ros_joint_state_publisher.so"
MODEL_PLUGINS = (JOINT_STATE_PUBLISHER,)


@dataclass
class JointStatesConfig:
    """libgazebo_ros_joint_state_publisher.so: positions and velocities of the named joints."""

    joints: List[str]
    update_rate: float
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>

    @property
    def joints_needed(self) -> Tuple[str, ...]:
        return tuple(self.joints)


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> JointStatesConfig:
    joints = [name.strip() for name in text(plugin, "jointName", "").split(",") if name.strip()]
    if not joints:
        raise ModelError(f"{plugin.filename} needs <jointName> (comma-separated joint names)")
    return JointStatesConfig(
        joints=joints,
        update_rate=number(plugin, "updateRate", 100.0),
        robot_namespace=robot_namespace_tag(plugin.params),
    )
