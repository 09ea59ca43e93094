"""Pacing of the run loop and the names the services accept and show (issue #16): ROS-free."""
import math

import pytest

from turtle_sim_ode.ros.names import legal_base_name, legal_name, shorten_names_in, shown
from turtle_sim_ode.ros.pacing import MAX_PACING_LAG_S, Pacing, pacing_problem, steps_per_clock
from turtle_sim_ode.ros.settings import SettingsError, settings_from_params

RATES = [0.0, 5e-324, 1e-300, 1e-12, 1e-3, 1.0, 1000.0, 1e9, 1e300, 1.7976931348623157e308]
STEPS = [5e-324, 1e-300, 1e-9, 1e-6, 1e-3, 0.1]


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("time_step", STEPS)
def test_no_accepted_value_raises(rate, time_step):
    """Whatever the world layer accepts (finite, >= 0), the checks and the loop's arithmetic never raise."""
    problem = pacing_problem(time_step, rate, 100.0)
    pacing = Pacing(0.0, 0.0, rate * time_step)
    for now in (0.0, 1e-3, 1.0, 1e6):
        wait = pacing.wait(0.5, now)
        assert not math.isnan(wait)
        assert min(wait, 0.1) <= 0.1  # the loop's bounded wait takes any of them
    if not problem:  # accepted: a /clock message comes within the bound
        steps = steps_per_clock(time_step, 100.0)
        assert steps <= 100000 and (rate == 0 or steps / rate <= 10.0)


def test_pacing_refusals_name_the_value_and_the_bound():
    assert "time_step [1e-09] s is too small" in pacing_problem(1e-9, 1e9, 100.0)
    assert "time_step must be >= 1e-07 s" in pacing_problem(1e-9, 1e9, 100.0)
    message = pacing_problem(1e-3, 1e-3, 100.0)
    assert "max_update_rate [0.001]" in message and ">= 1 steps/s" in message
    assert pacing_problem(1e-12, 0.0, 100.0)  # flat out, but 1e7 steps per /clock
    for time_step, rate in ((1e-3, 1000.0), (1e-3, 0.0), (1e-3, 1.0), (0.1, 0.1), (1e-6, 1e6)):
        assert pacing_problem(time_step, rate, 100.0) == ""


def test_rate_change_does_not_keep_the_old_anchor():
    """Unpaced for a while (sim time far ahead of the wall), then paced again: the next step is due now."""
    pacing = Pacing(0.0, 0.0, 0.0)
    assert pacing.wait(3.0, 141.0) == 0.0  # unpaced: always due
    pacing.restart(3.0, 141.0, 1.0)  # what the loop does when the rate changes
    assert pacing.wait(3.0, 141.0) == 0.0
    assert pacing.wait(3.0, 141.5) == pytest.approx(0.5)


def test_lag_is_not_caught_up():
    pacing = Pacing(0.0, 0.0, 1.0)
    assert pacing.wait(10.0, 1.0) == 0.0  # 9 s behind: re-anchored
    assert pacing.wait(10.0, 1.5) == pytest.approx(0.5)
    assert pacing.wait(10.0 + MAX_PACING_LAG_S / 2, 1.0) <= 0.0


def test_settings_refuse_a_pace_without_clock():
    with pytest.raises(SettingsError, match="real_time_factor"):
        settings_from_params({"real_time_factor": 1e-9})
    assert settings_from_params({"real_time_factor": 0.0}).real_time_factor == 0.0


@pytest.mark.parametrize("name", ["tb_\u00e9", "\u0442\u0431", "a\u0661", "", "1a", "a b", "a/b"])
def test_base_names_are_ascii(name):
    assert not legal_base_name(name)


def test_names():
    assert legal_base_name("tb3_0") and legal_name("/a/b_1") and not legal_name("/\u00e9")
    long_name = "x" * 100000
    assert shown(long_name) == "x" * 80 + "... (100000 characters)"
    assert shown("short") == "short"
    message = shorten_names_in("model '%s' does not exist" % long_name, [long_name])
    assert message == "model '%s' does not exist" % shown(long_name)
    assert len(shorten_names_in("y" * 10**6, [])) < 5000
