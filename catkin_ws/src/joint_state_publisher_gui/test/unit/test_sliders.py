"""The slider arithmetic against upstream's (ros/joint_state_publisher noetic-devel, joint_state_publisher_gui
__init__.py: RANGE, valueToSlider, sliderToValue, generate_grid_positions and the slider loop of __init__)."""
from __future__ import annotations

import math

from hypothesis import assume, given
from hypothesis import strategies as st

from joint_state_publisher_gui.sliders import RANGE, grid_positions, slider_joints, slider_to_value, value_to_slider

CONTINUOUS = {"min": -math.pi, "max": math.pi}


def test_upstreams_range_and_mapping():
    assert RANGE == 10000
    joint = {"min": -1.2, "max": 1.5}
    assert value_to_slider(-1.2, joint) == 0 and value_to_slider(1.5, joint) == RANGE
    # upstream's arithmetic, rounding included: the top end comes out as 1.5000000000000002
    assert slider_to_value(0, joint) == -1.2 and slider_to_value(RANGE, joint) == -1.2 + 2.7
    assert value_to_slider(0.0, CONTINUOUS) == RANGE // 2
    assert slider_to_value(RANGE // 2, CONTINUOUS) == 0.0


def test_fixed_and_pinned_joints_get_no_slider():
    free = {"a": {"min": -1, "max": 1}, "pinned": {"min": 0.3, "max": 0.3}, "b": {"min": 0, "max": 2}}
    assert slider_joints(["b", "mimic", "pinned", "a"], free) == ["b", "a"]


def test_grid_is_filled_column_by_column():
    assert grid_positions(5, 2) == [(0, 0), (1, 0), (0, 1), (1, 1), (0, 2)]
    assert grid_positions(3, 3) == [(0, 0), (1, 0), (2, 0)]
    assert grid_positions(4, 0) == []


limits = st.tuples(st.floats(-100, 100), st.floats(1e-3, 200)).map(lambda t: {"min": t[0], "max": t[0] + t[1]})


@given(limits, st.floats(0, 1))
def test_slider_values_are_ints_in_range_and_round_trip(joint, fraction):
    value = joint["min"] + fraction * (joint["max"] - joint["min"])
    assume(joint["min"] <= value <= joint["max"])
    slider = value_to_slider(value, joint)
    assert type(slider) is int  # QSlider.setValue takes an int only (PyQt 5.15)
    assert 0 <= slider <= RANGE
    step = (joint["max"] - joint["min"]) / RANGE
    assert abs(slider_to_value(slider, joint) - value) <= step * (1 + 1e-6)


@given(st.integers(1, 40), st.integers(1, 40))
def test_grid_positions_are_distinct_and_within_rows(count, rows):
    positions = grid_positions(count, rows)
    assert len(positions) == count == len(set(positions))
    assert all(0 <= row < rows for row, _ in positions)
