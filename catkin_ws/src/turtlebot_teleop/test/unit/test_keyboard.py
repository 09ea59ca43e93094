"""turtlebot_teleop_key's keys and smoothing, without ROS or a terminal. Expected values from turtlebot/turtlebot
(melodic) turtlebot_teleop/scripts/turtlebot_teleop_key: moveBindings, speedBindings, the start speeds
(speed .2, turn 1), the main loop's ramps (0.02 and 0.1 per loop), the stop after more than 4 loops without a
known key, space/k resetting the control speeds, Ctrl-C ending the loop, and the usage text (msg)."""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtlebot_teleop.keyboard import MOVES, SPEED_STEPS, USAGE, KeyboardTeleop


def run(keys):
    teleop = KeyboardTeleop()
    out = []
    for key in keys:
        teleop.step(key)
        out.append(tuple(round(v, 6) for v in teleop.twist()))
    return teleop, out


def test_key_map_is_upstreams():
    assert MOVES == {
        "i": (1, 0), "o": (1, -1), "j": (0, 1), "l": (0, -1),
        "u": (1, 1), ",": (-1, 0), ".": (-1, 1), "m": (-1, -1),
    }  # fmt: skip
    assert SPEED_STEPS == {
        "q": (1.1, 1.1), "z": (0.9, 0.9), "w": (1.1, 1), "x": (0.9, 1), "e": (1, 1.1), "c": (1, 0.9),
    }  # fmt: skip


def test_usage_text_lines():
    lines = USAGE.strip().splitlines()
    assert lines[0] == "Control Your Turtlebot!"
    assert "   u    i    o" in lines and "   j    k    l" in lines and "   m    ,    ." in lines
    assert "q/z : increase/decrease max speeds by 10%" in lines
    assert "space key, k : force stop" in lines and lines[-1] == "CTRL-C to quit"


def test_one_press_ramps_up_then_stops_smoothly():
    # key i, then no key: the target holds for 4 idle loops, then drops to 0; linear moves 0.02 a loop
    _, out = run(["i"] + [""] * 9)
    assert [lin for lin, _ in out] == [0.02, 0.04, 0.06, 0.08, 0.1, 0.08, 0.06, 0.04, 0.02, 0.0]
    assert all(ang == 0.0 for _, ang in out)


def test_holding_a_key_reaches_the_speed_and_turn():
    _, out = run(["u"] * 12)  # a held key repeats faster than the 0.1 s loop
    assert out[-1] == (0.2, 1.0)
    assert out[0] == (0.02, 0.1)


def test_force_stop_is_immediate():
    for stop in (" ", "k"):
        _, out = run(["i"] * 12 + [stop])
        assert out[-2] == (0.2, 0.0) and out[-1] == (0.0, 0.0)


def test_speed_steps_scale_the_targets():
    teleop, out = run(["q", "w", "c"] + ["i"] * 20)
    assert teleop.speed == pytest.approx(0.2 * 1.1 * 1.1)
    assert teleop.turn == pytest.approx(1.0 * 1.1 * 0.9)
    assert out[-1][0] == pytest.approx(0.242)


def test_speed_change_prints_speeds_and_usage_every_fifteenth():
    teleop = KeyboardTeleop()
    printed = [teleop.step("z") for _ in range(15)]
    assert printed[0][0].startswith("currently:\tspeed 0.18")
    assert all(len(p) == 1 for p in printed[:14]) and printed[14][1] == USAGE


def test_ctrl_c_quits_without_a_new_twist():
    teleop, out = run(["i", "\x03"])
    assert teleop.quit and out[-1] == out[-2]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(sorted(MOVES) + sorted(SPEED_STEPS) + [" ", "k", "", "a"]), max_size=60))
def test_speeds_never_jump_nor_overshoot(keys):
    """Invariants after each key: a step changes linear by at most 0.02 and angular by at most 0.1 unless it is a
    force stop (then both are 0), and neither exceeds the current maxima."""
    teleop = KeyboardTeleop()
    for key in keys:
        before = teleop.twist()
        teleop.step(key)
        linear, angular = teleop.twist()
        if key in (" ", "k"):
            assert (linear, angular) == (0.0, 0.0)
            continue
        assert abs(linear - before[0]) <= 0.02 + 1e-12 and abs(angular - before[1]) <= 0.1 + 1e-12
        assert abs(linear) <= max(teleop.speed, abs(before[0])) + 1e-12
        assert abs(angular) <= max(teleop.turn, abs(before[1])) + 1e-12
