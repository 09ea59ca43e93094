"""DiffDriveController logic on recording joints, and WheelOdometry integration."""
import math

import pytest

from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.world.diff_drive import DiffDriveController, DiffDriveParams, WheelOdometry


class RecordingHinge:
    def __init__(self):
        self.params = {}

    def setParam(self, param, value):  # noqa: N802 (PyODE's name)
        self.params[param] = value


def controller(**overrides):
    left, right = RecordingHinge(), RecordingHinge()
    return DiffDriveController(left, right, DiffDriveParams(**overrides)), left, right


def test_motors_get_torque_through_our_fmax_constant():
    _, left, right = controller(max_wheel_torque=2.5)
    for hinge in (left, right):
        assert hinge.params == {oc.PARAM_VEL: 0.0, oc.PARAM_FMAX: 2.5}


def test_wheel_speeds_from_command():
    drive, left, right = controller(wheel_separation=0.2, wheel_radius=0.05)
    assert drive.set_command(0.5, 1.0, now=0.0)
    drive.update(0.0, 0.001)
    assert left.params[oc.PARAM_VEL] == pytest.approx((0.5 - 0.1) / 0.05)
    assert right.params[oc.PARAM_VEL] == pytest.approx((0.5 + 0.1) / 0.05)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_command_is_rejected_and_ignored(bad):
    drive, _, _ = controller()
    drive.set_command(0.2, 0.1, 0.0)
    assert drive.set_command(bad, 0.0, 0.1) is False
    assert drive.set_command(0.0, bad, 0.1) is False
    assert drive.command == (0.2, 0.1)


def test_command_is_clamped():
    drive, _, _ = controller(max_linear=0.7, max_angular=3.0)
    drive.set_command(5.0, -10.0, 0.0)
    assert drive.command == (0.7, -3.0)


def test_watchdog_zeroes_stale_command():
    drive, left, _ = controller(cmd_timeout=0.6)
    drive.set_command(0.35, 0.0, 1.0)
    drive.update(1.59, 0.001)
    assert left.params[oc.PARAM_VEL] == pytest.approx(10.0)
    drive.update(1.61, 0.001)
    assert drive.timed_out(1.61) and left.params[oc.PARAM_VEL] == 0.0
    drive.set_command(0.35, 0.0, 1.7)
    drive.update(1.7, 0.001)
    assert left.params[oc.PARAM_VEL] == pytest.approx(10.0)


def test_zero_timeout_disables_watchdog():
    drive, left, _ = controller(cmd_timeout=0.0)
    drive.set_command(0.35, 0.0, 0.0)
    drive.update(1000.0, 0.001)
    assert left.params[oc.PARAM_VEL] == pytest.approx(10.0)


def test_acceleration_limit_ramps_both_wheels_keeping_curvature():
    drive, left, right = controller(max_wheel_acceleration=10.0, cmd_timeout=0.0)
    drive.set_command(0.35, 1.0, 0.0)
    target = drive.params
    final_left = (0.35 - target.wheel_separation / 2) / target.wheel_radius
    final_right = (0.35 + target.wheel_separation / 2) / target.wheel_radius
    previous = (0.0, 0.0)
    for step in range(200):
        drive.update(step * 0.01, 0.01)
        speeds = drive.wheel_speeds
        assert max(abs(speeds[0] - previous[0]), abs(speeds[1] - previous[1])) <= 0.1 + 1e-12
        if speeds[1] != final_right:
            assert speeds[0] / speeds[1] == pytest.approx(final_left / final_right)
        previous = speeds
    assert (left.params[oc.PARAM_VEL], right.params[oc.PARAM_VEL]) == pytest.approx((final_left, final_right))


def test_stop_clears_command_and_motors():
    drive, left, _ = controller()
    drive.set_command(0.3, 0.0, 0.0)
    drive.update(0.0, 0.001)
    drive.stop()
    assert drive.command == (0.0, 0.0) and left.params[oc.PARAM_VEL] == 0.0
    drive.update(0.001, 0.001)
    assert drive.wheel_speeds == (0.0, 0.0)


@pytest.mark.parametrize(
    "field, value",
    [
        ("wheel_separation", 0.0),
        ("wheel_radius", -1.0),
        ("max_wheel_torque", math.nan),
        ("max_wheel_acceleration", -1.0),
        ("cmd_timeout", -0.1),
        ("max_linear", 0.0),
        ("odometry_integration", "euler"),
    ],
)
def test_params_validation_names_field(field, value):
    with pytest.raises(ValueError, match=field):
        DiffDriveParams(**{field: value}).validate()


def test_params_from_kobuki_plugin():
    params = DiffDriveParams.from_kobuki_plugin(
        {
            "wheel_separation": ".230",
            "wheel_diameter": "0.070",
            "torque": "1.0",
            "velocity_command_timeout": "0.6",
            "publish_tf": "1",
        },
        max_linear=0.5,
    )
    assert (
        params.wheel_separation,
        params.wheel_radius,
        params.max_wheel_torque,
        params.cmd_timeout,
        params.max_linear,
    ) == (0.23, 0.035, 1.0, 0.6, 0.5)
    assert DiffDriveParams.from_kobuki_plugin({"torque": "1.0"}, max_wheel_torque=3.0).max_wheel_torque == 3.0
    with pytest.raises(ValueError, match="not a number"):
        DiffDriveParams.from_kobuki_plugin({"torque": "strong"})


def test_odometry_straight_and_velocity():
    odometry = WheelOdometry(0.2, 0.05)
    odometry.update(0.0, 0.0, 0.0)
    odometry.update(10.0, 10.0, 2.0)
    assert odometry.pose == pytest.approx((0.5, 0.0, 0.0))
    assert (odometry.linear, odometry.angular) == pytest.approx((0.25, 0.0))


def test_exact_integration_follows_the_arc_midpoint_approximates_it():
    separation, radius = 0.2, 0.05
    turn = math.pi / 2  # a quarter circle of radius 1 m in a single update
    left = (1.0 - separation / 2) * turn / radius
    right = (1.0 + separation / 2) * turn / radius
    results = {}
    for integration in ("exact", "midpoint"):
        odometry = WheelOdometry(separation, radius, integration)
        odometry.update(0.0, 0.0, 0.0)
        odometry.update(left, right, 1.0)
        results[integration] = odometry.pose
    assert results["exact"] == pytest.approx((1.0, 1.0, turn))
    assert results["midpoint"][0] == pytest.approx(turn * math.cos(turn / 2))
    # In small steps both converge to the arc.
    odometry = WheelOdometry(separation, radius, "midpoint")
    for k in range(101):
        odometry.update(left * k / 100, right * k / 100, k / 100)
    assert odometry.pose == pytest.approx((1.0, 1.0, turn), abs=1e-4)


def test_odometry_reset_keeps_encoder_baseline_out():
    odometry = WheelOdometry(0.2, 0.05)
    odometry.update(0.0, 0.0, 0.0)
    odometry.update(4.0, 4.0, 1.0)
    odometry.reset(1.0, 2.0, 0.5)
    odometry.update(100.0, 100.0, 2.0)  # new baseline, no jump
    assert odometry.pose == (1.0, 2.0, 0.5)
    odometry.update(102.0, 102.0, 3.0)
    assert odometry.pose == pytest.approx((1.0 + 0.1 * math.cos(0.5), 2.0 + 0.1 * math.sin(0.5), 0.5))
