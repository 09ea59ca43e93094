"""The simulator node's parameters are checked before anything starts: each bad value is named."""
import pytest

from turtle_sim_ode.ros.settings import SettingsError, settings_from_params


def test_defaults_match_the_documented_ones():
    settings = settings_from_params({})
    assert settings.real_time_factor == 1.0 and not settings.paused
    assert settings.pub_clock_frequency == 100.0 and settings.publish_rate == 50.0
    assert settings.physics.time_step == 0.001 and settings.physics.solver == "quick"
    assert settings.physics.solver_iterations == 50 and settings.write_batch_period == 0.001
    assert (settings.odom_frame, settings.base_frame) == ("odom", "base_footprint")


def test_values_are_taken():
    settings = settings_from_params(
        {
            "real_time_factor": 0,
            "paused": True,
            "time_step": 0.01,
            "solver": "world",
            "gravity": [0, 0, -1.62],
            "spawn_x": 1,
            "spawn_yaw": 0.5,
            "diff_drive": {"cmd_timeout": 1.0, "odometry_integration": "exact"},
        }
    )
    assert settings.real_time_factor == 0.0 and settings.paused
    assert settings.physics.time_step == 0.01 and settings.physics.solver == "world"
    assert settings.physics.gravity == (0.0, 0.0, -1.62)
    assert settings.spawn_pose == (1.0, 0.0, 0.0, 0.0, 0.0, 0.5)
    assert settings.drive_overrides == {"cmd_timeout": 1.0, "odometry_integration": "exact"}


@pytest.mark.parametrize(
    "params, message",
    [
        ({"time_step": 0}, "~time_step must be in (0, 0.1] s"),
        ({"time_step": -0.001}, "~time_step"),
        ({"time_step": "fast"}, "~time_step must be a finite number, got ['fast']"),
        ({"time_step": float("nan")}, "~time_step must be a finite number"),
        ({"solver": "fast"}, "~solver must be one of"),
        ({"solver_iterations": 10**6}, "~solver_iterations must be an integer in 1..1000"),
        ({"solver_iterations": 2.5}, "~solver_iterations must be of type int"),
        ({"gravity": [0, 0]}, "~gravity must be a list of 3 numbers"),
        ({"gravity": [0, 0, float("nan")]}, "~gravity must be a finite number"),
        ({"real_time_factor": -1}, "~real_time_factor must be >= 0.0, got [-1]"),
        ({"paused": "yes"}, "~paused must be of type bool"),
        ({"pub_clock_frequency": 0}, "~pub_clock_frequency must be > 0.0"),
        ({"publish_rate": True}, "~publish_rate must be a finite number"),
        ({"write_batch_period": -0.001}, "~write_batch_period must be >= 0.0"),
        ({"write_batch_period": 1.0}, "~write_batch_period must be <= 0.1"),
        ({"odom_frame": ""}, "~odom_frame must not be empty"),
        ({"base_frame": 3}, "~base_frame must be of type str"),
        ({"spawn_x": "left"}, "~spawn_x must be a finite number"),
        ({"diff_drive": {"top_speed": 1}}, "~diff_drive has unknown keys ['top_speed']"),
        ({"diff_drive": {"cmd_timeout": -1}}, "~diff_drive/cmd_timeout must be >= 0.0"),
        ({"diff_drive": 5}, "~diff_drive must be a dictionary"),
    ],
)
def test_bad_values_are_named(params, message):
    with pytest.raises(SettingsError) as error:
        settings_from_params(params)
    assert message in str(error.value)
