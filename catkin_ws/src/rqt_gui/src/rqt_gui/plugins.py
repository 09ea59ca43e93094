"""The tools the `rqt` main window's Plugins menu opens: (menu label, module, factory) each.

A factory is called with the tool's command-line arguments (a list, empty from the menu) and returns the tool's
QWidget; the widget's ``shutdown()``, where it has one, is called when its dock closes.
"""
from __future__ import annotations

import importlib
import importlib.util
from typing import Callable, List, NamedTuple, Sequence


class Plugin(NamedTuple):
    label: str  # "Group/Name", as rqt's Plugins menu nests them
    module: str
    factory: str

    @property
    def package(self) -> str:
        return self.module.split(".")[0]


PLUGINS = (
    Plugin("Introspection/Node Graph", "rqt_graph.graph_widget", "GraphWidget"),
    Plugin("Logging/Console", "rqt_console.console_widget", "ConsoleWidget"),
    Plugin("Logging/Logger Level", "rqt_logger_level.logger_level_widget", "LoggerLevelWidget"),
    Plugin("Visualization/Plot", "rqt_plot.plot_widget", "PlotWidget"),
)


def _importable(module: str) -> bool:
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # the parent package is missing, or a module made at run time
        return False


def available(plugins: Sequence[Plugin] = PLUGINS) -> List[Plugin]:
    """The plugins whose module can be imported here (a tool not built or not installed is left out)."""
    return [plugin for plugin in plugins if _importable(plugin.module)]


def load(plugin: Plugin) -> Callable[[List[str]], object]:
    """The plugin's widget factory."""
    return getattr(importlib.import_module(plugin.module), plugin.factory)
