"""Unit tests of the ROS-free motion core (twin of test/test_motion.cpp)."""
import math

import pytest

from my_first_rospkg.motion import (
    Bouncer,
    CircleTrajectory,
    Pose2D,
    SpiralTrajectory,
    SquareController,
    SquareParams,
    SquareState,
    Velocity,
    normalize_angle,
    yaw_from_quaternion,
)


def step(p: Pose2D, v: Velocity, dt: float) -> Pose2D:
    return Pose2D(
        p.x + v.linear * math.cos(p.yaw) * dt,
        p.y + v.linear * math.sin(p.yaw) * dt,
        normalize_angle(p.yaw + v.angular * dt),
    )


@pytest.mark.parametrize(
    "angle, expected", [(3 * math.pi, math.pi), (-math.pi, math.pi), (0.5, 0.5), (-2 * math.pi - 0.5, -0.5)]
)
def test_normalize_angle(angle, expected):
    assert normalize_angle(angle) == pytest.approx(expected, abs=1e-12)


def test_yaw_from_quaternion():
    assert yaw_from_quaternion(0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)) == pytest.approx(math.pi / 2)


def test_circle():
    circle = CircleTrajectory(2.0, 0.5, 1.0)
    assert circle.duration() == pytest.approx(2 * math.pi * 2.0 / 0.5)
    assert circle.velocity_at(1.0) == (0.5, 0.25)
    assert circle.velocity_at(circle.duration()) == (0.0, 0.0)
    assert circle.velocity_at(-1.0) == (0.0, 0.0)


def test_spiral():
    spiral = SpiralTrajectory(0.2, 0.04, 0.5, 1.0)
    assert spiral.duration() == pytest.approx(0.8 / 0.02)
    assert spiral.radius_at(10.0) == pytest.approx(0.2 + 0.04 * 5.0)
    v = spiral.velocity_at(10.0)
    assert v.angular == 0.5
    assert v.linear / v.angular == pytest.approx(spiral.radius_at(10.0))
    assert spiral.velocity_at(spiral.duration()) == (0.0, 0.0)


def test_bouncer_reverses_only_when_leaving():
    bouncer = Bouncer(0.5, 2.0, 2.0)
    assert bouncer.update(Pose2D(1.0, 0.0, 0.0)).linear == 0.5
    assert bouncer.update(Pose2D(2.1, 0.0, 0.0)).linear == -0.5
    assert bouncer.update(Pose2D(2.05, 0.0, 0.0)).linear == -0.5
    assert bouncer.update(Pose2D(-2.1, 0.0, 0.0)).linear == 0.5
    assert bouncer.update(Pose2D(0.0, 2.1, math.pi / 2)).linear == -0.5


def test_bouncer_stays_inside():
    bouncer = Bouncer(0.5, 2.0, 2.0)
    p = Pose2D(0.0, 0.0, 0.3)
    for _ in range(6000):
        p = step(p, bouncer.update(p), 0.02)
        assert abs(p.x) <= 2.0 + 0.5 * 0.02 + 1e-9
        assert abs(p.y) <= 2.0 + 0.5 * 0.02 + 1e-9


def test_square_closes_with_four_corners():
    params = SquareParams()
    square = SquareController(params)
    p = start = Pose2D(0.5, -0.2, 0.3)
    corners, previous, t = 0, square.state, 0.0
    while t < 200.0 and not square.done():
        v = square.update(p, t)
        if square.state == SquareState.STOP_AFTER_TURN and previous != square.state:
            corners += 1
            assert normalize_angle(p.yaw - start.yaw - corners * math.pi / 2) == pytest.approx(
                0.0, abs=params.angle_tolerance + 0.01
            )
        previous = square.state
        p = step(p, v, 0.02)
        t += 0.02
    assert square.done()
    assert corners == 3
    assert square.sides_done == 4
    assert math.hypot(p.x - start.x, p.y - start.y) < 0.03
    assert square.update(p, t) == (0.0, 0.0)


def test_square_stops_after_a_side():
    square = SquareController(SquareParams(side=0.1))
    p, t = Pose2D(), 0.0
    while t < 5.0:
        v = square.update(p, t)
        if square.state == SquareState.STOP_AFTER_DRIVE:
            assert v.linear == 0.0
            return
        p = step(p, v, 0.02)
        t += 0.02
    pytest.fail("never stopped after the first side")
