"""KeyTeleop against upstream's teleop_twist_keyboard.py 1.0.0 (moveBindings, speedBindings, the main loop)."""
from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from teleop_twist_keyboard.keys import CTRL_C, MOVES, SPEED_STEPS, USAGE, KeyTeleop, speeds_line


def test_the_key_layout_is_upstreams():
    # upstream moveBindings, key by key
    assert MOVES["i"] == (1, 0, 0, 0) and MOVES["o"] == (1, 0, 0, -1) and MOVES["u"] == (1, 0, 0, 1)
    assert MOVES["j"] == (0, 0, 0, 1) and MOVES["l"] == (0, 0, 0, -1)
    assert MOVES[","] == (-1, 0, 0, 0) and MOVES["."] == (-1, 0, 0, 1) and MOVES["m"] == (-1, 0, 0, -1)
    assert MOVES["U"] == (1, 1, 0, 0) and MOVES["I"] == (1, 0, 0, 0) and MOVES["O"] == (1, -1, 0, 0)
    assert MOVES["J"] == (0, 1, 0, 0) and MOVES["L"] == (0, -1, 0, 0)
    assert MOVES["M"] == (-1, 1, 0, 0) and MOVES["<"] == (-1, 0, 0, 0) and MOVES[">"] == (-1, -1, 0, 0)
    assert MOVES["t"] == (0, 0, 1, 0) and MOVES["b"] == (0, 0, -1, 0)
    assert len(MOVES) == 18 and "k" not in MOVES and "K" not in MOVES
    assert SPEED_STEPS == {"q": (1.1, 1.1), "z": (0.9, 0.9), "w": (1.1, 1), "x": (0.9, 1), "e": (1, 1.1), "c": (1, 0.9)}
    for row in (
        "   u    i    o",
        "   j    k    l",
        "   m    ,    .",
        "   U    I    O",
        "   J    K    L",
        "   M    <    >",
    ):
        assert row in USAGE.splitlines()


def test_moves_scale_with_speed_and_turn():
    teleop = KeyTeleop(0.5, 1.0)
    assert teleop.press("u") == (True, [])
    assert teleop.twist() == ((0.5, 0.0, 0.0), 1.0)
    teleop.press("L")
    assert teleop.twist() == ((0.0, -0.5, 0.0), 0.0)
    teleop.press("b")
    assert teleop.twist() == ((0.0, 0.0, -0.5), 0.0)


def test_speed_keys_print_the_speeds_and_keep_moving():
    teleop = KeyTeleop(0.5, 1.0)
    teleop.press("i")
    publish, lines = teleop.press("q")
    assert publish and lines == [speeds_line(0.5 * 1.1, 1.0 * 1.1)]
    assert lines[0] == "currently:\tspeed 0.55\tturn 1.1 "
    assert teleop.twist() == ((0.5 * 1.1, 0.0, 0.0), 0.0)


def test_the_usage_comes_back_with_every_15th_speed_change():
    teleop = KeyTeleop(0.5, 1.0)
    with_usage = [i for i in range(45) if USAGE in teleop.press("w")[1]]
    assert with_usage == [14, 29, 44]


def test_other_keys_stop_and_a_timeout_stops_once():
    teleop = KeyTeleop(0.5, 1.0)
    assert teleop.press("") == (False, [])  # standing: a key timeout publishes nothing
    teleop.press("i")
    assert teleop.press("k") == (True, [])
    assert teleop.twist() == ((0.0, 0.0, 0.0), 0.0)
    teleop.press("i")
    assert teleop.press("") == (True, [])  # moving: the key timeout stops the robot
    assert teleop.press("") == (False, [])
    teleop.press(CTRL_C)
    assert teleop.quit


@given(st.lists(st.sampled_from(sorted(MOVES) + sorted(SPEED_STEPS) + ["", "k", " ", "a"]), max_size=60))
def test_the_twist_is_always_a_layout_direction_times_the_speeds(keys):
    teleop = KeyTeleop(0.5, 1.0)
    for key in keys:
        teleop.press(key)
        (x, y, z), yaw = teleop.twist()
        assert teleop.direction in set(MOVES.values()) | {(0, 0, 0, 0)}
        dx, dy, dz, dyaw = teleop.direction
        assert (x, y, z, yaw) == (dx * teleop.speed, dy * teleop.speed, dz * teleop.speed, dyaw * teleop.turn)
        assert math.isfinite(teleop.speed) and teleop.speed > 0 and teleop.turn > 0
        assert not teleop.quit
