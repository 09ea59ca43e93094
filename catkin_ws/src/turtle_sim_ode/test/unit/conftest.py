"""Shared helpers: a TurtleBot in a PhysicsWorld driven like the ROS node will drive it."""
from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import List, Optional, Tuple

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT / "src"))

from turtle_sim_ode.models.resources import ResourcePaths  # noqa: E402
from turtle_sim_ode.physics.settings import PhysicsParams  # noqa: E402
from turtle_sim_ode.world.simulation import Simulation

TURTLEBOT_URDF = (PACKAGE_ROOT / "urdf" / "turtlebot.urdf").read_text()
FIXTURES = PACKAGE_ROOT / "test" / "fixtures"
MESH_PACKAGE = FIXTURES / "tso_mesh_worlds"  # a package of models, worlds and meshes (see its package.xml)
COMMAND_PERIOD = 0.1  # cmd_vel arrives at 10 Hz
ODOMETRY_PERIOD = 0.02  # the Kobuki base publishes odometry at 50 Hz


def fixture_paths() -> ResourcePaths:
    """As ros.resource_paths finds them with test/fixtures on ROS_PACKAGE_PATH."""
    return ResourcePaths({"tso_mesh_worlds": str(MESH_PACKAGE)}, [str(MESH_PACKAGE / "models")], [str(FIXTURES)])


def yaw_of(quaternion_xyzw: Tuple[float, float, float, float]) -> float:
    x, y, z, w = quaternion_xyzw
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


class TurtleSim:
    """TurtleBot URDF + Kobuki diff drive + wheel odometry on a fixed-step world, through Simulation."""

    def __init__(self, solver: str = "quick", z: float = 0.0, **drive_overrides: float) -> None:
        self.sim = Simulation(PhysicsParams(solver=solver), drive_overrides)
        self.sim.spawn_urdf("mobile_base", TURTLEBOT_URDF, (0.0, 0.0, z, 0.0, 0.0, 0.0))
        robot = self.sim.robots["mobile_base"]
        self.physics = self.sim.physics
        self.model = robot.model
        self.params = robot.params
        self.left, self.right = robot.left, robot.right
        self.drive = robot.drive
        self.odometry = robot.odometry
        self._steps_per_command = round(COMMAND_PERIOD / self.physics.time_step)
        self._steps_per_odometry = round(ODOMETRY_PERIOD / self.physics.time_step)

    def pose(self) -> Tuple[float, float, float]:
        """Ground truth (x, y, yaw) of base_footprint."""
        position, quaternion = self.model.link_pose("base_footprint")
        return position[0], position[1], yaw_of(quaternion)

    def run(
        self, seconds: float, command: Optional[Tuple[float, float]] = None, sample_period: Optional[float] = None
    ) -> List[Tuple[float, float, float]]:
        """Step for ``seconds``, re-sending ``command`` at 10 Hz; returns sampled poses."""
        samples: List[Tuple[float, float, float]] = []
        dt = self.physics.time_step
        sample_steps = round(sample_period / dt) if sample_period else 0
        for step in range(round(seconds / dt)):
            now = self.physics.sim_time
            if command is not None and step % self._steps_per_command == 0:
                self.drive.set_command(command[0], command[1], now)
            self.sim.step()
            if step % self._steps_per_odometry == 0:
                self.odometry.update(self.left.angle(), self.right.angle(), self.physics.sim_time)
            if sample_steps and step % sample_steps == 0:
                samples.append(self.pose())
        return samples

    def settle(self) -> None:
        self.run(0.5)
        self.odometry.reset()
        self.odometry.update(self.left.angle(), self.right.angle(), self.physics.sim_time)
