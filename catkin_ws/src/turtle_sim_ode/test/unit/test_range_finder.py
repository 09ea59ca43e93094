"""libgazebo_ros_range.so: tags and defaults as GazeboRosRange::Load reads them, and PutRangeData's range: the nearest
of the sensor's rays, noise only below the maximum (gazebo_plugins/src/gazebo_ros_range.cpp)."""
from __future__ import annotations

import numpy as np
import pytest
from ray_grid_helpers import ray_grid_sdf

from turtle_sim_ode.sensors.config import read_sdf_sensors
from turtle_sim_ode.sensors.lidar import MultiBeamLidar
from turtle_sim_ode.sensors.plugins.range_finder import INFRARED, ULTRASOUND, RangeConfig, nearest
from turtle_sim_ode.world.simulation import Simulation


def sonar_sdf(tags: str = "") -> str:
    """A sonar as hector and turtlebot descriptions write one: 5 x 5 rays over +-0.1 rad, 0.02 .. 4 m, 10 Hz."""
    range_tags = "<min>0.02</min><max>4</max><resolution>0.01</resolution>"
    return ray_grid_sdf(
        "sonar_link", "sonar", 10, (5, -0.1, 0.1), (5, -0.1, 0.1), range_tags, "libgazebo_ros_range.so", tags
    )


WALL_SDF = """<sdf version="1.6"><model name="wall"><static>true</static><link name="link">
  <collision name="c"><geometry><box><size>0.2 2 2</size></box></geometry></collision></link></model></sdf>"""


def test_defaults_and_tags() -> None:
    (config,) = read_sdf_sensors(sonar_sdf()).configs
    assert isinstance(config, RangeConfig)
    # Load: /range, frame /world, ultrasound, fov 0.05, no noise, updateRate 0; range limits the sensor's.
    assert (config.topic, config.frame, config.radiation, config.field_of_view) == (
        "/range",
        "/world",
        ULTRASOUND,
        0.05,
    )
    assert (config.range_min, config.range_max, config.samples, config.vertical_samples) == (0.02, 4.0, 5, 5)
    tags = "<topicName>sonar_front</topicName><frameName>sonar_link</frameName><radiation>infrared</radiation>"
    (config,) = read_sdf_sensors(sonar_sdf(tags + "<fov>0.3</fov>")).configs
    assert (config.topic, config.frame, config.radiation, config.field_of_view) == (
        "sonar_front",
        "sonar_link",
        INFRARED,
        0.3,
    )


def test_the_nearest_ray_reads_the_wall() -> None:
    sim = Simulation()
    sim.spawn_sdf("bot", sonar_sdf())
    (config,) = sim.plugins["bot"].configs
    lidar = MultiBeamLidar(sim.physics, sim.models["bot"], config)
    assert nearest(lidar.ranges(), config.range_max, 0.0, None) == 4.0  # nothing ahead: the maximum
    sim.spawn_sdf("wall", WALL_SDF, (1.6, 0.0, 1.0, 0, 0, 0))
    assert nearest(lidar.ranges(), config.range_max, 0.0, None) == pytest.approx(1.5, abs=1e-6)  # the centre ray


def test_noise_only_below_the_maximum() -> None:
    def plus_one(mean: float, sigma: float) -> float:
        return 1.0

    assert nearest(np.array([1.0, 2.0]), 4.0, 0.1, plus_one) == 2.0
    assert nearest(np.array([3.5]), 4.0, 0.1, plus_one) == 4.0  # clipped at the maximum
    assert nearest(np.array([4.0]), 4.0, 0.1, plus_one) == 4.0
