"""The "Exclude Messages" and "Highlight Messages" panels: rows of filters, each with an on/off box, what it
tests, and a remove button; + adds one of a kind, as rqt_console's filter menu does."""
from __future__ import annotations

from typing import Callable, Iterable, List

from python_qt_binding.QtCore import Qt, Signal
from python_qt_binding.QtWidgets import (
    QCheckBox,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QMenu,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from .filters import FILTER_KINDS, FilterCollection, LogFilter, SelectionFilter, SeverityFilter, TextFilter
from .log_record import SEVERITY_LABELS


class FilterRow(QWidget):
    """Edits one filter; `changed` after every edit."""

    changed = Signal()
    removed = Signal(object)

    def __init__(self, log_filter: LogFilter, parent=None) -> None:
        super().__init__(parent)
        self.filter = log_filter
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.enabled_box = QCheckBox()
        self.enabled_box.setChecked(True)
        self.enabled_box.setToolTip("enable this filter")
        self.enabled_box.toggled.connect(self._on_enabled)
        layout.addWidget(self.enabled_box)
        layout.addWidget(QLabel(log_filter.label))
        self.text_edit = self.regex_box = self.choices = None
        if isinstance(log_filter, TextFilter):
            self.text_edit = QLineEdit()
            self.text_edit.textChanged.connect(self._on_text)
            self.regex_box = QCheckBox("Regex")
            self.regex_box.toggled.connect(self._on_text)
            layout.addWidget(self.text_edit, 1)
            layout.addWidget(self.regex_box)
        else:
            self.choices = QListWidget()
            self.choices.setMaximumHeight(70)
            self.choices.itemChanged.connect(self._on_choice)
            layout.addWidget(self.choices, 1)
            if isinstance(log_filter, SeverityFilter):
                self.set_choices(SEVERITY_LABELS)
        remove = QToolButton()
        remove.setText("\u00d7")
        remove.setToolTip("remove this filter")
        remove.clicked.connect(lambda: self.removed.emit(self))
        layout.addWidget(remove)

    def set_choices(self, values: Iterable) -> None:
        """Offers these values (severity numbers, node names, topics); adds those not offered yet."""
        offered = {self.choices.item(i).data(Qt.UserRole) for i in range(self.choices.count())}
        labels = SEVERITY_LABELS if isinstance(self.filter, SeverityFilter) else {}
        for value in sorted(set(values) - offered):
            item = QListWidgetItem(labels.get(value, str(value)))
            item.setData(Qt.UserRole, value)
            item.setFlags(item.flags() | Qt.ItemIsUserCheckable)
            item.setCheckState(Qt.Unchecked)
            self.choices.addItem(item)

    def check(self, value) -> None:
        for i in range(self.choices.count()):
            if self.choices.item(i).data(Qt.UserRole) == value:
                self.choices.item(i).setCheckState(Qt.Checked)

    def _on_enabled(self, enabled: bool) -> None:
        self.filter.enabled = enabled
        self.changed.emit()

    def _on_text(self, *_) -> None:
        self.filter.set_text(self.text_edit.text(), self.regex_box.isChecked())
        self.text_edit.setStyleSheet("background-color: #ffc0c0;" if self.filter.error else "")
        self.text_edit.setToolTip(self.filter.error)
        self.changed.emit()

    def _on_choice(self, _item) -> None:
        self.filter.selected = {
            self.choices.item(i).data(Qt.UserRole)
            for i in range(self.choices.count())
            if self.choices.item(i).checkState() == Qt.Checked
        }
        self.changed.emit()


class FilterPanel(QGroupBox):
    """A titled list of filter rows over one FilterCollection; `changed` after any edit."""

    changed = Signal()

    def __init__(self, title: str, collection: FilterCollection, parent=None) -> None:
        super().__init__(title, parent)
        self.collection = collection
        self.rows: List[FilterRow] = []
        self._choice_sources: dict = {}
        layout = QVBoxLayout(self)
        header = QHBoxLayout()
        self.add_button = QToolButton()
        self.add_button.setText("+")
        self.add_button.setToolTip("add a filter")
        self.add_button.setPopupMode(QToolButton.InstantPopup)
        menu = QMenu(self)
        for kind in FILTER_KINDS:
            menu.addAction(kind.label).triggered.connect(lambda _checked=False, k=kind: self.add_filter(k))
        self.add_button.setMenu(menu)
        header.addWidget(self.add_button)
        header.addStretch(1)
        layout.addLayout(header)
        self._rows_layout = QVBoxLayout()
        layout.addLayout(self._rows_layout)
        layout.addStretch(1)

    def add_header_widget(self, widget: QWidget) -> None:
        self.layout().itemAt(0).layout().insertWidget(1, widget)

    def add_filter(self, kind: Callable[[], LogFilter]) -> FilterRow:
        row = FilterRow(kind(), self)
        self.collection.filters.append(row.filter)
        self.rows.append(row)
        self._rows_layout.addWidget(row)
        row.changed.connect(self.changed.emit)
        row.removed.connect(self.remove_row)
        if isinstance(row.filter, SelectionFilter) and row.filter.kind in self._choice_sources:
            row.set_choices(self._choice_sources[row.filter.kind])
        self.changed.emit()
        return row

    def remove_row(self, row: FilterRow) -> None:
        self.rows.remove(row)
        self.collection.filters.remove(row.filter)
        row.setParent(None)
        row.deleteLater()
        self.changed.emit()

    def offer(self, kind: str, values: Iterable) -> None:
        """Node names or topics seen: offered by the rows of that kind, now and when added."""
        known = self._choice_sources.setdefault(kind, set())
        known.update(values)
        for row in self.rows:
            if row.filter.kind == kind:
                row.set_choices(known)
