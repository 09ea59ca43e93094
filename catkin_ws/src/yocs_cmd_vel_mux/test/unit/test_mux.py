"""The multiplexer's rules, without ROS. Expected behaviour from yujinrobot/yujin_ocs (devel)
yocs_cmd_vel_mux/src/cmd_vel_mux_nodelet.cpp: CmdVelMuxNodelet::cmdVelCallback (forward if vacant, the same input,
or a higher priority), timerCallback (an input's own timeout, and the common one of twice the longest, make it
"idle"); the inputs are turtlebot/turtlebot (melodic) turtlebot_bringup/param/mux.yaml's."""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from yocs_cmd_vel_mux.mux import IDLE, CmdVelMux, ConfigError, Input, parse_inputs

TURTLEBOT = [
    {"name": "Safe reactive controller", "topic": "input/safety_controller", "timeout": 0.2, "priority": 10},
    {"name": "Teleoperation", "topic": "input/teleop", "timeout": 1.0, "priority": 7},
    {"name": "Switch", "topic": "input/switch", "timeout": 1.0, "priority": 6},
    {"name": "Navigation", "topic": "input/navi", "timeout": 1.0, "priority": 5},
]
SAFETY, TELEOP, SWITCH, NAVI = range(4)


def mux() -> CmdVelMux:
    return CmdVelMux(parse_inputs(TURTLEBOT))


def test_starts_idle_and_the_first_input_wins():
    m = mux()
    assert m.active == IDLE
    assert m.command(NAVI, 0.0) and m.active == "Navigation"


def test_higher_priority_takes_over_and_lower_is_refused():
    m = mux()
    assert m.command(NAVI, 0.0)
    assert m.command(TELEOP, 0.1) and m.active == "Teleoperation"
    assert not m.command(NAVI, 0.2) and not m.command(SWITCH, 0.3)
    assert m.active == "Teleoperation"
    assert m.command(SAFETY, 0.4) and m.active == "Safe reactive controller"


def test_the_active_input_times_out_then_a_lower_one_may_drive():
    m = mux()
    assert m.command(TELEOP, 0.0)
    assert not m.command(NAVI, 0.9)
    assert not m.expire(0.99) and m.active == "Teleoperation"
    assert m.expire(1.0) and m.active == IDLE
    assert m.command(NAVI, 1.05) and m.active == "Navigation"


def test_a_command_right_after_the_timeout_is_not_held_up_by_the_timer():
    m = mux()
    m.command(SAFETY, 0.0)
    assert m.command(NAVI, 0.21) and m.active == "Navigation"  # safety's 0.2 s are over


def test_common_timeout_is_twice_the_longest():
    assert mux().common_timeout == 2.0


@pytest.mark.parametrize(
    "subscribers, complaint",
    [
        ([], "non-empty list"),
        (None, "non-empty list"),
        ([{"name": "a", "topic": "t", "timeout": 1.0}], "priority missing"),
        ([{"name": "a", "topic": "t", "timeout": 0, "priority": 1}], "timeout must be a positive number, got [0]"),
        ([{"name": "a", "topic": "t", "timeout": 1, "priority": -1}], "unsigned integer, got [-1]"),
        ([{"name": "a", "topic": "t", "timeout": 1, "priority": 1}] * 2, "unique"),
        (["x"], "a mapping is needed"),
    ],
)
def test_bad_configuration_is_named(subscribers, complaint):
    with pytest.raises(ConfigError, match=complaint.replace("[", r"\[").replace("]", r"\]")):
        parse_inputs(subscribers)


def test_short_desc_is_optional():
    entry = dict(TURTLEBOT[0], short_desc="stops at cliffs")
    assert parse_inputs([entry])[0] == Input(
        "Safe reactive controller", "input/safety_controller", 0.2, 10, "stops at cliffs"
    )


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 3), st.floats(0.0, 1.5), st.booleans()), max_size=40))
def test_rules_hold_after_every_event(events):
    """After each command or timer tick: the active input has sent within its timeout; a forwarded command makes
    its input the active one; a refused one came while a higher-priority input was active and fresh."""
    m = mux()
    inputs = m.inputs
    now = 0.0
    last = {}
    for index, dt, is_tick in events:
        now += dt
        if is_tick:
            m.expire(now)
        else:
            before = m.active
            fresh_higher = [
                i for i, src in enumerate(inputs)
                if src.name == before and src.priority >= inputs[index].priority and i != index
                and now - last[i] < src.timeout
            ]  # fmt: skip
            forwarded = m.command(index, now)
            last[index] = now
            assert forwarded == (not fresh_higher)
            if forwarded:
                assert m.active == inputs[index].name
        if m.active != IDLE:
            active = [i for i, src in enumerate(inputs) if src.name == m.active][0]
            assert now - last[active] < inputs[active].timeout or not is_tick
