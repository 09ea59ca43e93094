"""The rqt_logger_level widget: Nodes, Loggers and Levels lists side by side, as the real one has them, and a
Refresh button. Choosing a level sets it at once. Every ROS call runs in the background with a time-out."""
from __future__ import annotations

import argparse
from typing import Dict, List, Optional, Sequence, Tuple

from python_qt_binding.QtCore import Qt
from python_qt_binding.QtWidgets import QGridLayout, QLabel, QListWidget, QPushButton, QWidget

from rqt_logger_level.background import BackgroundCalls
from rqt_logger_level.logger_model import LEVELS, level_index

CALL_TIMEOUT = 2.0  # s for a node (or the master) to answer


def parse_arguments(args: List[str]) -> argparse.Namespace:
    """rqt_logger_level takes no options of its own: --help, and an error for anything else."""
    parser = argparse.ArgumentParser(prog="rqt_logger_level", description="See and set the logger levels of nodes.")
    return parser.parse_args(args)


class RosLoggerServices:
    """The calls the widget makes; tests give it fakes with the same four members."""

    def __init__(self) -> None:
        import rospy

        from rqt_logger_level import logger_services

        self._caller_id = rospy.get_name()
        self._services = logger_services

    def list_nodes(self) -> List[str]:
        return self._services.list_nodes(self._caller_id)

    def get_loggers(self, node: str) -> List[Tuple[str, str]]:
        return self._services.get_loggers(node)

    def set_level(self, node: str, logger: str, level: str) -> None:
        self._services.set_level(node, logger, level)


class LoggerLevelWidget(QWidget):
    """``LoggerLevelWidget(args)``: ``args`` is rqt_logger_level's command line (no options of its own)."""

    def __init__(self, args: Optional[Sequence[str]] = None, services=None, timeout: float = CALL_TIMEOUT):
        super().__init__()
        parse_arguments(list(args or []))
        self.setObjectName("LoggerLevel")
        self.setWindowTitle("Logger Level")
        self._services = services or RosLoggerServices()
        self._calls = BackgroundCalls(timeout, self)
        self.levels: Dict[str, str] = {}  # logger -> level as the node reported it (or as last set)
        self._filling = False  # lists being filled by code, not chosen by the user

        self.node_list, self.logger_list, self.level_list = QListWidget(), QListWidget(), QListWidget()
        self.node_list.setObjectName("node_list")
        self.logger_list.setObjectName("logger_list")
        self.level_list.setObjectName("level_list")
        self.level_list.addItems(LEVELS)
        self.refresh_button = QPushButton("Refresh")
        self.status = QLabel("")
        self.status.setWordWrap(True)
        grid = QGridLayout(self)
        for column, (title, widget) in enumerate(
            (("Nodes", self.node_list), ("Loggers", self.logger_list), ("Levels", self.level_list))
        ):
            grid.addWidget(QLabel(title), 0, column)
            grid.addWidget(widget, 1, column)
        grid.setColumnStretch(0, 3)
        grid.setColumnStretch(1, 3)
        grid.setColumnStretch(2, 1)
        grid.addWidget(self.refresh_button, 2, 0)
        grid.addWidget(self.status, 3, 0, 1, 3)

        self.refresh_button.clicked.connect(self.refresh)
        self.node_list.currentTextChanged.connect(self._node_chosen)
        self.logger_list.currentTextChanged.connect(self._logger_chosen)
        self.level_list.currentTextChanged.connect(self._level_chosen)
        self.refresh()

    # -- what the user does --------------------------------------------------------------------------------------
    def refresh(self) -> None:
        """List the nodes again (keeping the chosen one if it is still there) and reload its loggers."""
        self.status.setText("asking the master for nodes...")
        self._calls.call(self._services.list_nodes, self._on_nodes)

    def choose(self, node: str, logger: Optional[str] = None, level: Optional[str] = None) -> None:
        """Select by name, as a click would (for scripts and tests)."""
        self._select(self.node_list, node, quiet=False)
        if logger is not None:
            self._select(self.logger_list, logger, quiet=False)
        if level is not None:
            self._select(self.level_list, level, quiet=False)

    def _node_chosen(self, node: str) -> None:
        if self._filling:
            return
        self._fill(self.logger_list, [])
        self.levels = {}
        if node:
            self.status.setText("asking %s for its loggers..." % node)
            self._calls.call(lambda: self._services.get_loggers(node), lambda r, e: self._on_loggers(node, r, e))

    def _logger_chosen(self, logger: str) -> None:
        if self._filling:
            return
        row = level_index(self.levels.get(logger, ""))
        self._filling = True
        self.level_list.setCurrentRow(-1 if row is None else row)
        self._filling = False

    def _level_chosen(self, level: str) -> None:
        node, logger = self._current(self.node_list), self._current(self.logger_list)
        if self._filling or not (level and node and logger):
            return
        self.status.setText("setting %s %s to %s..." % (node, logger, level))
        self._calls.call(
            lambda: self._services.set_level(node, logger, level),
            lambda _r, error: self._on_level_set(node, logger, level, error),
        )

    # -- answers, in the Qt thread -------------------------------------------------------------------------------
    def _on_nodes(self, nodes: Optional[List[str]], error: Optional[BaseException]) -> None:
        if error is not None:
            self.status.setText("cannot list nodes: %s" % error)
            return
        chosen = self._current(self.node_list)
        self._fill(self.node_list, nodes)
        self.status.setText("%d nodes offer set_logger_level" % len(nodes))
        if chosen in nodes:
            self._select(self.node_list, chosen, quiet=True)
            self._node_chosen(chosen)
        else:
            self._fill(self.logger_list, [])

    def _on_loggers(self, node: str, loggers, error: Optional[BaseException]) -> None:
        if node != self._current(self.node_list):
            return  # the user moved on
        if error is not None:
            self.status.setText("%s did not answer get_loggers: %s" % (node, error))
            return
        chosen = self._current(self.logger_list)
        self.levels = dict(loggers)
        self._fill(self.logger_list, [name for name, _level in loggers])
        self.status.setText("%s: %d loggers" % (node, len(loggers)))
        if chosen in self.levels:
            self._select(self.logger_list, chosen, quiet=False)

    def _on_level_set(self, node: str, logger: str, level: str, error: Optional[BaseException]) -> None:
        if error is not None:
            self.status.setText("%s did not set %s to %s: %s" % (node, logger, level, error))
            if node == self._current(self.node_list) and logger == self._current(self.logger_list):
                self._logger_chosen(logger)  # show the level the logger still has
            return
        if node == self._current(self.node_list):
            self.levels[logger] = level.upper()
        self.status.setText("%s: %s set to %s" % (node, logger, level))

    # -- list helpers -------------------------------------------------------------------------------------------
    @staticmethod
    def _current(widget: QListWidget) -> str:
        item = widget.currentItem()
        return item.text() if item is not None else ""

    def _fill(self, widget: QListWidget, names: List[str]) -> None:
        self._filling = True
        widget.clear()
        widget.addItems(names)
        self._filling = False

    def _select(self, widget: QListWidget, name: str, quiet: bool) -> None:
        matches = widget.findItems(name, Qt.MatchExactly)
        self._filling = quiet
        widget.setCurrentItem(matches[0] if matches else None)
        self._filling = False

    def shutdown(self) -> None:
        self._calls.shutdown()
