"""The controller_manager commands' argument handling and order of calls, against a recording fake of the services
(expected behaviour from ros_control noetic-devel: controller_manager/scripts/spawner, parse_args and main;
controller_manager/scripts/controller_manager; controller_manager_interface.py)."""
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "src"))
rospy = pytest.importorskip("rospy")
pytest.importorskip("controller_manager_msgs.srv", reason="source a devel space with controller_manager_msgs")

from controller_manager_dropin import commands, spawner  # noqa: E402
from controller_manager_dropin.services import service_name  # noqa: E402


def test_spawner_defaults_as_upstream():
    args = spawner.parse_args(["arm_controller", "joint_state_controller"])
    assert (args.stopped, args.timeout, args.no_timeout, args.namespace) == (False, 30, False, None)
    assert args.controllers == ["arm_controller", "joint_state_controller"]
    assert spawner.parse_args(["--stopped", "--shutdown-timeout", "3", "c"]).shutdown_timeout == "3"


def test_service_names():
    assert service_name("load_controller") == "controller_manager/load_controller"
    assert service_name("load_controller", "/arm") == "/arm/controller_manager/load_controller"


@pytest.fixture
def calls(monkeypatch):
    recorded = []

    def fake_proxy(name, namespace="", timeout=None):
        def call(*args):
            recorded.append((name,) + args)
            return SimpleNamespace(ok=True, controller=[], types=["a/B"])

        return call

    monkeypatch.setattr(commands, "proxy", fake_proxy)
    return recorded


def test_spawn_loads_all_then_starts_each(calls):
    commands.run("spawn", ["a", "b"])
    assert [c[0] for c in calls] == ["load_controller"] * 2 + ["switch_controller"] * 2
    assert calls[2][1:3] == (["a"], [])


def test_kill_stops_then_unloads(calls, capsys):
    commands.run("kl", ["a"])
    assert [c[0] for c in calls] == ["switch_controller", "unload_controller"]
    assert "Stopped ['a'] successfully" in capsys.readouterr().out


def test_unknown_command_prints_usage_and_fails(calls, capsys):
    with pytest.raises(SystemExit) as exit_info:
        commands.run("explode", [])
    assert exit_info.value.code == 1 and "spawn <name>" in capsys.readouterr().out


def test_list_without_controllers(calls, capsys):
    commands.run("list", [])
    assert capsys.readouterr().out == "No controllers are loaded in mechanism control\n"
