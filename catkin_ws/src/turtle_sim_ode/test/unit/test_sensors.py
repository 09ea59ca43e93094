"""Laser, IMU, bumper and cliff sensors on the TurtleBot in a Simulation (no ROS)."""
from __future__ import annotations

import dataclasses
import math
import random
import re
import statistics
from typing import List, Tuple

import pytest
from conftest import PACKAGE_ROOT, TURTLEBOT_URDF, TurtleSim
from workspace_testing.timing import assert_within, best_seconds

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.sensors import laser as sensors
from turtle_sim_ode.sensors.config import LaserConfig, read_sdf_sensors, read_sensors
from turtle_sim_ode.sensors.imu import ImuSensor
from turtle_sim_ode.sensors.kobuki import (
    CENTER,
    CLIFF,
    FLOOR,
    LEFT,
    PRESSED,
    RELEASED,
    RIGHT,
    BumperSensor,
    CliffSensor,
    bumper_of,
)
from turtle_sim_ode.sensors.laser import LaserScanner
from turtle_sim_ode.world.simulation import Simulation

BOX_URDF = (PACKAGE_ROOT / "test" / "models" / "box.urdf").read_text()  # 0.2 m cube, 1 kg
LASER_BLOCK = """
  <gazebo reference="base_scan">
    <sensor type="ray" name="lds_lfcd_sensor">
      <update_rate>5</update_rate>
      <ray>
        <scan><horizontal>
          <samples>360</samples><resolution>1</resolution><min_angle>0.0</min_angle><max_angle>6.28319</max_angle>
        </horizontal></scan>
        <range><min>0.120</min><max>3.5</max><resolution>0.015</resolution></range>
        <noise><type>gaussian</type><mean>0.0</mean><stddev>0.01</stddev></noise>
      </ray>
      <plugin name="gazebo_ros_lds_lfcd_controller" filename="libgazebo_ros_laser.so">
        <topicName>/scan</topicName>
        <frameName>base_scan</frameName>
      </plugin>
    </sensor>
  </gazebo>
"""
# The shipped TurtleBot has a laser of its own; these tests put theirs in its place.
BARE_URDF = re.sub(r'\s*<gazebo reference="base_scan">.*?</gazebo>', "", TURTLEBOT_URDF, flags=re.S)
LASER_URDF = BARE_URDF.replace("</robot>", LASER_BLOCK + "</robot>")
SCAN_HEIGHT = 0.0102 + 0.12  # base_scan above the ground when the robot rests


def static_box(sim: Simulation, name: str, size: Tuple[float, float, float], xyz: Tuple[float, float, float]) -> None:
    sdf = f"""<sdf version="1.6"><model name="{name}"><static>true</static><link name="link">
      <collision name="collision"><geometry><box><size>{size[0]} {size[1]} {size[2]}</size></box></geometry></collision>
      </link></model></sdf>"""
    sim.spawn_sdf(name, sdf, (xyz[0], xyz[1], xyz[2], 0.0, 0.0, 0.0))


def laser_config(**changes: object) -> LaserConfig:
    fields = {"noise_stddev": 0.0}
    fields.update(changes)
    return dataclasses.replace(read_sensors(LASER_URDF).lasers[0], **fields)


def beam(config: LaserConfig, angle: float) -> int:
    return round((angle - config.min_angle) / config.angle_increment) % config.samples


@pytest.fixture(scope="module")
def resting() -> TurtleSim:
    """A TurtleBot settled at the origin (read-only for the tests that share it)."""
    sim = TurtleSim()
    sim.settle()
    return sim


# --- laser configuration ---------------------------------------------------------------------
def test_read_sensors_lasers_takes_gazebo_sensor_tags() -> None:
    (config,) = read_sensors(LASER_URDF).lasers
    assert config.link == "base_scan" and config.name == "lds_lfcd_sensor"
    assert config.samples == 360 and config.min_angle == 0.0 and config.max_angle == pytest.approx(6.28319)
    assert (config.range_min, config.range_max, config.range_resolution) == (0.12, 3.5, 0.015)
    assert config.update_rate == 5.0 and config.noise_stddev == 0.01
    assert (config.topic, config.frame) == ("/scan", "base_scan")
    assert config.angle_increment == pytest.approx(6.28319 / 359)
    assert read_sensors(BARE_URDF).lasers == []


def test_shipped_turtlebot_has_the_issue_laser() -> None:
    (config,) = read_sensors(TURTLEBOT_URDF).lasers
    assert (config.link, config.frame, config.topic) == ("base_scan", "base_scan", "scan")
    assert (config.samples, config.range_min, config.range_max, config.update_rate) == (360, 0.12, 3.5, 10.0)


@pytest.mark.parametrize(
    "old, new, message",
    [
        ("<samples>360</samples>", "<samples>many</samples>", "integer"),
        ("<max>3.5</max>", "<max>0.1</max>", "range min < range max"),
        ('reference="base_scan"', 'reference="nowhere"', "reference"),
        ("<stddev>0.01</stddev>", "<stddev>-1</stddev>", "noise_stddev"),
    ],
)
def test_read_sensors_lasers_rejects_bad_values(old: str, new: str, message: str) -> None:
    with pytest.raises(ModelError, match=message):
        read_sensors(LASER_URDF.replace(old, new))


def test_ray_sensor_plugin_and_no_plugin() -> None:
    ray_sensor = LASER_URDF.replace("libgazebo_ros_laser.so", "libgazebo_ros_ray_sensor.so")
    assert read_sensors(ray_sensor).lasers[0].topic == "/scan"
    no_plugin = LASER_URDF.replace("libgazebo_ros_laser.so", "libother.so")
    assert read_sensors(no_plugin).lasers[0].topic == ""


# --- laser scans ----------------------------------------------------------------------------
def test_scan_measures_a_box_within_a_centimetre() -> None:
    sim = TurtleSim()
    sim.sim.spawn_urdf("front_box", BOX_URDF, (1.0, 0.0, 0.1, 0.0, 0.0, 0.0))
    static_box(sim.sim, "left_box", (0.2, 0.2, 0.4), (0.0, 1.5, 0.2))
    sim.settle()
    config = laser_config()
    ranges = LaserScanner(sim.physics, sim.model, "base_scan", config).scan()
    assert len(ranges) == 360
    (x, y, _), _ = sim.model.link_pose("base_scan")
    assert ranges[beam(config, 0.0)] == pytest.approx(0.9 - x, abs=0.01)
    assert ranges[beam(config, math.pi / 2)] == pytest.approx(1.4 - y, abs=0.01)
    # Beams between the two boxes, and behind the robot, reach nothing within 3.5 m.
    for angle in (math.radians(45), math.pi, math.radians(270)):
        assert ranges[beam(config, angle)] == math.inf
    assert all(r == math.inf or 0.12 <= r <= 3.5 for r in ranges)


def test_beams_past_range_max_read_inf_and_too_close_read_minus_inf() -> None:
    sim = TurtleSim()
    static_box(sim.sim, "far", (0.2, 4.0, 0.5), (4.0, 0.0, 0.25))  # face at 3.9 m > range_max
    sim.settle()
    config = laser_config()
    assert set(LaserScanner(sim.physics, sim.model, "base_scan", config).scan()) == {math.inf}
    # A box 5 cm in front of a laser raised above the robot: closer than range_min.
    static_box(sim.sim, "near", (0.1, 0.1, 0.1), (0.1, 0.0, 0.5))
    raised = laser_config(pose=(0.0, 0.0, 0.5 - SCAN_HEIGHT, 0.0, 0.0, 0.0))
    ranges = LaserScanner(sim.physics, sim.model, "base_scan", raised).scan()
    assert ranges[beam(raised, 0.0)] == -math.inf
    assert ranges[beam(raised, math.pi)] == math.inf


def test_own_body_is_not_seen_but_another_robot_is() -> None:
    sim = TurtleSim()
    sim.sim.spawn_urdf("other", LASER_URDF, (1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    sim.settle()
    # Scan plane 5 cm above the ground: through both robots' base cylinders (r 0.178 m).
    low = laser_config(pose=(0.0, 0.0, 0.05 - SCAN_HEIGHT, 0.0, 0.0, 0.0))
    ranges = LaserScanner(sim.physics, sim.model, "base_scan", low).scan()
    (x, _, _), _ = sim.model.link_pose("base_scan")
    (other_x, _, _), _ = sim.sim.models["other"].link_pose("base_footprint")
    assert ranges[beam(low, 0.0)] == pytest.approx(other_x - 0.178 - x, abs=0.01)
    assert ranges[beam(low, math.pi)] == math.inf  # not its own cylinder, wheels or casters
    assert ranges[beam(low, math.pi / 2)] == math.inf
    # And the other robot does not see itself but sees this one.
    other = sim.sim.models["other"]
    back = LaserScanner(sim.physics, other, "base_scan", low).scan()
    assert back[beam(low, math.pi)] == pytest.approx(other_x - 0.178 - x, abs=0.01)
    assert back[beam(low, 0.0)] == math.inf


def test_models_out_of_reach_are_skipped_whole(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = TurtleSim()
    sim.sim.spawn_urdf("near", LASER_URDF, (1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    sim.sim.spawn_urdf("far", LASER_URDF, (9.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    sim.settle()
    near = {geom for geoms in sim.sim.models["near"].geoms.values() for geom in geoms}
    far = {geom for geoms in sim.sim.models["far"].geoms.values() for geom in geoms}
    tested: List[object] = []
    world_geoms = sensors.world_geoms

    def recording(*args):  # type: ignore[no-untyped-def]
        for geom in world_geoms(*args):
            tested.append(geom)
            yield geom

    monkeypatch.setattr(sensors, "world_geoms", recording)
    # Level (AABB footprint culling) and tilted (bounding spheres): the near robot is seen, the far one never tested.
    for pitch in (0.0, 0.02):
        config = laser_config(pose=(0.0, 0.0, 0.05 - SCAN_HEIGHT, 0.0, pitch, 0.0))
        tested.clear()
        assert math.isfinite(LaserScanner(sim.physics, sim.model, "base_scan", config).scan()[beam(config, 0.0)])
        assert near <= set(tested)
        assert not far & set(tested)


def test_noise_has_the_configured_stddev() -> None:
    sim = TurtleSim()
    static_box(sim.sim, "wall", (0.2, 3.0, 0.5), (1.1, 0.0, 0.25))
    sim.settle()
    config = laser_config(noise_stddev=0.01)
    exact = LaserScanner(sim.physics, sim.model, "base_scan", laser_config()).scan()
    scanner = LaserScanner(sim.physics, sim.model, "base_scan", config, rng=random.Random(7))
    errors: List[float] = []
    for _ in range(20):
        for noisy, true in zip(scanner.scan(), exact):
            if math.isfinite(true):
                errors.append(noisy - true)
    assert len(errors) > 1000
    assert statistics.mean(errors) == pytest.approx(0.0, abs=0.002)
    assert statistics.pstdev(errors) == pytest.approx(0.01, rel=0.15)


def test_rays_make_no_contacts_and_leave_the_step_alone() -> None:
    sim = TurtleSim()
    static_box(sim.sim, "wall", (0.2, 3.0, 0.5), (1.1, 0.0, 0.25))
    sim.settle()
    before = sim.physics.space.getNumGeoms()
    scanner = LaserScanner(sim.physics, sim.model, "base_scan", laser_config())
    cliff = CliffSensor(sim.physics, sim.model)
    scanner.scan()
    cliff.distances()
    sim.run(0.01)
    contacts = sim.physics.contact_count
    assert sim.physics.space.getNumGeoms() == before
    scanner.scan()
    sim.run(0.01)
    assert sim.physics.contact_count == contacts


def test_scan_cost() -> None:
    """A 360-beam scan among walls on every side costs under half the 200 steps between two scans at 5 Hz (about a
    quarter here): both timed in this run."""
    sim = TurtleSim()
    for name, size, xyz in (
        ("north", (0.2, 4.0, 0.5), (1.5, 0.0, 0.25)),
        ("south", (0.2, 4.0, 0.5), (-1.5, 0.0, 0.25)),
        ("east", (4.0, 0.2, 0.5), (0.0, 1.5, 0.25)),
        ("west", (4.0, 0.2, 0.5), (0.0, -1.5, 0.25)),
    ):
        static_box(sim.sim, name, size, xyz)
    sim.sim.spawn_urdf("box", BOX_URDF, (0.7, 0.7, 0.1, 0.0, 0.0, 0.0))
    sim.settle()
    scanner = LaserScanner(sim.physics, sim.model, "base_scan", laser_config())
    assert all(math.isfinite(r) for r in scanner.scan())
    # Windows of about the same length, the best of five each: a busy machine slows the best of both alike.
    scan = best_seconds(lambda: [scanner.scan() for _ in range(20)], 5) / 20
    step = best_seconds(lambda: [sim.sim.step() for _ in range(1000)], 5) / 1000
    print(f"360-beam scan, walls all around: {scan * 1e6:.0f} us, {scan / step:.0f} steps")
    assert_within(scan, step, 100, "a 360-beam scan")


# --- IMU ------------------------------------------------------------------------------------
def test_imu_at_rest_feels_gravity_up(resting: TurtleSim) -> None:
    imu = ImuSensor(resting.model, "imu_link", resting.physics.params.gravity)
    for _ in range(5):
        resting.run(0.02)
        reading = imu.read(resting.physics.sim_time)
    ax, ay, az = reading.linear_acceleration
    assert az == pytest.approx(9.81, rel=0.01)
    assert abs(ax) < 0.05 and abs(ay) < 0.05
    assert all(abs(w) < 1e-3 for w in reading.angular_velocity)
    x, y, z, w = reading.orientation
    assert abs(w) == pytest.approx(1.0, abs=1e-4)
    assert len(reading.orientation_covariance) == 9 and len(reading.linear_acceleration_covariance) == 9


def test_imu_yaw_rate_matches_a_commanded_spin() -> None:
    sim = TurtleSim()
    sim.settle()
    imu = ImuSensor(sim.model, "imu_link", sim.physics.params.gravity)
    sim.run(2.0, (0.0, 1.0))
    rates = []
    for _ in range(25):
        sim.run(0.02, (0.0, 1.0))
        rates.append(imu.read(sim.physics.sim_time).angular_velocity[2])
    assert statistics.mean(rates) == pytest.approx(1.0, rel=0.02)
    # The link spins about its own z: no roll or pitch rate, gravity still up.
    reading = imu.read(sim.physics.sim_time + 1e-9)
    assert abs(reading.angular_velocity[0]) < 0.02 and abs(reading.angular_velocity[1]) < 0.02


def test_imu_noise_sets_covariances() -> None:
    from turtle_sim_ode.sensors.config import ImuNoise

    sim = TurtleSim()
    imu = ImuSensor(sim.model, "imu_link", noise=ImuNoise(0.01, 0.02, 0.1), rng=random.Random(1))
    reading = imu.read(0.0)
    assert reading.orientation_covariance[0] == pytest.approx(1e-4)
    assert reading.angular_velocity_covariance[4] == pytest.approx(4e-4)
    assert reading.linear_acceleration_covariance[8] == pytest.approx(0.01)
    assert reading.linear_acceleration_covariance[1] == 0.0


# --- bumper ---------------------------------------------------------------------------------
def test_bumper_sectors() -> None:
    assert bumper_of(0.0) == CENTER and bumper_of(math.radians(29)) == CENTER
    assert bumper_of(math.radians(31)) == LEFT and bumper_of(math.radians(90)) == LEFT
    assert bumper_of(math.radians(-31)) == RIGHT and bumper_of(math.radians(-90)) == RIGHT
    assert bumper_of(math.pi) is None and bumper_of(math.radians(100)) is None
    assert bumper_of(math.radians(360 + 45)) == LEFT


def test_bumper_presses_against_a_wall_and_releases() -> None:
    sim = TurtleSim()
    static_box(sim.sim, "wall", (0.1, 2.0, 0.5), (0.55, 0.0, 0.25))  # face at x = 0.5
    sim.settle()
    bumper = BumperSensor(sim.physics, sim.model)
    events: List[Tuple[float, int, int]] = []

    def drive(seconds: float, command: Tuple[float, float]) -> None:
        for _ in range(round(seconds / 0.01)):
            sim.run(0.01, command)
            events.extend((sim.physics.sim_time, b, s) for b, s in bumper.changes())

    drive(0.5, (0.0, 0.0))
    assert events == []  # resting on the ground presses nothing
    drive(2.5, (0.2, 0.0))
    assert [(b, s) for _, b, s in events] == [(CENTER, PRESSED)]
    assert bumper.pressed() == [False, True, False]
    drive(1.0, (-0.2, 0.0))
    assert [(b, s) for _, b, s in events] == [(CENTER, PRESSED), (CENTER, RELEASED)]
    bumper.close()
    assert bumper.pressed() == [False, False, False]


def test_contact_watch_records_and_unwatches() -> None:
    sim = TurtleSim()
    sim.settle()
    wheel = sim.model.geoms["wheel_left_link"]
    watch = sim.physics.watch_contacts(wheel)
    sim.run(0.001)
    assert watch.contacts and all(c.geom is wheel[0] and c.other is sim.physics.ground for c in watch.contacts)
    assert all(c.normal[2] > 0.99 for c in watch.contacts)  # pushes the wheel up, out of the ground
    sim.physics.unwatch_contacts(watch)
    sim.physics.unwatch_contacts(watch)  # twice is fine
    assert not sim.physics._watched and not sim.physics._watches


# --- cliff ----------------------------------------------------------------------------------
def test_no_cliff_at_rest(resting: TurtleSim) -> None:
    cliff = CliffSensor(resting.physics, resting.model)
    distances = cliff.distances()
    assert distances == pytest.approx([0.0316] * 3, abs=0.002)
    assert cliff.changes() == []


def test_cliff_when_lifted_and_floor_when_back() -> None:
    sim = TurtleSim()
    sim.settle()
    cliff = CliffSensor(sim.physics, sim.model)
    assert cliff.changes() == []
    sim.model.set_pose(0.0, 0.0, 0.1)
    lifted = cliff.changes()
    assert [(sensor, state) for sensor, state, _ in lifted] == [(LEFT, CLIFF), (CENTER, CLIFF), (RIGHT, CLIFF)]
    assert [distance for _, _, distance in lifted] == pytest.approx([0.1316] * 3, abs=0.003)
    assert cliff.changes() == []
    sim.model.set_pose(0.0, 0.0, 0.0)
    sim.settle()
    back = cliff.changes()
    assert [(sensor, state) for sensor, state, _ in back] == [(LEFT, FLOOR), (CENTER, FLOOR), (RIGHT, FLOOR)]


def test_front_cliff_over_the_edge_of_a_platform() -> None:
    sim = TurtleSim(z=0.05)
    static_box(sim.sim, "platform", (2.0, 2.0, 0.05), (-0.87, 0.0, 0.025))  # top at z 0.05, edge at x 0.13
    sim.settle()
    cliff = CliffSensor(sim.physics, sim.model)
    left, front, right = cliff.distances()
    assert left == pytest.approx(0.0316, abs=0.003) and right == pytest.approx(0.0316, abs=0.003)
    assert front == pytest.approx(0.0816, abs=0.003)  # down to the ground beyond the edge
    assert cliff.changes() == [(CENTER, CLIFF, front)]


def test_tilted_laser_sees_the_ground_and_boxes() -> None:
    sim = TurtleSim()
    sim.sim.spawn_urdf("front_box", BOX_URDF, (1.0, 0.0, 0.1, 0.0, 0.0, 0.0))
    sim.settle()
    (x, _, z), _ = sim.model.link_pose("base_scan")
    down = laser_config(pose=(0.0, 0.0, 0.0, 0.0, 0.3, 0.0))  # pitched 0.3 rad down
    ranges = LaserScanner(sim.physics, sim.model, "base_scan", down).scan()
    assert ranges[beam(down, 0.0)] == pytest.approx(z / math.sin(0.3), abs=0.005)
    assert ranges[beam(down, math.pi)] == math.inf  # looks up behind the robot
    slight = laser_config(pose=(0.0, 0.0, 0.0, 0.0, 0.02, 0.0))  # above the "level" tolerance
    ranges = LaserScanner(sim.physics, sim.model, "base_scan", slight).scan()
    assert ranges[beam(slight, 0.0)] == pytest.approx((0.9 - x) / math.cos(0.02), abs=0.01)


# --- IMU and contact sensor tags ------------------------------------------------------------------
SENSOR_BLOCKS = """
  <gazebo reference="imu_link">
    <sensor type="imu" name="imu">
      <update_rate>100</update_rate>
      <plugin name="imu_sensor" filename="libgazebo_ros_imu_sensor.so">
        <topicName>imu/data</topicName><frameName>imu_frame</frameName><gaussianNoise>0.002</gaussianNoise>
      </plugin>
    </sensor>
  </gazebo>
  <gazebo reference="base_link">
    <sensor type="contact" name="bumper">
      <update_rate>25</update_rate>
      <contact><collision>base_link_collision</collision></contact>
      <plugin name="bumper_plugin" filename="libgazebo_ros_bumper.so">
        <bumperTopicName>base_bumper</bumperTopicName><frameName>base_link</frameName>
      </plugin>
    </sensor>
    <sensor type="contact" name="no_ros"><contact><collision>base_link_collision</collision></contact></sensor>
  </gazebo>
"""


def test_read_sensors_imu_and_contact_tags() -> None:
    blocks = read_sensors(BARE_URDF.replace("</robot>", SENSOR_BLOCKS + "</robot>"))
    (imu,) = blocks.imus
    assert (imu.link, imu.topic, imu.frame, imu.update_rate) == ("imu_link", "imu/data", "imu_frame", 100.0)
    assert imu.noise.angular_velocity == imu.noise.linear_acceleration == 0.002
    (contact,) = blocks.contacts  # the sensor without a ROS plugin publishes nothing
    assert (contact.link, contact.name, contact.collisions) == ("base_link", "bumper", ("base_link_collision",))
    assert (contact.topic, contact.frame, contact.update_rate) == ("base_bumper", "base_link", 25.0)


def test_read_sensors_rejects_bad_imu_rate() -> None:
    bad = SENSOR_BLOCKS.replace("<update_rate>100</update_rate>", "<update_rate>-1</update_rate>")
    with pytest.raises(ModelError, match="<update_rate> must be >= 0"):
        read_sensors(BARE_URDF.replace("</robot>", bad + "</robot>"))


SENSOR_SDF = """<sdf version="1.6"><model name="sensor_post"><static>true</static>
  <link name="post">
    <collision name="collision"><geometry><box><size>0.1 0.1 0.4</size></box></geometry></collision>
    <sensor type="ray" name="post_laser">
      <pose>0 0 0.25 0 0 0</pose>
      <update_rate>5</update_rate>
      <ray><scan><horizontal><samples>4</samples><min_angle>0</min_angle><max_angle>4.71239</max_angle>
      </horizontal></scan><range><min>0.06</min><max>5.0</max></range></ray>
      <plugin name="laser" filename="libgazebo_ros_ray_sensor.so"><topicName>post_scan</topicName>
        <frameName>post</frameName></plugin>
    </sensor>
    <sensor type="contact" name="post_bumper"><contact><collision>collision</collision></contact>
      <plugin name="bumper" filename="libgazebo_ros_bumper.so"><bumperTopicName>post_contacts</bumperTopicName></plugin>
    </sensor>
  </link>
</model></sdf>"""


def test_sdf_model_sensors_are_read_and_scan() -> None:
    blocks = read_sdf_sensors(SENSOR_SDF)
    (laser,) = blocks.lasers
    assert (laser.link, laser.topic, laser.samples, laser.update_rate) == ("post", "post_scan", 4, 5.0)
    assert [(c.link, c.topic) for c in blocks.contacts] == [("post", "post_contacts")]
    sim = Simulation()
    sim.spawn_sdf("post", SENSOR_SDF, (0, 0, 0.2, 0, 0, 0))
    static_box(sim, "target", (0.2, 0.2, 0.6), (1.1, 0.0, 0.3))
    assert sim.plugins["post"].lasers == [laser] and sim.plugins["post"].contacts == blocks.contacts
    ranges = LaserScanner(sim.physics, sim.models["post"], "post", laser).scan()
    assert ranges[0] == pytest.approx(1.0, abs=0.01)  # the target's near face, 1 m ahead of the post's centre
    assert all(math.isinf(r) for r in ranges[1:])


def test_sdf_sensor_errors_name_the_sensor() -> None:
    with pytest.raises(ModelError, match="post_laser"):
        read_sdf_sensors(SENSOR_SDF.replace("<samples>4</samples>", "<samples>four</samples>"))
    with pytest.raises(ModelError, match="XML guard"):
        read_sdf_sensors('<!DOCTYPE m [<!ENTITY e "x">]><model name="m">&e;</model>')
