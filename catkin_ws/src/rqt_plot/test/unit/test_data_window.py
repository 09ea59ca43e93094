"""The bounded data window: a series keeps the newest `capacity` points in order, whatever the batches; points
pushed from other threads all arrive, in each thread's order."""
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rqt_plot.data_window import DataWindow, Series


@settings(max_examples=300, deadline=None)
@given(capacity=st.integers(2, 40), batches=st.lists(st.integers(0, 100), max_size=30))
def test_series_keeps_the_newest_points_after_every_batch(capacity, batches):
    series, everything, counter = Series(capacity), [], 0
    for size in batches:
        xs = np.arange(counter, counter + size, dtype=float)
        counter += size
        series.extend(xs, -xs)
        everything.extend(xs)
        expected = everything[-capacity:]
        assert series.x().tolist() == expected
        assert series.y().tolist() == [-x for x in expected]
        assert len(series) == len(expected) <= capacity


def test_series_capacity_must_hold_a_line():
    with pytest.raises(ValueError):
        Series(1)


def test_ten_minutes_of_three_fields_at_62_5_hz_stay_bounded():
    window = DataWindow(capacity=20000)
    for name in "xyz":
        window.add(name)
    for tick in range(int(600 * 62.5)):
        for name in "xyz":
            window.push(name, tick / 62.5, float(tick))
        if tick % 3 == 0:
            window.drain()
    window.drain()
    for name in "xyz":
        series = window.series[name]
        assert len(series) == 20000
        assert series.x()[-1] == pytest.approx((600 * 62.5 - 1) / 62.5)
        assert np.all(np.diff(series.x()) > 0)
    assert window.latest_x() == pytest.approx((600 * 62.5 - 1) / 62.5)


def test_pushes_from_threads_all_arrive_in_order():
    window = DataWindow(capacity=100000)
    window.add("a")
    window.add("b")

    def publish(name):
        for i in range(5000):
            window.push(name, float(i), float(i))

    threads = [threading.Thread(target=publish, args=(name,)) for name in "ab"]
    for thread in threads:
        thread.start()
    drained = {"a": 0, "b": 0}
    while any(thread.is_alive() for thread in threads):
        for name in window.drain():
            drained[name] += 1
    for thread in threads:
        thread.join()
    window.drain()
    for name in "ab":
        assert window.series[name].x().tolist() == [float(i) for i in range(5000)]


def test_clear_and_remove():
    window = DataWindow(capacity=10)
    window.add("a")
    window.push("a", 1.0, 1.0)
    window.drain()
    window.push("a", 2.0, 2.0)
    window.clear()
    assert window.drain() == [] and len(window.series["a"]) == 0
    window.remove("a")
    window.push("a", 3.0, 3.0)  # a subscriber still delivering for a removed curve
    assert window.drain() == [] and "a" not in window.series
