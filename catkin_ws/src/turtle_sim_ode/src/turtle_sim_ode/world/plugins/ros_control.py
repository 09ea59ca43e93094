"""gazebo_ros_control (``libgazebo_ros_control.so``): the plugin's tags, kept for its ROS side, which builds the
hardware simulation and the controller manager (control.plugin) once it can read the robot's parameters."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Mapping

from turtle_sim_ode.models.description import GazeboPlugin

ROS_CONTROL = "libgazebo_ros_control.so"
MODEL_PLUGINS = (ROS_CONTROL,)


@dataclass
class RosControlPluginConfig:
    """The plugin's tags as text (robotNamespace, controlPeriod, robotSimType, robotParam, legacyModeNS,
    eStopTopic): control.plugin.RosControlConfig reads them against the physics step."""

    params: Dict[str, str]


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> RosControlPluginConfig:
    return RosControlPluginConfig(dict(plugin.params))
