"""libhector_gazebo_ros_imu.so: tags and defaults as hector_gazebo_plugins' GazeboRosIMU::Load and SensorModel_::Load
read them, and its readings as GazeboRosIMU::Update makes them (hector_gazebo_plugins/src/gazebo_ros_imu.cpp,
include/hector_gazebo_plugins/sensor_model.h)."""
from __future__ import annotations

import math
import random

import pytest
from hypothesis import given
from hypothesis import strategies as st

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.hector_imu import HECTOR_IMU, ErrorModel, HectorImu, SensorError
from turtle_sim_ode.world.plugins.hector_sensor_model import RECONFIGURE_FIELDS, reconfigure
from turtle_sim_ode.world.simulation import Simulation

BOX_SDF = """<sdf version="1.6"><model name="box"><link name="imu_link">
  <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link></model></sdf>"""


def read(params: dict):  # type: ignore[no-untyped-def]
    (config,) = read_plugins("m", [GazeboPlugin(HECTOR_IMU, "imu", params)], {}, []).configs
    return config


def test_defaults() -> None:
    config = read({})
    # Load: topic "imu", bias topic topic + "/bias", service topic + "/calibrate", frame = the link, body = the
    # canonical link; SensorModel_(): drift frequency 1/3600 Hz, scale error 1, the rest 0; UpdateTimer: every step.
    assert (config.topic, config.bias_topic, config.service, config.frame, config.body) == (
        "imu",
        "imu/bias",
        "imu/calibrate",
        "",
        "",
    )
    assert config.accel == ErrorModel() and config.accel.drift_frequency == (1 / 3600,) * 3
    assert config.update_rate == 0.0


def test_tags_as_smb_writes_them() -> None:
    config = read(
        {
            "topicName": "imu0",
            "bodyName": "imu_link",
            "frameId": "imu_link",
            "updateRate": "200.0",
            "accelOffset": "0.1 0.2 0.3",
            "accelDrift": "0.5 0.5 0.5",
            "accelGaussianNoise": "0.35 0.35 0.3",
            "rateDrift": "0.1 0.1 0.1",
            "rateGaussianNoise": "0.05 0.05 0.015",
            "yawDrift": "0.1",
            "yawGaussianNoise": "0.1",
            "accelDriftFrequency": "0.01 0.01 0.01",
        }
    )
    assert (config.topic, config.bias_topic, config.service, config.update_rate) == (
        "imu0",
        "imu0/bias",
        "imu0/calibrate",
        200.0,
    )
    assert config.accel.offset == (0.1, 0.2, 0.3) and config.accel.drift_frequency == (0.01,) * 3
    assert config.rate.gaussian_noise == (0.05, 0.05, 0.015) and config.yaw.drift[0] == 0.1
    # The old gazebo_ros_imu tag overrides accel and rate noise when not 0.
    assert read({"gaussianNoise": "0.2"}).rate.gaussian_noise == (0.2,) * 3
    assert read({"updatePeriod": "0.05"}).update_rate == pytest.approx(20.0)


def test_bad_tags_are_named() -> None:
    with pytest.raises(ModelError, match="<accelOffset> must be 1 or 3 numbers"):
        read({"accelOffset": "1 2"})
    with pytest.raises(ModelError, match="<rateDrift>"):
        read({"rateDrift": "-1 0 0"})


def test_the_error_model_is_sensor_model_s() -> None:
    """offset + drift + white noise on value * scale; the drift decays by exp(-dt f) (its random walk off here)."""
    error = SensorError(ErrorModel(offset=(0.1, 0.0, 0.0), scale_error=(2.0, 1.0, 1.0)), random.Random(1))
    assert error.apply((1.0, 1.0, 1.0), 0.01) == pytest.approx((2.1, 1.0, 1.0))
    error.reset((0.5, 0.0, 0.0))  # set_*_bias
    assert error.bias == pytest.approx((0.6, 0.0, 0.0))
    frequency = 1.0 / 3600.0
    assert error.apply((0.0, 0.0, 0.0), 10.0)[0] == pytest.approx(0.1 + 0.5 * math.exp(-10.0 * frequency))


def imu_on_box(height: float = 0.1, **errors):  # type: ignore[no-untyped-def]
    sim = Simulation()
    sim.spawn_sdf("box", BOX_SDF, (0, 0, height, 0, 0, 0))
    config = read({"bodyName": "imu_link", **errors})
    return sim, HectorImu(sim.models["box"], "imu_link", config, (0.0, 0.0, -9.81), random.Random(3))


def test_at_rest_it_reads_gravity_up_and_no_rate() -> None:
    sim, imu = imu_on_box()
    for _ in range(200):
        sim.step()
        reading = imu.update(sim.sim_time)
    assert reading.linear_acceleration == pytest.approx((0.0, 0.0, 9.81), abs=0.05)
    assert reading.angular_velocity == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    assert reading.orientation == pytest.approx((1.0, 0.0, 0.0, 0.0), abs=1e-4)


def test_rate_comes_from_the_orientation_change() -> None:
    sim, imu = imu_on_box(height=5.0)  # in the air: no friction slows the turn
    body = sim.models["box"].links["imu_link"].body
    imu.update(sim.sim_time)
    for _ in range(50):
        body.setAngularVel((0.0, 0.0, 1.5))
        sim.step()
        reading = imu.update(sim.sim_time)
    assert reading.angular_velocity[2] == pytest.approx(1.5, rel=0.02)


def test_accel_bias_tilts_the_orientation_and_yaw_drift_turns_it() -> None:
    """Update's pseudo AHRS: orientation error = yaw(bias) * (1, bias_y / 2g, -bias_x / 2g, 0)."""
    sim, imu = imu_on_box(accelOffset="0.981 0 0", yawOffset="0.2")
    imu.update(sim.sim_time)
    sim.step()
    reading = imu.update(sim.sim_time)
    assert reading.accel_bias == pytest.approx((0.981, 0.0, 0.0))
    cy, sy, tilt = math.cos(0.1), math.sin(0.1), -0.5 * 0.981 / 9.81
    expected = (cy, -sy * tilt, cy * tilt, sy)  # (cos, 0, 0, sin) * (1, 0, tilt, 0)
    norm = math.sqrt(sum(c * c for c in expected))
    assert reading.orientation_error == pytest.approx(tuple(c / norm for c in expected), abs=1e-6)


def test_xyz_offset_changes_nothing_published() -> None:
    """GazeboRosIMU::Load reads <xyzOffset> into offset_.Pos(); Update never uses it (the position line is commented
    out), so the readings are those without it."""
    readings = []
    for extra in ({}, {"xyzOffset": "0.3 -0.2 0.5"}):
        sim, imu = imu_on_box(height=5.0, **extra)
        body = sim.models["box"].links["imu_link"].body
        imu.update(sim.sim_time)
        for _ in range(20):
            body.setAngularVel((0.4, 0.0, 1.5))
            sim.step()
            reading = imu.update(sim.sim_time)
        readings.append(reading)
    assert readings[0] == readings[1]


REFUSED_LEVEL = ~0  # dynamic_reconfigure servers' first callback (C++ and Python alike)


def test_reconfigure_first_call_reports_the_tags_as_scalar_value_averages_them() -> None:
    """sensor_model.h dynamicReconfigureCallback, level != 1: the config gets the model's values, a vector's as the
    mean of its axes (helpers::scalar_value), a scalar's (yaw) as it is; the model stays."""
    error = SensorError(
        ErrorModel(offset=(0.1, 0.2, 0.6), gaussian_noise=(0.3, 0.3, 0.0), scale_error=(1.0, 1.0, 1.3)),
        random.Random(1),
    )
    before = error.model
    values = reconfigure(error, dict.fromkeys(RECONFIGURE_FIELDS, 0.0), REFUSED_LEVEL)
    assert values == pytest.approx(
        {"offset": 0.3, "gaussian_noise": 0.2, "scale_error": 1.1, "drift": 0.0, "drift_frequency": 1 / 3600}
    )
    assert error.model is before
    yaw = SensorError(ErrorModel(offset=(0.2, 0.2, 0.2)), random.Random(1))
    assert reconfigure(yaw, dict.fromkeys(RECONFIGURE_FIELDS, 0.0), 0, scalar=True)["offset"] == 0.2


def test_reconfigure_level_one_sets_every_axis_and_the_readings_follow() -> None:
    """level 1 (every SensorModel.cfg field's level): each field to the config's value on every axis."""
    error = SensorError(ErrorModel(offset=(0.1, 0.2, 0.3)), random.Random(1))
    values = dict(gaussian_noise=0.0, offset=0.5, drift=0.0, drift_frequency=0.01, scale_error=2.0)
    assert reconfigure(error, values, 1) == pytest.approx(values)
    assert error.model == ErrorModel((0.5,) * 3, (0.0,) * 3, (0.01,) * 3, (0.0,) * 3, (2.0,) * 3)
    assert error.apply((1.0, -1.0, 0.0), 0.0) == pytest.approx((2.5, -1.5, 0.5))


def test_reconfigured_accel_noise_changes_the_orientation_covariance_only() -> None:
    """Load fills the rate and acceleration covariances once; Update the orientation's, from the accel and yaw
    noises of each update."""
    _, imu = imu_on_box(accelGaussianNoise="0.1 0.1 0.1", rateGaussianNoise="0.02 0.02 0.02")
    orientation, rate, accel = imu.covariances()
    values = dict(gaussian_noise=0.5, offset=0.0, drift=0.0, drift_frequency=0.0, scale_error=1.0)
    reconfigure(imu.accel_error, values, 1)
    reconfigure(imu.yaw_error, values, 1, scalar=True)
    after = imu.covariances()
    assert after[1:] == (rate, accel)
    assert after[0][0] == pytest.approx(0.25 / 9.81**2) and after[0][8] == pytest.approx(0.25)
    assert orientation[0] == pytest.approx(0.01 / 9.81**2) and orientation[8] == 0.0


@given(
    st.fixed_dictionaries({name: st.floats(allow_nan=True, allow_infinity=True) for name in RECONFIGURE_FIELDS}),
    st.sampled_from([1, 0, REFUSED_LEVEL]),
)
def test_reconfigure_never_takes_a_non_finite_value(values, level) -> None:  # type: ignore[no-untyped-def]
    error = SensorError(ErrorModel(), random.Random(1))
    try:
        reported = reconfigure(error, values, level)
    except ValueError as refused:
        assert level == 1 and any(not math.isfinite(v) for v in values.values()), refused
        assert error.model == ErrorModel()
        return
    assert all(math.isfinite(v) for v in reported.values())
    if level == 1:
        assert reported == pytest.approx(values)
    else:
        assert error.model == ErrorModel()
