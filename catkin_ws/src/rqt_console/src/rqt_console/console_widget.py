"""rqt_console's window: the log table, pause/resume, clear, save/load, the buffer limit, and the exclude and
highlight filters."""
from __future__ import annotations

import argparse
from typing import Optional, Sequence

import rospy
from python_qt_binding.QtCore import QSize, Qt, QTimer
from python_qt_binding.QtWidgets import (
    QAbstractItemView,
    QFileDialog,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QMessageBox,
    QPushButton,
    QSpinBox,
    QSplitter,
    QTableView,
    QVBoxLayout,
    QWidget,
    QCheckBox,
)

from .filters import MessageFilter, SeverityFilter
from .filter_panel import FilterPanel
from .log_file import read_records, write_records
from .log_model import DEFAULT_LIMIT, LogFilterProxy, LogTableModel
from .log_source import LogQueue, LogSubscriber

DRAIN_INTERVAL_MS = 100  # rqt_console's Console._timer: the queue goes into the table ten times a second
COLUMN_WIDTHS = (60, 100, 70, 100, 100, 100, 100)  # rqt_console's ConsoleWidget._columnwidth
MAX_LIMIT = 1000000


def parse_arguments(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="rqt_console", description="Show and filter the ROS log (/rosout_agg).")
    parser.add_argument(
        "--limit", type=int, default=DEFAULT_LIMIT, help="messages kept, the oldest dropped first (default 20000)"
    )
    args = parser.parse_args(list(argv))
    if not 1 <= args.limit <= MAX_LIMIT:
        parser.error("--limit must be in [1, %d], got %d" % (MAX_LIMIT, args.limit))
    return args


class ConsoleWidget(QWidget):
    """The console. With subscribe=False nothing is subscribed (tests feed self.queue themselves)."""

    def __init__(self, args_list: Sequence[str] = (), subscribe: bool = True) -> None:
        super().__init__()
        self.setObjectName("ConsoleWidget")
        self.setWindowTitle("Console")
        args = parse_arguments(args_list)
        self.model = LogTableModel(args.limit)
        self.proxy = LogFilterProxy(self.model)
        self.queue = LogQueue(args.limit)
        self._subscriber: Optional[LogSubscriber] = LogSubscriber(self.queue) if subscribe else None

        self.pause_button = QPushButton("Pause")
        self.pause_button.setCheckable(True)
        self.pause_button.setToolTip("pause: messages arriving meanwhile are dropped")
        self.clear_button = QPushButton("Clear")
        self.save_button = QPushButton("Save")
        self.load_button = QPushButton("Load")
        self.limit_box = QSpinBox()
        self.limit_box.setRange(1, MAX_LIMIT)
        self.limit_box.setValue(args.limit)
        self.limit_box.setToolTip("buffer limit: the oldest messages beyond it are dropped")
        self.status_label = QLabel()
        toolbar = QHBoxLayout()
        toolbar.addWidget(self.status_label, 1)
        for widget in (QLabel("Limit"), self.limit_box, self.pause_button, self.clear_button):
            toolbar.addWidget(widget)
        toolbar.addWidget(self.save_button)
        toolbar.addWidget(self.load_button)

        self.table_view = QTableView()
        self.table_view.setModel(self.proxy)
        self.table_view.setSelectionBehavior(QAbstractItemView.SelectRows)
        self.table_view.setWordWrap(False)
        self.table_view.verticalHeader().hide()
        self.table_view.verticalHeader().setDefaultSectionSize(self.fontMetrics().height() + 6)
        header = self.table_view.horizontalHeader()
        for column, width in enumerate(COLUMN_WIDTHS):
            header.resizeSection(column, width)
        header.setSectionResizeMode(1, QHeaderView.Stretch)

        self.exclude_panel = FilterPanel("Exclude Messages", self.proxy.exclude)
        self.highlight_panel = FilterPanel("Highlight Messages", self.proxy.highlight)
        self.highlighted_only_box = QCheckBox("show highlighted only")
        self.highlight_panel.add_header_widget(self.highlighted_only_box)
        filters = QWidget()
        filters_layout = QHBoxLayout(filters)
        filters_layout.setContentsMargins(0, 0, 0, 0)
        filters_layout.addWidget(self.exclude_panel)
        filters_layout.addWidget(self.highlight_panel)
        splitter = QSplitter(Qt.Vertical)
        splitter.addWidget(self.table_view)
        splitter.addWidget(filters)
        splitter.setStretchFactor(0, 3)
        splitter.setStretchFactor(1, 1)
        layout = QVBoxLayout(self)
        layout.addLayout(toolbar)
        layout.addWidget(splitter, 1)
        # the filters rqt_console opens with (ConsoleWidget.restore_settings without saved settings)
        self.exclude_panel.add_filter(SeverityFilter)
        self.highlight_panel.add_filter(MessageFilter)

        self.pause_button.toggled.connect(self.set_paused)
        self.clear_button.clicked.connect(self.clear)
        self.save_button.clicked.connect(self._save_clicked)
        self.load_button.clicked.connect(self._load_clicked)
        self.limit_box.valueChanged.connect(self.set_limit)
        self.exclude_panel.changed.connect(self._filters_changed)
        self.highlight_panel.changed.connect(self._filters_changed)
        self.highlighted_only_box.toggled.connect(self.proxy.set_highlighted_only)
        self.proxy.rowsInserted.connect(self.update_status)
        self.proxy.rowsRemoved.connect(self.update_status)
        self.proxy.modelReset.connect(self.update_status)
        self._timer = QTimer(self)
        self._timer.timeout.connect(self.drain)
        self._timer.start(DRAIN_INTERVAL_MS)
        self.update_status()

    def sizeHint(self) -> QSize:
        return QSize(1000, 600)  # room for the Message column next to the six others

    def drain(self) -> int:
        """Moves the queued messages into the table in one batch; returns how many."""
        records = self.queue.take()
        if records:
            self.model.insert_records(records)
            for panel in (self.exclude_panel, self.highlight_panel):
                panel.offer("node", {record.node for record in records})
                panel.offer("topic", {topic for record in records for topic in record.topics})
        return len(records)

    def set_paused(self, paused: bool) -> None:
        self.queue.paused = paused
        self.pause_button.setChecked(paused)
        self.pause_button.setText("Resume" if paused else "Pause")

    def set_limit(self, limit: int) -> None:
        self.model.set_limit(limit)
        self.queue.set_limit(limit)
        if self.limit_box.value() != limit:
            self.limit_box.setValue(limit)

    def clear(self) -> None:
        self.queue.take()
        self.model.clear()

    def save_to(self, path: str) -> int:
        """Writes the messages the table shows (filters applied), oldest first; returns how many."""
        with open(path, "w") as stream:
            return write_records(reversed(self.proxy.visible_records()), stream)

    def load_from(self, path: str) -> int:
        """Adds a file's messages and pauses, so that live ones do not mix in (as rqt_console does)."""
        with open(path) as stream:
            records, skipped = read_records(stream)
        for reason in skipped:
            rospy.logwarn("rqt_console: %s: skipped a row: %s" % (path, reason))
        self.set_paused(True)
        self.model.insert_records(records)
        return len(records)

    def update_status(self, *_) -> None:
        shown, kept = self.proxy.rowCount(), self.model.rowCount()
        if shown == kept:
            self.status_label.setText("Displaying %d messages" % kept)
        else:
            self.status_label.setText("Displaying %d of %d messages" % (shown, kept))

    def shutdown(self) -> None:
        self._timer.stop()
        if self._subscriber is not None:
            self._subscriber.shutdown()
            self._subscriber = None

    def _filters_changed(self) -> None:
        self.proxy.filters_changed()
        self.update_status()

    def _save_clicked(self) -> None:
        path, _ = QFileDialog.getSaveFileName(self, "Save to File", ".", "rqt_console message file (*.csv)")
        if path:
            if not path.endswith(".csv"):
                path += ".csv"
            try:
                self.save_to(path)
            except OSError as error:
                QMessageBox.warning(self, "Save failed", str(error))

    def _load_clicked(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Load from File", ".", "rqt_console message file (*.csv)")
        if path:
            try:
                self.load_from(path)
            except (OSError, ValueError) as error:
                QMessageBox.warning(self, "Load failed", str(error))
