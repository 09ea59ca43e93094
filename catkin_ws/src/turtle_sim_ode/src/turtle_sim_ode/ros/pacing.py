"""Pacing of the simulator's run loop, ROS-free: when the next step is due in wall time, and which pairs of
time_step and max_update_rate let /clock advance."""
from __future__ import annotations

import math

# The run loop waits for a step's wall time in chunks of at most this (s): whatever the pace, it sees a change of
# rate, pause, reset or shutdown within one (they also wake it at once).
MAX_PACING_WAIT_S = 0.1
# Behind its pace by more than this (wall s), the loop runs on from where it is instead of catching up.
MAX_PACING_LAG_S = 0.5

# Pacing that /clock can follow: a /clock message at least every MAX_CLOCK_GAP_S wall seconds at the asked
# max_update_rate, and at most MAX_STEPS_PER_CLOCK steps between two (flat out, ~1e4-1e5 steps per wall second).
MAX_CLOCK_GAP_S = 10.0
MAX_STEPS_PER_CLOCK = 100000


def steps_per_clock(time_step: float, pub_clock_frequency: float) -> float:
    """Physics steps between two /clock messages (at least one; inf where the product underflows)."""
    product = pub_clock_frequency * time_step
    if not product > 0 or not math.isfinite(1.0 / product):
        return math.inf
    return max(1.0, float(math.ceil(1.0 / product - 1e-9)))


def pacing_problem(time_step: float, max_update_rate: float, pub_clock_frequency: float) -> str:
    """Why the pair (time_step s, max_update_rate steps per wall second; 0 = as fast as possible) would leave /clock
    standing still, naming the value and its bound; "" if /clock advances. Values are assumed finite, >= 0 (as
    world.values checks them) and time_step > 0."""
    steps = steps_per_clock(time_step, pub_clock_frequency)
    if steps > MAX_STEPS_PER_CLOCK:
        smallest = 1.0 / (pub_clock_frequency * MAX_STEPS_PER_CLOCK)
        return (
            f"time_step [{time_step:g}] s is too small: /clock (every {1.0 / pub_clock_frequency:g} s of sim time) "
            f"would come every {steps:.3g} steps; time_step must be >= {smallest:g} s"
        )
    if max_update_rate > 0 and steps / max_update_rate > MAX_CLOCK_GAP_S:
        slowest = steps / MAX_CLOCK_GAP_S
        return (
            f"max_update_rate [{max_update_rate:g}] steps/s would publish /clock only every "
            f"{steps / max_update_rate:.3g} s of wall time; at time_step {time_step:g} s it must be 0 (as fast as "
            f"possible) or >= {slowest:g} steps/s (/clock at least every {MAX_CLOCK_GAP_S:g} s)"
        )
    return ""


class Pacing:
    """When the next step is due in wall time: sim time runs ``rtf`` times as fast as wall time from an anchor
    (rtf 0: unpaced). ROS-free; no value of rtf >= 0 or time makes it raise."""

    def __init__(self, wall: float, sim: float, rtf: float) -> None:
        self.restart(wall, sim, rtf)

    def restart(self, wall: float, sim: float, rtf: float) -> None:
        """Anchor at (wall, sim): after a change of rate, pause, reset or lockstep, nothing is owed or ahead."""
        self.wall, self.sim, self.rtf = wall, sim, rtf

    def wait(self, wall: float, sim: float) -> float:
        """Wall seconds (> 0) until sim time ``sim`` is due, or <= 0 if it is due now. More than MAX_PACING_LAG_S
        behind, the anchor moves to now: a slow stretch is not caught up later."""
        if self.rtf <= 0:
            return 0.0
        ahead = sim - self.sim
        due = self.wall + ahead / self.rtf if ahead > 0 else self.wall  # inf for a tiny rtf: waits, never raises
        wait = due - wall
        if wait < -MAX_PACING_LAG_S:
            self.restart(wall, sim, self.rtf)
            return 0.0
        return wait
