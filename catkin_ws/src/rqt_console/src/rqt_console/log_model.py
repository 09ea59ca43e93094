"""The table's models: every kept message, newest first, and the proxy that applies the exclude and highlight
filters. Qt, no ROS."""
from __future__ import annotations

from typing import Iterable, List, Optional, Set

from python_qt_binding.QtCore import QAbstractTableModel, QModelIndex, QSortFilterProxyModel, Qt
from python_qt_binding.QtGui import QBrush, QColor

from .filters import FilterCollection
from .log_record import COLUMNS, DEBUG, ERROR, FATAL, INFO, WARN, LogRecord

DEFAULT_LIMIT = 20000  # rqt_console's MessageDataModel._message_limit
SEVERITY_COLUMN = 2
# rqt_console's MessageDataModel.severity_colors
SEVERITY_BRUSHES = {
    DEBUG: QBrush(Qt.darkCyan),
    INFO: QBrush(Qt.darkBlue),
    WARN: QBrush(Qt.darkYellow),
    ERROR: QBrush(Qt.darkRed),
    FATAL: QBrush(Qt.red),
}
DIMMED = QBrush(QColor(Qt.gray))


class LogTableModel(QAbstractTableModel):
    """At most `limit` messages; row 0 is the newest. Messages come in batches (insert_records), so the views
    update once per batch however fast /rosout_agg is."""

    def __init__(self, limit: int = DEFAULT_LIMIT) -> None:
        super().__init__()
        self._records: List[LogRecord] = []  # oldest first: appending and dropping the oldest stay cheap
        self._limit = limit
        self._next_number = 1

    # Qt's interface
    def rowCount(self, parent: QModelIndex = QModelIndex()) -> int:
        return 0 if parent.isValid() else len(self._records)

    def columnCount(self, parent: QModelIndex = QModelIndex()) -> int:
        return 0 if parent.isValid() else len(COLUMNS)

    def data(self, index: QModelIndex, role: int = Qt.DisplayRole):
        record = self.record(index.row())
        if record is None:
            return None
        if role in (Qt.DisplayRole, Qt.ToolTipRole):
            return record.column_text(index.column())
        if role == Qt.ForegroundRole and index.column() == SEVERITY_COLUMN:
            return SEVERITY_BRUSHES.get(record.severity)
        return None

    def headerData(self, section: int, orientation, role: int = Qt.DisplayRole):
        if orientation == Qt.Horizontal and role == Qt.DisplayRole and 0 <= section < len(COLUMNS):
            return COLUMNS[section]
        return None

    # the console's interface
    def record(self, row: int) -> Optional[LogRecord]:
        if 0 <= row < len(self._records):
            return self._records[len(self._records) - 1 - row]
        return None

    def records(self) -> List[LogRecord]:
        """Oldest first."""
        return list(self._records)

    @property
    def limit(self) -> int:
        return self._limit

    def set_limit(self, limit: int) -> None:
        if limit < 1:
            raise ValueError("the buffer limit must be at least 1, got %d" % limit)
        self._limit = limit
        self._drop_oldest(len(self._records) - limit)

    def insert_records(self, records: Iterable[LogRecord]) -> None:
        """Numbers the records and puts them on top; the oldest go beyond the limit."""
        batch = list(records)[-self._limit :]
        if not batch:
            return
        self._drop_oldest(len(self._records) + len(batch) - self._limit)
        for record in batch:
            record.number = self._next_number
            self._next_number += 1
        self.beginInsertRows(QModelIndex(), 0, len(batch) - 1)
        self._records.extend(batch)
        self.endInsertRows()

    def clear(self) -> None:
        """Forgets every message; numbering starts again at 1, as rqt_console's clear does."""
        self.beginResetModel()
        self._records = []
        self._next_number = 1
        self.endResetModel()

    def nodes(self) -> Set[str]:
        return {record.node for record in self._records}

    def topics(self) -> Set[str]:
        return {topic for record in self._records for topic in record.topics}

    def _drop_oldest(self, count: int) -> None:
        if count <= 0:
            return
        rows = len(self._records)
        self.beginRemoveRows(QModelIndex(), rows - count, rows - 1)
        del self._records[:count]
        self.endRemoveRows()


class LogFilterProxy(QSortFilterProxyModel):
    """Hides what an exclude filter matches; dims (grey text) what no highlight filter matches, or hides it when
    only highlighted messages are shown (rqt_console's MessageProxyModel)."""

    def __init__(self, source: LogTableModel) -> None:
        super().__init__()
        self.exclude = FilterCollection()
        self.highlight = FilterCollection()
        self._highlighted_only = False
        self._source = source
        self.setSourceModel(source)

    def filterAcceptsRow(self, source_row: int, source_parent: QModelIndex) -> bool:
        record = self._source.record(source_row)
        if record is None or self.exclude.matches(record):
            return False
        return not self._highlighted_only or self.is_highlighted(record)

    def is_highlighted(self, record: LogRecord) -> bool:
        return self.highlight.matches(record, default=True)

    def data(self, index: QModelIndex, role: int = Qt.DisplayRole):
        if role == Qt.ForegroundRole:
            record = self._source.record(self.mapToSource(index).row())
            if record is not None and not self.is_highlighted(record):
                return DIMMED
        return super().data(index, role)

    @property
    def highlighted_only(self) -> bool:
        return self._highlighted_only

    def set_highlighted_only(self, highlighted_only: bool) -> None:
        self._highlighted_only = highlighted_only
        self.invalidateFilter()

    def filters_changed(self) -> None:
        """Call after changing a filter: rows are tested again and their colours redrawn."""
        self.invalidateFilter()
        if self.rowCount():
            self.dataChanged.emit(self.index(0, 0), self.index(self.rowCount() - 1, self.columnCount() - 1))

    def visible_records(self) -> List[LogRecord]:
        """What the table shows, top (newest) first."""
        return [self._source.record(self.mapToSource(self.index(row, 0)).row()) for row in range(self.rowCount())]
