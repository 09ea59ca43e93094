"""smb_gazebo's OdometrySource (``libodometry_source_plugin.so``; ETHZ-RobotX/smb_common, smb_gazebo/src/
OdometrySource.cpp): its tags as OdometrySource::Load reads them (defaults from include/smb_gazebo/
OdometrySource.hpp), and OdometrySource::UpdateChild's per-step behaviour: the wait for the link to rest (a check
each second of sim time, both speeds against maxAngularSpeedBeforeSettle), the odometry frame at the rested link's
position and heading, the rate control, the pose relative to that frame with the offsets, and the twist as upstream
turns it (the world velocities turned by the frame's heading, then into the link's axes relative to the frame)."""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.transforms import quat_from_rpy, quat_multiply, quat_rotate, rpy_of
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.odometry_source import ODOMETRY_SOURCE, OdometrySource, OdometrySourceConfig
from world_helpers import floating

# The tags as smb_description's smb_odometry.gazebo.xacro writes them for the tracking camera (realsense_t265)
T265_TAGS = {
    "robotNamespace": "smb",
    "bodyName": "tracking_camera_link",
    "topicName": "/tracking_camera/odom/sample",
    "odomFrame": "tracking_camera_odom_frame",
    "childOdomFrame": "tracking_camera_pose_frame",
    "publishTf": "false",
    "xyzOffset": "0 0 0",
    "rpyOffset": "0 0 0",
    "gaussianNoise": "0",
    "updateRate": "200",
    "maxLinearSpeedBeforeSettle": "0.01",
    "maxAngularSpeedBeforeSettle": "0.05",
}
STEP = 0.001
REST = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def read(tags):
    (config,) = read_plugins("smb", [GazeboPlugin(ODOMETRY_SOURCE, "smb_odometry_plugin", tags)], {}, []).configs
    return config


def test_the_course_tags_are_read():
    config = read(T265_TAGS)
    assert (config.body, config.topic) == ("tracking_camera_link", "/tracking_camera/odom/sample")
    assert (config.odom_frame, config.child_frame) == ("tracking_camera_odom_frame", "tracking_camera_pose_frame")
    assert config.publish_tf is False and config.update_rate == 200.0 and config.gaussian_noise == 0.0
    assert (config.max_linear_speed_before_settle, config.max_angular_speed_before_settle) == (0.01, 0.05)
    assert config.robot_namespace == "smb"


def test_defaults_of_the_optional_tags():
    """Load: publishTf false, xyz/rpy offsets 0, gaussianNoise 0, updateRate 0; OdometrySource.hpp: the settle
    speeds 1e-3 and 1e-2."""
    required = {tag: T265_TAGS[tag] for tag in ("bodyName", "topicName", "odomFrame", "childOdomFrame")}
    config = read(required)
    assert config.publish_tf is False and config.update_rate == 0.0 and config.gaussian_noise == 0.0
    assert config.xyz_offset == (0.0, 0.0, 0.0) and config.rpy_offset == (0.0, 0.0, 0.0)
    assert (config.max_linear_speed_before_settle, config.max_angular_speed_before_settle) == (1e-3, 1e-2)
    assert config.robot_namespace is None


@pytest.mark.parametrize("tag", ["bodyName", "topicName", "odomFrame", "childOdomFrame"])
def test_a_missing_required_tag_is_named(tag):
    """Load gives up (ROS_FATAL "plugin missing <tag>") without any of these four."""
    tags = dict(T265_TAGS)
    del tags[tag]
    with pytest.raises(ModelError, match="<%s>" % tag):
        read(tags)


@pytest.mark.parametrize("tag,value", [("publishTf", "maybe"), ("updateRate", "-1"), ("xyzOffset", "1 2")])
def test_bad_values_are_refused_with_their_tag(tag, value):
    with pytest.raises(ModelError, match=tag):
        read(dict(T265_TAGS, **{tag: value}))


def run(source, start, end, state):
    """Readings of source for steps from start to end (s of sim time), (time, reading) where one is given."""
    readings = []
    for index in range(int(round((end - start) / STEP)) + 1):
        now = start + index * STEP
        reading = source.update(now, lambda: state(now))
        if reading is not None:
            readings.append((now, reading))
    return readings


def resting(position, yaw):
    return lambda now: (position, quat_from_rpy(0.0, 0.0, yaw), *REST)


def config(**changes):
    base = OdometrySourceConfig(body="l", topic="odom", odom_frame="odom", child_frame="link")
    for name, value in changes.items():
        setattr(base, name, value)
    return base


def test_a_resting_link_settles_after_one_second_and_reads_zero():
    source = OdometrySource(config())
    readings = run(source, 0.0, 1.0, resting((1.0, 2.0, 0.3), 0.5))
    assert readings == [] and source.odom_frame is None  # dt > 1.0 s first
    readings = run(source, 1.0 + STEP, 1.0 + 3 * STEP, resting((1.0, 2.0, 0.3), 0.5))
    # settled at the first step past 1 s (no reading then), read from the next step on (updateRate 0)
    assert [round(now, 6) for now, _ in readings] == [1.002, 1.003]
    origin, heading = source.odom_frame
    assert origin == (1.0, 2.0, 0.3) and rpy_of(heading)[2] == pytest.approx(0.5)
    reading = readings[0][1]
    assert reading.position == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    assert reading.orientation == pytest.approx((1.0, 0.0, 0.0, 0.0), abs=1e-12)


def test_a_moving_link_is_checked_again_each_second():
    moving_until = 2.5

    def state(now):
        speed = 0.2 if now < moving_until else 0.0
        return (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), (speed, 0.0, 0.0), (0.0, 0.0, 0.0)

    source = OdometrySource(config())
    readings = run(source, 0.0, 4.0, state)
    # checks at 1.001 (moving), 2.002 (moving), 3.003 (at rest: settled), readings from 3.004
    assert round(readings[0][0], 6) == 3.004


def test_both_speeds_are_held_to_the_angular_limit():
    """UpdateChild compares the linear speed with max_angular_speed_before_settle_ too (the linear limit is only
    logged): a link creeping at 5 mm/s settles under maxLinear 1 mm/s when maxAngular is 10 mrad/s."""
    creeping = lambda now: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), (0.005, 0.0, 0.0), (0.0, 0.0, 0.0))  # noqa: E731
    source = OdometrySource(config(max_linear_speed_before_settle=1e-3, max_angular_speed_before_settle=1e-2))
    run(source, 0.0, 1.01, creeping)
    assert source.odom_frame is not None
    source = OdometrySource(config(max_angular_speed_before_settle=1e-3))
    run(source, 0.0, 1.01, creeping)
    assert source.odom_frame is None


def test_the_update_rate_spaces_the_readings():
    source = OdometrySource(config(update_rate=200.0))
    readings = run(source, 0.0, 1.5, resting((0.0, 0.0, 0.0), 0.0))
    gaps = [round(b - a, 6) for (a, _), (b, _) in zip(readings, readings[1:])]
    assert gaps and all(gap == 0.005 for gap in gaps)


ANGLE = st.floats(-math.pi, math.pi)
COORD = st.floats(-50.0, 50.0)
SPEED = st.floats(-3.0, 3.0)
VEC = st.tuples(COORD, COORD, COORD)


@settings(max_examples=200, deadline=None)
@given(
    origin=VEC,
    heading=ANGLE,
    position=VEC,
    rpy=st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5), ANGLE),
    linear=st.tuples(SPEED, SPEED, SPEED),
    angular=st.tuples(SPEED, SPEED, SPEED),
    xyz_offset=st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-1, 1)),
    rpy_offset=st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-1, 1)),
)
def test_readings_relative_to_the_settled_frame(
    origin, heading, position, rpy, linear, angular, xyz_offset, rpy_offset
):
    """After settling at (origin, heading): the position is the link's turned back by the heading plus xyzOffset,
    the orientation rpyOffset * heading^-1 * the link's; the twist is turned (not back) by the heading, then into
    the link's axes relative to the frame, so its length is kept, and with heading 0 it is the body-axes twist."""
    source = OdometrySource(config(xyz_offset=xyz_offset, rpy_offset=rpy_offset))
    run(source, 0.0, 1.001, resting(origin, heading))
    assert source.odom_frame is not None
    orientation = quat_from_rpy(*rpy)
    reading = source.update(2.0, lambda: (position, orientation, linear, angular))
    back = quat_from_rpy(0.0, 0.0, -heading)
    relative = quat_rotate(back, tuple(p - o for p, o in zip(position, origin)))
    expected = tuple(r + x for r, x in zip(relative, xyz_offset))
    assert reading.position == pytest.approx(expected, abs=1e-9)
    rotation = quat_multiply(back, orientation)
    expected_q = quat_multiply(quat_from_rpy(*rpy_offset), rotation)
    sign = 1.0 if sum(a * b for a, b in zip(expected_q, reading.orientation)) >= 0 else -1.0
    assert tuple(sign * c for c in reading.orientation) == pytest.approx(expected_q, abs=1e-9)
    into_link = (rotation[0], -rotation[1], -rotation[2], -rotation[3])
    turned = quat_rotate(into_link, quat_rotate(quat_from_rpy(0.0, 0.0, heading), linear))
    assert reading.linear == pytest.approx(turned, abs=1e-9)
    assert math.hypot(*reading.angular) == pytest.approx(math.hypot(*angular), abs=1e-9)
    assert reading.variance == 0.0
    # the same link seen from a frame with heading 0 gives its twist in its own axes
    level = OdometrySource(config())
    run(level, 0.0, 1.001, resting(origin, 0.0))
    body = level.update(2.0, lambda: (position, orientation, linear, angular)).linear
    assert body == pytest.approx(quat_rotate((orientation[0], *(-c for c in orientation[1:])), linear), abs=1e-9)


def test_noise_goes_on_the_twist_only_and_its_variance_on_both_covariances():
    source = OdometrySource(config(gaussian_noise=0.1))
    run(source, 0.0, 1.001, resting((0.0, 0.0, 0.0), 0.0))
    reading = source.update(2.0, lambda: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), *REST))
    assert reading.position == (0.0, 0.0, 0.0) and reading.variance == pytest.approx(0.01)
    assert reading.linear != (0.0, 0.0, 0.0)


SMB_STYLE_URDF = """<robot name="rover">
  <link name="base_link">
    <inertial><mass value="10"/><inertia ixx="0.2" iyy="0.2" izz="0.2" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.6 0.4 0.2"/></geometry></collision>
  </link>
  <link name="tracking_camera_link">
    <inertial><mass value="0.05"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="camera_joint" type="fixed">
    <parent link="base_link"/><child link="tracking_camera_link"/><origin xyz="0.3 0 0.1"/>
  </joint>
  <gazebo>
    <plugin name="smb_odometry_plugin" filename="libodometry_source_plugin.so">
      <robotNamespace>smb</robotNamespace>
      <bodyName>tracking_camera_link</bodyName>
      <topicName>/tracking_camera/odom/sample</topicName>
      <odomFrame>tracking_camera_odom_frame</odomFrame>
      <childOdomFrame>tracking_camera_pose_frame</childOdomFrame>
      <publishTf>false</publishTf>
      <updateRate>200</updateRate>
      <maxLinearSpeedBeforeSettle>0.01</maxLinearSpeedBeforeSettle>
      <maxAngularSpeedBeforeSettle>0.05</maxAngularSpeedBeforeSettle>
    </plugin>
  </gazebo>
</robot>"""


def test_a_spawned_model_settles_and_reads_its_own_motion():
    """The plugin read from a spawned URDF over the simulator's own link state (a floating model, zero gravity):
    the frame is set at the camera link after the first second; the model moved 0.3 m along x and turned 0.2 rad
    afterwards, the camera link reads where it went in that frame."""
    sim = floating(("rover", SMB_STYLE_URDF, (0.0, 0.0, 1.0, 0.0, 0.0, 0.0)))
    (plugin_config,) = [c for c in sim.plugins["rover"].configs if isinstance(c, OdometrySourceConfig)]
    source = OdometrySource(plugin_config)
    model = sim.models["rover"]

    def state():
        position, orientation = model.link_transform("tracking_camera_link")
        return (position, orientation, *model.link_twist("tracking_camera_link"))

    while source.odom_frame is None and sim.sim_time < 2.0:
        sim.step()
        source.update(sim.sim_time, state)
    assert source.odom_frame is not None, "not settled after 2 s"
    assert source.odom_frame[0] == pytest.approx((0.3, 0.0, 1.1), abs=1e-6)
    yaw = 0.2
    w, x, y, z = quat_from_rpy(0.0, 0.0, yaw)
    sim.set_model_state("rover", (0.3, 0.0, 1.0), (x, y, z, w))  # ROS order
    reading = None
    while reading is None:
        sim.step()
        reading = source.update(sim.sim_time, state)
    # the camera sits 0.3 m ahead of the base: (0.3 + 0.3 cos yaw - 0.3, 0.3 sin yaw, 0) from where it rested
    expected = (0.3 * math.cos(yaw), 0.3 * math.sin(yaw), 0.0)
    assert reading.position == pytest.approx(expected, abs=1e-6)
    assert rpy_of(reading.orientation)[2] == pytest.approx(yaw, abs=1e-6)
