"""The window without ROS: messages are queued as the subscriber would queue them and the timer drains them."""
import pytest

from rqt_console.console_widget import ConsoleWidget
from rqt_console.filters import MessageFilter, NodeFilter
from rqt_console.log_record import INFO, WARN, LogRecord


def record(text, severity=INFO, node="/n", topics=("/rosout",)):
    return LogRecord(text, severity, node, (1700000000, 0), topics, "f.py:g:1")


@pytest.fixture
def console(qtbot):
    widget = ConsoleWidget([], subscribe=False)
    qtbot.addWidget(widget)
    yield widget
    widget.shutdown()


def test_timer_moves_queued_messages_into_the_table(console, qtbot):
    # rqt_console opens with a severity exclude filter and a message highlight filter (restore_settings)
    assert [f.kind for f in console.proxy.exclude.filters] == ["severity"]
    assert [f.kind for f in console.proxy.highlight.filters] == ["message"]
    for i in range(250):
        console.queue.put(record("m%d" % i))
    qtbot.waitUntil(lambda: console.model.rowCount() == 250, timeout=2000)
    assert console.status_label.text() == "Displaying 250 messages"
    assert console.model.record(0).message == "m249" and console.model.record(0).number == 250


def test_pause_drops_and_resume_takes_again(console):
    console.pause_button.click()
    assert console.pause_button.text() == "Resume"
    console.queue.put(record("lost"))
    console.pause_button.click()
    console.queue.put(record("kept"))
    console.drain()
    assert [r.message for r in console.model.records()] == ["kept"]


def test_filter_rows_edit_the_filters(console):
    console.queue.put(record("Oh no! I hit the wall!", WARN, "/turtlesim", ("/rosout", "/turtle1/pose")))
    console.queue.put(record("hello", INFO, "/talker"))
    console.drain()
    severity_row = console.exclude_panel.rows[0]
    assert [severity_row.choices.item(i).text() for i in range(5)] == ["Debug", "Info", "Warn", "Error", "Fatal"]
    severity_row.check(WARN)
    assert [r.message for r in console.proxy.visible_records()] == ["hello"]
    console.exclude_panel.remove_row(severity_row)
    exclude_row = console.exclude_panel.add_filter(MessageFilter)
    exclude_row.text_edit.setText("hello")
    assert [r.message for r in console.proxy.visible_records()] == ["Oh no! I hit the wall!"]
    assert console.status_label.text() == "Displaying 1 of 2 messages"
    exclude_row.enabled_box.setChecked(False)
    assert console.proxy.rowCount() == 2
    node_row = console.exclude_panel.add_filter(NodeFilter)
    assert sorted(node_row.choices.item(i).text() for i in range(node_row.choices.count())) == ["/talker", "/turtlesim"]
    node_row.check("/turtlesim")
    assert [r.message for r in console.proxy.visible_records()] == ["hello"]
    console.exclude_panel.remove_row(node_row)
    assert console.proxy.rowCount() == 2
    regex_row = console.highlight_panel.rows[0]
    regex_row.regex_box.setChecked(True)
    regex_row.text_edit.setText("wall!$")
    console.highlighted_only_box.setChecked(True)
    assert [r.message for r in console.proxy.visible_records()] == ["Oh no! I hit the wall!"]


def test_save_then_load_gives_the_same_messages_and_pauses(console, tmp_path):
    for i in range(5):
        console.queue.put(record('line "%d"\nsecond' % i, WARN if i % 2 else INFO))
    console.drain()
    path = str(tmp_path / "log.csv")
    assert console.save_to(path) == 5
    saved = console.model.records()
    console.clear()
    assert console.model.rowCount() == 0
    assert console.load_from(path) == 5
    assert console.pause_button.isChecked()
    loaded = console.model.records()
    assert [(r.message, r.severity, r.node, r.stamp, r.topics, r.location) for r in loaded] == [
        (r.message, r.severity, r.node, r.stamp, r.topics, r.location) for r in saved
    ]


def test_limit_box_and_command_line(qtbot, console):
    console.queue.put(record("a"))
    console.queue.put(record("b"))
    console.drain()
    console.limit_box.setValue(1)
    assert [r.message for r in console.model.records()] == ["b"]
    small = ConsoleWidget(["--limit", "3"], subscribe=False)
    qtbot.addWidget(small)
    assert small.model.limit == 3 and small.limit_box.value() == 3
    small.shutdown()
    with pytest.raises(SystemExit):
        ConsoleWidget(["--limit", "0"], subscribe=False)
