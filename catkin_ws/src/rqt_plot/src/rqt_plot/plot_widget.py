"""rqt_plot's window: the Topic box with completion, + and -, autoscroll, pause, clear, and the plot."""
from __future__ import annotations

from typing import Callable, Dict, List, Optional, Sequence, Set

import rospy
from python_qt_binding.QtCore import Qt, QStringListModel, QTimer
from python_qt_binding.QtWidgets import (
    QAction,
    QCheckBox,
    QCompleter,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QMenu,
    QPushButton,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from .data_window import DataWindow
from .fields import completions
from .plot_canvas import PlotCanvas
from .ros_plot_data import TopicSubscriptions, curves_for, load_message_class, published_topic_types
from .topic_args import parse_arguments

REDRAW_INTERVAL_MS = 40  # rqt_plot's PlotWidget._redraw_interval
RETRY_INTERVAL_MS = 1000  # fields named on the command line whose topic is not published yet are tried again


class PlotWidget(QWidget):
    """The plot of the fields named in args_list (rqt_plot's command line without ROS remappings)."""

    def __init__(
        self, args_list: Sequence[str] = (), topic_types: Callable[[], Dict[str, str]] = published_topic_types
    ) -> None:
        super().__init__()
        self.setObjectName("PlotWidget")
        self.setWindowTitle("Plot")  # as rqt_plot's resource/plot.ui
        args = parse_arguments(args_list)
        self._topic_types = topic_types
        self.window = DataWindow(args.buffer_size)
        self.subscriptions = TopicSubscriptions(self.window, rospy.get_time())
        self._pending: List[str] = list(args.topics)
        self._unshown: Set[str] = set()  # curves with points the plot does not show yet

        self.topic_edit = QLineEdit()
        self.topic_edit.setObjectName("topic_edit")
        self.topic_edit.setText("/")
        self._completion_model = QStringListModel()
        completer = QCompleter(self._completion_model, self)
        completer.setCaseSensitivity(Qt.CaseInsensitive)
        self.topic_edit.setCompleter(completer)
        self.add_button = QPushButton("+")
        self.add_button.setToolTip("add topic to plot")
        self.add_button.setEnabled(False)
        self.remove_button = QToolButton()
        self.remove_button.setText("\u2212")
        self.remove_button.setPopupMode(QToolButton.InstantPopup)
        self.remove_menu = QMenu(self)
        self.remove_button.setMenu(self.remove_menu)
        self.autoscroll_checkbox = QCheckBox("autoscroll")
        self.autoscroll_checkbox.setChecked(True)
        self.pause_button = QPushButton("pause")
        self.pause_button.setCheckable(True)
        self.pause_button.setChecked(args.start_paused)
        self.pause_button.setToolTip("pause plot")
        self.clear_button = QPushButton("clear")
        self.clear_button.setToolTip("clear plot")
        self.canvas = PlotCanvas(self)

        controls = QHBoxLayout()
        for widget in (QLabel("Topic"), self.topic_edit, self.add_button, self.remove_button):
            controls.addWidget(widget)
        for widget in (self.autoscroll_checkbox, self.pause_button, self.clear_button):
            controls.addWidget(widget)
        layout = QVBoxLayout(self)
        layout.addLayout(controls)
        layout.addWidget(self.canvas, 1)

        self.topic_edit.textChanged.connect(self._on_topic_text)
        self.topic_edit.returnPressed.connect(self._on_return)
        self.add_button.clicked.connect(lambda: self.add_topic(self.topic_edit.text()))
        self.autoscroll_checkbox.toggled.connect(self._on_autoscroll)
        self.clear_button.clicked.connect(self.clear)
        self._redraw_timer = QTimer(self)
        self._redraw_timer.timeout.connect(self.update_plot)
        self._redraw_timer.start(REDRAW_INTERVAL_MS)
        self._retry_timer = QTimer(self)
        self._retry_timer.timeout.connect(self._add_pending)
        self.refresh_completions()
        self._add_pending()
        self._update_remove_menu()

    def refresh_completions(self) -> Dict[str, str]:
        types = self._topic_types()
        names = []
        for topic, type_name in sorted(types.items()):
            names.extend(completions(topic, type_name, load_message_class))
        self._completion_model.setStringList(names)
        return types

    def add_topic(self, path: str, topic_types: Optional[Dict[str, str]] = None) -> bool:
        """Adds the curves a field path gives (a message: its numeric fields); False if it gives none."""
        types = topic_types if topic_types is not None else self._topic_types()
        curves, why = curves_for(path.strip(), types)
        added = False
        for curve in curves:
            if curve in self.canvas.curve_names():
                continue
            problem = self.subscriptions.add(curve, types)
            if problem:
                rospy.logwarn("rqt_plot: %s" % problem)
                continue
            self.canvas.add_curve(curve)
            added = True
        if not curves:
            rospy.logwarn("rqt_plot: cannot plot %s: %s" % (path, why))
        self._update_remove_menu()
        return added

    def remove_topic(self, curve: str) -> None:
        self.subscriptions.remove(curve)
        self.canvas.remove_curve(curve)
        self._update_remove_menu()

    def remove_all(self) -> None:
        for curve in self.canvas.curve_names():
            self.remove_topic(curve)

    def clear(self) -> None:
        self.window.clear()
        self._unshown.clear()
        self.canvas.clear_values()

    def update_plot(self) -> None:
        """Drains the subscribers' points into the window; while paused the plot stands still and the points are
        kept (within the window's bound), to be shown on resume as rqt_plot does."""
        self._unshown.update(self.window.drain())
        if self.pause_button.isChecked() or not self._unshown:
            return
        self.canvas.show(self.window.series, self._unshown)
        self._unshown.clear()

    def shutdown(self) -> None:
        self._redraw_timer.stop()
        self._retry_timer.stop()
        self.subscriptions.shutdown()

    def _add_pending(self) -> None:
        if not self._pending:
            self._retry_timer.stop()
            return
        types = self._topic_types()
        waiting = []
        for path in self._pending:
            if not curves_for(path, types)[0]:
                waiting.append(path)
            else:
                self.add_topic(path, types)
        if waiting and not self._retry_timer.isActive():
            rospy.loginfo("rqt_plot: waiting for %s to be published" % ", ".join(waiting))
            self._retry_timer.start(RETRY_INTERVAL_MS)
        self._pending = waiting
        if not waiting:
            self._retry_timer.stop()

    def _on_topic_text(self, text: str) -> None:
        types = self.refresh_completions() if text in ("", "/") else self._topic_types()
        curves, why = curves_for(text, types) if text not in ("", "/") else ([], "")
        self.add_button.setEnabled(bool(curves))
        self.add_button.setToolTip(why)

    def _on_return(self) -> None:
        if self.add_button.isEnabled():
            self.add_topic(self.topic_edit.text())

    def _on_autoscroll(self, checked: bool) -> None:
        self.canvas.autoscroll = checked
        self.canvas.show(self.window.series, self.window.series)

    def _update_remove_menu(self) -> None:
        self.remove_menu.clear()
        names = sorted(self.canvas.curve_names())
        for name in names:
            action = QAction(name, self.remove_menu)
            action.triggered.connect(lambda _checked=False, curve=name: self.remove_topic(curve))
            self.remove_menu.addAction(action)
        if len(names) > 1:
            everything = QAction("All", self.remove_menu)
            everything.triggered.connect(self.remove_all)
            self.remove_menu.addAction(everything)
        self.remove_button.setEnabled(bool(names))
