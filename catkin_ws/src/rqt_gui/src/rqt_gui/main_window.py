"""The `rqt` main window: a Plugins menu (Introspection, Logging, Visualization) opening each tool in a dock.

    rqt [--list-plugins] [-s PLUGIN [ARGS...]]

``-s/--standalone PLUGIN`` (a package name such as rqt_graph) runs one tool alone, with ARGS as its command line.
"""
from __future__ import annotations

import argparse
import sys
from typing import List, Optional, Sequence

from python_qt_binding.QtCore import Qt
from python_qt_binding.QtWidgets import QDockWidget, QMainWindow

from rqt_gui import plugins as plugin_table
from rqt_standalone.runner import run

TITLE = "Default - rqt"  # the real rqt names its window after the perspective, "Default" at first


class PluginDock(QDockWidget):
    """A dock holding one tool; closing it shuts the tool down."""

    def __init__(self, title: str, widget, parent=None):
        super().__init__(title, parent)
        self.setObjectName(title)
        self.setWidget(widget)
        self.setAttribute(Qt.WA_DeleteOnClose)

    def shutdown_plugin(self) -> None:
        shutdown = getattr(self.widget(), "shutdown", None)
        if callable(shutdown):
            shutdown()

    def closeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        self.shutdown_plugin()
        super().closeEvent(event)


class MainWindow(QMainWindow):
    def __init__(self, plugins: Sequence[plugin_table.Plugin]):
        super().__init__()
        self.setDockNestingEnabled(True)
        self.resize(1000, 700)
        self.docks: List[PluginDock] = []
        menu = self.menuBar().addMenu("&Plugins")
        groups = {}
        for plugin in plugins:
            group, _, name = plugin.label.rpartition("/")
            if group not in groups:
                groups[group] = menu.addMenu(group) if group else menu
            action = groups[group].addAction(name)
            action.setObjectName(plugin.package)
            action.triggered.connect(lambda _checked=False, chosen=plugin: self.open_plugin(chosen))
        if not plugins:
            menu.addAction("(no plugins built)").setEnabled(False)
        self.statusBar().showMessage("Open a tool from the Plugins menu")

    def open_plugin(self, plugin: plugin_table.Plugin, args: Sequence[str] = ()) -> Optional[PluginDock]:
        """Open the tool in a new dock (tabbed with the last one opened); None, with a status message, if it fails."""
        try:
            widget = plugin_table.load(plugin)(list(args))
        except Exception as error:  # a broken tool must not take the main window down
            self.statusBar().showMessage("%s failed to open: %s" % (plugin.package, error))
            return None
        dock = PluginDock(plugin.label.rpartition("/")[2], widget, self)
        dock.destroyed.connect(lambda _obj=None, closed=dock: self._forget(closed))
        if self.docks:
            self.tabifyDockWidget(self.docks[-1], dock)
        else:
            self.addDockWidget(Qt.TopDockWidgetArea, dock)
        self.docks.append(dock)
        dock.show()
        dock.raise_()
        self.statusBar().clearMessage()
        return dock

    def _forget(self, dock: PluginDock) -> None:
        if dock in self.docks:
            self.docks.remove(dock)

    def shutdown(self) -> None:
        """Shut every open tool down (the runner calls this when the window closes)."""
        for dock in list(self.docks):
            dock.shutdown_plugin()
        self.docks.clear()


def _find(name: str, plugins: Sequence[plugin_table.Plugin]) -> Optional[plugin_table.Plugin]:
    for plugin in plugins:
        if name in (plugin.package, plugin.label, plugin.label.rpartition("/")[2]):
            return plugin
    return None


def main(argv: Optional[Sequence[str]] = None) -> int:
    import rospy

    argv = list(sys.argv if argv is None else argv)
    parser = argparse.ArgumentParser(prog="rqt", description=__doc__.splitlines()[0])
    parser.add_argument("-s", "--standalone", metavar="PLUGIN", help="run one tool alone (e.g. rqt_graph)")
    parser.add_argument("--list-plugins", action="store_true", help="print the tools this rqt can open")
    options, rest = parser.parse_known_args(rospy.myargv(argv)[1:])
    found = plugin_table.available()
    if options.list_plugins:
        for plugin in found:
            print("%s\t%s" % (plugin.package, plugin.label))
        return 0
    if options.standalone:
        plugin = _find(options.standalone, found)
        if plugin is None:
            print("rqt: no plugin %r (rqt --list-plugins names them)" % options.standalone, file=sys.stderr)
            return 2
        return run(lambda args: plugin_table.load(plugin)(parser.parse_known_args(args)[1]), argv, plugin.package)
    if rest:
        parser.error("unrecognized arguments: %s" % " ".join(rest))
    return run(lambda _args: MainWindow(found), argv, TITLE)
