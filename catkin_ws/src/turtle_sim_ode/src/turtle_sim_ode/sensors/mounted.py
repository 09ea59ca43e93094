"""What every sensor on a link keeps, as Gazebo's Sensor keeps its parent link and its pose on it."""
from __future__ import annotations

import random
from typing import Any, Optional

import numpy as np

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Transform, compose, quat_from_rpy
from turtle_sim_ode.physics.world import PhysicsWorld


class MountedSensor:
    """A sensor on ``config.link`` at ``config.pose`` (x y z roll pitch yaw in the link's frame), with a numpy
    generator for its noise seeded from ``rng``; KeyError at once for a link the model does not have."""

    def __init__(
        self, physics: PhysicsWorld, model: BuiltModel, config: Any, rng: Optional[random.Random] = None
    ) -> None:
        model.link_transform(config.link)  # KeyError now for a missing link
        self.physics = physics
        self.model = model
        self.config = config
        self._rng = np.random.default_rng((rng or random.Random()).getrandbits(32))
        self._mount: Transform = (tuple(config.pose[:3]), quat_from_rpy(*config.pose[3:]))  # type: ignore[assignment]

    def world_transform(self) -> Transform:
        """The sensor's pose in the world now (world from sensor)."""
        return compose(self.model.link_transform(self.config.link), self._mount)
