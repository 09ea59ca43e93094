"""The rqt main window's Plugins menu: tools nested by group, each opening in a dock that shuts it down on close."""
import importlib.machinery
import sys
import types

import pytest

from rqt_gui import plugins
from rqt_gui.main_window import MainWindow


class FakeTool:
    """A tool module's widget factory: records the arguments and shutdowns."""

    made = []

    def __new__(cls, args):
        from python_qt_binding.QtWidgets import QLabel

        widget = QLabel("fake %s" % args)
        widget.args = args
        widget.shut = 0

        def shutdown():
            widget.shut += 1

        widget.shutdown = shutdown
        cls.made.append(widget)
        return widget


@pytest.fixture
def fake_plugins(monkeypatch):
    module = types.ModuleType("fake_tool_widget")
    module.__spec__ = importlib.machinery.ModuleSpec("fake_tool_widget", None)
    module.FakeWidget = FakeTool
    monkeypatch.setitem(sys.modules, "fake_tool_widget", module)
    FakeTool.made = []
    return [
        plugins.Plugin("Introspection/Fake Graph", "fake_tool_widget", "FakeWidget"),
        plugins.Plugin("Logging/Fake Console", "fake_tool_widget", "FakeWidget"),
    ]


def test_the_table_names_the_four_tools_as_rqts_menu_does():
    # Group and name as the real plugins declare them (rqt_graph/plugin.xml "Introspection" / "Node Graph",
    # rqt_console and rqt_logger_level "Logging", rqt_plot "Visualization").
    labels = {plugin.package: plugin.label for plugin in plugins.PLUGINS}
    assert labels == {
        "rqt_graph": "Introspection/Node Graph",
        "rqt_console": "Logging/Console",
        "rqt_logger_level": "Logging/Logger Level",
        "rqt_plot": "Visualization/Plot",
    }


def test_tools_that_cannot_be_imported_are_left_out(fake_plugins):
    missing = plugins.Plugin("Other/Missing", "no_such_package_here.widget", "Widget")
    assert plugins.available(fake_plugins + [missing]) == fake_plugins


def test_menu_opens_tools_in_tabbed_docks_and_closing_shuts_them_down(qtbot, fake_plugins):
    window = MainWindow(fake_plugins)
    qtbot.addWidget(window)
    window.show()
    menu = window.menuBar().actions()[0].menu()
    assert menu.title() == "&Plugins"
    groups = {action.text(): action.menu() for action in menu.actions()}
    assert sorted(groups) == ["Introspection", "Logging"]
    groups["Introspection"].actions()[0].trigger()
    groups["Logging"].actions()[0].trigger()
    assert [dock.windowTitle() for dock in window.docks] == ["Fake Graph", "Fake Console"]
    assert [widget.args for widget in FakeTool.made] == [[], []]
    assert window.tabifiedDockWidgets(window.docks[0]) == [window.docks[1]]
    first = window.docks[0]
    with qtbot.waitSignal(first.destroyed):
        first.close()
    assert FakeTool.made[0].shut == 1 and len(window.docks) == 1
    window.shutdown()
    assert FakeTool.made[1].shut == 1 and window.docks == []


def test_a_tool_that_fails_to_open_leaves_a_message(qtbot, fake_plugins, monkeypatch):
    window = MainWindow(fake_plugins)
    qtbot.addWidget(window)

    def broken(args):
        raise RuntimeError("no master")

    monkeypatch.setattr(FakeTool, "__new__", lambda cls, args: broken(args))
    assert window.open_plugin(fake_plugins[0]) is None
    assert window.statusBar().currentMessage() == "fake_tool_widget failed to open: no master"
