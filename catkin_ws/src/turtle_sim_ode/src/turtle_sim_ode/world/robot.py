"""A model's differential drive: its plugin's configuration, the wheel motors and encoder odometry."""
from __future__ import annotations

from turtle_sim_ode.models.builder import BuiltModel
from turtle_sim_ode.world.diff_drive import DiffDriveController, WheelOdometry
from turtle_sim_ode.world.plugins import DriveConfig


class DiffDriveRobot:
    """A model's differential drive plugin: velocity motors on two wheel joints and encoder odometry."""

    def __init__(self, model: BuiltModel, config: DriveConfig) -> None:
        self.model = model
        self.config = config
        self.params = config.params
        self.left = model.joint(config.left_joint)
        self.right = model.joint(config.right_joint)
        self.drive = DiffDriveController(self.left.joint, self.right.joint, self.params)
        self.odometry = WheelOdometry.from_params(self.params)

    def update_odometry(self, now: float) -> None:
        """Read the encoders (call at the odometry rate, after a step)."""
        self.odometry.update(self.left.angle(), self.right.angle(), now)

    def reset_odometry(self, now: float) -> None:
        self.odometry.reset()
        self.update_odometry(now)
