"""sensors.trigger: a triggered camera's frames taken and sent in sim time only, as GazeboRosTriggeredCamera's counted
triggers (gazebo_ros_pkgs gazebo_plugins/src/gazebo_ros_triggered_camera.cpp: TriggerCamera, PreRender, OnNewFrame)
and gazebo-classic's one update per sim time (gazebo/sensors/Sensor.cc, Sensor::Update) have them."""
from __future__ import annotations

from typing import Dict, List, Sequence, Tuple

from hypothesis import given
from hypothesis import strategies as st

from turtle_sim_ode.sensors.trigger import TRIGGERED_FRAME_DELAY_S, TriggeredFrames

STEP_MS = 1  # the physics step (ms), ODE's and Gazebo's default max_step_size
CLOCK_MS = 10  # a /clock message every 10 ms of sim time (pub_clock_frequency 100 Hz)


def run(arrivals_ms: Sequence[float], until_ms: int, delay: float = TRIGGERED_FRAME_DELAY_S) -> Dict[int, int]:
    """Triggers reaching the simulator at ``arrivals_ms`` (sim time, ms, between steps), stepped every STEP_MS up to
    ``until_ms``: {step (ms) a frame was sent: the step it was taken}. Invariants checked at each step."""
    frames: TriggeredFrames[int] = TriggeredFrames(delay)
    pending = sorted(arrivals_ms)
    sent: Dict[int, int] = {}
    taken: List[int] = []
    for now_ms in range(0, until_ms + 1, STEP_MS):
        while pending and pending[0] < now_ms:
            frames.trigger()
            pending.pop(0)
        for stamp_ms in frames.due(now_ms / 1000.0):
            assert now_ms not in sent, "two frames sent at one step"
            sent[now_ms] = stamp_ms
        if frames.take():
            taken.append(now_ms)
            frames.hold(now_ms / 1000.0, now_ms)
        triggered = len(arrivals_ms) - len(pending)
        assert len(taken) <= triggered  # no frame without its trigger
        assert sorted(sent.values()) == taken[: len(sent)]  # sent oldest first
    return sent


def test_no_trigger_no_frame() -> None:
    assert run([], 1000) == {}


def test_a_frame_is_stamped_at_the_step_after_its_trigger_and_sent_the_delay_later() -> None:
    delay_ms = round(TRIGGERED_FRAME_DELAY_S * 1000)
    assert run([100.5], 1000) == {101 + delay_ms: 101}


def test_two_triggers_before_a_step_give_frames_at_two_steps() -> None:
    """Gazebo renders once per sim time (Sensor::Update), so the second counted trigger waits for the next step."""
    delay_ms = round(TRIGGERED_FRAME_DELAY_S * 1000)
    assert run([100.2, 100.4], 1000) == {101 + delay_ms: 101, 102 + delay_ms: 102}


def upstream_test_counts(lag_a_ms: float, lag_b_ms: float) -> Tuple[int, int]:
    """gazebo_plugins/test/camera/triggered_camera.cpp, cameraSubscribeTest after its first frame: trigger A sent as
    the test's clock reads tick c, trigger B at tick c + 10 ms (its 10 ms sleep), each reaching the simulator
    ``lag`` later; frames are looked for at c + 10 (the spinOnce after B), at c + 20 and then every 100 ms up to 10
    times while fewer than two of them were seen; a frame sent at a tick's step is seen at that tick's look (its
    /clock goes out after it). Returns (frames seen at the look after B, frames seen at the look ending the loop)."""
    tick = 1000
    sent = sorted(run([tick + lag_a_ms, tick + CLOCK_MS + lag_b_ms], tick + 2000))
    after_b = sum(1 for at in sent if at <= tick + CLOCK_MS)
    if after_b:
        return after_b, after_b
    for look in [tick + 2 * CLOCK_MS + 100 * k for k in range(10)]:
        seen = sum(1 for at in sent if at <= look)
        if seen:
            return 0, seen
    return 0, 0


def test_the_upstream_tests_two_triggers_arrive_together() -> None:
    """Its EXPECT_EQ(images_received_, 3): both frames at one look, none at the look right after trigger B."""
    assert upstream_test_counts(0.5, 0.5) == (0, 2)
    assert upstream_test_counts(0.5, 9.0) == (0, 2)


@given(lag_a_ms=st.floats(0.0, 59.0), lag_b_ms=st.floats(0.0, 59.0))
def test_the_upstream_tests_frames_arrive_together_whatever_the_lags(lag_a_ms: float, lag_b_ms: float) -> None:
    """Whatever the triggers' lags up to 59 ms of sim time (trigger B no earlier than A), as the delay's comment
    promises; rendering's speed does not enter."""
    lag_b_ms = max(lag_b_ms, lag_a_ms - CLOCK_MS)
    assert upstream_test_counts(lag_a_ms, lag_b_ms) == (0, 2)


@given(
    arrivals_ms=st.lists(st.floats(0.0, 500.0, exclude_min=True), max_size=40),
    delay_ms=st.integers(STEP_MS, 200),  # a frame goes out at a step after the one that took it
)
def test_every_trigger_gets_one_frame_a_step_sent_its_delay_after_its_stamp(
    arrivals_ms: List[float], delay_ms: int
) -> None:
    sent = run(arrivals_ms, 1000, delay_ms / 1000.0)
    assert len(sent) == len(arrivals_ms)  # a frame a trigger (all sent by 500 + 40 + 200 ms)
    stamps = sorted(sent.values())
    assert len(set(stamps)) == len(stamps)  # at most one frame a step
    for arrival, stamp in zip(sorted(arrivals_ms), stamps):
        assert stamp > arrival  # taken at a step after its trigger
    for at, stamp in sent.items():
        assert at == stamp + delay_ms  # sent at the first step its delay after the stamp
