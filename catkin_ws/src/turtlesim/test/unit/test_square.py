"""The draw_square state machine without ROS (twin of test/test_square_driver.cpp)."""
from __future__ import annotations

import math

import pytest

from turtlesim.square import ANGULAR_SPEED, LINEAR_SPEED, STOP_FORWARD, TURN, SquareDriver, SquarePose


def test_drives_forward_to_a_goal_two_metres_ahead():
    driver, log = SquareDriver(), []
    assert driver.step(SquarePose(1.0, 1.0, math.pi / 2, 0.0, 0.0), log) == (LINEAR_SPEED, 0.0)
    assert (driver.goal.x, driver.goal.y) == (pytest.approx(1.0), pytest.approx(3.0))
    assert len(log) == 1 and log[0].startswith("New goal [")


def test_stops_then_turns_a_quarter_turn():
    driver, log = SquareDriver(), []
    driver.step(SquarePose(0.0, 0.0, 0.0, 0.0, 0.0), log)
    assert driver.step(SquarePose(1.95, 0.0, 0.0, 1.0, 0.0), log) == (0.0, 0.0)
    assert driver.state == STOP_FORWARD
    driver.step(SquarePose(1.95, 0.0, 0.0, 0.0, 0.0), log)
    assert driver.state == TURN and driver.goal.theta == pytest.approx(math.pi / 2)
    assert driver.step(SquarePose(1.95, 0.0, 0.5, 0.0, 0.0), log) == (0.0, ANGULAR_SPEED)
    assert "Reached goal" in log


def test_a_quarter_turn_past_pi_wraps():
    driver, log = SquareDriver(), []
    driver.step(SquarePose(0.0, 0.0, 3.0, 0.0, 0.0), log)
    driver.step(SquarePose(2 * math.cos(3.0), 2 * math.sin(3.0), 3.0, 1.0, 0.0), log)
    driver.step(SquarePose(2 * math.cos(3.0), 2 * math.sin(3.0), 3.0, 0.0, 0.0), log)
    assert driver.goal.theta == pytest.approx(3.0 + math.pi / 2 - 2 * math.pi)
