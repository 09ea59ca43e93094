"""Gazebo's server command line as the drop-in reads it. Option names and meanings are gazebo-classic's
(gazebo/Server.cc, Server::ParseArgs: world file positional, default worlds/empty.world; -u/--pause;
-e/--physics; -s/--server-plugin repeatable; --verbose; -r/--record and --record_*), and gazebo_ros's scripts
(gazebo_ros/scripts/libcommon.sh, relocate_remappings: ROS remappings are set apart from Gazebo's arguments)."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "src"))

from gazebo_ros_dropin.command_line import (  # noqa: E402
    DEFAULT_WORLD,
    CommandLineError,
    parse_server_args,
    split_ros_arguments,
)


def test_no_arguments_load_gazebos_empty_world() -> None:
    options = parse_server_args([])
    assert (options.world, options.paused, options.physics, options.notes) == (DEFAULT_WORLD, False, "ode", [])
    assert DEFAULT_WORLD == "worlds/empty.world"


def test_a_test_files_command_line() -> None:
    # as gazebo_ros_pkgs' tests write it: <node pkg="gazebo_ros" type="gzserver" args="--verbose $(find p)/x.world"/>
    options = parse_server_args(["--verbose", "/ws/src/p/worlds/x.world"])
    assert (options.world, options.verbose, options.paused) == ("/ws/src/p/worlds/x.world", True, False)


@pytest.mark.parametrize("flag", ["-u", "--pause"])
def test_paused(flag: str) -> None:
    assert parse_server_args([flag, "w.world"]).paused


@pytest.mark.parametrize("args", [["-e", "ode"], ["--physics", "ode"], ["--physics=ode"]])
def test_ode_is_taken_silently(args) -> None:
    options = parse_server_args(args + ["w.world"])
    assert (options.physics, options.notes, options.world) == ("ode", [], "w.world")


def test_another_engine_is_named() -> None:
    options = parse_server_args(["-e", "bullet"])
    assert options.notes == ["physics engine [bullet] is not available: the simulator is always ODE"]


def test_plugins_are_named_in_a_warning_and_gazebo_ros_own_are_built_in() -> None:
    options = parse_server_args(
        [
            "-s",
            "/opt/lib/libgazebo_ros_api_plugin.so",
            "--server-plugin",
            "libmy_world_plugin.so",
            "-g",
            "libmy_gui.so",
            "-s",
            "libgazebo_ros_paths_plugin.so",
        ]
    )
    assert options.plugins[1] == "libmy_world_plugin.so" and len(options.plugins) == 3
    assert options.notes == [
        "server plugin [libmy_world_plugin.so] not loaded: Gazebo plugins cannot run here",
        "GUI plugin [libmy_gui.so] not loaded: Gazebo plugins cannot run here",
    ]


@pytest.mark.parametrize(
    "args", [["-r"], ["--record"], ["--record_path", "/tmp/x"], ["--record_encoding=zlib"], ["--record_resources"]]
)
def test_recording_is_refused_with_a_message(args) -> None:
    with pytest.raises(CommandLineError, match="no Gazebo state log.*rosbag"):
        parse_server_args(args + ["w.world"])


def test_playing_a_log_is_refused() -> None:
    with pytest.raises(CommandLineError, match="cannot play"):
        parse_server_args(["-p", "state.log"])


@pytest.mark.parametrize("option", ["-e", "-s", "--seed"])
def test_an_option_without_its_value(option: str) -> None:
    with pytest.raises(CommandLineError, match="needs a value"):
        parse_server_args([option])


def test_options_with_no_effect_are_noted_and_unknown_ones_passed() -> None:
    options = parse_server_args(["--seed", "3", "--lockstep", "--iters", "10", "--frobnicate", "w.world", "rest"])
    assert len(options.notes) == 4 and "--frobnicate" in options.notes[3]
    assert (options.world, options.extra) == ("w.world", ["rest"])


def test_ros_remappings_are_set_apart() -> None:
    argv = ["-u", "__name:=gazebo", "w.world", "__log:=/tmp/x.log", "/clock:=/sim/clock"]
    assert split_ros_arguments(argv) == ["-u", "w.world"]
