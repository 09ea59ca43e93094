"""Per-step work removed for issue #33, checked to leave behaviour as it was: the node's count of quiet steps (none of
them due, the due step never skipped), diff_drive_controller's odometry velocities worked out when read (the rolling
means of odometry.cpp's Odometry::update), and the Kobuki's events read only while someone listens."""
from __future__ import annotations

from types import SimpleNamespace
from typing import List

from hypothesis import given
from hypothesis import strategies as st

from turtle_sim_ode.control.diff_drive import Odometry
from turtle_sim_ode.ros import node
from turtle_sim_ode.ros.plugins import kobuki
from turtle_sim_ode.sensors.kobuki import report_changes

DUE_TOLERANCE_S = 1e-9  # Periodic.publish_due: due from due - 1e-9 s on


def first_due_step(base: float, steps: int, time_step: float, due: float) -> int:
    """How many steps after step ``steps`` the first one comes whose sim time (PhysicsWorld.sim_time: base + steps *
    time_step) is due."""

    def is_due(later: int) -> bool:
        return base + (steps + later) * time_step >= due - DUE_TOLERANCE_S

    later = max(1, int((due - base) / time_step) - steps - 2)  # near it, then step by step to the first
    while later > 1 and is_due(later - 1):
        later -= 1
    while not is_due(later):
        later += 1
    return later


@given(
    base=st.sampled_from([0.0, 0.5, 12.345]),
    steps=st.integers(0, 10**6),
    time_step=st.sampled_from([1e-3, 1e-2, 4e-3, 1e-4, 1e-7]),
    rate=st.sampled_from([100.0, 50.0, 30.0, 10.0, 7.0]),
    periods=st.integers(1, 3),
)
def test_quiet_steps_end_before_the_due_step_and_never_pass_it(base, steps, time_step, rate, periods):
    """The due time is a sum of periods from the step's time, as Periodic schedules it."""
    now = base + steps * time_step
    due = now
    for _ in range(periods):
        due = due + 1.0 / rate
    quiet = node.quiet_steps(now, due, time_step)
    due_step = first_due_step(base, steps, time_step, due)
    assert quiet < due_step  # none of the quiet steps is due
    if abs((due - now) / time_step - round((due - now) / time_step)) < 1e-6:
        assert quiet == due_step - 1  # a whole number of steps away: _advance's step is the due one


def test_quiet_steps_at_1_ms_and_100_hz_leave_one_step_to_advance():
    """0.01 / 0.001 is 9.999...: truncated, it left two steps (a loop turn with nothing due)."""
    for steps in range(0, 100000, 10):
        now = steps * 0.001
        assert node.quiet_steps(now, now + 0.01, 0.001) == 9


def rolling_means(updates, window: int):
    """odometry.cpp's Odometry::update, velocities kept as a list: the mean of the last ``window`` estimates."""
    linear: List[float] = []
    angular: List[float] = []
    left_old, right_old, stamp = updates[0][0], updates[0][1], 0.0
    for left, right, separation, time in updates:
        d_left, d_right = left - left_old, right - right_old
        left_old, right_old = left, right
        dt = time - stamp
        if dt < 0.0001:
            continue
        stamp = time
        linear.append((d_right + d_left) * 0.5 / dt)
        angular.append((d_right - d_left) / separation / dt)
    if not linear:
        return 0.0, 0.0
    return sum(linear[-window:]) / len(linear[-window:]), sum(angular[-window:]) / len(angular[-window:])


@given(
    window=st.integers(1, 12),
    moves=st.lists(
        st.tuples(st.floats(-0.05, 0.05), st.floats(-0.05, 0.05), st.sampled_from([0.0, 0.00005, 0.001, 0.02])),
        min_size=1,
        max_size=40,
    ),
)
def test_odometry_velocities_are_the_rolling_means_of_the_estimates(window, moves):
    odometry = Odometry(window)
    updates, left, right, time = [], 0.0, 0.0, 0.0
    for d_left, d_right, dt in moves:
        left, right, time = left + d_left, right + d_right, time + dt
        updates.append((left, right, 0.23, time))
        odometry.update(left, right, 0.23, time)
        assert (odometry.linear, odometry.angular) == rolling_means(updates, window)


def test_open_loop_odometry_reports_the_commanded_velocities():
    odometry = Odometry(10)
    odometry.update_open_loop(0.4, -0.2, 0.01)
    assert (odometry.linear, odometry.angular) == (0.4, -0.2)
    odometry.reset(0.0)
    assert (odometry.linear, odometry.angular) == (0.0, 0.0)


class FakePublisher:
    """A rospy publisher whose subscribers the test sets (rospy keeps them in impl.connections)."""

    def __init__(self, topic, msg_type, queue_size):
        self.impl = SimpleNamespace(connections=[])
        self.sent = []

    def publish(self, message):
        self.sent.append(message)


class FakeBumper:
    """A sensor whose state the test sets; counts its readings."""

    def __init__(self):
        self.pressed = [False, False, False]
        self._reported = [False, False, False]
        self.readings = 0

    def changes(self):
        self.readings += 1
        return report_changes(self._reported, self.pressed, 1, 0)

    def close(self):
        pass


def events_and_core(monkeypatch):
    monkeypatch.setattr(kobuki, "publisher", FakePublisher)
    core = SimpleNamespace(pub=FakePublisher("core", None, 10))
    sensor = FakeBumper()
    events = kobuki.BumperEventPublisher(sensor, "events/bumper", 50.0, lambda: bool(core.pub.impl.connections))
    return events, core, sensor


def test_kobuki_events_read_their_sensor_only_while_someone_listens(monkeypatch):
    events, core, sensor = events_and_core(monkeypatch)
    events.publish(None, 0.0)
    assert sensor.readings == 0  # nobody listens: not read
    core.pub.impl.connections.append("core subscriber")
    events.publish(None, 0.02)
    assert sensor.readings == 1  # sensors/core reports what the events last read
    core.pub.impl.connections.clear()
    events._pub.impl.connections.append("events subscriber")
    sensor.pressed[1] = True
    events.publish(None, 0.04)
    assert [(m.bumper, m.state) for m in events._pub.sent] == [(1, 1)]


def test_a_change_made_while_nobody_listened_is_told_at_the_first_reading(monkeypatch):
    """As documented in the README: a change is one from the state last read."""
    events, _core, sensor = events_and_core(monkeypatch)
    sensor.pressed[0] = True
    events.publish(None, 0.0)
    events._pub.impl.connections.append("late subscriber")
    events.publish(None, 0.02)
    events.publish(None, 0.04)
    assert [(m.bumper, m.state) for m in events._pub.sent] == [(0, 1)]
