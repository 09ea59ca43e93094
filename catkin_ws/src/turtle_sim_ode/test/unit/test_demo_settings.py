"""circle_demo's parameters: defaults, and a clear error naming a bad one."""
import math
import os

import pytest

from turtle_sim_ode.ros.demo import MAX_DURATION_S, HeadingTurn, demo_settings
from turtle_sim_ode.ros.settings import SettingsError


def test_defaults_drive_one_lap_by_the_heading_within_three_nominal_laps():
    settings = demo_settings({})
    assert (settings.linear, settings.angular, settings.one_lap) == (0.5, 0.5, True)
    assert settings.duration == pytest.approx(3 * 4 * math.pi)
    assert settings.output == os.path.expanduser("~/.ros/turtle_sim_ode_demo.png")


def test_a_duration_given_is_driven_as_it_is():
    settings = demo_settings({"duration": 5.0})
    assert (settings.duration, settings.one_lap) == (5.0, False)


@pytest.mark.parametrize("headings, turned", [([0.0, 3.0, -3.0, -0.1], 2 * math.pi - 0.1), ([0.0, -2.0, 2.5], -3.78)])
def test_the_turn_counts_across_the_wrap(headings, turned):
    heading = HeadingTurn()
    for value in headings:
        heading.add(value)
    assert heading.turned == pytest.approx(turned, abs=0.01)


def test_straight_line_lasts_ten_seconds_and_a_slow_turn_is_capped():
    assert (demo_settings({"angular": 0.0}).duration, demo_settings({"angular": 0.0}).one_lap) == (10.0, False)
    assert demo_settings({"angular": 1e-9}).duration == MAX_DURATION_S


@pytest.mark.parametrize(
    "name, value",
    [
        ("linear", "fast"),
        ("linear", math.nan),
        ("angular", True),
        ("angular", math.inf),
        ("duration", 0.0),
        ("duration", -5),
        ("duration", 1e9),
        ("output", 42),
        ("output", "  "),
    ],
)
def test_bad_parameter_is_named_with_its_value(name, value):
    with pytest.raises(SettingsError) as error:
        demo_settings({name: value})
    assert "~" + name in str(error.value) and repr(value) in str(error.value)
