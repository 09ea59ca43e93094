"""ROS-free simulation: a PhysicsWorld with named models, and the drive plugins found in their URDFs."""
from __future__ import annotations

import logging
from typing import Dict, List, Mapping, Optional, Tuple

from .diff_drive import DiffDriveController, DiffDriveParams, WheelOdometry
from .model_builder import BuiltModel, build_model
from .physics import PhysicsParams, PhysicsWorld
from .urdf_model import GazeboPlugin, ModelError, parse_urdf

KOBUKI_PLUGIN = "libgazebo_ros_kobuki.so"
Pose6 = Tuple[float, float, float, float, float, float]

log = logging.getLogger(__name__)


class DiffDriveRobot:
    """A model's Kobuki-style drive: velocity motors on two wheel joints and encoder odometry."""

    def __init__(self, model: BuiltModel, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> None:
        self.model = model
        self.plugin = plugin
        self.params = DiffDriveParams.from_kobuki_plugin(plugin.params, **overrides)
        try:
            self.left = model.joint(plugin.params["left_wheel_joint_name"])
            self.right = model.joint(plugin.params["right_wheel_joint_name"])
        except KeyError as error:
            raise ModelError(f"{plugin.filename}: {error.args[0]}") from None
        self.drive = DiffDriveController(self.left.joint, self.right.joint, self.params)
        self.odometry = WheelOdometry.from_params(self.params)

    def update_odometry(self, now: float) -> None:
        """Read the encoders (call at the odometry rate, after a step)."""
        self.odometry.update(self.left.angle(), self.right.angle(), now)

    def reset_odometry(self, now: float) -> None:
        self.odometry.reset()
        self.update_odometry(now)


class Simulation:
    """Models by name in one physics world, stepped with their drives."""

    def __init__(self, physics_params: Optional[PhysicsParams] = None,
                 drive_overrides: Optional[Mapping[str, object]] = None) -> None:
        self.physics = PhysicsWorld(physics_params)
        self.models: Dict[str, BuiltModel] = {}
        self.robots: Dict[str, DiffDriveRobot] = {}
        self._drive_overrides = dict(drive_overrides or {})

    @property
    def sim_time(self) -> float:
        return self.physics.sim_time

    def spawn_urdf(self, name: str, urdf: str, pose: Pose6 = (0, 0, 0, 0, 0, 0)) -> List[str]:
        """Build the URDF as model `name` at pose (x, y, z, roll, pitch, yaw); return the parser's warnings.

        Raises ModelError (a ValueError) with a message for the caller when the name or the model is bad;
        the world is left as it was.
        """
        if not name:
            raise ModelError("model name is empty")
        if name in self.models:
            raise ModelError(f"a model named '{name}' already exists")
        robot = parse_urdf(urdf)
        model = build_model(self.physics, robot, tuple(pose))
        model.name = name
        warnings = list(robot.warnings)
        try:
            plugin = robot.plugin(KOBUKI_PLUGIN)
            if plugin is not None:
                self.robots[name] = DiffDriveRobot(model, plugin, self._drive_overrides)
                self.robots[name].reset_odometry(self.sim_time)
        except (ModelError, ValueError) as error:
            model.remove()
            raise ModelError(f"model '{name}': {error}") from None
        self.models[name] = model
        for plugin in robot.plugins:
            if plugin.filename != KOBUKI_PLUGIN:
                warnings.append(f"plugin {plugin.filename} ({plugin.name}) is not supported: ignored")
        return warnings

    def delete(self, name: str) -> None:
        """Remove model `name`; KeyError if there is none."""
        model = self.models.pop(name)
        self.robots.pop(name, None)
        model.remove()

    def step(self) -> None:
        """One physics step with every drive's motors set for it."""
        now = self.physics.sim_time
        dt = self.physics.time_step
        for robot in self.robots.values():
            robot.drive.update(now, dt)
        self.physics.step()
