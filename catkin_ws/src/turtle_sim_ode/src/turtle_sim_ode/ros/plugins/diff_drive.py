"""gazebo_ros_diff_drive's topics (world.plugins.diff_drive): the drive interface of the model's drive."""
from __future__ import annotations

from typing import List

from turtle_sim_ode.ros.periodic import ModelContext, Periodic
from turtle_sim_ode.ros.plugins.drive import DriveInterface
from turtle_sim_ode.world.plugins import DriveConfig


def interfaces(context: ModelContext, config: DriveConfig) -> List[Periodic]:
    """The model's drive (the first drive plugin; the others were warned about at spawn)."""
    robot = context.sim.robots.get(context.name)
    if robot is None or robot.config is not config:
        return []
    return [
        DriveInterface(context.name, robot, context.settings, context.tf_broadcaster, context.sim, context.namespace)
    ]
