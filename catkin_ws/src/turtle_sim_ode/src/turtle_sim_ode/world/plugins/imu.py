"""gazebo_ros_imu (``libgazebo_ros_imu.so``) as a model plugin, as turtlebot3 has it: the tags are those of the sensor
form (sensors.plugins.imu), with <bodyName> required."""
from __future__ import annotations

from typing import Mapping

from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.sensors.plugins.imu import ImuConfig, imu_config

IMU = "libgazebo_ros_imu.so"
MODEL_PLUGINS = (IMU,)


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> ImuConfig:
    return imu_config(plugin.filename, plugin.params)
