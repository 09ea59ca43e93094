"""The steering rules against upstream's (ros-visualization/rqt_robot_steering 0.5.12: robot_steering.py
RobotSteering.slider_factor, the shortcut table in __init__, _send_twist; RobotSteering.ui's slider steps)."""
from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from rqt_robot_steering.steering import (
    PAGE_STEP,
    PUBLISH_PERIOD_MS,
    SHORTCUTS,
    SINGLE_STEP,
    TwistGate,
    slider_units,
    stepped,
)


def test_upstreams_steps_and_rate():
    assert (SINGLE_STEP, PAGE_STEP, PUBLISH_PERIOD_MS) == (10, 100, 100)
    assert slider_units(1.0) == 1000 and slider_units(-3.0) == -3000 and slider_units(0.3) == 300
    assert SHORTCUTS == {
        "W": ("linear", 1), "X": ("linear", 0), "S": ("linear", -1),
        "A": ("angular", 1), "Z": ("angular", 0), "D": ("angular", -1),
    }  # fmt: skip


def test_steps():
    assert stepped(0, 1, strong=False) == 10 and stepped(0, 1, strong=True) == 100
    assert stepped(250, -1, strong=True) == 150 and stepped(250, 0, strong=True) == 0


def test_zero_goes_out_once_until_something_else_or_stop():
    gate = TwistGate()
    assert gate.next_twist(0, 0) == (0.0, 0.0)
    assert gate.next_twist(0, 0) is None
    assert gate.next_twist(10, 0) == (0.01, 0.0)
    assert gate.next_twist(10, 0) == (0.01, 0.0)
    assert gate.next_twist(0, 0) == (0.0, 0.0) and gate.next_twist(0, 0) is None
    gate.resend_zero()
    assert gate.next_twist(0, 0) == (0.0, 0.0)


@given(st.lists(st.tuples(st.integers(-3000, 3000), st.integers(-3000, 3000)) | st.just((0, 0)), max_size=50))
def test_every_non_zero_goes_out_and_zeros_never_twice_in_a_row(values):
    gate, sent = TwistGate(), []
    for linear, angular in values:
        twist = gate.next_twist(linear, angular)
        if (linear, angular) != (0, 0):
            assert twist == (linear / 1000.0, angular / 1000.0)
        if twist is not None:
            sent.append(twist)
    assert all(not (a == b == (0.0, 0.0)) for a, b in zip(sent, sent[1:]))
