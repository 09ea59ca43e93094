"""Parameters as RosFilter::loadParams (ros_filter.cpp) reads them: defaults, sensors counted from 0, update vectors
split into parts; values upstream cannot use are refused with the parameter named."""
from __future__ import annotations

import os

import numpy as np
import pytest
import yaml

from robot_localization.ekf import DEFAULT_PROCESS_NOISE
from robot_localization.params import Config, ConfigError, defaults

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.join(HERE, "..", "..")


def load(name: str) -> dict:
    with open(name) as stream:
        return yaml.safe_load(stream)


def flags(*indices: int) -> list:
    return [i in indices for i in range(15)]


def test_smb_course_config():
    """The SMB course's settings: odom0's twist (vx, vy, vz, vyaw) and imu0's orientation and rates; a 2D filter
    at 50 Hz in odom; queue sizes as given."""
    config = Config(load(os.path.join(HERE, "..", "config", "smb_localization.yaml")))
    assert config.frequency == 50.0 and config.sensor_timeout == pytest.approx(0.02)
    assert config.two_d_mode and config.world_frame == config.odom_frame == "odom"
    assert config.publish_tf and config.base_link_frame_output == "base_link"
    odom, imu = config.sensors
    assert (odom.name, odom.topic, odom.queue_size) == ("odom0", "smb_velocity_controller/odom", 10)
    assert not any(odom.pose_update) and odom.twist_update == flags(6, 7, 8, 11)
    assert (imu.name, imu.topic, imu.differential, imu.remove_gravitational_acceleration) == (
        "imu0",
        "imu/data",
        True,
        True,
    )
    assert imu.pose_update == flags(3, 4, 5) and imu.twist_update == flags(9, 10, 11)
    assert not any(imu.acceleration_update)
    np.testing.assert_array_equal(config.process_noise_covariance, DEFAULT_PROCESS_NOISE)
    assert config.initial_estimate_covariance is None and config.warnings() == []


def test_sensors_stop_at_the_first_gap_and_a_name_without_number_is_no_sensor():
    """loadParams looks for odom0, odom1, ... while hasParam; `imu` (no number) is not an input."""
    config = Config({"odom0": "a", "odom2": "c", "imu": "imu/data", "twist0": "t", "pose0": "p", "imu0": "i"})
    assert [s.name for s in config.sensors] == ["odom0", "pose0", "twist0", "imu0"]


def test_update_vectors_are_split_by_message_kind():
    """pose inputs keep x..yaw, twist inputs vx..vyaw, IMUs orientation, rates and accelerations only."""
    everything = [True] * 15
    kinds = ("odom", "pose", "twist", "imu")
    config = Config(dict([(k + "0", k) for k in kinds] + [(k + "0_config", everything) for k in kinds]))
    odom, pose, twist, imu = config.sensors
    assert odom.pose_update == flags(0, 1, 2, 3, 4, 5) and odom.twist_update == flags(6, 7, 8, 9, 10, 11)
    assert not any(pose.twist_update) and pose.pose_update == flags(0, 1, 2, 3, 4, 5)
    assert not any(twist.pose_update) and twist.twist_update == flags(6, 7, 8, 9, 10, 11)
    assert imu.pose_update == flags(3, 4, 5) and imu.twist_update == flags(9, 10, 11)
    assert imu.acceleration_update == flags(12, 13, 14)
    assert any("no position or linear velocity" in w for w in config.warnings())


def test_differential_wins_over_relative():
    config = Config({"pose0": "p", "pose0_config": flags(0), "pose0_differential": True, "pose0_relative": True})
    assert config.sensors[0].differential and not config.sensors[0].relative
    assert "Using differential mode" in config.warnings()[0]


def test_defaults_file_matches_the_code():
    """config/ekf_localization_node.yaml documents the defaults the node uses."""
    documented = load(os.path.join(PACKAGE, "config", "ekf_localization_node.yaml"))
    assert documented == {k: v for k, v in defaults().items() if k in documented}
    assert set(defaults()) - set(documented) == {"sensor_timeout", "base_link_frame_output", "world_frame"}


@pytest.mark.parametrize(
    "params, named",
    [
        ({"frequency": 0}, "~frequency is [0]"),
        ({"frequency": "fast"}, "~frequency is ['fast']"),
        ({"two_d_mode": "yes"}, "~two_d_mode is ['yes']"),
        ({"odom0": "o", "odom0_config": [1, 0]}, "~odom0_config"),
        ({"odom0": "o", "odom0_config": True}, "~odom0_config"),
        ({"odom0": "o", "odom0_queue_size": 0}, "~odom0_queue_size is [0]"),
        ({"process_noise_covariance": [0.1] * 15}, "~process_noise_covariance"),
        ({"odom_frame": "base_link"}, "odom_frame [base_link]"),
        ({"world_frame": "earth"}, "world_frame [earth]"),
        ({"imu0": "i", "imu0_pose_rejection_threshold": -1}, "~imu0_pose_rejection_threshold is [-1]"),
    ],
)
def test_bad_values_are_refused_with_the_parameter_named(params, named):
    with pytest.raises(ConfigError) as error:
        Config(params)
    assert named in str(error.value)


def test_short_update_vector_is_padded_and_matrices_are_read_row_by_row():
    matrix = np.arange(225.0).reshape(15, 15)
    config = Config(
        {
            "twist0": "t",
            "twist0_config": [False] * 6 + [True],
            "initial_estimate_covariance": matrix.flatten().tolist(),
            "unused_param": 1,
        }
    )
    assert config.sensors[0].twist_update == flags(6)
    np.testing.assert_array_equal(config.initial_estimate_covariance, matrix)
