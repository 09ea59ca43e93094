"""libgazebo_ros_velodyne_laser.so / _gpu_laser.so: tags as GazeboRosVelodyneLaser::Load (velodyne_gazebo_plugins
1.0.12) reads them, a VLP-16's rays as Gazebo's MultiRayShape casts them (C kernel and numpy alike), and the cloud
as OnScan lays it out."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from conftest import TurtleSim
from workspace_testing.timing import assert_within, best_seconds

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.sensors.config import read_sdf_sensors
from turtle_sim_ode.sensors.lidar import MultiBeamLidar, grid_angles
from turtle_sim_ode.sensors.plugins.velodyne import POINT, VelodyneCloud, VelodyneConfig
from turtle_sim_ode.world.simulation import Simulation

# A VLP-16 as velodyne_description's VLP-16.urdf.xacro writes it (16 lasers, +-15 deg, range 0.3 .. 131 m), on a
# static post 1 m above the ground.
VLP16_SDF = """<sdf version="1.6"><model name="post"><static>true</static><link name="velodyne">
  <pose>0 0 1.0 0 0 0</pose>
  <collision name="c"><geometry><cylinder><radius>0.05</radius><length>0.07</length></cylinder></geometry></collision>
  <sensor type="{kind}" name="velodyne-VLP16"><pose>0 0 0 0 0 0</pose><update_rate>10</update_rate>
    <ray><scan>
      <horizontal><samples>{samples}</samples><resolution>1</resolution><min_angle>-3.14159265</min_angle>
        <max_angle>3.14159265</max_angle></horizontal>
      <vertical><samples>16</samples><resolution>1</resolution><min_angle>-0.2617993877991494</min_angle>
        <max_angle>0.2617993877991494</max_angle></vertical></scan>
      <range><min>0.3</min><max>131</max><resolution>0.001</resolution></range>
      <noise><type>gaussian</type><mean>0.0</mean><stddev>0.0</stddev></noise></ray>
    <plugin name="gazebo_ros_laser_controller" filename="{filename}">
      <topicName>/velodyne_points</topicName><frameName>velodyne</frameName>{extra}
      <min_range>0.9</min_range><max_range>130.0</max_range><gaussianNoise>0.0</gaussianNoise></plugin>
  </sensor></link></model></sdf>"""
PILLAR_SDF = """<sdf version="1.6"><model name="pillar"><static>true</static><link name="link">
  <collision name="c"><geometry><cylinder><radius>1.0</radius><length>4</length></cylinder></geometry></collision>
  </link></model></sdf>"""
LASER = "libgazebo_ros_velodyne_laser.so"


def vlp16(samples: int = 1800, kind: str = "ray", filename: str = LASER, extra: str = "") -> str:
    return VLP16_SDF.format(samples=samples, kind=kind, filename=filename, extra=extra)


def test_tags_and_defaults() -> None:
    (config,) = read_sdf_sensors(vlp16()).configs
    assert isinstance(config, VelodyneConfig)
    assert (config.samples, config.vertical_samples, config.range_min, config.range_max) == (1800, 16, 0.3, 131)
    assert (config.topic, config.frame, config.min_range, config.max_range) == (
        "/velodyne_points",
        "velodyne",
        0.9,
        130,
    )
    assert config.update_rate == 10 and not config.organize_cloud
    bare = vlp16().replace("<topicName>/velodyne_points</topicName><frameName>velodyne</frameName>", "")
    bare = bare.replace("<min_range>0.9</min_range><max_range>130.0</max_range><gaussianNoise>0.0</gaussianNoise>", "")
    (config,) = read_sdf_sensors(bare).configs
    # Load's defaults: /points, frame /world, min_range 0, max_range infinity, no noise; no robotNamespace: the
    # spawn's (gazebo_ros adds it to a plugin without one; Load's own default "/" is the same root).
    assert (config.topic, config.frame, config.min_range, config.max_range) == ("/points", "/world", 0.0, math.inf)
    assert (config.gaussian_noise, config.robot_namespace) == (0.0, None)


def test_the_gpu_plugin_needs_a_gpu_ray_sensor() -> None:
    (config,) = read_sdf_sensors(vlp16(kind="gpu_ray", filename="libgazebo_ros_velodyne_gpu_laser.so")).configs
    assert isinstance(config, VelodyneConfig)
    blocks = read_sdf_sensors(vlp16(kind="ray", filename="libgazebo_ros_velodyne_gpu_laser.so"))
    assert not blocks.configs and list(blocks.unsupported) == [
        "libgazebo_ros_velodyne_gpu_laser.so (sensor 'velodyne-VLP16')"
    ]


def test_bad_tags_are_named() -> None:
    with pytest.raises(ModelError, match="<organize_cloud> must be true or false"):
        read_sdf_sensors(vlp16(extra="<organize_cloud>maybe</organize_cloud>"))
    with pytest.raises(ModelError, match="more than 300000"):
        read_sdf_sensors(vlp16(samples=20000))


def scanner(samples: int = 1800, kernel: bool = True, extra: str = "") -> tuple:
    sim = Simulation()
    sim.spawn_sdf("post", vlp16(samples, extra=extra))
    sim.spawn_sdf("pillar", PILLAR_SDF, (3.0, 1.0, 2.0, 0, 0, 0))
    (config,) = sim.plugins["post"].configs
    lidar = MultiBeamLidar(sim.physics, sim.models["post"], config, ray_kernel=kernel)
    return lidar, VelodyneCloud(config, lidar.directions, np.random.default_rng(1))


def test_points_lie_on_the_pillar_and_the_ground() -> None:
    """The pillar's axis is at (3, 1) in the world, the sensor at (0, 0, 1): every point off the ground is 1.0 m
    from the axis (+- 2 cm); every point below the sensor's plane that misses the pillar is on the ground."""
    lidar, cloud = scanner()
    assert lidar.uses_ray_kernel, "libturtle_sim_ode_rays.so not found: run scripts/build.sh"
    points, height, width, dense = cloud.points(lidar.ranges())
    assert height == 1 and width == len(points) and dense
    xyz = np.stack((points["x"], points["y"], points["z"]), axis=1).astype(float)
    world = xyz + (0.0, 0.0, 1.0)
    on_ground = np.abs(world[:, 2]) < 0.02
    off_axis = np.hypot(world[:, 0] - 3.0, world[:, 1] - 1.0)
    assert np.all(np.abs(off_axis[~on_ground] - 1.0) < 0.02)
    assert (~on_ground).sum() > 100 and on_ground.sum() > 1000
    # Rings: j from the lowest laser up (Gazebo > 2), x = r cos p cos y etc.
    assert set(np.unique(points["ring"])) <= set(range(16)) and np.all(points["time"] == 0)
    elevation = np.arctan2(xyz[:, 2], np.hypot(xyz[:, 0], xyz[:, 1]))
    expected = -math.radians(15) + points["ring"] * math.radians(2)
    assert np.allclose(elevation, expected, atol=1e-4)
    # The plugin's band: nothing at or within min_range 0.9, nor past max_range 130.
    assert np.all(np.linalg.norm(xyz, axis=1) > 0.9)


def test_numpy_rays_agree_with_the_kernel() -> None:
    fast, _ = scanner(samples=180)
    slow, _ = scanner(samples=180, kernel=False)
    assert np.allclose(fast.ranges(), slow.ranges(), atol=1e-6)


def test_organised_cloud_keeps_every_ray() -> None:
    lidar, cloud = scanner(samples=360, extra="<organize_cloud>true</organize_cloud>")
    points, height, width, dense = cloud.points(lidar.ranges())
    assert (height, width, dense) == (360, 16, False) and points.shape == (360, 16)
    assert np.all(points["ring"] == np.arange(16)) and np.isnan(points["x"]).any()


def test_a_vlp16_scan_costs_about_the_turtlebot_steps_between_two_scans() -> None:
    """16 x 1800 rays at 10 Hz: a scan (rays and cloud) costs about what the 100 physics steps of a TurtleBot between
    two scans cost (1.5 x here), both timed in this run: a VLP-16 on a robot keeps a good part of its rate."""
    lidar, cloud = scanner()
    scan = best_seconds(lambda: cloud.points(lidar.ranges()), 5)
    turtlebot = TurtleSim()
    assert_within(scan, best_seconds(lambda: [turtlebot.sim.step() for _ in range(100)], 5), 4, "a VLP-16 scan")


def onscan_reference(config: VelodyneConfig, directions: np.ndarray, ranges: np.ndarray, rng) -> bytes:
    """The cloud point by point, azimuth by azimuth and ring by ring as OnScan loops: the noise drawn for every ray
    (rng.normal in that order); unorganised, a point where both the noisy and the measured range are within the band;
    organised (organize_cloud), every ray, NaN where the noisy range is out of the band."""
    rings, azimuths = ranges.shape
    noise = rng.normal(0.0, config.gaussian_noise, (azimuths, rings)) if config.gaussian_noise else None
    low, high = max(config.min_range, config.range_min), min(config.max_range, config.range_max)
    cloud = []
    for i in range(azimuths):
        for j in range(rings):
            measured = ranges[j, i]
            noisy = measured + noise[i, j] if noise is not None else measured
            x, y, z = (noisy * directions[j, i, axis] for axis in range(3))
            if config.organize_cloud:
                cloud.append((x, y, z, 0.0, j, 0.0) if low < noisy < high else (math.nan,) * 4 + (j, 0.0))
            elif low < noisy < high and low < measured < high and 0.0 >= config.min_intensity:
                cloud.append((x, y, z, 0.0, j, 0.0))
    return np.array(cloud, dtype=POINT).tobytes()


@settings(max_examples=25, deadline=None)
@given(
    grid=st.tuples(st.integers(1, 40), st.integers(1, 8)),
    noise=st.sampled_from([0.0, 0.008, 2.0]),
    band=st.tuples(st.floats(0.0, 10.0), st.floats(5.0, 200.0)),
    seed=st.integers(0, 2**32 - 1),
    kernel=st.booleans(),
    organised=st.booleans(),
)
def test_the_cloud_is_onscan_point_for_point(grid, noise, band, seed, kernel, organised) -> None:
    """VelodyneCloud.points (issue #33: in C, tso_velodyne_cloud; in numpy, scratch reused, noise drawn into it,
    points picked by index) against OnScan's loop written out: the same bytes, scan after scan, and the generator
    left where rng.normal leaves it."""
    samples, rings = grid
    (config,) = read_sdf_sensors(vlp16(samples)).configs
    config = replace(config, vertical_samples=rings, min_range=band[0], max_range=band[1], gaussian_noise=noise)
    config = replace(config, organize_cloud=organised)
    pitch, yaw = np.meshgrid(
        grid_angles(rings, config.vertical_min_angle, config.vertical_max_angle),
        grid_angles(samples, config.min_angle, config.max_angle),
        indexing="ij",
    )
    directions = np.stack((np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), np.sin(pitch)), axis=-1)
    cloud = VelodyneCloud(config, directions, np.random.default_rng(seed), kernel=kernel)
    assert kernel == (cloud._lib is not None), "libturtle_sim_ode_rays.so not found: run scripts/build.sh"
    reference_rng, ranges_rng = np.random.default_rng(seed), np.random.default_rng(seed + 1)
    for _ in range(3):
        ranges = ranges_rng.uniform(0.0, 140.0, (rings, samples))
        ranges[ranges_rng.random(ranges.shape) < 0.2] = config.range_max  # rays that hit nothing
        points, height, width, dense = cloud.points(ranges)
        assert points.tobytes() == onscan_reference(config, directions, ranges, reference_rng)
        assert (height, width, dense) == ((samples, rings, False) if organised else (1, len(points), True))
    assert cloud._rng.random() == reference_rng.random()
