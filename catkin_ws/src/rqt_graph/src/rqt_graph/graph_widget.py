"""The rqt_graph widget: controls as the real one's (refresh, mode, filters, group, highlight, fit, hide, save) over
a graphics view. The master is queried in a worker thread; its snapshot reaches the widgets through a Qt signal
(queued into the Qt thread), so a hanging node never freezes the window."""
from __future__ import annotations

import argparse
import queue
import threading
from typing import Callable, List, Optional

from python_qt_binding.QtCore import QObject, Qt, Signal
from python_qt_binding.QtGui import QImage, QPainter
from python_qt_binding.QtWidgets import (
    QCheckBox,
    QComboBox,
    QFileDialog,
    QGraphicsScene,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from rqt_graph.dot_layout import lay_out, run_dot, to_dot, to_pydot
from rqt_graph.graph_model import MODES, Graph, GraphOptions, SystemState, build_graph
from rqt_graph.graph_view import GraphView, draw, text_width


class StateFetcher(QObject):
    """Runs ``query()`` in a thread of its own on request; the result arrives as a signal in the Qt thread."""

    fetched = Signal(object)
    failed = Signal(str)

    def __init__(self, query: Callable[[], SystemState]):
        super().__init__()
        self._query = query
        self._requests: "queue.Queue[bool]" = queue.Queue()
        self._thread = threading.Thread(target=self._serve, name="rqt_graph query", daemon=True)
        self._thread.start()

    def request(self) -> None:
        self._requests.put(True)

    def stop(self) -> None:
        self._requests.put(False)
        self._thread.join(timeout=5.0)

    def _serve(self) -> None:
        while self._requests.get():
            while not self._requests.empty():  # refreshes asked for meanwhile: one query answers them all
                if not self._requests.get_nowait():
                    return
            try:
                self.fetched.emit(self._query())
            except Exception as error:  # master down, network trouble: shown, never raised into Qt
                self.failed.emit(str(error) or type(error).__name__)


def _default_query() -> SystemState:
    import rospy

    from rqt_graph.ros_query import query_system_state

    return query_system_state(rospy.get_name())


def parse_arguments(args: List[str]) -> argparse.Namespace:
    """rqt_graph takes no options of its own: --help, and an error for anything else."""
    return argparse.ArgumentParser(prog="rqt_graph", description="The ROS computation graph in a window.").parse_args(
        args
    )


class GraphWidget(QWidget):
    """``GraphWidget(args)``: ``args`` is rqt_graph's command line (it takes no options of its own)."""

    def __init__(self, args: Optional[List[str]] = None, query: Optional[Callable[[], SystemState]] = None):
        super().__init__()
        parse_arguments(args or [])
        self.setObjectName("RosGraph")
        self.setWindowTitle("Node Graph")
        self.state: Optional[SystemState] = None
        self.graph = Graph()
        self.vertex_items = {}
        self._build_controls()
        self._fetcher = StateFetcher(query or _default_query)
        self._fetcher.fetched.connect(self._on_state)
        self._fetcher.failed.connect(self._on_failure)
        self.refresh()

    def _build_controls(self) -> None:
        self.refresh_button = QPushButton("Refresh")
        self.refresh_button.setToolTip("Refresh ROS graph")
        self.mode_box = QComboBox()
        for mode, label in MODES:
            self.mode_box.addItem(label, mode)
        self.node_filter = QLineEdit("/")
        self.node_filter.setToolTip(
            "Namespace filter, comma separated list of names/regexp to include or exclude. " "Example: -/rqt.*"
        )
        self.topic_filter = QLineEdit("/")
        self.topic_filter.setToolTip(
            "Topic filter, comma separated list of names/regexp to include or exclude. " "Example: -/tf"
        )
        self.save_dot_button = QPushButton("Save DOT")
        self.save_svg_button = QPushButton("Save SVG")
        self.save_image_button = QPushButton("Save image")
        self.group_box = self._check("Namespaces", True, "Show namespace boxes")
        self.highlight_box = self._check("Highlight", True, "Highlight incoming and outgoing connections on mouse over")
        self.fit_box = self._check("Fit", True, "Automatically fit graph into view on update")
        self.fit_button = QPushButton("Fit in view")
        self.dead_sinks_box = self._check("Dead sinks", True, "Hide topics without subscribers")
        self.leaf_topics_box = self._check("Leaf topics", True, "Hide topics with one connection only")
        self.debug_box = self._check("Debug", True, "Hide common debugging nodes (/rosout, /rqt*, /clock, ...)")
        self.unreachable_box = self._check("Unreachable", False, "Hide nodes that did not answer (drawn red)")
        self.status = QLabel("querying the master...")
        self.scene = QGraphicsScene(self)
        self.scene.setBackgroundBrush(Qt.white)
        self.view = GraphView(self.scene, self)

        top = QHBoxLayout()
        for widget in (self.refresh_button, self.mode_box, self.node_filter, self.topic_filter):
            top.addWidget(widget)
        top.addStretch(1)
        for widget in (self.save_dot_button, self.save_svg_button, self.save_image_button):
            top.addWidget(widget)
        options = QHBoxLayout()
        options.addWidget(QLabel("Group:"))
        for widget in (
            self.group_box,
            self.highlight_box,
            self.fit_box,
            self.fit_button,
            QLabel("Hide:"),
            self.dead_sinks_box,
            self.leaf_topics_box,
            self.debug_box,
            self.unreachable_box,
        ):
            options.addWidget(widget)
        options.addStretch(1)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(options)
        layout.addWidget(self.view, 1)
        layout.addWidget(self.status)

        self.refresh_button.clicked.connect(self.refresh)
        self.mode_box.currentIndexChanged.connect(self.redraw)
        self.node_filter.editingFinished.connect(self.redraw)
        self.topic_filter.editingFinished.connect(self.redraw)
        for box in (self.group_box, self.dead_sinks_box, self.leaf_topics_box, self.debug_box, self.unreachable_box):
            box.toggled.connect(self.redraw)
        self.highlight_box.toggled.connect(self._set_highlight)
        self.fit_button.clicked.connect(self.view.fit)
        self.save_dot_button.clicked.connect(lambda: self._ask_and_save("DOT graph (*.dot)", self.save_dot))
        self.save_svg_button.clicked.connect(lambda: self._ask_and_save("SVG (*.svg)", self.save_svg))
        self.save_image_button.clicked.connect(lambda: self._ask_and_save("PNG image (*.png)", self.save_image))

    def _check(self, text: str, checked: bool, tip: str) -> QCheckBox:
        box = QCheckBox(text)
        box.setChecked(checked)
        box.setToolTip(tip)
        return box

    def options(self) -> GraphOptions:
        return GraphOptions(
            mode=self.mode_box.currentData(),
            node_filter=self.node_filter.text(),
            topic_filter=self.topic_filter.text(),
            hide_debug=self.debug_box.isChecked(),
            hide_dead_sinks=self.dead_sinks_box.isChecked(),
            hide_leaf_topics=self.leaf_topics_box.isChecked(),
            hide_unreachable=self.unreachable_box.isChecked(),
        )

    def refresh(self) -> None:
        """Ask the master again (in the worker thread)."""
        self.status.setText("querying the master...")
        self._fetcher.request()

    def _on_state(self, state: SystemState) -> None:
        self.state = state
        self.redraw()

    def _on_failure(self, message: str) -> None:
        self.status.setText("cannot reach the ROS master: %s" % message)

    def redraw(self) -> None:
        """Rebuild and lay out the graph from the last snapshot with the current options."""
        if self.state is None:
            return
        self.graph = build_graph(self.state, self.options())
        try:
            layout = lay_out(self.graph, self.group_box.isChecked(), text_width)
        except Exception as error:  # graphviz missing or failing: say so instead of drawing
            self.status.setText("graphviz dot failed: %s" % error)
            return
        self.vertex_items = draw(self.scene, layout, self.graph.nodes, self.group_box.isChecked())
        self._set_highlight(self.highlight_box.isChecked())
        self.scene.setSceneRect(self.scene.itemsBoundingRect().adjusted(-20, -20, 20, 20))
        if self.fit_box.isChecked():
            self.view.fit()
        dead = sum(1 for alive in self.graph.nodes.values() if not alive)
        self.status.setText(
            "%d nodes, %d topics, %d connections%s"
            % (len(self.graph.nodes), len(self.graph.topics), len(self.graph.edges), ", %d dead" % dead if dead else "")
        )

    def _set_highlight(self, on: bool) -> None:
        for item in self.vertex_items.values():
            item.highlight = on

    def save_dot(self, path: str) -> None:
        with open(path, "w") as out:
            out.write(to_dot(self.graph, self.group_box.isChecked()))

    def save_svg(self, path: str) -> None:
        with open(path, "wb") as out:
            out.write(run_dot(to_pydot(self.graph, self.group_box.isChecked()), "svg"))

    def save_image(self, path: str) -> None:
        """The scene as shown, at twice its size in points, as PNG."""
        rect = self.scene.sceneRect()
        image = QImage(int(rect.width() * 2), int(rect.height() * 2), QImage.Format_ARGB32)
        image.fill(Qt.white)
        painter = QPainter(image)
        painter.setRenderHint(QPainter.Antialiasing)
        self.scene.render(painter)
        painter.end()
        image.save(path)

    def _ask_and_save(self, file_filter: str, save: Callable[[str], None]) -> None:
        path, _ = QFileDialog.getSaveFileName(self, "Save as...", "rosgraph", file_filter)
        if path:
            save(path)

    def shutdown(self) -> None:
        self._fetcher.stop()
