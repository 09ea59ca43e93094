"""Exclude and highlight filters, without Qt. Semantics of rqt_console's filters/*.py: a filter with nothing set
matches nothing; a collection matches a message when any enabled, set filter matches it."""
from __future__ import annotations

import re
from typing import Iterable, List, Optional, Pattern

from .log_record import LogRecord


class LogFilter:
    """Base: enabled or not; has_filter() when it has something to test."""

    kind = ""
    label = ""

    def __init__(self) -> None:
        self.enabled = True

    def has_filter(self) -> bool:
        raise NotImplementedError

    def matches(self, record: LogRecord) -> bool:
        raise NotImplementedError


class TextFilter(LogFilter):
    """Text in one field: a substring (case-sensitive), or with regex a regular expression found anywhere in it
    (rqt_console wraps a pattern in .* unless it starts with ^ or ends with $, which comes to the same).
    An invalid expression matches nothing; `error` says why."""

    def __init__(self, text: str = "", regex: bool = False) -> None:
        super().__init__()
        self.text = ""
        self.regex = False
        self.error = ""
        self._pattern: Optional[Pattern[str]] = None
        self.set_text(text, regex)

    def set_text(self, text: str, regex: Optional[bool] = None) -> None:
        self.text = text
        if regex is not None:
            self.regex = regex
        self.error, self._pattern = "", None
        if self.regex and text:
            try:
                self._pattern = re.compile(text, re.DOTALL)
            except re.error as error:
                self.error = "invalid regular expression: %s" % error

    def has_filter(self) -> bool:
        return self.text != ""

    def field(self, record: LogRecord) -> str:
        raise NotImplementedError

    def matches(self, record: LogRecord) -> bool:
        if not self.enabled or not self.text:
            return False
        value = self.field(record)
        if self.regex:
            return self._pattern is not None and self._pattern.search(value) is not None
        return self.text in value


class MessageFilter(TextFilter):
    kind, label = "message", "...containing"

    def field(self, record: LogRecord) -> str:
        return record.message


class LocationFilter(TextFilter):
    kind, label = "location", "...from location"

    def field(self, record: LogRecord) -> str:
        return record.location


class SelectionFilter(LogFilter):
    """A set of chosen values (severities, node names, topics)."""

    def __init__(self, selected: Iterable = ()) -> None:
        super().__init__()
        self.selected = set(selected)

    def has_filter(self) -> bool:
        return bool(self.selected)


class SeverityFilter(SelectionFilter):
    kind, label = "severity", "...with severities"

    def matches(self, record: LogRecord) -> bool:
        return self.enabled and record.severity in self.selected


class NodeFilter(SelectionFilter):
    kind, label = "node", "...from node"

    def matches(self, record: LogRecord) -> bool:
        return self.enabled and record.node in self.selected


class TopicFilter(SelectionFilter):
    kind, label = "topic", "...from topic"

    def matches(self, record: LogRecord) -> bool:
        return self.enabled and any(topic in self.selected for topic in record.topics)


FILTER_KINDS = (MessageFilter, SeverityFilter, NodeFilter, TopicFilter, LocationFilter)


class FilterCollection:
    """rqt_console's FilterCollection.test_message: True as soon as one enabled filter with something set
    matches; `default` when none is enabled and set."""

    def __init__(self) -> None:
        self.filters: List[LogFilter] = []

    def active(self) -> List[LogFilter]:
        return [f for f in self.filters if f.enabled and f.has_filter()]

    def matches(self, record: LogRecord, default: bool = False) -> bool:
        active = self.active()
        if not active:
            return default
        return any(f.matches(record) for f in active)
