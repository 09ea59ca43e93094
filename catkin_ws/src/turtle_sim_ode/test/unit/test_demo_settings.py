"""circle_demo's parameters: defaults, and a clear error naming a bad one."""
import math
import os

import pytest

from turtle_sim_ode.ros.demo import MAX_DURATION_S, demo_settings
from turtle_sim_ode.ros.settings import SettingsError


def test_defaults_drive_one_turn():
    settings = demo_settings({})
    assert (settings.linear, settings.angular) == (0.5, 0.5)
    assert settings.duration == pytest.approx(4 * math.pi)
    assert settings.output == os.path.expanduser("~/.ros/turtle_sim_ode_demo.png")


def test_straight_line_lasts_ten_seconds_and_a_slow_turn_is_capped():
    assert demo_settings({"angular": 0.0}).duration == 10.0
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
