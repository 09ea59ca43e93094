"""The widget on a fake master: the query runs in a worker thread (a hanging one never blocks the Qt thread),
options redraw, dead nodes are red, the three save formats."""
import threading

from fake_state import turtlesim_session
from python_qt_binding.QtGui import QColor, QImage

from rqt_graph.graph_model import NODES_TOPICS_ACTIVE
from rqt_graph.graph_view import DEAD, INCOMING, OUTGOING
from rqt_graph.graph_widget import GraphWidget


def make_widget(qtbot, query):
    widget = GraphWidget([], query=query)
    qtbot.addWidget(widget)
    widget.resize(900, 500)
    widget.show()
    return widget


def test_snapshot_from_the_worker_is_drawn(qtbot):
    threads = []

    def query():
        threads.append(threading.current_thread())
        return turtlesim_session()

    widget = make_widget(qtbot, query)
    qtbot.waitUntil(lambda: widget.state is not None)
    assert threads[0] is not threading.main_thread()
    assert set(widget.vertex_items) == {"n_/turtlesim", "n_/teleop_turtle", "n_/ghost", "n_/listener"}
    assert widget.status.text() == "4 nodes, 0 topics, 1 connections, 1 dead"
    ghost = widget.vertex_items["n_/ghost"]
    assert not ghost.alive and ghost._shape.pen().color() == DEAD
    widget.shutdown()


def test_options_redraw_without_asking_the_master_again(qtbot):
    calls = []
    widget = make_widget(qtbot, lambda: calls.append(1) or turtlesim_session())
    qtbot.waitUntil(lambda: widget.state is not None)
    widget.mode_box.setCurrentIndex(widget.mode_box.findData(NODES_TOPICS_ACTIVE))
    assert "t_/turtle1/cmd_vel" in widget.vertex_items
    widget.debug_box.setChecked(False)
    assert "n_/rosout" in widget.vertex_items
    assert calls == [1]
    widget.refresh()
    qtbot.waitUntil(lambda: len(calls) == 2)
    widget.shutdown()


def test_hover_highlights_connections(qtbot):
    widget = make_widget(qtbot, turtlesim_session)
    qtbot.waitUntil(lambda: widget.state is not None)
    teleop, turtlesim = widget.vertex_items["n_/teleop_turtle"], widget.vertex_items["n_/turtlesim"]
    teleop.set_highlighted(True)
    assert teleop.outgoing[0]._line.pen().color() == OUTGOING
    assert turtlesim.incoming[0] is teleop.outgoing[0]
    teleop.set_highlighted(False)
    turtlesim.set_highlighted(True)
    assert turtlesim.incoming[0]._line.pen().color() == INCOMING
    widget.shutdown()


def test_a_hanging_master_query_leaves_the_window_responsive(qtbot):
    release = threading.Event()

    def query():
        release.wait(10)
        return turtlesim_session()

    widget = make_widget(qtbot, query)
    qtbot.wait(200)  # the Qt loop runs while the query hangs
    assert widget.state is None and widget.status.text() == "querying the master..."
    release.set()
    qtbot.waitUntil(lambda: widget.state is not None)
    widget.shutdown()


def test_master_failure_is_reported(qtbot):
    def query():
        raise ConnectionRefusedError("[Errno 111] Connection refused")

    widget = make_widget(qtbot, query)
    qtbot.waitUntil(lambda: "cannot reach" in widget.status.text())
    assert widget.status.text() == "cannot reach the ROS master: [Errno 111] Connection refused"
    widget.shutdown()


def test_save_dot_svg_and_png(qtbot, tmp_path):
    widget = make_widget(qtbot, turtlesim_session)
    qtbot.waitUntil(lambda: widget.state is not None)
    widget.save_dot(str(tmp_path / "g.dot"))
    widget.save_svg(str(tmp_path / "g.svg"))
    widget.save_image(str(tmp_path / "g.png"))
    assert (tmp_path / "g.dot").read_text().startswith("digraph rosgraph {")
    assert "<svg" in (tmp_path / "g.svg").read_text() and "/teleop_turtle" in (tmp_path / "g.svg").read_text()
    image = QImage(str(tmp_path / "g.png"))
    assert not image.isNull() and image.width() > 100
    reds = sum(
        1
        for x in range(0, image.width(), 2)
        for y in range(0, image.height(), 2)
        if QColor(image.pixel(x, y)).red() > 200 and QColor(image.pixel(x, y)).green() < 80
    )
    assert reds > 0  # the dead node's outline
    widget.shutdown()


def test_unknown_options_are_refused():
    import pytest

    with pytest.raises(SystemExit):
        GraphWidget(["--no-such-option"], query=turtlesim_session)
