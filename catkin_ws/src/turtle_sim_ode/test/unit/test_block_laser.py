"""libgazebo_ros_block_laser.so: tags and defaults as GazeboRosBlockLaser::Load reads them, and PutLaserData's
points (gazebo_plugins/src/gazebo_ros_block_laser.cpp): the angle of point i is the mean of rays i and i + 1 (the
last ray's own), REP 117 infinities, noise only off the maximum."""
from __future__ import annotations

import numpy as np
import pytest
from ray_grid_helpers import ray_grid_sdf

from turtle_sim_ode.sensors.config import read_sdf_sensors
from turtle_sim_ode.sensors.lidar import MultiBeamLidar
from turtle_sim_ode.sensors.plugins.block_laser import BlockLaserConfig, block_points
from turtle_sim_ode.world.simulation import Simulation


def block_sdf(tags: str = "") -> str:
    """A 3 x 3 block laser over +-0.2 rad across and +-0.1 rad up and down, 0.1 .. 5 m, 5 Hz."""
    plugin = "libgazebo_ros_block_laser.so"
    return ray_grid_sdf("laser", "block", 5, (3, -0.2, 0.2), (3, -0.1, 0.1), "<min>0.1</min><max>5</max>", plugin, tags)


WALL_SDF = """<sdf version="1.6"><model name="wall"><static>true</static><link name="link">
  <collision name="c"><geometry><box><size>0.2 0.2 4</size></box></geometry></collision></link></model></sdf>"""


def no_noise(mean, sigma, shape):  # type: ignore[no-untyped-def]
    raise AssertionError("no noise asked for")


def test_defaults() -> None:
    (config,) = read_sdf_sensors(block_sdf()).configs
    assert isinstance(config, BlockLaserConfig)
    assert (config.topic, config.frame, config.gaussian_noise) == ("/world", "/world", 0.0)  # Load's, sic


def test_points_and_half_step_angles() -> None:
    sim = Simulation()
    sim.spawn_sdf("bot", block_sdf("<topicName>cloud</topicName>"))
    sim.spawn_sdf("wall", WALL_SDF, (1.6, 0.0, 2.0, 0, 0, 0))  # a narrow post: only the centre column hits it
    (config,) = sim.plugins["bot"].configs
    lidar = MultiBeamLidar(sim.physics, sim.models["bot"], config)
    points, intensities = block_points(lidar.ranges(), config, no_noise)
    assert points.shape == (9, 3) and np.all(intensities == 0)
    # Row j = 0 (pitch -0.1 rays), column i = 1: ray 1 measured 1.5 / cos(-0.1), aimed at yaw 0.1 (between rays 1
    # and 2) and pitch -0.05 (between rays 0 and 1).
    r = 1.5 / np.cos(0.1)
    assert points[1] == pytest.approx(
        [r * np.cos(0.05) * np.cos(0.1), r * np.cos(0.05) * np.sin(0.1), -r * np.sin(0.05)]
    )
    # A miss reads the maximum, 5 m, finite.
    assert np.linalg.norm(points[0]) == pytest.approx(5.0)


def test_noise_spares_points_at_the_maximum() -> None:
    (config,) = read_sdf_sensors(block_sdf("<gaussianNoise>0.01</gaussianNoise>")).configs
    ranges = np.array([[5.0, 1.0, 0.05]] * 3)
    calls = []

    def count(mean, sigma, shape):  # type: ignore[no-untyped-def]
        calls.append(shape)
        return np.zeros(shape)

    points, _ = block_points(ranges, config, count)
    assert calls == [(6, 3), (9,)]  # 6 points off the maximum, every intensity
    assert np.isinf(points[2]).any()  # 0.05 is below range min 0.1: -inf


def test_the_ray_shape_ranges_are_without_the_sensor_noise() -> None:
    """RaySensor adds <ray><noise> to its scan message; gazebo_ros_block_laser's PutLaserData reads the ray shape
    (LaserShape()->GetRange), which has none: hits just past range min stay finite and within the range."""
    noisy = block_sdf().replace(
        "</range>", "</range><noise><type>gaussian</type><mean>0</mean><stddev>0.5</stddev></noise>"
    )
    sim = Simulation()
    sim.spawn_sdf("bot", noisy)
    sim.spawn_sdf("wall", WALL_SDF, (1.6, 0.0, 2.0, 0, 0, 0))
    (config,) = sim.plugins["bot"].configs
    lidar = MultiBeamLidar(sim.physics, sim.models["bot"], config)
    shape = lidar.ranges(noisy=False)
    assert shape[1, 1] == pytest.approx(1.5) and np.all((shape >= config.range_min) & (shape <= config.range_max))
    assert not np.allclose(lidar.ranges(), shape)  # the scan message's ranges do carry the noise
