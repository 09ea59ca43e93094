"""The table and its proxy: columns as rqt_console's MessageDataModel (#, Message, Severity, Node, Stamp, Topics,
Location), severity colours from MessageDataModel.severity_colors, a buffer limit of 20,000 by default that drops
the oldest, newest on top; exclude hides, highlight greys out the rest (MessageProxyModel)."""
import time
from types import SimpleNamespace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from python_qt_binding.QtCore import Qt

from rqt_console.filters import MessageFilter, SeverityFilter
from rqt_console.log_model import DEFAULT_LIMIT, DIMMED, LogFilterProxy, LogTableModel
from rqt_console.log_record import DEBUG, ERROR, FATAL, INFO, WARN, LogRecord


def record(text, severity=INFO, node="/n"):
    return LogRecord(text, severity, node, (1700000000, 0), ("/rosout",), "f.py:g:1")


def test_from_a_rosgraph_log_message():
    log = SimpleNamespace(
        msg="Oh no! I hit the wall!",
        level=4,
        name="/turtlesim",
        topics=["/turtle1/pose", "/rosout"],
        header=SimpleNamespace(stamp=SimpleNamespace(secs=5, nsecs=7)),
        file="world.py",
        function="update",
        line=3,
    )
    made = LogRecord.from_log(log)
    assert (made.message, made.severity, made.node, made.stamp) == (
        "Oh no! I hit the wall!",
        WARN,
        "/turtlesim",
        (5, 7),
    )
    assert made.topics == ("/rosout", "/turtle1/pose") and made.location == "world.py:update:3"


@pytest.fixture
def utc(monkeypatch):
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    yield
    monkeypatch.undo()
    time.tzset()


def test_columns_text_and_colours(qtmodeltester, utc):
    model = LogTableModel()
    assert model.limit == DEFAULT_LIMIT == 20000
    assert [model.headerData(c, Qt.Horizontal) for c in range(7)] == [
        "#",
        "Message",
        "Severity",
        "Node",
        "Stamp",
        "Topics",
        "Location",
    ]
    model.insert_records([record("first", DEBUG), record("second", WARN)])
    qtmodeltester.check(model)
    assert [model.data(model.index(0, c)) for c in (0, 1, 2, 3, 5, 6)] == [
        "#2",
        "second",
        "Warn",
        "/n",
        "/rosout",
        "f.py:g:1",
    ]
    # rqt_console's stamp format 'hh:mm:ss.ZZZ (yyyy-MM-dd)', ZZZ the nanoseconds in 9 digits (Message.stamp)
    assert model.data(model.index(0, 4)) == "22:13:20.000000000 (2023-11-14)"
    colours = {}
    for severity in (DEBUG, INFO, WARN, ERROR, FATAL):
        model.insert_records([record("x", severity)])
        colours[severity] = model.data(model.index(0, 2), Qt.ForegroundRole).color()
    assert colours == {DEBUG: Qt.darkCyan, INFO: Qt.darkBlue, WARN: Qt.darkYellow, ERROR: Qt.darkRed, FATAL: Qt.red}


@settings(max_examples=100, deadline=None)
@given(limit=st.integers(1, 30), batches=st.lists(st.integers(0, 40), max_size=12))
def test_buffer_limit_keeps_the_newest_after_every_batch(limit, batches):
    model, sent = LogTableModel(limit), 0
    for size in batches:
        model.insert_records([record("m%d" % (sent + i)) for i in range(size)])
        sent += size
        assert model.rowCount() == min(sent, limit)
        shown = [model.record(row).message for row in range(model.rowCount())]
        assert shown == ["m%d" % i for i in reversed(range(sent - model.rowCount(), sent))]


def test_lowering_the_limit_drops_the_oldest_and_clear_restarts_numbering():
    model = LogTableModel(10)
    model.insert_records([record("m%d" % i) for i in range(10)])
    model.set_limit(3)
    assert [r.message for r in model.records()] == ["m7", "m8", "m9"]
    with pytest.raises(ValueError):
        model.set_limit(0)
    model.clear()
    model.insert_records([record("again")])
    assert model.record(0).number == 1 and model.rowCount() == 1


def test_exclude_hides_and_highlight_greys_the_rest(qtmodeltester):
    model = LogTableModel()
    proxy = LogFilterProxy(model)
    model.insert_records([record("wall hit", WARN, "/turtlesim"), record("hello", INFO), record("debug", DEBUG)])
    proxy.exclude.filters.append(SeverityFilter({DEBUG}))
    proxy.filters_changed()
    qtmodeltester.check(proxy)
    assert [r.message for r in proxy.visible_records()] == ["hello", "wall hit"]
    proxy.highlight.filters.append(MessageFilter("wall"))
    proxy.filters_changed()
    assert proxy.data(proxy.index(0, 1), Qt.ForegroundRole) is DIMMED  # "hello"
    assert proxy.data(proxy.index(1, 1), Qt.ForegroundRole) is None
    assert proxy.data(proxy.index(1, 2), Qt.ForegroundRole).color() == Qt.darkYellow
    proxy.set_highlighted_only(True)
    assert [r.message for r in proxy.visible_records()] == ["wall hit"]
    model.insert_records([record("another wall"), record("not shown")])
    assert [r.message for r in proxy.visible_records()] == ["another wall", "wall hit"]
