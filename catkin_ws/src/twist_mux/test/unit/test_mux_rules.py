"""The core of the twist_mux drop-in (src/mux_core.cpp, driven through test/replay_mux) against a model of
upstream's rules (ros-teleop/twist_mux 3.1.3, noetic-devel), on generated input schedules (Hypothesis).

The rules, from upstream's topic_handle.h and twist_mux.cpp: an input has expired when its timeout is > 0 and more
than the timeout has passed since its last message (initially at time 0: TopicHandle_::hasExpired); a lock holds
while its last Bool was true or while it has expired (LockTopicHandle::isLocked); the lock priority is the highest
priority of the holding locks, else 0 (TwistMux::getLockPriority); a velocity input is masked when expired or
below the lock priority (VelocityTopicHandle::isMasked); a command is published when its input is the first
unmasked input of highest priority, priorities counting from above 0 (TwistMux::hasPriority).
"""
from __future__ import annotations

import subprocess
from typing import List, Tuple

import pytest
from catkin.find_in_workspaces import find_in_workspaces
from hypothesis import given, settings
from hypothesis import strategies as st


def replay_binary() -> str:
    found = find_in_workspaces(["libexec"], project="twist_mux", path="replay_mux", first_match_only=True)
    if not found:
        pytest.fail("replay_mux not built: run scripts/build.sh and source the workspace")
    return found[0]


class Model:
    """Upstream's rules on plain lists: (priority, timeout) per input, the last stamp and lock value."""

    def __init__(self, velocities: List[Tuple[int, float]], locks: List[Tuple[int, float]]) -> None:
        self.velocities, self.locks = velocities, locks
        self.velocity_stamps = [0.0] * len(velocities)
        self.lock_stamps = [0.0] * len(locks)
        self.lock_values = [False] * len(locks)

    @staticmethod
    def expired(timeout: float, stamp: float, now: float) -> bool:
        return timeout > 0.0 and now - stamp > timeout

    def lock_priority(self, now: float) -> int:
        holding = [
            priority
            for (priority, timeout), stamp, value in zip(self.locks, self.lock_stamps, self.lock_values)
            if value or self.expired(timeout, stamp, now)
        ]
        return max(holding, default=0)

    def eligible(self, now: float) -> List[int]:
        """The inputs whose commands may pass: fresh, not below the lock priority, of priority above 0."""
        lock_priority = self.lock_priority(now)
        return [
            index
            for index, ((priority, timeout), stamp) in enumerate(zip(self.velocities, self.velocity_stamps))
            if not self.expired(timeout, stamp, now) and priority >= lock_priority and priority > 0
        ]

    def selected(self, now: float) -> int:
        eligible = self.eligible(now)
        if not eligible:
            return -1
        best = max(self.velocities[i][0] for i in eligible)
        return next(i for i in eligible if self.velocities[i][0] == best)


def replay(velocities, locks, events) -> List[Tuple[str, int, int]]:
    lines = ["velocity %d %r" % spec for spec in velocities] + ["lock %d %r" % spec for spec in locks]
    for kind, index, value, now in events:
        lines.append("v %d %r" % (index, now) if kind == "v" else "l %d %d %r" % (index, value, now))
    result = subprocess.run(
        [replay_binary()], input="\n".join(lines) + "\n", stdout=subprocess.PIPE, universal_newlines=True, check=True
    )
    answers = []
    for line in result.stdout.splitlines():
        forwarded, selected, lock_priority = line.split()
        answers.append((forwarded, int(selected), int(lock_priority)))
    return answers


def check(velocities, locks, events) -> None:
    model = Model(velocities, locks)
    answers = replay(velocities, locks, events)
    assert len(answers) == len(events)
    for (kind, index, value, now), (forwarded, selected, lock_priority) in zip(events, answers):
        if kind == "v":
            model.velocity_stamps[index] = now
        else:
            model.lock_stamps[index], model.lock_values[index] = now, bool(value)
        assert lock_priority == model.lock_priority(now)
        assert selected == model.selected(now), (kind, index, now)
        if kind == "v":
            # the output is always the command of the highest-priority unlocked unexpired input
            assert (forwarded == "1") == (index == selected)
        if selected >= 0:
            eligible = model.eligible(now)
            assert all(velocities[selected][0] >= velocities[i][0] for i in eligible)
            assert all(velocities[selected][0] > velocities[i][0] for i in eligible if i < selected)


def test_upstream_system_test_schedule():
    """upstream test/system_config.yaml's inputs and locks (input1 5 @ 0.7 s, input2 1 @ none, input3 10 @ 0.3 s;
    emergency_255 @ 0.5 s, emergency_10 @ none), on the beats of its system_blackbox.py cases."""
    velocities = [(5, 0.7), (1, 0.0), (10, 0.3)]
    locks = [(255, 0.5), (10, 0.0)]
    events = [("l", 0, 0, 1.0), ("v", 1, 0, 1.0), ("v", 0, 0, 1.1), ("v", 1, 0, 1.2), ("v", 2, 0, 1.3)]
    events += [("v", 0, 0, 1.4), ("l", 1, 1, 1.5), ("v", 2, 0, 1.5), ("v", 0, 0, 1.55), ("l", 1, 0, 1.6)]
    events += [("l", 0, 0, 1.9), ("v", 0, 0, 2.0), ("l", 0, 0, 2.9), ("v", 1, 0, 3.0), ("v", 0, 0, 3.6)]
    answers = replay(velocities, locks, events)
    # at 1.55 and 3.6 emergency_255 has been silent for more than 0.5 s: it holds, and masks everything
    expected = ["-", "1", "1", "0", "1", "0", "-", "1", "0", "-", "-", "1", "-", "1", "0"]
    assert [a[0] for a in answers] == expected
    check(velocities, locks, events)


priorities = st.one_of(st.sampled_from([0, 1, 10, 100, 255]), st.integers(0, 255))
timeouts = st.sampled_from([0.0, 0.1, 0.25, 0.3, 0.5, 1.0])
steps = st.one_of(st.sampled_from([0.0, 0.05, 0.1, 0.25, 0.3, 0.5]), st.floats(0.0, 1.2))


@st.composite
def schedules(draw):
    velocities = draw(st.lists(st.tuples(priorities, timeouts), min_size=1, max_size=5))
    locks = draw(st.lists(st.tuples(priorities, timeouts), max_size=3))
    now, events = 0.0, []
    for _ in range(draw(st.integers(1, 40))):
        now += draw(steps)
        if locks and draw(st.booleans()) and draw(st.booleans()):
            events.append(("l", draw(st.integers(0, len(locks) - 1)), int(draw(st.booleans())), now))
        else:
            events.append(("v", draw(st.integers(0, len(velocities) - 1)), 0, now))
    return velocities, locks, events


@settings(max_examples=150, deadline=None, derandomize=True)
@given(schedules())
def test_generated_schedules(schedule):
    check(*schedule)
