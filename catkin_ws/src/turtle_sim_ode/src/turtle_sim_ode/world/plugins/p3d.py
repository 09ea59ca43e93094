"""gazebo_ros_p3d (``libgazebo_ros_p3d.so``): a body's pose and velocity from the physics state."""
from __future__ import annotations

import random
from dataclasses import dataclass
from typing import List, Mapping, Optional, Tuple

from turtle_sim_ode.models.transforms import Vec3
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins.tags import number, text, triple

P3D = "libgazebo_ros_p3d.so"
MODEL_PLUGINS = (P3D,)


@dataclass
class GroundTruthConfig:
    """libgazebo_ros_p3d.so: a body's pose and velocity from the physics state, as nav_msgs/Odometry."""

    body: str
    topic: str
    frame: str
    update_rate: float
    gaussian_noise: float
    xyz_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> GroundTruthConfig:
    body = text(plugin, "bodyName", "")
    if not body:
        raise ModelError(f"{plugin.filename} needs <bodyName>")
    return GroundTruthConfig(
        body=body,
        topic=text(plugin, "topicName", "ground_truth"),
        frame=text(plugin, "frameName", "world"),
        update_rate=number(plugin, "updateRate", 0.0),
        gaussian_noise=number(plugin, "gaussianNoise", 0.0),
        xyz_offset=triple(plugin, "xyzOffsets" if "xyzOffsets" in plugin.params else "xyzOffset"),
        rpy_offset=triple(plugin, "rpyOffsets" if "rpyOffsets" in plugin.params else "rpyOffset"),
        robot_namespace=robot_namespace_tag(plugin.params),
    )


def find_body(link_names: List[str], body: str) -> Optional[str]:
    """p3d's bodyName may be scoped ('model::link'): the link it names, if the model has it."""
    name = body.split("::")[-1]
    return name if name in link_names else None


def noisy(values: Vec3, sigma: float) -> Vec3:
    """GaussianKernel(0, sigma) added to each value, none for sigma 0 (gazebo_ros_p3d.cpp, gazebo_ros_ft_sensor.cpp)."""
    if not sigma:
        return values
    return tuple(v + random.gauss(0.0, sigma) for v in values)  # type: ignore[return-value]
